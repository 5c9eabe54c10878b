/**
 * @class   vtkDistanceFieldAlgorithm
 * @brief   Base of the filters that sample a field of a vtkPolyData on a vtkImageData.
 *
 * Holds what every such filter shares: the output grid (the default grid of
 * shared/docs/GRID.md from Resolution and Padding, or an explicit origin, spacing and
 * dimensions), the Backend (Auto, GPU, CPU), the memory limit checked before
 * allocating, and what the last run used (backend, GL renderer, time).
 *
 * The output honours UPDATE_EXTENT: a requested sub-extent is computed alone.
 */
#ifndef vtkDistanceFieldAlgorithm_h
#define vtkDistanceFieldAlgorithm_h

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <string> // For the renderer string

class vtkImageData;
#ifndef __VTK_WRAP__
namespace vtkdf
{
class HeadlessGL;
struct IndexBox;
struct SampleGrid;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkDistanceFieldAlgorithm : public vtkImageAlgorithm
{
public:
  vtkTypeMacro(vtkDistanceFieldAlgorithm, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum BackendType
  {
    BACKEND_AUTO = 0, ///< the GPU when a hardware-accelerated context exists, else the CPU
    BACKEND_GPU = 1,  ///< the GPU, even a software rasterizer; an error when there is none
    BACKEND_CPU = 2   ///< vtkSMPTools on the CPU
  };
  vtkSetClampMacro(Backend, int, BACKEND_AUTO, BACKEND_CPU);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(BACKEND_AUTO); }
  void SetBackendToGPU() { this->SetBackend(BACKEND_GPU); }
  void SetBackendToCPU() { this->SetBackend(BACKEND_CPU); }

  ///@{
  /// Default grid: Resolution samples along the longest side of the input's bounds
  /// padded by Padding times that side on every side (defaults 64 and 0.1).
  vtkSetClampMacro(Resolution, int, 2, VTK_INT_MAX);
  vtkGetMacro(Resolution, int);
  vtkSetClampMacro(Padding, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Padding, double);
  ///@}

  ///@{
  /// Explicit grid, used when ExplicitGrid is on (spacing may differ per axis).
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
  /// default) means half of the physical memory. Larger grids fail before allocating.
  vtkSetClampMacro(MemoryLimit, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  /// What the last run used: "gpu" or "cpu".
  const char* GetLastBackend() const { return this->LastBackend.c_str(); }
  /// GL_RENDERER of the last GPU run, or "cpu".
  const char* GetLastRenderer() const { return this->LastRenderer.c_str(); }
  /// Seconds the last run spent computing (input conversion and arrays included, no I/O).
  vtkGetMacro(LastTime, double);
  /// Seconds per stage of the last run, as "name:seconds,name:seconds,..." (the stages
  /// are the filter's own, e.g. sites, culling, scan, finalize).
  const char* GetLastStageTimes() const { return this->LastStageTimes.c_str(); }

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

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Bounds of the points that the cells use (GRID.md ignores unused points); false
  /// when no cell uses any point.
  static bool CellBounds(vtkDataSet* input, double bounds[6]);

#ifndef __VTK_WRAP__
  /// The GL context to run on (null: the CPU), from Backend; false, with the error
  /// reported, when the GPU is asked for and there is none.
  bool ChooseBackend(vtkdf::HeadlessGL*& gl);

  ///@{
  /// The timing of a run: StartTiming() first in RequestData, EndStage(name) after each
  /// stage (LastStageTimes gets "name:seconds", comma separated), FinishTiming(gl) when
  /// the output is complete (LastTime, and LastBackend/LastRenderer from `gl`, null for
  /// the CPU).
  void StartTiming();
  void EndStage(const char* name);
  void FinishTiming(vtkdf::HeadlessGL* gl);
  ///@}
#endif

  /// Filters that also take a vtkImageData (a field or masks on a grid) set this; the
  /// output then has the image's grid, and the whole image is requested.
  bool AcceptsImageInput = false;
  /// Whether a sub-extent can be computed alone (else the whole grid is produced).
  bool ProducesSubExtents = true;

  /// The memory limit in bytes (resolving 0 to half the physical memory).
  double EffectiveMemoryLimit() const;

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
#endif

  int Backend = BACKEND_AUTO;
  int Resolution = 64;
  double Padding = 0.1;
  bool ExplicitGrid = false;
  double GridOrigin[3] = { 0, 0, 0 };
  double GridSpacing[3] = { 1, 1, 1 };
  int GridDimensions[3] = { 64, 64, 64 };
  double MemoryLimit = 0;

  std::string LastBackend = "none";
  std::string LastRenderer = "none";
  double LastTime = 0;
  std::string LastStageTimes;
  double TimingStart = 0, StageStart = 0; // steady-clock seconds

private:
  vtkDistanceFieldAlgorithm(const vtkDistanceFieldAlgorithm&) = delete;
  void operator=(const vtkDistanceFieldAlgorithm&) = delete;
};

#endif
