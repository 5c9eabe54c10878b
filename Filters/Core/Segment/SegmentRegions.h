// SegmentRegions: the region index of every sample of a grid (Yamazaki et al., SMI 2003,
// section 3.3.2, steps 2-6), from the exact unsigned field and each sample's closest feature,
// without VTK types.
//
// Labels: each patch has a front (0) and a back (1) side, label 2 patch + side. A sample
// takes the side of one triangle at its closest feature (a face, an edge or a vertex):
// among the triangles that share that feature, whatever their patch, the one whose
// wedge around it (the triangle's angle at a vertex, its half-plane at an edge) is
// nearest in angle to the sample's direction u from the closest point. The shortest arc
// from u to that wedge crosses no other sheet, so the sample lies in the space cell next
// to it, on the side sign(u . n) (n in the patch's orientation). Where the nearest
// direction of a vertex's wedges is one of its edges (two wedges share it, and the planes
// of both may disagree), the triangles around that edge decide, as for an edge feature.
// At a junction line this picks the patch whose angular sector holds the sample, not the
// lowest index, which mislabels reflex sectors.
//
// Merge: two adjacent samples a, b (along an axis, spacing w) with different labels are
// evidence that their regions are one when d_a + d_b > w (1 + 1e-5): by the triangle
// inequality no surface lies between them (the factor keeps an axis-aligned sheet exactly
// between two samples, d_a + d_b = w, from passing by rounding). Region pairs are merged
// in a canonical order: by the number of sample pairs that support them, largest first,
// ties by the lower then the higher label; a merge that would put the two sides of one
// patch in one region is refused. The result is a function of the field alone: the same
// for any thread count or visiting order. Regions are numbered from 0 in the order of
// their lowest label.
//
// Pieces: the merge reads only the labels the samples take and the support of each
// label pair (RegionEvidence). A piece of a distributed run counts them over the samples
// it owns (PieceOwnership), its ranks add them up (Combine), and every piece runs the
// same merge on the same sums: its regions are the whole grid's, bit for bit.
#ifndef vtkdf_SegmentRegions_h
#define vtkdf_SegmentRegions_h

#include "Common/Parallel.h"
#include "Common/PieceOwnership.h"
#include "Common/SampleGrid.h"
#include "Segment/SegmentedField.h"
#include "Segment/SurfacePatches.h"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vtkdf
{

struct SegmentInput
{
  const SurfacePatches* Patches = nullptr; // in the grid's frame
  SampleGrid Grid;                         // its Whole extent is the samples'
  // Per sample (x fastest over Grid.Whole):
  const float* Distance = nullptr; // unsigned, in the grid's units
  const int64_t* ClosestTriangle = nullptr;
  const uint8_t* ClosestFeature = nullptr; // 0 vertex, 1 edge, 2 face
  const double* ClosestPoint = nullptr;    // xyz in the grid's frame
  /// Optional: each sample's side label already computed (SegmentFieldGPU); then
  /// ClosestTriangle, ClosestFeature and ClosestPoint are not read.
  const int32_t* Labels = nullptr;
  /// A piece of a distributed run (null: Grid.Whole is the whole grid): Grid.Whole must
  /// hold the piece and the sample after it along each axis within WholeGrid; the piece
  /// counts the evidence of the samples it owns and Combine makes it the whole grid's
  /// (the sum over the pieces, the same on every piece; false and an error when it
  /// cannot).
  const PieceOwnership* Ownership = nullptr;
  IndexBox WholeGrid;
  std::function<bool(RegionEvidence&, std::string&)> Combine;
};

struct SegmentResult
{
  std::vector<int32_t> Region; // per sample
  std::vector<int32_t> Patch;  // per sample: the patch whose side it took
  int32_t RegionCount = 0;
  /// Per region, its (patch, side) pairs, sorted.
  std::vector<std::vector<std::pair<int64_t, int>>> Sides;
  int64_t Merges = 0;  // region pairs merged
  int64_t Refused = 0; // region pairs refused (they would join the two sides of a patch)
};

/// Fills `result` (per sample of Grid.Whole); `parallelFor` (optional) runs the
/// per-sample passes in parallel, with the same result. False and `error` when a piece's
/// samples or its Combine fail.
bool SegmentRegions(const SegmentInput& input,
  SegmentResult& result,
  std::string& error,
  const ParallelFor& parallelFor = ParallelFor());

/// The label (2 patch + side) of a sample at `p` whose closest point `c` lies on `feature`
/// (0 vertex, 1 edge, 2 face) of `triangle`; -1 when the triangle has no patch. Exposed
/// for the tests.
int64_t SideLabel(const SurfacePatches& patches,
  const double p[3],
  const double c[3],
  int64_t triangle,
  int feature,
  std::vector<int64_t>& scratch);

} // namespace vtkdf

#endif
