/**
 * @class   vtkSegmentedDistanceContour
 * @brief   The surface of a segmented distance field, boundaries and junctions kept.
 *
 * The polygonizer of Yamazaki et al. (SMI 2003) (section 3.3, eqs. 5-7) for the output of
 * vtkSegmentedDistanceField: an interface point on every grid edge between two regions
 * whose samples' distances add up to at most the edge's length, where eq. 6 puts it; the
 * points joined cell by cell (Filters/Core/Segment/SegmentContour.h): by marching cubes
 * where a cell holds two regions and every edge between them has its point (so a closed
 * surface gives what vtkFlyingEdges3D gives at 0 on its signed field), else around a
 * vertex at the cell's centre of interface points, which is where junctions of three or
 * more sheets meet and where open sheets end (a boundary is where eq. 7 suppresses the
 * points: no spurious sheet across a hole, unlike a signed field's zero level set).
 *
 * Input: vtkImageData with `SegmentedDistance` and the field-data `RegionOffset` (what
 * vtkSegmentedDistanceField makes); each sample's region and distance are read back
 * from f = min(d, Delta) + RegionOffset * r. When the input also has `ClosestPoint` (the
 * samples' closest points on the surface, which vtkSegmentedDistanceField writes by
 * default) and UseClosestPoints is on, vertices follow the surface's features: the
 * vertex of a junction or boundary cell goes onto the junction line or the open rim, and
 * a marching-cubes cell whose tangent planes differ by more than FeatureAngle (an apex,
 * a crease) is fanned around its feature point, as in extended marching cubes (see
 * SegmentContour.h). Marching cubes then no longer rounds sharp apices and rims; with
 * UseClosestPoints off the surface is the paper's, and a closed smooth surface is
 * exactly vtkFlyingEdges3D's. Output: vtkPolyData of triangles with the
 * cell array `Regions` (int, 2 components: the lower and the higher region the triangle
 * separates; it faces the higher). CPU. In a distributed run rank 0 gathers the
 * field's pieces and outputs the whole surface (one process's, bit for bit); the other
 * ranks output nothing.
 */
#ifndef vtkSegmentedDistanceContour_h
#define vtkSegmentedDistanceContour_h

#include "vtkDistanceFieldPolyDataAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#include <vector> // For the field's samples

class vtkImageData;
#ifndef __VTK_WRAP__
namespace vtkdf
{
struct ContourInput;
struct ContourResult;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkSegmentedDistanceContour
  : public vtkDistanceFieldPolyDataAlgorithm
{
public:
  static vtkSegmentedDistanceContour* New();
  vtkTypeMacro(vtkSegmentedDistanceContour, vtkDistanceFieldPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Vertices from the input's ClosestPoint array when it has one (default on), and the
  /// angle between tangent planes (degrees, in (0, 180]; default 30) above which a
  /// marching-cubes cell holds a feature.
  vtkSetMacro(UseClosestPoints, bool);
  vtkGetMacro(UseClosestPoints, bool);
  vtkBooleanMacro(UseClosestPoints, bool);
  vtkSetMacro(FeatureAngle, double);
  vtkGetMacro(FeatureAngle, double);
  ///@}

  /// Cells of the last run done by marching cubes (of which FeatureCells fanned around a
  /// feature point), and around a cell vertex (junctions and boundaries).
  vtkGetMacro(LastMarchingCells, vtkTypeInt64);
  vtkGetMacro(LastFeatureCells, vtkTypeInt64);
  vtkGetMacro(LastOtherCells, vtkTypeInt64);

protected:
  vtkSegmentedDistanceContour() = default;
  ~vtkSegmentedDistanceContour() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
  /// The samples of the (whole) segmented field `field` as the core takes them: its grid,
  /// distances and regions (held in `distance` and `region`), and its closest points
  /// (held in `closest`) when UseClosestPoints is on and it has them. False with the
  /// error reported.
  bool ReadField(vtkImageData* field,
    vtkdf::ContourInput& input,
    std::vector<float>& distance,
    std::vector<int32_t>& region,
    std::vector<double>& closest);
  /// The surface as the output: points, triangles, the Regions pair of each triangle.
  static void WriteSurface(const vtkdf::ContourResult& result, vtkPolyData* output);
#endif

  bool UseClosestPoints = true;
  double FeatureAngle = 30;
  vtkTypeInt64 LastMarchingCells = 0;
  vtkTypeInt64 LastFeatureCells = 0;
  vtkTypeInt64 LastOtherCells = 0;

private:
  vtkSegmentedDistanceContour(const vtkSegmentedDistanceContour&) = delete;
  void operator=(const vtkSegmentedDistanceContour&) = delete;
};

#endif
