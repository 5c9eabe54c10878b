/**
 * @class   vtkUnionClosestPoint
 * @brief   Closest point on the boundary of a union of convex polytopes (paper 003).
 *
 * Given convex pieces M_i and query points O, finds for each O the closest point on the
 * boundary of M = union of M_i, without building the union: its signed distance
 * (negative inside M), the point, the unit direction from O to it and the piece whose face
 * holds it. Faces shared by touching pieces are not boundary: two unit cubes side by side
 * give 0.5 from (0.9, 0.5, 0.5), not 0.1. Exact, in double precision, on the CPU
 * (vtkSMPTools over the queries); see Filters/Core/Union/UnionClosestPoint.h. The GPU
 * path of the paper (image-space, then certified) is still to come.
 *
 * Input 0, the pieces: a vtkPolyData whose connected components (cells sharing point
 * ids: touching pieces that repeat their shared corners stay apart) are the pieces, in
 * the order of their lowest cell id; or a vtkMultiBlockDataSet /
 * vtkPartitionedDataSetCollection / vtkPartitionedDataSet of vtkPolyData, one piece per
 * leaf, in traversal order. With PieceArray, a vtkPolyData's pieces are instead the cells
 * sharing a value of that cell-data array, in the order of their lowest cell id. Each
 * piece must be closed and convex (within a tolerance relative to the pieces' size);
 * otherwise an error names the piece, unless UseConvexHulls replaces every piece by its
 * convex hull (qhull), which a warning says.
 * Input 1 (optional): a vtkPointSet whose points are the queries; without it, the
 * QueryPoint property.
 *
 * Output: vtkPolyData whose first points are the queries (point i is query i), followed
 * by their closest points, with a line from each query to its closest point, and the
 * point data `Distance`, `ClosestPoint` (float x3), `Direction` (unit, O to the closest
 * point), `Inside` (uint8), `ClosestPiece` (int) and `ErrorBound` (0: exact), the same on
 * a query and on its closest point.
 */
#ifndef vtkUnionClosestPoint_h
#define vtkUnionClosestPoint_h

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

class VTKDISTANCEFIELDS_EXPORT vtkUnionClosestPoint : public vtkPolyDataAlgorithm
{
public:
  static vtkUnionClosestPoint* New();
  vtkTypeMacro(vtkUnionClosestPoint, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The query when input 1 is not connected (default 0, 0, 0).
  vtkSetVector3Macro(QueryPoint, double);
  vtkGetVector3Macro(QueryPoint, double);

  /// The queries (port 1).
  void SetQueryConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetQueryData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// The name of a cell-data array of piece ids (integers) of a vtkPolyData input: its
  /// pieces are the cells of one id, not its connected components. Empty (default):
  /// connected components.
  vtkSetStdStringFromCharMacro(PieceArray);
  vtkGetCharFromStdStringMacro(PieceArray);
  ///@}

  ///@{
  /// Replace each piece by its convex hull (qhull) instead of refusing non-convex or open
  /// pieces (default off); a warning says how many pieces changed. A piece with no
  /// three-dimensional hull (fewer than four points, flat) is still an error.
  vtkSetMacro(UseConvexHulls, bool);
  vtkGetMacro(UseConvexHulls, bool);
  vtkBooleanMacro(UseConvexHulls, bool);
  ///@}

  /// Pieces and faces visited by the last run, summed over the queries.
  vtkGetMacro(LastPieceCount, int);
  vtkGetMacro(LastFacesVisited, vtkTypeInt64);

protected:
  vtkUnionClosestPoint();
  ~vtkUnionClosestPoint() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData's work; 0 on failure.
  int Compute(vtkInformation*, vtkInformationVector**, vtkInformationVector*);

  double QueryPoint[3] = { 0, 0, 0 };
  std::string PieceArray;
  bool UseConvexHulls = false;
  int LastPieceCount = 0;
  vtkTypeInt64 LastFacesVisited = 0;

private:
  vtkUnionClosestPoint(const vtkUnionClosestPoint&) = delete;
  void operator=(const vtkUnionClosestPoint&) = delete;
};

#endif
