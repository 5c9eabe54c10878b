#include "vtkDistanceFieldProximity.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "GL/HeadlessGL.h"
#include "Proximity/ProximityQuery.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldMeshInput.h"
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

#include <cmath>

static_assert(vtkdf::SameBackendValues<vtkDistanceFieldProximity>(),
  "Backend values differ from BackendChoice");

vtkStandardNewMacro(vtkDistanceFieldProximity);

vtkDistanceFieldProximity::vtkDistanceFieldProximity()
  : ModelA(new vtkdf::ProximityModel)
  , ModelB(new vtkdf::ProximityModel)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(4);
}

vtkDistanceFieldProximity::~vtkDistanceFieldProximity() = default;

int vtkDistanceFieldProximity::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

bool vtkDistanceFieldProximity::CheckProperties()
{
  std::string error;
  if (!vtkdf::enums::Backend.Check(this->Backend, error) ||
    !vtkdf::enums::ProximitySign.Check(this->SignMode, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  if (this->Resolution < 1 || this->Resolution > 65536)
  {
    vtkErrorMacro("Resolution must be 1 to 65536; it is " << this->Resolution << ".");
    return false;
  }
  if (!(this->Spacing >= 0) || !std::isfinite(this->Spacing))
  {
    vtkErrorMacro(
      "Spacing must be finite and at least 0 (0: from Resolution); it is " << this->Spacing << ".");
    return false;
  }
  if (!(this->ContactMargin >= 0) || !std::isfinite(this->ContactMargin))
  {
    vtkErrorMacro(
      "ContactMargin must be finite and at least 0; it is " << this->ContactMargin << ".");
    return false;
  }
  if (this->MaximumSamples < 1)
  {
    vtkErrorMacro("MaximumSamples must be at least 1; it is " << this->MaximumSamples << ".");
    return false;
  }
  return true;
}

int vtkDistanceFieldProximity::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return this->CheckProperties() ? 1 : 0;
}

int vtkDistanceFieldProximity::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  vtkdf::RequestWholeInputs(inputVector, 2);
  return 1;
}

bool vtkDistanceFieldProximity::LoadModel(vtkPolyData* input,
  int port,
  vtkdf::ProximityModel& model)
{
  const char* name = port == 0 ? "A" : "B";
  std::string error;
  double bounds[6];
  vtkdf::MeshInput mesh;
  vtkdf::MeshCopyReport report;
  // The queries run in world coordinates: the identity frame.
  if (!input || !vtkdf::UsedPointBounds(input, bounds, error) ||
    !vtkdf::CopyMesh(input, bounds, vtkdf::GridFrame(), mesh, report, error))
  {
    vtkErrorMacro("Model " << name << " (input " << port
                           << "): " << (input ? error : std::string("no input")) << ".");
    return false;
  }
  const std::string warning = report.Warnings();
  if (!warning.empty())
  {
    vtkWarningMacro("Model " << name << " (input " << port << "): " << warning);
  }
  const auto rule = this->SignMode == PSEUDO_NORMAL ? vtkdf::InsideRule::PseudoNormal
                                                    : vtkdf::InsideRule::WindingNumber;
  if (!model.Load(mesh, name, rule, error))
  {
    vtkErrorMacro("Model " << name << " (input " << port << "): " << error << ".");
    return false;
  }
  return true;
}

