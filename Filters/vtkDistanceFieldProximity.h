/**
 * @class vtkDistanceFieldProximity
 * @brief Collision, separation, penetration and contacts between two deforming meshes.
 *
 * The proximity queries of Sud, Govindaraju, Gayle, Kabul and Manocha, "Interactive 3D
 * distance field computation using linear factorization" (ACM I3D 2006, section 6.2),
 * between model A (input 0) and model B (input 1): triangles, polygons and strips;
 * open, non-manifold and soups allowed.
 *
 * Each model's distance field is evaluated only where the other's surface needs it, in
 * the interaction region (the overlap of the bounding boxes grown by ContactMargin), and
 * every value it reads is exact: the distance of one point to the other model through a
 * bounding-volume hierarchy of its triangles. The grid of the paper survives as the step
 * h of the surface samples: Resolution samples along the region's longest side (or
 * Spacing).
 *
 * Output 0 (vtkPolyData) holds the witnesses as lines, with the cell array `Witness`
 * (0: the closest pair when apart, 1: A's deepest point to B's surface, 2: B's deepest
 * point to A's surface), and the answers as field data:
 * - `Colliding` (0/1), exact: a pair of triangles with a point in common (exact
 *   orientation predicates, grazing contact included), or a point of one model inside
 *   the other by SignMode;
 * - `SeparationDistance` when apart: the exact mesh-to-mesh distance (0 when colliding),
 *   however far apart the models are;
 * - `MaximumPenetrationAB` / `BA`: the largest distance to B's surface over A's
 *   vertices and face samples (a barycentric lattice of step h on each triangle) inside
 *   the region and inside B, each at its exact distance (and swapped), with
 *   `DeepestPointAB` and `ContactNormalAB` (the unit direction from it to its closest
 *   point on B), and BA alike;
 * - `Step`, `InteractionRegion`, `PointQueries` (the exact distances evaluated),
 *   `ReusedTopology` (0: the first frame or new cells; 1: A and 2: B kept their
 *   topology, 3: both). The run's time is GetLastSeconds() (not in the output, which
 *   depends on the inputs alone).
 * Output 1: the contacts, every sample of one model inside the other as a vertex with
 * point arrays `Depth`, `Normal` (the direction to the other's closest point) and
 * `Model` (0: a point of A inside B, 1: of B inside A).
 * Outputs 2 and 3: copies of A and B with the point array `DistanceToOther`, each
 * point's signed distance to the other model (negative inside it; NaN for points no
 * triangle uses).
 *
 * Frame after frame: a new execution with the same cells and moved points (a deforming
 * model) keeps each model's topology (the hierarchy's order, refitted to the new
 * coordinates, and the edges of the pseudonormals) and recomputes only what depends on
 * the coordinates; the answers equal those of a fresh filter on that frame.
 *
 * Relation to vtkPenetrationDepth: that filter gives the true minimum translation that
 * separates two solids made of convex pieces; this one gives, for any two meshes, the
 * maximum penetration of each surface into the other (the paper's estimate, which is not
 * a separating translation) and the contacts.
 *
 * Backend: on the CPU (vtkSMPTools), every exact distance searched when it is needed;
 * on the GPU (a compute shader in the filter's own headless OpenGL 4.5 context), the
 * nearest triangles of all face samples of the triangles meeting the region at once,
 * with the models' topology kept on the GPU between frames and only the coordinates
 * sent; inside-ness, contact and separation stay on the CPU. Both backends search in
 * double precision with the same operations: the answers agree to rounding. Auto is the
 * CPU. In a distributed run (ParaView's MPI
 * engine) every rank must hold both models whole; each rank takes its share of the face
 * samples, and rank 0 gathers the shares and answers, equal bit for bit to one process;
 * the other ranks' outputs are empty. A failure leaves every output empty and a non-zero
 * GetErrorCode().
 */
#ifndef vtkDistanceFieldProximity_h
#define vtkDistanceFieldProximity_h

#include "vtkDistanceFieldPolyDataAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <string> // For std::string

#ifndef __VTK_WRAP__
namespace vtkdf
{
class ProximityDevice;
class ProximityModel;
struct ProximityReport;
}
#endif

class vtkPolyData;

