#include "vtkMeshHausdorffDistance.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "LinearFactor/HausdorffDistance.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldMeshInput.h"
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

#include <cmath>

vtkStandardNewMacro(vtkMeshHausdorffDistance);

namespace
{
/// `mesh` as the cores take it, in world coordinates; false with `error` otherwise.
bool ToMeshInput(vtkPolyData* mesh,
  vtkdf::MeshInput& input,
  std::string& warning,
  std::string& error)
{
  double bounds[6];
  vtkdf::MeshCopyReport report;
  if (!vtkdf::UsedPointBounds(mesh, bounds, error) ||
    !vtkdf::CopyMesh(mesh, bounds, vtkdf::GridFrame(), input, report, error))
  {
    return false;
  }
  warning = report.Warnings();
  return true;
}

/// A field data array of `tuples` tuples of `components` values.
void AddTuples(vtkFieldData* data,
  const char* name,
  int tuples,
  int components,
  std::initializer_list<double> values)
{
  auto array = vtkdf::NewArray<vtkDoubleArray>(name, tuples, components);
  int i = 0;
  for (const double v : values)
  {
    array->SetValue(i++, v);
  }
  data->AddArray(array);
}
} // namespace

vtkMeshHausdorffDistance::vtkMeshHausdorffDistance()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

int vtkMeshHausdorffDistance::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

bool vtkMeshHausdorffDistance::CheckProperties()
{
  if (!(this->RelativeError > 0 && this->RelativeError <= 1))
  {
    vtkErrorMacro(
      "RelativeError must be positive and at most 1; it is " << this->RelativeError << ".");
    return false;
  }
  return true;
}

int vtkMeshHausdorffDistance::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return this->CheckProperties() ? 1 : 0;
}

int vtkMeshHausdorffDistance::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Both meshes whole: the distance of a piece of one depends on all of the other.
  vtkdf::RequestWholeInputs(inputVector, 2);
  return 1;
}

vtkdf::RunStatus vtkMeshHausdorffDistance::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkPolyData* meshA = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* meshB = vtkPolyData::GetData(inputVector[1], 0);
  vtkPolyData* outA = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* outB = vtkPolyData::GetData(outputVector, 1);
  if (!meshA)
  {
    return run.Fail("No mesh A (input 0).");
  }
  if (!meshB)
  {
    return run.Fail("No mesh B (input 1).");
  }
  if (!this->CheckProperties())
  {
    return vtkdf::RunStatus::Failed;
  }
  // A distributed run: every rank holds both meshes whole (collective); rank 0 answers,
  // so that the ranks' outputs do not repeat the meshes.
  vtkPolyData* inputs[2] = { meshA, meshB };
  std::string error, warning;
  if (!vtkdf::BothMeshesOnEveryRank(inputs, "Mesh", error))
  {
    return run.Fail(error);
  }
  if (!vtkdf::IsFirstRank())
  {
    return run.Empty();
  }
  vtkdf::MeshInput a, b;
  if (!ToMeshInput(meshA, a, warning, error))
  {
    return run.Fail("Mesh A (input 0): " + error + ".");
  }
  if (!warning.empty())
  {
    vtkWarningMacro("Mesh A (input 0): " << warning);
  }
  if (!ToMeshInput(meshB, b, warning, error))
  {
    return run.Fail("Mesh B (input 1): " + error + ".");
  }
  if (!warning.empty())
  {
    vtkWarningMacro("Mesh B (input 1): " << warning);
  }
  run.Timer.End("input");

  auto distanceA = vtkdf::NewArray<vtkDoubleArray>("Distance", meshA->GetNumberOfPoints(), 1);
  auto distanceB = vtkdf::NewArray<vtkDoubleArray>("Distance", meshB->GetNumberOfPoints(), 1);
  vtkdf::HausdorffOptions options;
  options.RelativeError = this->RelativeError;
  options.DistanceA = distanceA->GetPointer(0);
  options.DistanceB = distanceB->GetPointer(0);
  vtkdf::HausdorffResult result;
  if (!vtkdf::ComputeHausdorffDistance(
        std::move(a), std::move(b), options, run.MakeExecution(0.05, 1), result, error))
  {
    return run.Fail(error + ".");
  }
  if (result.Aborted)
  {
    return run.Empty();
  }

  const vtkdf::OneSidedHausdorff& ab = result.AToB;
  const vtkdf::OneSidedHausdorff& ba = result.BToA;
  const bool fromB = ba.Distance > ab.Distance;
  const vtkdf::OneSidedHausdorff& larger = fromB ? ba : ab;
  this->HausdorffDistance = larger.Distance;
  this->HausdorffBounds[0] = result.Lower;
  this->HausdorffBounds[1] = result.Upper;
  this->DistanceAToB = ab.Distance;
  this->DistanceBToA = ba.Distance;
  this->LastPieces = ab.Pieces + ba.Pieces;
  this->LastRounds = std::max(ab.Rounds, ba.Rounds);
  this->LastEvaluations = ab.Evaluations + ba.Evaluations;

  outA->ShallowCopy(meshA);
  outB->ShallowCopy(meshB);
  outA->GetPointData()->AddArray(distanceA);
  outA->GetPointData()->SetActiveScalars("Distance");
  outB->GetPointData()->AddArray(distanceB);
  outB->GetPointData()->SetActiveScalars("Distance");
  for (vtkPolyData* out : { outA, outB })
  {
    vtkFieldData* fd = out->GetFieldData();
    AddTuples(fd, "HausdorffDistance", 1, 1, { larger.Distance });
    AddTuples(fd, "HausdorffBounds", 1, 2, { result.Lower, result.Upper });
    AddTuples(fd, "OneSidedHausdorffDistance", 1, 2, { ab.Distance, ba.Distance });
    AddTuples(fd, "OneSidedHausdorffBounds", 2, 2, { ab.Lower, ab.Upper, ba.Lower, ba.Upper });
    AddTuples(fd,
      "HausdorffPoints",
      2,
      3,
      { larger.From[0], larger.From[1], larger.From[2], larger.To[0], larger.To[1], larger.To[2] });
    auto source = vtkdf::NewArray<vtkIntArray>("HausdorffSource", 1);
    source->SetValue(0, fromB ? 1 : 0);
    fd->AddArray(source);
  }
  return vtkdf::RunStatus::Done;
}

void vtkMeshHausdorffDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RelativeError: " << this->RelativeError << "\n";
  os << indent << "HausdorffDistance: " << this->HausdorffDistance << "\n";
  os << indent << "HausdorffBounds: " << this->HausdorffBounds[0] << ", "
     << this->HausdorffBounds[1] << "\n";
  os << indent << "DistanceAToB: " << this->DistanceAToB << "\n";
  os << indent << "DistanceBToA: " << this->DistanceBToA << "\n";
  os << indent << "LastPieces: " << this->LastPieces << "\n";
  os << indent << "LastRounds: " << this->LastRounds << "\n";
  os << indent << "LastEvaluations: " << this->LastEvaluations << "\n";
}
