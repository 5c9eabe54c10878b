/**
 * @class   vtkConvexQueryAlgorithm
 * @brief   Base of the filters that query unions of convex pieces.
 *
 * Holds what vtkUnionClosestPoint and vtkPenetrationDepth share: how their inputs become
 * convex pieces (PieceArray, UseConvexHulls), where the query runs (Backend; on the GPU,
 * ViewResolution and Certify) and what the last run used (LastBackend, LastRenderer,
 * LastPasses, LastFacesVisited).
 *
 * An input of pieces is a vtkPolyData whose connected components (cells sharing point
 * ids: touching pieces that repeat their shared corners stay apart) are the pieces, in
 * the order of their lowest cell id; or, with PieceArray, whose cells of one value of that
 * cell-data array are; or a vtkMultiBlockDataSet / vtkPartitionedDataSetCollection /
 * vtkPartitionedDataSet of vtkPolyData, one piece per leaf, in traversal order. Each
 * piece must be closed and convex (within 1e-6 of the pieces' box diagonal for float
 * points, 1e-9 for double); otherwise an error names the piece, unless UseConvexHulls
 * replaces it by its convex hull (qhull), which a warning says.
 *
 * Properties are not clamped when set: an invalid value is reported by name when the
 * filter runs. A failure leaves the outputs empty and a non-zero GetErrorCode().
 */
#ifndef vtkConvexQueryAlgorithm_h
#define vtkConvexQueryAlgorithm_h

#include "vtkDistanceFieldPolyDataAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#include <string> // For std::string

#ifndef __VTK_WRAP__
namespace vtkdf
{
class HeadlessGL;
struct ConvexPieceInput;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkConvexQueryAlgorithm : public vtkDistanceFieldPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkConvexQueryAlgorithm, vtkDistanceFieldPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

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

  /// Where the query runs (the values of vtkDistanceFieldAlgorithm's BackendType).
  enum BackendType
  {
    BACKEND_AUTO = 0, ///< the faster backend as measured: today the CPU
    BACKEND_GPU = 1,  ///< the GPU, even a software rasterizer; an error when there is none
    BACKEND_CPU = 2   ///< exact, on the CPU
  };
  ///@{
  /// Where the query runs (default Auto). The CPU is exact, in double precision; the GPU
  /// renders six cube-face views of ViewResolution pixels around each query point
  /// (Kim et al.'s Algorithm 2.1), whose answer Certify then makes exact on the CPU.
  vtkSetMacro(Backend, int);
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
  /// so that the answer is exact; off, the image-space answer alone (ErrorBound then
  /// holds an image-space estimate that a gap narrower than a pixel can exceed).
  vtkSetMacro(Certify, bool);
  vtkGetMacro(Certify, bool);
  vtkBooleanMacro(Certify, bool);
  ///@}

  /// The backend the last run used (BACKEND_GPU or BACKEND_CPU; its renderer and
  /// platform: GetLastRenderer, GetLastPlatform), its rendering rounds (summed over the
  /// queries), and the faces the exact search visited.
  vtkGetMacro(LastBackend, int);
  vtkGetMacro(LastPasses, vtkTypeInt64);
  vtkGetMacro(LastFacesVisited, vtkTypeInt64);

protected:
  vtkConvexQueryAlgorithm() = default;
  ~vtkConvexQueryAlgorithm() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The pieces (solids) whole on every input port, the queries' port excepted: in a
  /// distributed run each rank takes its own piece of the queries (IsQueryPort).
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Whether input `port` holds query points, split across the ranks of a distributed run.
  virtual bool IsQueryPort(int /*port*/) { return false; }

  /// Checks the properties before a run; reports the first invalid one and returns false.
  virtual bool CheckProperties();

#ifndef __VTK_WRAP__
  /// Resolves Backend for `run` (FilterRun::ResolveBackend) and sets LastBackend; false,
  /// with the error reported, when the GPU is asked for and there is none.
  bool ChooseBackend(vtkdf::FilterRun& run);

  /// The pieces of `input` on `port` (checked, or replaced by their hulls with a
  /// warning); false with the error reported. `solid` ("P", "Q") names the input in the
  /// messages of a filter that takes two. Collective in a distributed run: a mesh that
  /// differs between the ranks (partitioned upstream) is an error.
  bool ReadPieces(vtkDataObject* input,
    const char* solid,
    int port,
    vtkdf::ConvexPieceInput& pieces);
#endif

  std::string PieceArray;
  bool UseConvexHulls = false;
  int Backend = BACKEND_AUTO;
  int ViewResolution = 256;
  bool Certify = true;
  int LastBackend = BACKEND_CPU;
  vtkTypeInt64 LastPasses = 0;
  vtkTypeInt64 LastFacesVisited = 0;

private:
  vtkConvexQueryAlgorithm(const vtkConvexQueryAlgorithm&) = delete;
  void operator=(const vtkConvexQueryAlgorithm&) = delete;
};

#endif