vtkdf::RunStatus vtkDistanceFieldProximity::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkPolyData* a = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* b = vtkPolyData::GetData(inputVector[1]);
  this->LastBackend = "none";
  if (!this->CheckProperties())
  {
    return vtkdf::RunStatus::Failed;
  }
  // A distributed run: every rank holds both models whole (collective); each takes its
  // share of the face samples, and rank 0 puts the shares together and answers.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  const int rank = controller ? controller->GetLocalProcessId() : 0;
  vtkPolyData* inputs[2] = { a, b };
  std::string error;
  if (!vtkdf::BothMeshesOnEveryRank(inputs, "Model", error))
  {
    return run.Fail(error);
  }
  if (!this->LoadModel(a, 0, *this->ModelA) || !this->LoadModel(b, 1, *this->ModelB))
  {
    return vtkdf::RunStatus::Failed;
  }
  run.Progress(0.05);
  run.Timer.End("models");
  if (!run.ResolveBackend(this->Backend))
  {
    return vtkdf::RunStatus::Failed;
  }
  vtkdf::HeadlessGL* gl = run.Context();
  this->LastBackend = gl ? "gpu" : "cpu";
  if (gl && (!this->Device || &this->Device->Context() != gl))
  {
    this->Device.reset(new vtkdf::ProximityDevice(*gl));
  }

  vtkdf::ProximityRequest request;
  request.Device = gl ? this->Device.get() : nullptr;
  request.Rule = this->SignMode == PSEUDO_NORMAL ? vtkdf::InsideRule::PseudoNormal
                                                 : vtkdf::InsideRule::WindingNumber;
  request.ContactMargin = this->ContactMargin;
  request.Step = this->Spacing;
  request.Resolution = this->Resolution;
  request.Contacts = this->ContactPoints;
  request.MaximumSamples = this->MaximumSamples;
  request.Share = rank;
  request.Shares = ranks;
  // A rank that stopped alone would leave the others waiting in the gather: only one
  // process aborts.
  const vtkdf::Execution execution = run.MakeExecution(0.05, 0.95, ranks == 1);
  vtkdf::ProximityReport report;
  const bool computed =
    vtkdf::ComputeProximity(*this->ModelA, *this->ModelB, request, report, execution, error);
  if (!computed)
  {
    vtkErrorMacro(<< (error == "aborted" ? std::string("Aborted") : "No answer: " + error) << ".");
    if (ranks == 1)
    {
      return vtkdf::RunStatus::Failed;
    }
  }
  if (ranks > 1)
  {
    const vtkdf::RunStatus gathered = this->GatherShares(computed, report, run);
    if (gathered != vtkdf::RunStatus::Done)
    {
      return gathered;
    }
  }
  run.Timer.End("proximity");
  this->WriteOutputs(report, inputs, outputVector);
  this->LastSeconds = run.Timer.Elapsed();
  return vtkdf::RunStatus::Done;
}

vtkdf::RunStatus vtkDistanceFieldProximity::GatherShares(bool computed,
  vtkdf::ProximityReport& report,
  vtkdf::FilterRun& run)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller->GetNumberOfProcesses();
  const int rank = controller->GetLocalProcessId();
  // A rank that failed sends nothing: rank 0 then misses a share and fails too, and
  // no rank waits for one that stopped.
  std::vector<double> mine = computed ? vtkdf::PackProximityShare(report) : std::vector<double>();
  vtkNew<vtkDoubleArray> send, received;
  send->SetArray(mine.data(), static_cast<vtkIdType>(mine.size()), 1);
  controller->GatherV(send, received, 0);
  if (rank != 0 || !computed)
  {
    // rank 0 answers for all
    return computed ? vtkdf::RunStatus::Empty : vtkdf::RunStatus::Failed;
  }
  std::vector<vtkdf::ProximityReport> shares;
  if (!vtkdf::UnpackProximityShares(received->GetPointer(0),
        static_cast<size_t>(received->GetNumberOfValues()),
        report,
        shares) ||
    shares.size() != static_cast<size_t>(ranks))
  {
    return run.Fail("The ranks' shares of the answer could not be read back.");
  }
  vtkdf::MergeProximityShares(shares, report);
  return vtkdf::RunStatus::Done;
}

void vtkDistanceFieldProximity::WriteOutputs(const vtkdf::ProximityReport& report,
  vtkPolyData* const inputs[2],
  vtkInformationVector* outputVector)
{
  this->LastColliding = report.Contact.Colliding;
  this->LastSeparationDistance = report.Contact.Separation;
  this->LastPenetrationAB = report.AInB.Depth;
  this->LastPenetrationBA = report.BInA.Depth;
  this->LastStep = report.Step;
  this->LastPointQueries = report.PointQueries;
  this->LastBytesToDevice = report.BytesToDevice;
  this->LastBytesFromDevice = report.BytesFromDevice;
  this->LastReusedTopology =
    (this->ModelA->ReusedTopology() ? 1 : 0) | (this->ModelB->ReusedTopology() ? 2 : 0);

  vtkPolyData* copies[2] = { vtkPolyData::GetData(outputVector, 2),
    vtkPolyData::GetData(outputVector, 3) };
  const std::vector<double>* distances[2] = { &report.DistanceA, &report.DistanceB };
  for (int m = 0; m < 2; ++m)
  {
    copies[m]->ShallowCopy(inputs[m]);
    vtkNew<vtkDoubleArray> distance;
    distance->SetName("DistanceToOther");
    distance->SetNumberOfValues(static_cast<vtkIdType>(distances[m]->size()));
    std::copy(distances[m]->begin(), distances[m]->end(), distance->GetPointer(0));
    copies[m]->GetPointData()->AddArray(distance);
  }
  this->WriteContacts(report, vtkPolyData::GetData(outputVector, 1));
  this->WriteAnswers(report, vtkPolyData::GetData(outputVector, 0));
}

