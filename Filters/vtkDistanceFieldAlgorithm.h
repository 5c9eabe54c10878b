/**
 * @class   vtkDistanceFieldAlgorithm
 * @brief   Base of the filters that sample a field of a vtkPolyData on a vtkImageData.
 *
 * Holds what every such filter shares: the output grid (the default grid of
 * docs/grid.md from Resolution and Padding, or an explicit origin, spacing and
 * dimensions), the Backend (Auto, GPU, CPU) and the memory limit checked before
 * allocating; what the last run used comes from vtkDistanceFieldImageAlgorithm, which
 * runs each request. Subclasses are adapters: their Execute takes the whole mesh and the
 * grid (OpenMeshRun), turns the input into the cores' types (ReadMesh), resolves the
 * Backend once (FilterRun::ResolveBackend), hands their arrays to one core entry point
 * with the run's progress and abort hooks (FilterRun::MakeExecution), and reports.
 *
 * The output honours UPDATE_EXTENT: a requested sub-extent is computed alone.
 *
 * Properties are not clamped when set: an invalid value (a NaN origin, a Resolution
 * below 2, an unknown enum) is reported by name when the filter runs. Every failure,
 * an allocation that fails included, is a vtkErrorMacro (so an ErrorEvent), a
 * non-zero GetErrorCode() and empty outputs; nothing is thrown to the caller.
 */
#ifndef vtkDistanceFieldAlgorithm_h
#define vtkDistanceFieldAlgorithm_h

#include "vtkDistanceFieldImageAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkSmartPointer.h"         // For the whole mesh

#include <string> // For the renderer string
#include <vector> // For the whole mesh's cell ids

class vtkImageData;
#ifndef __VTK_WRAP__
namespace vtkdf
{
class EnumTable;
struct IndexBox;
struct MeshInput;
struct SampleGrid;
}
#endif
class vtkPolyData;

