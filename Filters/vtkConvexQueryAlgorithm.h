/**
 * @class   vtkConvexQueryAlgorithm
 * @brief   Base of the filters that query unions of convex pieces.
 *
 * Holds what vtkUnionClosestPoint and vtkPenetrationDepth share: how their inputs become
 * convex pieces (PieceArray, UseConvexHulls), where the query runs (Backend) and what the
 * last run used (LastBackend, LastRenderer, LastFacesVisited).
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

#include "vtkDeprecation.h" // For VTK_DEPRECATION
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
  /// bounds each answer in a compute pass, from which the CPU's exact search starts: the
  /// same answers, bit for bit.
  vtkSetMacro(Backend, int);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToGPU() { this->SetBackend(BACKEND_GPU); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }
  ///@}

  ///@{
  /**
   * The settings of the GPU's rendered cube-face views, which the GPU backend no longer
   * renders: a compute pass bounds each answer and every answer is exact, so these do
   * nothing (ViewResolution reads 256, Certify on, LastPasses 0).
   * @deprecated Nothing replaces them: every backend's answer is exact.
   */
  VTK_DEPRECATION("The GPU backend renders no views: ViewResolution does nothing")
  void SetViewResolution(int) {}
  VTK_DEPRECATION("The GPU backend renders no views: ViewResolution does nothing")
  int GetViewResolution() { return 256; }
  VTK_DEPRECATION("Every answer is exact: Certify does nothing")
  void SetCertify(bool) {}
  VTK_DEPRECATION("Every answer is exact: Certify does nothing")
  bool GetCertify() { return true; }
  VTK_DEPRECATION("Every answer is exact: Certify does nothing")
  void CertifyOn() {}
  VTK_DEPRECATION("Every answer is exact: Certify does nothing")
  void CertifyOff() {}
  VTK_DEPRECATION("The GPU backend renders no views: LastPasses is 0")
  vtkTypeInt64 GetLastPasses() { return 0; }
  ///@}

  /// The backend the last run used (BACKEND_GPU or BACKEND_CPU; its renderer and
  /// platform: GetLastRenderer, GetLastPlatform) and the faces the exact search visited
  /// (on the GPU, from its bounds).
  vtkGetMacro(LastBackend, int);
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
  int LastBackend = BACKEND_CPU;
  vtkTypeInt64 LastFacesVisited = 0;

private:
  vtkConvexQueryAlgorithm(const vtkConvexQueryAlgorithm&) = delete;
  void operator=(const vtkConvexQueryAlgorithm&) = delete;
};

#endif
