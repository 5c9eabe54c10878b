/**
 * @class   vtkMeshDistanceFilter
 * @brief   Exact distance from the points of any dataset to a polygon mesh, with its
 * sign, closest point, closest cell and gradient.
 *
 * Input 0 is any vtkDataSet whose points are the queries (a point cloud, an unstructured,
 * structured or rectilinear grid, an image, another mesh); input 1 (the surface) is a
 * vtkPolyData of vertices, lines, polygons and strips, open, non-manifold or a soup.
 * The output is input 0 with these point arrays (double precision):
 * - `Distance`: the exact distance to the surface, unsigned or signed (negative inside)
 *   by SignMode, with the rules of vtkLinearFactorDistanceField: the same answer as that
 *   filter's at a grid sample, in double rather than float;
 * - `ClosestPoint` (3 components) and `ClosestCellId`: the smallest input cell holding
 *   the closest feature (vertex, edge or face interior), so that shared and duplicate
 *   cells give the same id;
 * - `ClosestBarycentric` (3 components) and `ClosestSubTriangle`: the closest point's
 *   coordinates on triangle `ClosestSubTriangle` of that cell as the module splits it
 *   (a polygon's ear-cut triangles, a strip's triangles in order; a line cell's
 *   segments, with 0 as the third coordinate; a vertex cell's points, as (1, 0, 0));
 * - `Gradient` (3 components): the unit vector from the closest point to the point,
 *   times the sign: the gradient of the distance wherever it is differentiable; on the
 *   surface itself, the closest feature's unit angle-weighted pseudonormal (0 on a
 *   vertex or line cell);
 * - `ClosestFeature` when asked for (ComputeClosestFeature, an unsigned char): where the
 *   closest point lies, 0 a vertex, 1 an edge, 2 a face's interior (255 beyond the cap),
 *   as vtkLinearFactorDistanceField's;
 * - `WindingNumber` when asked for (ComputeWindingNumber): the generalized winding
 *   number, within about 1e-3, exact where it is near 1/2.
 * and field data `MaximumAbsoluteDistance`, `MeanAbsoluteDistance`,
 * `RootMeanSquareDistance` (over the points within MaximumDistance; exact sums, so the
 * same on any threads and ranks), `FarthestPointId` and `FarthestPoint` (the first point
 * at the maximum; with global point ids, the smallest id's, and that id), `PointsBeyond`.
 * In a distributed run every rank measures its own points to the whole surface and the
 * field data covers all the ranks' points (collective: every rank executes the filter);
 * without global ids FarthestPointId is then -1 where several ranks hold points.
 *
 * Points farther than MaximumDistance hold that distance (its sign from the winding
 * number in WindingNumber mode; NaN in PseudoNormal mode, where no closest feature signs
 * them), ClosestCellId and ClosestSubTriangle -1, and NaN vectors: never a wrong closest
 * point.
 *
 * The queries run on the CPU (vtkSMPTools) through a bounding-volume hierarchy of the
 * surface's triangles, segments and points, in the Morton order of the points (the
 * answers come back in the input's order); the hierarchy is kept while the surface and
 * SignMode do not change, so a new set of points reuses it. A point with a NaN or
 * infinite coordinate is an error that names it; an empty point set gives empty arrays.
 */
#ifndef vtkMeshDistanceFilter_h
#define vtkMeshDistanceFilter_h

#include "vtkDistanceFieldDataSetAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#include <memory> // For std::unique_ptr

#ifndef __VTK_WRAP__
namespace vtkdf
{
class PointDistanceQueries;
struct PointDistanceArrays;
}
#endif

class vtkPointData;
class vtkPolyData;

