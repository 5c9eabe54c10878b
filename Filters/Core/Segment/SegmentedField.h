// SegmentedField: the entry point of the segmented distance field, section 3.3 of
// S. Yamazaki, K. Kase and K. Ikeuchi, "Hardware-accelerated visualization of
// volume-sampled distance fields", Shape Modeling International (SMI), 2003:
// f = min(d, delta) + D r, with d the exact unsigned distance to the surface, r the
// region of the sample (the cells of space that the surface's sheets cut apart) and D the
// offset between regions. It represents open and non-manifold surfaces, which a signed
// field cannot.
//
// The stages: the self-intersection cut (SelfIntersections: crossings become junction
// lines), the patches (SurfacePatches: the surface split along its junctions and
// boundaries), the exact field with each sample's closest feature (LinearFactor/), the
// regions (SegmentRegions; on the GPU the side labels are computed where the field lies,
// SegmentFieldGPU). A piece of a distributed run computes its samples alone and shares
// the regions' evidence with the other pieces (SegmentedFieldRequest::Combine).
#ifndef vtkdf_SegmentedField_h
#define vtkdf_SegmentedField_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/PieceOwnership.h"
#include "Common/SampleGrid.h"

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vtkdf
{
class HeadlessGL;

/// What the merge of labels into regions reads, counted over the samples a piece owns:
/// the labels they take, and per pair of labels the adjacent sample pairs (the lower
/// sample owned) with no surface between them. Pieces that own disjoint samples add up to
/// the whole grid's evidence.
struct RegionEvidence
{
  int64_t Samples = 0;         // owned samples counted
  std::vector<int64_t> Labels; // taken by an owned sample, increasing
  std::map<std::pair<int64_t, int64_t>, int64_t> Support;

  /// As 64-bit words, for the pieces to exchange; Add() reads them back.
  std::vector<int64_t> Pack() const;
  /// Adds the evidence packed in `words`; false (nothing added) when they are not one.
  bool Add(const int64_t* words, int64_t count);
};

struct SegmentedFieldRequest
{
  SampleGrid Grid; // world; Grid.Whole is the whole grid
  /// The samples computed, the arrays' extent (empty: Grid.Whole). A part of the grid
  /// needs Pieces: its regions are the whole grid's.
  IndexBox Extent;
  /// A piece of a distributed run: Extent must hold Pieces.Piece and one sample around
  /// it (within the grid); the piece counts the region evidence of the
  /// samples it owns and Combine makes it the whole grid's: the sum over the pieces,
  /// the same on every piece (RegionEvidence::Pack/Add). Null Combine: one piece, the
  /// whole grid.
  PieceOwnership Pieces;
  std::function<bool(RegionEvidence&, std::string&)> Combine;
  /// The distance cap delta and the region offset D, world units; 0: 2 and 4 times the
  /// largest spacing.
  double Delta = 0;
  double RegionOffset = 0;
  /// Cut the triangles that cross without sharing an edge along their crossings.
  bool CutSelfIntersections = true;
};

/// Per sample of the request's Extent (x fastest); ClosestPoint may be null.
struct SegmentedFieldArrays
{
  float* SegmentedDistance = nullptr;
  int32_t* RegionIndex = nullptr;
  float* Distance = nullptr; // unsigned, world units
  int32_t* PatchId = nullptr;
  float* ClosestPoint = nullptr; // 3 per sample, world coordinates
};

struct SegmentedFieldReport
{
  double Delta = 0, RegionOffset = 0; // as used
  int32_t RegionCount = 0;
  /// Per region, its (patch, side) pairs, sorted.
  std::vector<std::vector<std::pair<int64_t, int>>> Sides;
  int64_t PatchCount = 0;
  int64_t CrossedTriangles = 0; // input triangles cut along their crossings
  int64_t CutEdges = 0;         // edges a non-orientable patch was cut along
  int64_t RefusedMerges = 0;
  /// What the host should warn about (ignored cells, crossings left uncut, cut patches,
  /// the float resolution of far regions), one sentence each.
  std::vector<std::string> Warnings;
  bool Aborted = false;
};

/// The segmented field of `mesh` (world coordinates) on the CPU, or on the GPU when `gl`
/// is given (the field and the side labels there, the merge of the labels into regions
/// on the CPU). Stages crossings, patches, field, regions. False and `error` on invalid
/// input or when the GPU fails.
bool ComputeSegmentedField(MeshInput mesh,
  const SegmentedFieldRequest& request,
  HeadlessGL* gl,
  const SegmentedFieldArrays& arrays,
  const Execution& execution,
  SegmentedFieldReport& report,
  std::string& error);

/// Whether this build cuts crossing triangles (built with DF_USE_CGAL). Without it the
/// crossings are found and reported (SegmentedFieldReport::Warnings) but left uncut.
bool SelfIntersectionCutAvailable();

} // namespace vtkdf

#endif
