/**
 * @class   vtkSegmentedDistanceField
 * @brief   Segmented distance field of a surface that may be open or non-manifold.
 *
 * Implements section 3.3 of Yamazaki, Kase and Ikeuchi (SMI 2003): a signed distance
 * can only represent closed 2-manifolds; the segmented distance
 *   f(p) = min(d(p), Delta) + RegionOffset * r(p)
 * (d the exact unsigned distance, r the region index) also represents boundaries and
 * junctions of three or more sheets. The surface is split into patches along its
 * junction lines and boundaries; each side of each patch starts a region; regions that
 * meet in space merge, never the two sides of one patch. See
 * Filters/Core/Segment/SegmentRegions.h for how each sample gets its side (the wedge
 * nearest in angle at its closest feature, so junction sectors are right) and for the
 * merge rule (a function of the field alone: the same for any thread count).
 *
 * Input: vtkPolyData of triangles and polygons (open, non-manifold, several components,
 * soups: points at the same position are one); lines and vertices are ignored (a
 * warning says so), as are triangles without area. On the CPU the exact distance and
 * closest features come from vtkLinearFactorDistanceField on this filter's grid, and the
 * side labels and regions are computed with vtkSMPTools. On the GPU the field stays
 * there: the scan, its finalize and the side labels run where the field lies
 * (Filters/Core/Segment/SegmentFieldGPU.h, Shaders/SideLabel.comp.glsl), and only the
 * distances, closest points and labels come back for the merge into regions (CPU: one
 * pass over the samples).
 *
 * Distributed runs: the regions are global, yet each rank computes only its piece (and
 * one sample around it): the ranks add up the evidence the merge reads (which labels the
 * samples take, how many adjacent pairs support each pair of labels, each sample
 * counted by one rank) and every rank merges the same sums, so the pieces are the one
 * process's grid bit for bit. In one process a piece is cut from the whole grid.
 *
 * Output: vtkImageData (the requested extent) with `SegmentedDistance` (float), `RegionIndex`
 * (int), `Distance` (float, unsigned), `PatchId` (int: the patch whose side the sample
 * took) and, with ComputeClosestPoint (default on), `ClosestPoint` (float, 3 components:
 * each sample's closest point on the surface, which vtkSegmentedDistanceContour uses to
 * keep apices, rims and junction lines); field data `Delta`, `RegionOffset`, `RegionCount` and
 * `RegionSides` (int, 3 components per row: region, patch, side 0 front or 1 back; a merged region
 * has several rows).
 */
#ifndef vtkSegmentedDistanceField_h
#define vtkSegmentedDistanceField_h

#include "vtkDistanceFieldAlgorithm.h"

class vtkFieldData;
class vtkImageData;
class vtkPolyData;
#ifndef __VTK_WRAP__
namespace vtkdf
{
struct IndexBox;
struct SegmentedFieldReport;
struct SegmentedFieldRequest;
}
#endif
#include "vtkDistanceFieldsModule.h" // For export macro

class VTKDISTANCEFIELDS_EXPORT vtkSegmentedDistanceField : public vtkDistanceFieldAlgorithm
{
public:
  static vtkSegmentedDistanceField* New();
  vtkTypeMacro(vtkSegmentedDistanceField, vtkDistanceFieldAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Delta caps the distance within a region; RegionOffset (D) separates the regions'
  /// value ranges. 0 (the defaults) means 2 and 4 times the largest grid spacing. Delta
  /// must be at least the largest spacing (an interface needs the two distances across
  /// a grid edge, which sum to less than a spacing) and below RegionOffset.
  vtkSetMacro(Delta, double);
  vtkGetMacro(Delta, double);
  vtkSetMacro(RegionOffset, double);
  vtkGetMacro(RegionOffset, double);
  ///@}

  /// Whether the output has ClosestPoint (default on).
  vtkSetMacro(ComputeClosestPoint, bool);
  vtkGetMacro(ComputeClosestPoint, bool);
  vtkBooleanMacro(ComputeClosestPoint, bool);

  /// Whether triangles that cross without sharing an edge (a teapot's spout through its
  /// body) are cut along their crossings first (default on), so that each crossing is a
  /// junction line between patches (Filters/Core/Segment/SelfIntersections.h, CGAL's
  /// autorefinement). Uncut, the pocket between two crossing sheets belongs to two
  /// patches' sides at once and its interfaces end short of the crossing. When CGAL
  /// cannot refine the mesh, or the module was built without CGAL (DF_USE_CGAL=OFF, see
  /// IsSelfIntersectionCutAvailable), a warning says so and the field is that of the
  /// uncut mesh.
  vtkSetMacro(CutSelfIntersections, bool);
  vtkGetMacro(CutSelfIntersections, bool);
  vtkBooleanMacro(CutSelfIntersections, bool);

  /// Whether this build can cut crossings: false when it was configured with
  /// -DDF_USE_CGAL=OFF (BSD-compatible dependencies only, without CGAL's GPL-licensed
  /// Polygon Mesh Processing). The crossings are still found, and a warning names them.
  static bool IsSelfIntersectionCutAvailable();

  /// What the last run found: regions, patches, the input triangles cut along
  /// crossings, the edges where non-orientable patches were cut, and the region merges
  /// refused (they would have joined two sides of one patch).
  vtkGetMacro(LastRegionCount, int);
  vtkGetMacro(LastPatchCount, vtkTypeInt64);
  vtkGetMacro(LastCrossedTriangles, vtkTypeInt64);
  vtkGetMacro(LastCutEdges, vtkTypeInt64);
  vtkGetMacro(LastRefusedMerges, vtkTypeInt64);
  /// The samples the last run computed: the whole grid in one process; in a distributed
  /// run whose pieces tile the grid, the rank's piece and one sample around it.
  vtkGetVector6Macro(LastComputedExtent, int);

protected:
  vtkSegmentedDistanceField();
  ~vtkSegmentedDistanceField() override = default;

#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
  bool CheckProperties() override;
#ifndef __VTK_WRAP__
  /// Delta, RegionOffset, RegionCount and RegionSides, as the run used and found them.
  static void WriteFieldData(const vtkdf::SegmentedFieldReport& report, vtkFieldData* fd);
  /// Computes request.Extent (the grid and, in a distributed run, the pieces and the
  /// evidence's Combine are set) and outputs `piece` of it (Failed with the error
  /// reported, Empty when aborted).
  vtkdf::RunStatus ComputePiece(vtkPolyData* mesh,
    const vtkdf::SegmentedFieldRequest& request,
    const vtkdf::IndexBox& piece,
    vtkImageData* output,
    vtkdf::FilterRun& run);
#endif

  double Delta = 0;
  double RegionOffset = 0;
  bool ComputeClosestPoint = true;
  bool CutSelfIntersections = true;
  int LastRegionCount = 0;
  vtkTypeInt64 LastPatchCount = 0;
  vtkTypeInt64 LastCrossedTriangles = 0;
  vtkTypeInt64 LastCutEdges = 0;
  vtkTypeInt64 LastRefusedMerges = 0;
  int LastComputedExtent[6] = { 0, -1, 0, -1, 0, -1 };

private:
  vtkSegmentedDistanceField(const vtkSegmentedDistanceField&) = delete;
  void operator=(const vtkSegmentedDistanceField&) = delete;
};

#endif