void vtkDistanceFieldProximity::WriteAnswers(const vtkdf::ProximityReport& report,
  vtkPolyData* output) const
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> witness;
  witness->SetName("Witness");
  auto line = [&](const std::array<double, 3>& from, const std::array<double, 3>& to, int kind)
  {
    const vtkIdType ids[2] = { points->InsertNextPoint(from.data()),
      points->InsertNextPoint(to.data()) };
    lines->InsertNextCell(2, ids);
    witness->InsertNextValue(kind);
  };
  const vtkdf::ProximityResult& contact = report.Contact;
  if (!contact.Colliding && contact.ClosestTriangleA >= 0)
  {
    line(contact.ClosestA, contact.ClosestB, 0);
  }
  if (report.AInB.TriangleOfOther >= 0)
  {
    line(report.AInB.Deepest, report.AInB.ClosestOnOther, 1);
  }
  if (report.BInA.TriangleOfOther >= 0)
  {
    line(report.BInA.Deepest, report.BInA.ClosestOnOther, 2);
  }
  output->SetPoints(points);
  output->SetLines(lines);
  output->GetCellData()->AddArray(witness);

  vtkFieldData* fields = output->GetFieldData();
  auto tuple = [&](const char* name, const double* values, int components)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->InsertNextTuple(values);
    fields->AddArray(array);
  };
  auto scalar = [&](const char* name, double value) { tuple(name, &value, 1); };
  vtkNew<vtkUnsignedCharArray> colliding;
  colliding->SetName("Colliding");
  colliding->InsertNextValue(contact.Colliding ? 1 : 0);
  fields->AddArray(colliding);
  scalar("SeparationDistance", contact.Colliding ? 0 : contact.Separation);
  scalar("MaximumPenetrationAB", report.AInB.Depth);
  scalar("MaximumPenetrationBA", report.BInA.Depth);
  tuple("DeepestPointAB", report.AInB.Deepest.data(), 3);
  tuple("ContactNormalAB", report.AInB.Normal.data(), 3);
  tuple("DeepestPointBA", report.BInA.Deepest.data(), 3);
  tuple("ContactNormalBA", report.BInA.Normal.data(), 3);
  scalar("Step", report.Step);
  tuple("InteractionRegion", report.Region.data(), 6);
  scalar("PointQueries", static_cast<double>(report.PointQueries));
  scalar("ReusedTopology", this->LastReusedTopology);
}

void vtkDistanceFieldProximity::WriteContacts(const vtkdf::ProximityReport& report,
  vtkPolyData* output) const
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkDoubleArray> depth;
  depth->SetName("Depth");
  vtkNew<vtkDoubleArray> normal;
  normal->SetName("Normal");
  normal->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> model;
  model->SetName("Model");
  const vtkdf::PenetrationSide* sides[2] = { &report.AInB, &report.BInA };
  for (int m = 0; m < 2; ++m)
  {
    for (const vtkdf::ContactSample& sample : sides[m]->Contacts)
    {
      const vtkIdType id = points->InsertNextPoint(sample.Point.data());
      vertices->InsertNextCell(1, &id);
      depth->InsertNextValue(sample.Depth);
      normal->InsertNextTuple(sample.Normal.data());
      model->InsertNextValue(m);
    }
  }
  output->SetPoints(points);
  output->SetVerts(vertices);
  output->GetPointData()->AddArray(depth);
  output->GetPointData()->AddArray(normal);
  output->GetPointData()->AddArray(model);
}

void vtkDistanceFieldProximity::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Backend: " << vtkdf::enums::Backend.Name(this->Backend) << "\n";
  os << indent << "SignMode: " << vtkdf::enums::ProximitySign.Name(this->SignMode) << "\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "Spacing: " << this->Spacing << "\n";
  os << indent << "ContactMargin: " << this->ContactMargin << "\n";
  os << indent << "ContactPoints: " << this->ContactPoints << "\n";
  os << indent << "MaximumSamples: " << this->MaximumSamples << "\n";
  os << indent << "LastColliding: " << this->LastColliding << "\n";
  os << indent << "LastSeparationDistance: " << this->LastSeparationDistance << "\n";
  os << indent << "LastPenetrationAB: " << this->LastPenetrationAB << "\n";
  os << indent << "LastPenetrationBA: " << this->LastPenetrationBA << "\n";
  os << indent << "LastStep: " << this->LastStep << "\n";
  os << indent << "LastPointQueries: " << this->LastPointQueries << "\n";
  os << indent << "LastReusedTopology: " << this->LastReusedTopology << "\n";
  os << indent << "LastSeconds: " << this->LastSeconds << "\n";
  os << indent << "LastBackend: " << this->LastBackend << "\n";
  os << indent << "LastBytesToDevice: " << this->LastBytesToDevice << "\n";
  os << indent << "LastBytesFromDevice: " << this->LastBytesFromDevice << "\n";
}