class VTKDISTANCEFIELDS_EXPORT vtkDistanceFieldAlgorithm : public vtkDistanceFieldImageAlgorithm
{
public:
  vtkTypeMacro(vtkDistanceFieldAlgorithm, vtkDistanceFieldImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Where a filter runs (the values of vtkdf::BackendChoice, Common/BackendPolicy.h).
  enum BackendType
  {
    BACKEND_AUTO = 0, ///< the faster backend as measured: the CPU (docs/benchmarks.md)
    BACKEND_GPU = 1,  ///< the GPU, even a software rasterizer; an error when there is none
    BACKEND_CPU = 2   ///< vtkSMPTools on the CPU
  };
  vtkSetMacro(Backend, int);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToGPU() { this->SetBackend(BACKEND_GPU); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }

  ///@{
  /// Default grid: Resolution samples along the longest side of the input's bounds
  /// padded by Padding times that side on every side (defaults 64 and 0.1). Resolution
  /// must be at least 2 and Padding finite and >= 0.
  vtkSetMacro(Resolution, int);
  vtkGetMacro(Resolution, int);
  vtkSetMacro(Padding, double);
  vtkGetMacro(Padding, double);
  ///@}

  ///@{
  /// Explicit grid, used when ExplicitGrid is on (spacing may differ per axis): a finite
  /// origin, finite positive spacing, dimensions >= 1.
  vtkSetMacro(ExplicitGrid, bool);
  vtkGetMacro(ExplicitGrid, bool);
  vtkBooleanMacro(ExplicitGrid, bool);
  vtkSetVector3Macro(GridOrigin, double);
  vtkGetVector3Macro(GridOrigin, double);
  vtkSetVector3Macro(GridSpacing, double);
  vtkGetVector3Macro(GridSpacing, double);
  vtkSetVector3Macro(GridDimensions, int);
  vtkGetVector3Macro(GridDimensions, int);
  ///@}

  ///@{
  /// Largest number of bytes the output arrays and work buffers may take; 0 (the
  /// default) means half of the physical memory. Whatever it says, the limit is never
  /// above what the process can still get: its address-space limit (RLIMIT_AS, as set by
  /// `ulimit -v`) and its cgroup's memory limit, less what is in use. Larger grids fail
  /// before allocating.
  vtkSetMacro(MemoryLimit, double);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  /// The default grid for these bounds (xmin, xmax, ...), as origin, spacing, dimensions.
  static void ComputeDefaultGrid(const double bounds[6],
    int resolution,
    double padding,
    double origin[3],
    double spacing[3],
    int dimensions[3]);

protected:
  vtkDistanceFieldAlgorithm();
  ~vtkDistanceFieldAlgorithm() override = default;

  /// Checks the properties before a run; reports the first invalid one by name (with
  /// vtkErrorMacro) and returns false. Subclasses add their own and call this one.
  virtual bool CheckProperties();

#ifndef __VTK_WRAP__
  /// Whether an enumeration property holds one of its table's values
  /// (vtkDistanceFieldEnums.h); if not, reports the values it may take.
  bool CheckEnum(int value, const vtkdf::EnumTable& table);
#endif

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Bounds of the points that the cells of `mesh` use (the grid convention ignores
  /// unused points), computed once per version of the mesh: RequestInformation needs them
  /// for the default grid, RequestData finds them there. False, with `error` saying why,
  /// when a cell refers to a point that does not exist, a used point has a NaN or
  /// infinite coordinate, or no cell uses any point.
  bool MeshBounds(vtkPolyData* mesh, double bounds[6], std::string& error);

  /// Replaces a mesh input (`mesh`, this rank's piece) by the whole mesh every rank must
  /// work on: the input itself, or, when the ranks of a distributed run hold different
  /// pieces or the mesh carries global ids, the gathered mesh in global-id order
  /// (vtkDistanceFieldPartitions.h). Computed once per version of the input; collective
  /// in a distributed run (RequestInformation calls it on every rank). False, with the
  /// error reported, when a partitioned mesh has no global ids; a null mesh stays null.
  bool InputMesh(vtkPolyData*& mesh);

  /// Why this filter cannot take a point cloud (a mesh with points and no cells), as the
  /// end of a sentence that starts "The input has N points but no polygons: "; "" when
  /// it takes each point as a point site, as if it were a vertex cell of the point's id
  /// (InputMesh then hands on such a mesh, made once per version of the input).
  virtual std::string PointCloudRefusal();

#ifndef __VTK_WRAP__
  /// The opening of a mesh filter's Execute: `mesh`, the whole mesh of input port 0
  /// (gathered in a distributed run, InputMesh), and the output grid with the extent
  /// requested of it. Done when there is something to compute; Empty, with a warning,
  /// for an empty mesh or extent; Failed with the error reported.
  vtkdf::RunStatus OpenMeshRun(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run,
    vtkPolyData*& mesh,
    vtkdf::SampleGrid& grid,
    vtkdf::IndexBox& extent);

  /// `input` as the cores take it (MeshInput, world coordinates, with its bounds) for
  /// fields on `grid`; cells it cannot use are reported in a warning. False, with the
  /// error reported, on invalid input.
  bool ReadMesh(vtkPolyData* input, const vtkdf::SampleGrid& grid, vtkdf::MeshInput& mesh);

#endif

  /// Filters that also take a vtkImageData (a field or masks on a grid) set this; the
  /// output then has the image's grid, and the whole image is requested.
  bool AcceptsImageInput = false;
  /// Whether a sub-extent can be computed alone (else the whole grid is produced).
  bool ProducesSubExtents = true;

  /// The memory limit in bytes (resolving 0 to half the physical memory, and capped by
  /// what RLIMIT_AS and the cgroup leave); `source`, if given, names what set it.
  double EffectiveMemoryLimit(std::string* source = nullptr) const;

#ifndef __VTK_WRAP__
  /// Whether `bytes` fit in the memory limit and the grid's samples in vtkIdType; if
  /// not, reports the error (before anything is allocated) and returns false.
  bool CheckMemory(double bytes, const vtkdf::IndexBox& grid);

  /// The output grid of RequestInformation and the extent requested of it (false when
  /// that extent is empty).
  static bool GetOutputGrid(vtkInformation* outInfo,
    vtkdf::SampleGrid& grid,
    vtkdf::IndexBox& extent);

  /// Gives `output` that extent, origin and spacing.
  static void SetOutputExtent(vtkImageData* output,
    const vtkdf::SampleGrid& grid,
    const vtkdf::IndexBox& extent);

  /// The grid of an image (its extent as Whole); false when it is empty.
  static bool GetImageGrid(vtkImageData* image, vtkdf::SampleGrid& grid);
  /// For an image input that decides each output voxel from the voxels within `layers`
  /// of it: asks it for the requested piece grown by `layers` (all of it when `layers`
  /// < 0): as piece 0 of 1 with that extent, or, in a request by pieces, as this rank's
  /// piece with `layers` ghost levels (the same extent).
  static void RequestGrownImage(vtkInformation* inInfo, vtkInformation* outInfo, int layers);
#endif

  int Backend = BACKEND_AUTO;
  int Resolution = 64;
  double Padding = 0.1;
  bool ExplicitGrid = false;
  double GridOrigin[3] = { 0, 0, 0 };
  double GridSpacing[3] = { 1, 1, 1 };
  int GridDimensions[3] = { 64, 64, 64 };
  double MemoryLimit = 0;

private:
  // MeshBounds' last answer, and what it was for.
  vtkPolyData* BoundsMesh = nullptr;
  vtkMTimeType BoundsTime = 0;
  bool BoundsValid = false;
  // InputMesh's result for WholeInput at WholeInputTime.
  vtkPolyData* WholeInput = nullptr;
  vtkMTimeType WholeInputTime = 0;
  vtkSmartPointer<vtkPolyData> WholeMesh;
  std::vector<vtkIdType> WholeCellIds; // global cell ids of WholeMesh's cells (or empty)
  int WholeParts = 1;
  std::string WholeError;
  // The point sites of a point cloud (InputMesh), and what they were made of.
  vtkSmartPointer<vtkPolyData> PointSites;
  vtkPolyData* PointSitesInput = nullptr;
  vtkMTimeType PointSitesTime = 0;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  std::string BoundsError;

  vtkDistanceFieldAlgorithm(const vtkDistanceFieldAlgorithm&) = delete;
  void operator=(const vtkDistanceFieldAlgorithm&) = delete;
};

#endif
