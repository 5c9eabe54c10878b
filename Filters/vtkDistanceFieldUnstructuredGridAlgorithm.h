/**
 * @class   vtkDistanceFieldUnstructuredGridAlgorithm
 * @brief   Base of the module's filters whose output is a vtkUnstructuredGrid: the run
 * that every filter shares.
 *
 * Its subclass is vtkClipByMeshDistance. This class runs each request as the module's other
 * bases do (vtkDistanceFieldRun.h): ProcessRequest catches every exception (std::bad_alloc
 * as out of memory) and leaves an empty output and a non-zero GetErrorCode() after any
 * failure; RequestData empties the output, calls the subclass's Execute (which maps the
 * inputs onto one core entry point and the result back), reports progress and honours
 * abort, and records what the run used and took (GetLastTime() and friends).
 *
 * VTK's wrappers follow only the vtkObjectBase chain, so the module has one such base
 * per output type rather than a mix-in; all of them call the same functions.
 */
#ifndef vtkDistanceFieldUnstructuredGridAlgorithm_h
#define vtkDistanceFieldUnstructuredGridAlgorithm_h

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkUnstructuredGridAlgorithm.h"

#ifndef __VTK_WRAP__
#include "vtkDistanceFieldRunRecord.h" // For the record

namespace vtkdf
{
class FilterRun;
enum class RunStatus;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkDistanceFieldUnstructuredGridAlgorithm
  : public vtkUnstructuredGridAlgorithm
{
public:
  vtkTypeMacro(vtkDistanceFieldUnstructuredGridAlgorithm, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// GL_RENDERER of the last GPU run, "cpu" after a CPU run, "none" before a complete one.
  const char* GetLastRenderer() const { return this->Record.Renderer.c_str(); }
  /// How the last GPU run got its context ("EGL device", "EGL surfaceless", "OSMesa"),
  /// "cpu" after a CPU run, "none" before a complete one.
  const char* GetLastPlatform() const { return this->Record.Platform.c_str(); }
  /// Why the last complete run ran where it did (the Backend property, Auto's rule).
  const char* GetLastBackendReason() const { return this->Record.Reason.c_str(); }
  /// Seconds the last complete run spent computing (input conversion and arrays
  /// included, no I/O).
  double GetLastTime() const { return this->Record.Time; }
  /// The last run's peak memory above what the process held when it began, in MiB
  /// (the process's resident memory: Filters/Core/Common/ProcessMemory.h); -1 unknown.
  double GetLastPeakMemory() const { return this->Record.PeakMemory; }
  /// Seconds per stage of the last complete run, as "name:seconds,name:seconds,..." (the
  /// stages are the filter's own, e.g. sites, culling, scan, finalize).
  const char* GetLastStageTimes() const { return this->Record.StageTimes.c_str(); }

  /// Runs the request; a failure (a request returning 0, or an exception such as
  /// std::bad_alloc, which is caught here) leaves a non-zero error code and empty outputs.
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  vtkDistanceFieldUnstructuredGridAlgorithm() = default;
  ~vtkDistanceFieldUnstructuredGridAlgorithm() override = default;

  /// The shared run around Execute.
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

#ifndef __VTK_WRAP__
  /// The filter's own work: the inputs onto one core entry point, its result onto the
  /// outputs (which RequestData has emptied); errors and empty results through `run`.
  virtual vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) = 0;
#endif

#ifndef __VTK_WRAP__
  vtkdf::RunRecord Record;
#endif

private:
  vtkDistanceFieldUnstructuredGridAlgorithm(
    const vtkDistanceFieldUnstructuredGridAlgorithm&) = delete;
  void operator=(const vtkDistanceFieldUnstructuredGridAlgorithm&) = delete;
};

#endif
