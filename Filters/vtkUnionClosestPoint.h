/**
 * @class   vtkUnionClosestPoint
 * @brief   Closest point on the boundary of a union of convex polytopes.
 *
 * Implements Kim, Hoff, Lin and Manocha, "Closest Point Query Among the Union of Convex
 * Polytopes Using Rasterization Hardware" (Journal of Graphics Tools 7(4), 2002).
 * Given convex pieces M_i and query points O, finds for each O the closest point on the
 * boundary of M = union of M_i, without building the union: its signed distance
 * (negative inside M), the point, the unit direction from O to it and the piece whose face
 * holds it. Faces shared by touching pieces are not boundary: two unit cubes side by side
 * give 0.5 from (0.9, 0.5, 0.5), not 0.1.
 *
 * Backend CPU: exact, in double precision (vtkSMPTools over the queries, or over each
 * query's faces when there are few); see Filters/Core/Union/UnionClosestPoint.h.
 * Progress is reported, and an abort heard, per twentieth of the queries (CPU) or per
 * batch and per 64 certified queries (GPU); an aborted run leaves an empty output.
 * Backend GPU: the paper's Algorithm 2.1 on six cube-face views of ViewResolution pixels
 * around each query (stencil windows, the Euclidean distance as the depth, rounds until
 * one changes nothing; Filters/Core/Union/UnionClosestPointGPU.h), whose smallest distance
 * U is a boundary point; with Certify (default) the faces nearer than U are then searched
 * exactly on the CPU and the answer is exact (ErrorBound 0, Certified 1); without it the
 * answer is U's point, with an image-space estimate in ErrorBound that a gap of free space
 * narrower than a pixel can exceed (Certified 0). Auto: the CPU (on an NVIDIA H100 the GPU's
 * batches of queries were 50-60 times slower than the CPU's, docs/benchmarks.md).
 *
 * Input 0, the pieces, in the forms vtkConvexQueryAlgorithm describes.
 * Input 1 (optional): a vtkPointSet whose points are the queries; without it, the
 * QueryPoint property.
 *
 * Output: vtkPolyData whose first points are the queries (point i is query i), followed
 * by their closest points, with a line from each query to its closest point, and the
 * point data `Distance`, `ClosestPoint` (float x3), `Direction` (unit, O to the closest
 * point), `Inside` (uint8), `ClosestPiece` (int), `ErrorBound` (0: exact) and
 * `Certified` (uint8: 1 when exact), the same on a query and on its closest point.
 * Output 1 (GenerateViewImages, GPU backend): the last query's six cube-face views as a
 * vtkPartitionedDataSet of six vtkImageData, ViewResolution pixels a side over [-1, 1]^2
 * (tangent-plane coordinates), point data `Distance` (NaN where no boundary was seen),
 * field data `ViewFrame` (right, up, forward) and `QueryPoint`.
 */
#ifndef vtkUnionClosestPoint_h
#define vtkUnionClosestPoint_h

#include "vtkConvexQueryAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#include <vector> // For std::vector

#ifndef __VTK_WRAP__
namespace vtkdf
{
struct UnionGPUAnswer;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkUnionClosestPoint : public vtkConvexQueryAlgorithm
{
public:
  static vtkUnionClosestPoint* New();
  vtkTypeMacro(vtkUnionClosestPoint, vtkConvexQueryAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The query when input 1 is not connected (default 0, 0, 0).
  vtkSetVector3Macro(QueryPoint, double);
  vtkGetVector3Macro(QueryPoint, double);

  /// The queries (port 1).
  void SetQueryConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetQueryData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// GPU: the last query's six views on output 1 (default off).
  vtkSetMacro(GenerateViewImages, bool);
  vtkGetMacro(GenerateViewImages, bool);
  vtkBooleanMacro(GenerateViewImages, bool);
  ///@}

  /// The pieces of the last run (its faces visited, summed over the queries, are
  /// LastFacesVisited; with the GPU, the faces certification searched).
  vtkGetMacro(LastPieceCount, int);

protected:
  vtkUnionClosestPoint();
  ~vtkUnionClosestPoint() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  bool IsQueryPort(int port) override { return port == 1; }
  int FillOutputPortInformation(int port, vtkInformation* info) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
  /// The query points: input 1's points, or QueryPoint; false with the error reported
  /// when one is not finite.
  bool ReadQueries(vtkInformationVector* queryInput, std::vector<double>& queries);
#ifndef __VTK_WRAP__
  /// Output 0: the queries, their closest points, a line between them, the arrays.
  void WriteAnswers(const std::vector<double>& queries,
    const std::vector<vtkdf::UnionGPUAnswer>& answers,
    vtkPolyData* output);
#endif
  /// The six views of the last query onto output 1.
  void WriteViewImages(const std::vector<float>& images,
    const std::vector<double>& frames,
    const double query[3],
    vtkInformationVector* outputVector);

  double QueryPoint[3] = { 0, 0, 0 };
  bool GenerateViewImages = false;
  int LastPieceCount = 0;

private:
  vtkUnionClosestPoint(const vtkUnionClosestPoint&) = delete;
  void operator=(const vtkUnionClosestPoint&) = delete;
};

#endif
