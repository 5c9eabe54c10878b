/**
 * @class   vtkUnionClosestPoint
 * @brief   Closest point on the boundary of a union of convex polytopes (paper 003).
 *
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
 * narrower than a pixel can exceed (Certified 0). Auto: the GPU when a hardware-accelerated
 * context exists, else the CPU.
 *
 * Input 0, the pieces: a vtkPolyData whose connected components (cells sharing point
 * ids: touching pieces that repeat their shared corners stay apart) are the pieces, in
 * the order of their lowest cell id; or a vtkMultiBlockDataSet /
 * vtkPartitionedDataSetCollection / vtkPartitionedDataSet of vtkPolyData, one piece per
 * leaf, in traversal order. With PieceArray, a vtkPolyData's pieces are instead the cells
 * sharing a value of that cell-data array, in the order of their lowest cell id. Each
 * piece must be closed and convex (within a tolerance relative to the pieces' size: 1e-6
 * of their box's diagonal for float points, 1e-9 for double); otherwise an error names the
 * piece, unless UseConvexHulls replaces each such piece by its convex hull (qhull), which a
 * warning says.
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

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string
#include <vector> // For std::vector

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

  enum BackendType
  {
    BACKEND_AUTO = 0, ///< the GPU when a hardware-accelerated context exists, else the CPU
    BACKEND_GPU = 1,  ///< the GPU, even a software rasterizer; an error when there is none
    BACKEND_CPU = 2   ///< exact, vtkSMPTools on the CPU
  };
  ///@{
  /// Where the query runs (default Auto).
  vtkSetClampMacro(Backend, int, BACKEND_AUTO, BACKEND_CPU);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToGPU() { this->SetBackend(BACKEND_GPU); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }
  ///@}

  ///@{
  /// GPU: pixels a side of each of the six cube-face views (default 256, 8 to 8192).
  vtkSetMacro(ViewResolution, int);
  vtkGetMacro(ViewResolution, int);
  ///@}

  ///@{
  /// GPU: search the faces nearer than the images' answer exactly on the CPU (default on),
  /// so that the answer is exact; off, the image-space answer alone.
  vtkSetMacro(Certify, bool);
  vtkGetMacro(Certify, bool);
  vtkBooleanMacro(Certify, bool);
  ///@}

  ///@{
  /// GPU: the last query's six views on output 1 (default off).
  vtkSetMacro(GenerateViewImages, bool);
  vtkGetMacro(GenerateViewImages, bool);
  vtkBooleanMacro(GenerateViewImages, bool);
  ///@}

  /// Pieces and faces visited by the last run, summed over the queries (with the GPU,
  /// the faces certification searched).
  vtkGetMacro(LastPieceCount, int);
  vtkGetMacro(LastFacesVisited, vtkTypeInt64);
  /// The backend the last run used (BACKEND_GPU or BACKEND_CPU), the GPU's renderer, and
  /// its rendering rounds, summed over the queries.
  vtkGetMacro(LastBackend, int);
  const char* GetLastRenderer() const { return this->LastRenderer.c_str(); }
  vtkGetMacro(LastPasses, vtkTypeInt64);

protected:
  vtkUnionClosestPoint();
  ~vtkUnionClosestPoint() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData's work; 0 on failure.
  int Compute(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  /// The six views of the last query onto output 1.
  void WriteViewImages(const std::vector<float>& images,
    const std::vector<double>& frames,
    const double query[3],
    vtkInformationVector* outputVector);

  double QueryPoint[3] = { 0, 0, 0 };
  std::string PieceArray;
  bool UseConvexHulls = false;
  int Backend = BACKEND_AUTO;
  int ViewResolution = 256;
  bool Certify = true;
  bool GenerateViewImages = false;
  int LastPieceCount = 0;
  vtkTypeInt64 LastFacesVisited = 0;
  int LastBackend = BACKEND_CPU;
  std::string LastRenderer;
  vtkTypeInt64 LastPasses = 0;

private:
  vtkUnionClosestPoint(const vtkUnionClosestPoint&) = delete;
  void operator=(const vtkUnionClosestPoint&) = delete;
};

#endif
