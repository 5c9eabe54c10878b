#include "vtkDistanceFieldPolyDataAlgorithm.h"

#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"

#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

vtkTypeBool vtkDistanceFieldPolyDataAlgorithm::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vtkdf::ProcessRequestOrEmpty(
    this,
    request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()),
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); },
    [this](unsigned long code) { this->SetErrorCode(code); });
}

int vtkDistanceFieldPolyDataAlgorithm::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkdf::RunRecord record;
  const int done = vtkdf::RunRequestData(this,
    record,
    [&](vtkdf::FilterRun& run) { return this->Execute(inputVector, outputVector, run); });
  this->LastRenderer = record.Renderer;
  this->LastPlatform = record.Platform;
  this->LastTime = record.Time;
  this->LastStageTimes = record.StageTimes;
  this->LastBackendReason = record.Reason.empty() ? "none" : record.Reason;
  return done;
}

void vtkDistanceFieldPolyDataAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LastRenderer: " << this->LastRenderer << "\n";
  os << indent << "LastPlatform: " << this->LastPlatform << "\n";
  os << indent << "LastTime: " << this->LastTime << "\n";
  os << indent << "LastStageTimes: " << this->LastStageTimes << "\n";
  os << indent << "LastBackendReason: " << this->LastBackendReason << "\n";
}
