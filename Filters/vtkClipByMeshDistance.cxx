#include "vtkClipByMeshDistance.h"

#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMeshDistanceFilter.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTableBasedClipDataSet.h"
#include "vtkUnstructuredGrid.h"

#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

#include <cctype>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkClipByMeshDistance);

namespace
{
/// What an inner filter reports, made this filter's own: its last error's text (VTK does
/// not print an error that an observer takes), and its progress mapped onto this run's
/// first part, with this filter's abort passed on to it.
class InnerFilterObserver : public vtkCommand
{
public:
  static InnerFilterObserver* New() { return new InnerFilterObserver; }
  void Execute(vtkObject* caller, unsigned long event, void* data) override
  {
    if (event == vtkCommand::ErrorEvent && data && this->Error.empty())
    {
      // The filter's own error; its executive's "returned failure" follows.
      // "ERROR: In FILE, line N\nCLASS (ADDRESS): TEXT": the text alone.
      const std::string text = static_cast<const char*>(data);
      const size_t at = text.find("): ");
      this->Error = at == std::string::npos ? text : text.substr(at + 3);
      while (!this->Error.empty() && std::isspace(static_cast<unsigned char>(this->Error.back())))
      {
        this->Error.pop_back();
      }
    }
    else if (event == vtkCommand::ProgressEvent && data && this->Run)
    {
      this->Run->Progress(this->To * *static_cast<double*>(data));
      if (this->Run->AbortRequested())
      {
        vtkAlgorithm::SafeDownCast(caller)->SetAbortExecute(1);
      }
    }
  }
  std::string Error;
  vtkdf::FilterRun* Run = nullptr;
  double To = 1;
};
} // namespace

vtkClipByMeshDistance::vtkClipByMeshDistance()
{
  this->SetNumberOfInputPorts(2);
  this->Distances->ComputeClosestPointOff();
  this->Distances->ComputeClosestCellIdOff();
  this->Distances->ComputeBarycentricOff();
  this->Distances->ComputeGradientOff();
}

vtkClipByMeshDistance::~vtkClipByMeshDistance() = default;

bool vtkClipByMeshDistance::GetLastBuiltHierarchy() const
{
  return this->Distances->GetLastBuiltHierarchy();
}

int vtkClipByMeshDistance::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkDataSet" : "vtkPolyData");
  return 1;
}

bool vtkClipByMeshDistance::CheckProperties()
{
  std::string error;
  if (!vtkdf::enums::LinearFactorSign.Check(this->SignMode, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  if (!std::isfinite(this->Value))
  {
    vtkErrorMacro("Value must be finite; it is " << this->Value << ".");
    return false;
  }
  return true;
}

int vtkClipByMeshDistance::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return this->CheckProperties() ? 1 : 0;
}

int vtkClipByMeshDistance::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // The surface whole, whatever piece of the dataset is asked for (each rank clips its
  // own piece).
  if (vtkInformation* in = inputVector[1]->GetInformationObject(0))
  {
    vtkdf::RequestWholeInput(in);
  }
  return 1;
}

vtkdf::RunStatus vtkClipByMeshDistance::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkPolyData* surface = vtkPolyData::GetData(inputVector[1], 0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  if (!input || !output)
  {
    return run.Fail("No dataset to clip (input 0).");
  }
  if (!surface)
  {
    return run.Fail("No surface to measure distances to (input 1).");
  }
  if (!this->CheckProperties())
  {
    return vtkdf::RunStatus::Failed;
  }

  // The distances at the dataset's points (a shallow copy: the pipeline's input is not
  // connected to the inner filter).
  vtkSmartPointer<vtkDataSet> points;
  points.TakeReference(input->NewInstance());
  points->ShallowCopy(input);
  vtkNew<InnerFilterObserver> observer;
  observer->Run = &run;
  observer->To = 0.8;
  const unsigned long errorTag = this->Distances->AddObserver(vtkCommand::ErrorEvent, observer);
  const unsigned long progressTag =
    this->Distances->AddObserver(vtkCommand::ProgressEvent, observer);
  vtkExecutive* executive = this->Distances->GetExecutive();
  const unsigned long executiveTag = executive->AddObserver(vtkCommand::ErrorEvent, observer);
  this->Distances->SetSignMode(this->SignMode);
  this->Distances->SetInputData(0, points);
  this->Distances->SetSurfaceData(surface);
  this->Distances->Update();
  this->Distances->RemoveObserver(errorTag);
  this->Distances->RemoveObserver(progressTag);
  executive->RemoveObserver(executiveTag);
  vtkSmartPointer<vtkDataSet> measured = this->Distances->GetOutput();
  // The inner filter lets go of the inputs: the pipeline owns them.
  this->Distances->RemoveAllInputs();
  if (run.AbortRequested())
  {
    return run.Empty();
  }
  if (this->Distances->GetErrorCode() != 0 || !measured)
  {
    return run.Fail(observer->Error.empty() ? "The distances failed." : observer->Error);
  }
  run.Timer.End("distances");
  run.Progress(0.8);

  // The input's field data, not the distances' statistics.
  vtkSmartPointer<vtkDataSet> toClip;
  toClip.TakeReference(measured->NewInstance());
  toClip->ShallowCopy(measured);
  toClip->SetFieldData(input->GetFieldData());
  vtkNew<vtkTableBasedClipDataSet> clip;
  clip->SetInputData(toClip);
  clip->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Distance");
  clip->SetValue(this->Value);
  clip->SetInsideOut(this->InsideOut);
  // The cut's points where the exact distances put them, whatever the input's precision.
  clip->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  clip->Update();
  output->ShallowCopy(clip->GetOutput());
  run.Timer.End("clip");
  return vtkdf::RunStatus::Done;
}

void vtkClipByMeshDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SignMode: " << vtkdf::enums::LinearFactorSign.Name(this->SignMode) << "\n";
  os << indent << "Value: " << this->Value << "\n";
  os << indent << "InsideOut: " << this->InsideOut << "\n";
}
