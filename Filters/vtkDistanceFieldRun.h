// vtkDistanceFieldRun: the one flow of every filter's RequestData. The module's two
// wrapped bases (vtkDistanceFieldImageAlgorithm, vtkDistanceFieldPolyDataAlgorithm) run
// it; each filter supplies only its Execute, which maps VTK's data onto one core entry
// point and maps the result back. Private to the module (not wrapped).
#ifndef vtkDistanceFieldRun_h
#define vtkDistanceFieldRun_h

#include "vtkDistanceFieldRunRecord.h"

#include "Common/BackendPolicy.h"
#include "Common/Parallel.h"

#include <functional>
#include <string>

class vtkAlgorithm;

namespace vtkdf
{
class HeadlessGL;

/// How a filter's Execute ended.
enum class RunStatus
{
  Done,  ///< the outputs hold the result
  Empty, ///< nothing to compute (an empty input or extent) or aborted: empty outputs
  Failed ///< an error was reported: empty outputs and a non-zero error code
};

/// One run of a filter: its stage timer, the hooks a core runs with (vtkSMPTools, the
/// filter's progress and abort), the backend it resolved to, and the filter's way of
/// reporting an empty result or an error.
class FilterRun
{
public:
  explicit FilterRun(vtkAlgorithm* filter)
    : Filter(filter)
  {
  }

  StageTimer Timer;

  /// The plan for `work` (ChoosePlan, Common/BackendPolicy.h, over this machine's
  /// device) and the GL context of its field (null: the CPU); false, with the error
  /// reported, when the plan puts the field on the GPU and there is none. The record
  /// then says what ran, and why.
  bool Resolve(const WorkDescription& work);
  /// Resolve for a filter whose only choice is its Backend property.
  bool ResolveBackend(int backend);
  const ExecutionPlan& Plan() const { return this->Chosen; }
  HeadlessGL* Context() const { return this->GL; }

  /// The hooks a core runs with: vtkSMPTools, the filter's progress (the core's
  /// fraction mapped onto [from, to]) and, when `abortable`, its abort flag.
  Execution MakeExecution(double from = 0, double to = 1, bool abortable = true);
  /// The filter's progress, between the stages the adapter runs itself.
  void Progress(double fraction) const;
  /// Whether the user asked the filter to abort.
  bool AbortRequested() const;

  /// An empty result: `why`, if not empty, as a warning.
  RunStatus Empty(const std::string& why = std::string()) const;
  /// A failure: `error` as the filter's error.
  RunStatus Fail(const std::string& error) const;

private:
  vtkAlgorithm* Filter;
  ExecutionPlan Chosen;
  HeadlessGL* GL = nullptr;
};

/// Every filter's RequestData: empties the outputs, runs `execute`, and then: on Done,
/// reports progress 1 and fills `record` (time, stage times, backend); on Empty, leaves
/// empty outputs; on Failed returns 0 (ProcessRequestOrEmpty, vtkDistanceFieldExecution.h,
/// then empties the outputs and sets the error code).
int RunRequestData(vtkAlgorithm* filter,
  RunRecord& record,
  const std::function<RunStatus(FilterRun&)>& execute);

} // namespace vtkdf

#endif
