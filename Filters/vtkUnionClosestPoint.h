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
 * Backend GPU: a compute pass gives each query an upper bound U (the nearest face point
 * that is certainly on the boundary; all the queries in one dispatch), and the CPU's exact
 * search then visits only the faces nearer than U: the CPU backend's answers, bit for
 * bit (Filters/Core/Union/UnionClosestPointGPU.h). The paper renders six cube-face views
 * around each query to find U instead. Auto: the CPU (the exact search runs on the CPU
 * either way). Progress is reported, and an abort heard, per twentieth of the queries
 * (CPU) or per dispatch and per 64 certified queries (GPU); an aborted run leaves an empty
 * output.
 *
 * Input 0, the pieces, in the forms vtkConvexQueryAlgorithm describes.
 * Input 1 (optional): a vtkPointSet whose points are the queries; without it, the
 * QueryPoint property.
 *
 * Output: vtkPolyData whose first points are the queries (point i is query i), followed
 * by their closest points, with a line from each query to its closest point, and the
 * point data `Distance`, `ClosestPoint` (float x3), `Direction` (unit, O to the closest
 * point), `Inside` (uint8) and `ClosestPiece` (int), the same on a query and on its
 * closest point. Output 1, an empty vtkPartitionedDataSet, is kept for the pipelines that
 * took the GPU's rendered views from it (GenerateViewImages, deprecated).
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
  /**
   * The GPU's rendered views of the last query on output 1: the GPU backend no longer
   * renders views, so output 1 stays empty (a warning says so when this is on).
   * @deprecated Nothing replaces it.
   */
  VTK_DEPRECATION("The GPU backend renders no views: output 1 stays empty")
  void SetGenerateViewImages(bool value);
  VTK_DEPRECATION("The GPU backend renders no views: output 1 stays empty")
  bool GetGenerateViewImages() { return this->GenerateViewImages; }
  VTK_DEPRECATION("The GPU backend renders no views: output 1 stays empty")
  void GenerateViewImagesOn();
  VTK_DEPRECATION("The GPU backend renders no views: output 1 stays empty")
  void GenerateViewImagesOff();
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

  double QueryPoint[3] = { 0, 0, 0 };
  bool GenerateViewImages = false;
  int LastPieceCount = 0;

private:
  void ChangeGenerateViewImages(bool value); // the deprecated setters' one body
  vtkUnionClosestPoint(const vtkUnionClosestPoint&) = delete;
  void operator=(const vtkUnionClosestPoint&) = delete;
};

#endif
