#include "vtkDistanceFieldRun.h"

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkSetGet.h"

#include "GL/HeadlessGL.h"
#include "vtkDistanceFieldExecution.h"

#include <sstream>

namespace vtkdf
{

bool FilterRun::Resolve(const WorkDescription& work)
{
  this->Chosen = ChoosePlan(work, DescribeDevice());
  std::string error;
  if (!FieldContext(this->Chosen, this->GL, error))
  {
    this->Fail(error);
    return false;
  }
  return true;
}

bool FilterRun::ResolveBackend(int backend)
{
  WorkDescription work;
  work.Backend = static_cast<BackendChoice>(backend);
  return this->Resolve(work);
}

Execution FilterRun::MakeExecution(double from, double to, bool abortable)
{
  Execution execution;
  execution.For = SMPFor;
  execution.Stages = &this->Timer;
  vtkAlgorithm* filter = this->Filter;
  execution.Progress = [filter, from, to, abortable](double fraction)
  {
    filter->UpdateProgress(from + (to - from) * fraction);
    return !(abortable && filter->GetAbortExecute());
  };
  return execution;
}

void FilterRun::Progress(double fraction) const
{
  this->Filter->UpdateProgress(fraction);
}

bool FilterRun::AbortRequested() const
{
  return this->Filter->GetAbortExecute() != 0;
}

RunStatus FilterRun::Empty(const std::string& why) const
{
  if (!why.empty())
  {
    vtkWarningWithObjectMacro(this->Filter, << why);
  }
  return RunStatus::Empty;
}

RunStatus FilterRun::Fail(const std::string& error) const
{
  vtkErrorWithObjectMacro(this->Filter, << error);
  return RunStatus::Failed;
}

int RunRequestData(vtkAlgorithm* filter,
  RunRecord& record,
  const std::function<RunStatus(FilterRun&)>& execute)
{
  auto emptyOutputs = [filter]
  {
    for (int port = 0; port < filter->GetNumberOfOutputPorts(); ++port)
    {
      if (vtkDataObject* output = filter->GetOutputDataObject(port))
      {
        output->Initialize();
      }
    }
  };
  emptyOutputs();
  record = RunRecord();
  FilterRun run(filter);
  const RunStatus status = execute(run);
  if (status == RunStatus::Failed)
  {
    return 0;
  }
  if (status == RunStatus::Empty)
  {
    emptyOutputs();
    return 1;
  }
  HeadlessGL* gl = run.Context();
  record.Time = run.Timer.Elapsed();
  std::ostringstream text;
  for (const auto& stage : run.Timer.Times())
  {
    text << (text.tellp() > 0 ? "," : "") << stage.first << ":" << stage.second;
  }
  record.StageTimes = text.str();
  const int64_t peak = run.Timer.PeakMemory();
  record.PeakMemory = peak < 0 ? -1.0 : peak / 1048576.0;
  record.Backend = gl ? "gpu" : "cpu";
  record.Renderer = gl ? gl->Renderer() : "cpu";
  record.Platform = gl ? gl->Platform() : "cpu";
  record.Reason = run.Plan().Reason.empty() ? "none" : run.Plan().Reason;
  filter->UpdateProgress(1.0);
  return 1;
}

} // namespace vtkdf