class VTKDISTANCEFIELDS_EXPORT vtkMeshDistanceFilter : public vtkDistanceFieldDataSetAlgorithm
{
public:
  static vtkMeshDistanceFilter* New();
  vtkTypeMacro(vtkMeshDistanceFilter, vtkDistanceFieldDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The surface the distances are measured to (input 1); the points are input 0.
  void SetSurfaceConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSurfaceData(vtkDataObject* data) { this->SetInputData(1, data); }

  /// How Distance is signed (negative inside): the values and rules of
  /// vtkLinearFactorDistanceField's SignMode.
  enum SignModeType
  {
    UNSIGNED = 0,
    PSEUDO_NORMAL = 1,
    WINDING_NUMBER = 2
  };
  ///@{
  /// SignMode (default Unsigned).
  vtkSetMacro(SignMode, int);
  vtkGetMacro(SignMode, int);
  void SetSignModeToUnsigned() { this->SetSignMode(UNSIGNED); }
  void SetSignModeToPseudoNormal() { this->SetSignMode(PSEUDO_NORMAL); }
  void SetSignModeToWindingNumber() { this->SetSignMode(WINDING_NUMBER); }
  ///@}

  ///@{
  /// How far the search reaches (world units); 0 (the default) means everywhere.
  /// Otherwise finite and positive.
  vtkSetMacro(MaximumDistance, double);
  vtkGetMacro(MaximumDistance, double);
  ///@}

  ///@{
  /// Which arrays besides Distance to produce: ClosestPoint, ClosestCellId,
  /// ClosestBarycentric with ClosestSubTriangle, Gradient (on by default), ClosestFeature
  /// and WindingNumber (off).
  vtkSetMacro(ComputeClosestPoint, bool);
  vtkGetMacro(ComputeClosestPoint, bool);
  vtkBooleanMacro(ComputeClosestPoint, bool);
  vtkSetMacro(ComputeClosestCellId, bool);
  vtkGetMacro(ComputeClosestCellId, bool);
  vtkBooleanMacro(ComputeClosestCellId, bool);
  vtkSetMacro(ComputeBarycentric, bool);
  vtkGetMacro(ComputeBarycentric, bool);
  vtkBooleanMacro(ComputeBarycentric, bool);
  vtkSetMacro(ComputeGradient, bool);
  vtkGetMacro(ComputeGradient, bool);
  vtkBooleanMacro(ComputeGradient, bool);
  vtkSetMacro(ComputeClosestFeature, bool);
  vtkGetMacro(ComputeClosestFeature, bool);
  vtkBooleanMacro(ComputeClosestFeature, bool);
  vtkSetMacro(ComputeWindingNumber, bool);
  vtkGetMacro(ComputeWindingNumber, bool);
  vtkBooleanMacro(ComputeWindingNumber, bool);
  ///@}

  ///@{
  /// The last run's figures: primitive distances evaluated, points beyond
  /// MaximumDistance, and whether it built the surface's hierarchy (false: reused).
  vtkGetMacro(LastEvaluations, vtkTypeInt64);
  vtkGetMacro(LastPointsBeyond, vtkTypeInt64);
  vtkGetMacro(LastBuiltHierarchy, bool);
  ///@}

protected:
  vtkMeshDistanceFilter();
  ~vtkMeshDistanceFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif

  bool CheckProperties();
#ifndef __VTK_WRAP__
  /// The requested arrays on `pd`, `count` points each.
  vtkdf::PointDistanceArrays AddArrays(vtkPointData* pd, vtkIdType count) const;
#endif
  /// The surface's hierarchy for this SignMode, built unless the last one still holds.
  bool PrepareQueries(vtkPolyData* surface, vtkdf::FilterRun& run);

  int SignMode = UNSIGNED;
  double MaximumDistance = 0;
  bool ComputeClosestPoint = true;
  bool ComputeClosestCellId = true;
  bool ComputeBarycentric = true;
  bool ComputeGradient = true;
  bool ComputeClosestFeature = false;
  bool ComputeWindingNumber = false;

  vtkTypeInt64 LastEvaluations = 0;
  vtkTypeInt64 LastPointsBeyond = 0;
  bool LastBuiltHierarchy = false;

private:
#ifndef __VTK_WRAP__
  std::unique_ptr<vtkdf::PointDistanceQueries> Queries;
  vtkPolyData* QueriesSurface = nullptr; // compared, never dereferenced
  vtkMTimeType QueriesTime = 0;
  int QueriesSign = -1;
  bool QueriesWinding = false;
#endif

  vtkMeshDistanceFilter(const vtkMeshDistanceFilter&) = delete;
  void operator=(const vtkMeshDistanceFilter&) = delete;
};

#endif
