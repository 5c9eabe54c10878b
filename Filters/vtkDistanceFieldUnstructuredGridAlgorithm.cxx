#include "vtkDistanceFieldUnstructuredGridAlgorithm.h"

#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"

#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

vtkTypeBool vtkDistanceFieldUnstructuredGridAlgorithm::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vtkdf::ProcessRequestOrEmpty(
    this,
    request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()),
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); },
    [this](unsigned long code) { this->SetErrorCode(code); });
}

int vtkDistanceFieldUnstructuredGridAlgorithm::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vtkdf::RunRequestData(this,
    this->Record,
    [&](vtkdf::FilterRun& run) { return this->Execute(inputVector, outputVector, run); });
}

void vtkDistanceFieldUnstructuredGridAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Record.Print(os, indent, false);
}