class VTKDISTANCEFIELDS_EXPORT vtkDistanceFieldProximity : public vtkDistanceFieldPolyDataAlgorithm
{
public:
  static vtkDistanceFieldProximity* New();
  vtkTypeMacro(vtkDistanceFieldProximity, vtkDistanceFieldPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The two models: A on input 0, B on input 1.
  void SetModelAConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetModelBConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetModelAData(vtkDataObject* data) { this->SetInputData(0, data); }
  void SetModelBData(vtkDataObject* data) { this->SetInputData(1, data); }

  /// What "inside the other model" means.
  enum SignModeType
  {
    PSEUDO_NORMAL = 1, ///< the angle-weighted pseudonormal at the closest feature
    WINDING_NUMBER = 2 ///< the generalized winding number, |w| > 1/2: right on open meshes
  };
  ///@{
  /// Inside-ness (default WindingNumber; the values of vtkLinearFactorDistanceField's).
  vtkSetMacro(SignMode, int);
  vtkGetMacro(SignMode, int);
  void SetSignModeToPseudoNormal() { this->SetSignMode(PSEUDO_NORMAL); }
  void SetSignModeToWindingNumber() { this->SetSignMode(WINDING_NUMBER); }
  ///@}

  /// Where the searches run (the values of vtkDistanceFieldAlgorithm's Backend).
  enum BackendType
  {
    BACKEND_AUTO = 0, ///< the CPU
    BACKEND_GPU = 1,  ///< the GPU, even a software rasterizer; an error when there is none
    BACKEND_CPU = 2   ///< the CPU
  };
  ///@{
  /// Backend (default Auto).
  vtkSetMacro(Backend, int);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToGPU() { this->SetBackend(BACKEND_GPU); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }
  ///@}

  ///@{
  /// Samples along the interaction region's longest side (default 64, 1 to 65536): the
  /// face samples' step h is that side over Resolution.
  vtkSetMacro(Resolution, int);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /// The face samples' step h itself (default 0: from Resolution).
  vtkSetMacro(Spacing, double);
  vtkGetMacro(Spacing, double);
  ///@}

  ///@{
  /// How far each bounding box grows on every side to make the interaction region
  /// (default 0, at least 0).
  vtkSetMacro(ContactMargin, double);
  vtkGetMacro(ContactMargin, double);
  ///@}

  ///@{
  /// Whether output 1 lists every sample inside the other model (default on); off, only
  /// the deepest are found.
  vtkSetMacro(ContactPoints, bool);
  vtkGetMacro(ContactPoints, bool);
  vtkBooleanMacro(ContactPoints, bool);
  ///@}

  ///@{
  /// The most face samples a run may take (default 50,000,000): a step far below the
  /// triangles' size is an error, not an endless run.
  vtkSetMacro(MaximumSamples, vtkTypeInt64);
  vtkGetMacro(MaximumSamples, vtkTypeInt64);
  ///@}

  ///@{
  /// The last run's answers.
  vtkGetMacro(LastColliding, bool);
  vtkGetMacro(LastSeparationDistance, double);
  vtkGetMacro(LastPenetrationAB, double);
  vtkGetMacro(LastPenetrationBA, double);
  vtkGetMacro(LastStep, double);
  vtkGetMacro(LastPointQueries, vtkTypeInt64);
  /// 1 when A kept its topology from the previous run, 2 when B did, 3 both.
  vtkGetMacro(LastReusedTopology, int);
  vtkGetMacro(LastSeconds, double);
  /// "gpu" or "cpu": where the last run searched.
  const char* GetLastBackend() const { return this->LastBackend.c_str(); }
  /// On the GPU: the bytes the last run sent there (a deforming model whose topology the
  /// GPU holds sends only its coordinates) and read back.
  vtkGetMacro(LastBytesToDevice, vtkTypeInt64);
  vtkGetMacro(LastBytesFromDevice, vtkTypeInt64);
  ///@}

protected:
  vtkDistanceFieldProximity();
  ~vtkDistanceFieldProximity() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif

  int Backend = BACKEND_AUTO;
  int SignMode = WINDING_NUMBER;
  int Resolution = 64;
  double Spacing = 0;
  double ContactMargin = 0;
  bool ContactPoints = true;
  vtkTypeInt64 MaximumSamples = 50000000;

  bool LastColliding = false;
  double LastSeparationDistance = 0;
  double LastPenetrationAB = 0;
  double LastPenetrationBA = 0;
  double LastStep = 0;
  vtkTypeInt64 LastPointQueries = 0;
  int LastReusedTopology = 0;
  double LastSeconds = 0;
  vtkTypeInt64 LastBytesToDevice = 0;
  vtkTypeInt64 LastBytesFromDevice = 0;

private:
  vtkDistanceFieldProximity(const vtkDistanceFieldProximity&) = delete;
  void operator=(const vtkDistanceFieldProximity&) = delete;

#ifndef __VTK_WRAP__
  bool CheckProperties();
  bool LoadModel(vtkPolyData* input, int port, vtkdf::ProximityModel& model);
  /// A distributed run's answer: every rank's share of `report` gathered on rank 0 and
  /// merged there into `report`. Done on rank 0 with the answer; Empty on the other
  /// ranks; Failed (reported) when a share is missing.
  vtkdf::RunStatus GatherShares(bool computed,
    vtkdf::ProximityReport& report,
    vtkdf::FilterRun& run);
  /// The Last* reports and the four outputs from `report`.
  void WriteOutputs(const vtkdf::ProximityReport& report,
    vtkPolyData* const inputs[2],
    vtkInformationVector* outputVector);
  void WriteAnswers(const vtkdf::ProximityReport& report, vtkPolyData* output) const;
  void WriteContacts(const vtkdf::ProximityReport& report, vtkPolyData* output) const;

  // The models kept between runs: a deforming model reuses its topology.
  std::unique_ptr<vtkdf::ProximityModel> ModelA, ModelB;
  // The GPU's buffers and program, kept between runs on the GPU.
  std::unique_ptr<vtkdf::ProximityDevice> Device;
  std::string LastBackend = "none";
#endif
};

#endif
