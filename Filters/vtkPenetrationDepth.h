/**
 * @class   vtkPenetrationDepth
 * @brief   Penetration depth of two solids made of convex pieces (paper 003).
 *
 * P (input 0) and Q (input 1) are unions of convex pieces, in the forms
 * vtkUnionClosestPoint takes: a vtkPolyData whose connected components (or, with
 * PieceArray, whose cells of one piece id) are the pieces, one closed convex mesh, or a
 * vtkMultiBlockDataSet / vtkPartitionedDataSetCollection / vtkPartitionedDataSet of
 * vtkPolyData, one piece per leaf. The convex decomposition is the user's (robot and CAD
 * collision models come as convex pieces); UseConvexHulls replaces pieces that are not
 * closed and convex by their hulls.
 *
 * The penetration depth is the distance from the origin to the boundary of the
 * Minkowski difference P - Q, the union of the convex sums P_i - Q_j (each the qhull hull
 * of its corners' differences), found by the exact closest-point query of
 * vtkUnionClosestPoint (Algorithm 3.1 of the paper) without building the union. Unlike a
 * per-pair depth (FCL, Bullet, libccd), it is the global one: the deepest pair is only a
 * lower bound. Pairs whose sums cannot reach the answer are skipped before their hulls
 * are built. P and Q are in one frame. Backend, ViewResolution and Certify choose where the
 * query runs, as for vtkUnionClosestPoint: the CPU (exact), or the GPU's six views
 * certified on the CPU (exact) or not (ErrorBound then holds the image-space estimate).
 *
 * Output: vtkPolyData with the minimum translation vector as a line (from the point of Q
 * farthest against Direction, the one that leaves P last, to that point translated), and
 * field data `PenetrationDepth` (0 when P and Q do not intersect), `Direction` (unit:
 * translating Q by PenetrationDepth x Direction separates it from P, up to touching),
 * `Intersecting` (0/1), `ErrorBound` (0: exact), `WitnessPieces` (the pair of pieces, P's
 * then Q's, whose sum holds the answer) and, when P and Q do not intersect,
 * `SeparationDistance` (translating Q by it along Direction brings them into contact).
 */
#ifndef vtkPenetrationDepth_h
#define vtkPenetrationDepth_h

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

class VTKDISTANCEFIELDS_EXPORT vtkPenetrationDepth : public vtkPolyDataAlgorithm
{
public:
  static vtkPenetrationDepth* New();
  vtkTypeMacro(vtkPenetrationDepth, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The two solids: P on port 0, Q on port 1.
  void SetSolidPConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetSolidQConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSolidPData(vtkDataObject* data) { this->SetInputData(0, data); }
  void SetSolidQData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// The name of a cell-data array of piece ids of a vtkPolyData input (either solid):
  /// its pieces are the cells of one id, not its connected components. Empty (default):
  /// connected components.
  vtkSetStdStringFromCharMacro(PieceArray);
  vtkGetCharFromStdStringMacro(PieceArray);
  ///@}

  ///@{
  /// Replace each piece that is not closed and convex by its convex hull (qhull) instead
  /// of refusing it (default off); a warning says how many pieces changed.
  vtkSetMacro(UseConvexHulls, bool);
  vtkGetMacro(UseConvexHulls, bool);
  vtkBooleanMacro(UseConvexHulls, bool);
  ///@}

  enum BackendType
  {
    BACKEND_AUTO = 0, ///< the GPU when a hardware-accelerated context exists, else the CPU
    BACKEND_GPU = 1,  ///< the GPU, even a software rasterizer; an error when there is none
    BACKEND_CPU = 2   ///< exact, on the CPU
  };
  ///@{
  /// Where the union query runs (default Auto).
  vtkSetClampMacro(Backend, int, BACKEND_AUTO, BACKEND_CPU);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToGPU() { this->SetBackend(BACKEND_GPU); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }
  ///@}

  ///@{
  /// GPU: pixels a side of the six views (default 256) and certification (default on).
  vtkSetMacro(ViewResolution, int);
  vtkGetMacro(ViewResolution, int);
  vtkSetMacro(Certify, bool);
  vtkGetMacro(Certify, bool);
  vtkBooleanMacro(Certify, bool);
  ///@}

  ///@{
  /// The last run's answer.
  vtkGetMacro(LastPenetrationDepth, double);
  vtkGetMacro(LastSeparationDistance, double);
  vtkGetVector3Macro(LastDirection, double);
  vtkGetMacro(LastIntersecting, bool);
  vtkGetMacro(LastErrorBound, double);
  ///@}

  /// The backend the last run used (BACKEND_GPU or BACKEND_CPU), its renderer and passes.
  vtkGetMacro(LastBackend, int);
  const char* GetLastRenderer() const { return this->LastRenderer.c_str(); }
  vtkGetMacro(LastPasses, int);

  ///@{
  /// The last run's work: pairs of pieces, those whose sums were built, and the faces
  /// of the sums the query visited.
  vtkGetMacro(LastPairsTotal, vtkTypeInt64);
  vtkGetMacro(LastPairsKept, vtkTypeInt64);
  vtkGetMacro(LastFacesVisited, vtkTypeInt64);
  ///@}

protected:
  vtkPenetrationDepth();
  ~vtkPenetrationDepth() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData's work; 0 on failure.
  int Compute(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  std::string PieceArray;
  bool UseConvexHulls = false;
  double LastPenetrationDepth = 0;
  double LastSeparationDistance = 0;
  double LastDirection[3] = { 0, 0, 0 };
  bool LastIntersecting = false;
  double LastErrorBound = 0;
  int Backend = BACKEND_AUTO;
  int ViewResolution = 256;
  bool Certify = true;
  int LastBackend = BACKEND_CPU;
  std::string LastRenderer;
  int LastPasses = 0;
  vtkTypeInt64 LastPairsTotal = 0;
  vtkTypeInt64 LastPairsKept = 0;
  vtkTypeInt64 LastFacesVisited = 0;

private:
  vtkPenetrationDepth(const vtkPenetrationDepth&) = delete;
  void operator=(const vtkPenetrationDepth&) = delete;
};

#endif
