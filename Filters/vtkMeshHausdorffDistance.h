/**
 * @class   vtkMeshHausdorffDistance
 * @brief   The Hausdorff distance between two polygon meshes, certified to a requested
 * accuracy, with each mesh's per-point distance to the other.
 *
 * Input 0 (mesh A) and input 1 (mesh B) are vtkPolyData of vertices, lines, polygons and
 * strips: open, non-manifold or soups. The one-sided distance from A to B is the largest
 * distance from a point of A (anywhere on its faces and lines, not only at its vertices)
 * to B; the Hausdorff distance is the larger of the two one-sided ones. The filter finds
 * each within an interval whose width is at most RelativeError times the diagonal of the
 * box of both meshes: it measures the exact distance at the vertices, bounds each
 * triangle from above by the nearest triangles of the other mesh (the distance to a
 * triangle is convex, so over a triangle it is largest at a corner), and cuts the
 * triangles whose bound is not yet within the accuracy into four until it is (as Tang,
 * Lee and Kim, "Interactive Hausdorff distance computation for general polygonal
 * models", ACM Transactions on Graphics 28(3), 2009, and CGAL's bounded-error Hausdorff
 * distance do). The bounds are widened by the rounding of double precision at the
 * meshes' coordinates; an accuracy below that rounding is an error.
 *
 * Output 0 is A and output 1 is B, each with the point array `Distance` (double): every
 * point's exact distance to the other mesh. Both carry the field data
 * - `HausdorffDistance`: the largest distance found at a point of either mesh (the true
 *   value lies in HausdorffBounds, within the accuracy of it);
 * - `HausdorffBounds` (2 components): the certified interval [lower, upper];
 * - `OneSidedHausdorffDistance` (2 components): the largest distances found from A to B
 *   and from B to A, and `OneSidedHausdorffBounds` (2 tuples of 2: A to B, B to A);
 * - `HausdorffPoints` (2 tuples of 3): the point where HausdorffDistance was found and
 *   its closest point on the other mesh, and `HausdorffSource`: 0 when the first lies on
 *   A, 1 on B.
 *
 * The work runs on the CPU (vtkSMPTools); the result does not depend on the number of
 * threads. In a distributed run every rank needs both meshes whole (a mesh partitioned
 * upstream is an error) and rank 0 outputs the answer.
 */
#ifndef vtkMeshHausdorffDistance_h
#define vtkMeshHausdorffDistance_h

#include "vtkDistanceFieldPolyDataAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

class VTKDISTANCEFIELDS_EXPORT vtkMeshHausdorffDistance : public vtkDistanceFieldPolyDataAlgorithm
{
public:
  static vtkMeshHausdorffDistance* New();
  vtkTypeMacro(vtkMeshHausdorffDistance, vtkDistanceFieldPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Mesh B (input 1); mesh A is input 0.
  void SetMeshBConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetMeshBData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// The accuracy: the certified interval is at most RelativeError times the diagonal of
  /// both meshes' box wide (default 1e-6). Finite, positive and at most 1.
  vtkSetMacro(RelativeError, double);
  vtkGetMacro(RelativeError, double);
  ///@}

  ///@{
  /// The last run's result (world units): the largest distance found, the certified
  /// interval, and the one-sided distances found from A to B and from B to A.
  vtkGetMacro(HausdorffDistance, double);
  vtkGetVector2Macro(HausdorffBounds, double);
  vtkGetMacro(DistanceAToB, double);
  vtkGetMacro(DistanceBToA, double);
  ///@}

  ///@{
  /// The last run's work: pieces of triangles bounded, rounds of refinement (the larger
  /// of the two directions') and primitive distances computed.
  vtkGetMacro(LastPieces, vtkTypeInt64);
  vtkGetMacro(LastRounds, vtkTypeInt64);
  vtkGetMacro(LastEvaluations, vtkTypeInt64);
  ///@}

protected:
  vtkMeshHausdorffDistance();
  ~vtkMeshHausdorffDistance() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif

  bool CheckProperties();

  double RelativeError = 1e-6;
  double HausdorffDistance = 0;
  double HausdorffBounds[2] = { 0, 0 };
  double DistanceAToB = 0;
  double DistanceBToA = 0;
  vtkTypeInt64 LastPieces = 0;
  vtkTypeInt64 LastRounds = 0;
  vtkTypeInt64 LastEvaluations = 0;

private:
  vtkMeshHausdorffDistance(const vtkMeshHausdorffDistance&) = delete;
  void operator=(const vtkMeshHausdorffDistance&) = delete;
};

#endif
