#include "vtkLinearFactorDistanceField.h"

#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorField.h"
#include "Winding/WindingCrossings.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

#include <cmath>
#include <utility>

vtkStandardNewMacro(vtkLinearFactorDistanceField);

vtkLinearFactorDistanceField::vtkLinearFactorDistanceField()
  : Workspace(new vtkdf::LinearFactorWorkspace)
{
}

vtkLinearFactorDistanceField::~vtkLinearFactorDistanceField() = default;

vtkTypeInt64 vtkLinearFactorDistanceField::GetWorkBufferBytes() const
{
  return this->Workspace->Bytes();
}

void vtkLinearFactorDistanceField::ReleaseWorkBuffers()
{
  this->Workspace->Release();
}

vtkdf::RunStatus vtkLinearFactorDistanceField::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  this->LastEvaluations = 0;
  this->LastCullingFactor = 0;
  this->LastRoute = "none";
  this->LastSignBackend = "none";
  vtkPolyData* input = nullptr;
  vtkdf::LinearFactorRequest request;
  const vtkdf::RunStatus opened =
    this->OpenMeshRun(inputVector, outputVector, run, input, request.Grid, request.Extent);
  if (opened != vtkdf::RunStatus::Done)
  {
    return opened;
  }
  const vtkIdType n = static_cast<vtkIdType>(request.Extent.Count());
  const bool winding = this->SignMode == WINDING_NUMBER || this->ComputeWindingNumber;
  // Refuse grids that overflow indices or memory before allocating anything.
  // The surface coordinates need the closest cells and, for a signed gradient, the
  // distances: the core keeps its own where they are not asked for.
  const bool surface = this->ComputeClosestBarycentric || this->ComputeGradient;
  const bool cells = this->ComputeClosestCellId || surface;
  const bool distances =
    this->ComputeDistance || (this->ComputeGradient && this->SignMode != UNSIGNED);
  const double bytesPerSample = 8.0 /* nearest-site buffer */ + (distances ? 4 : 0) +
    (cells ? sizeof(vtkIdType) : 0) + (this->ComputeClosestFeature ? 1 : 0) +
    (this->ComputeClosestPoint ? 12 : 0) + (this->ComputeWindingNumber ? 4 : 0) +
    (winding ? 1 : 0) + (this->ComputeClosestBarycentric ? 12 + sizeof(vtkIdType) : 0) +
    (this->ComputeGradient ? 12 : 0);
  vtkdf::MeshInput mesh;
  if (!this->CheckMemory(double(n) * bytesPerSample, request.Extent) ||
    !this->ReadMesh(input, request.Grid, mesh))
  {
    return vtkdf::RunStatus::Failed;
  }
  run.Timer.End("input");
  // Where the field and the sign run (Common/BackendPolicy.h). Signs alone where the
  // crossings decide them stay on the CPU, in less than a GPU pass.
  vtkdf::WorkDescription work;
  work.Backend = static_cast<vtkdf::BackendChoice>(this->Backend);
  work.Samples = request.Extent.Count();
  work.WindingSign = winding;
  work.CrossingsDecide = [&]
  { return !this->ComputeWindingNumber && vtkdf::CrossingsDecide(mesh.Points, mesh.Triangles); };
  if (!run.Resolve(work))
  {
    return vtkdf::RunStatus::Failed;
  }
  vtkdf::HeadlessGL* gl = run.Context();
  request.SignContext = vtkdf::SignContext(run.Plan());
  request.Domains = static_cast<vtkdf::DomainShape>(this->DomainShape);
  request.Route = static_cast<vtkdf::FieldRoute>(this->Route);
  request.Sign = static_cast<vtkdf::SignMode>(this->SignMode);
  request.MaximumDistance = this->MaximumDistance;
  if (input != this->WorkspaceInput || input->GetMTime() != this->WorkspaceInputTime)
  {
    this->Workspace->Release(); // a new input: nothing of the last one stays
    this->WorkspaceInput = input;
    this->WorkspaceInputTime = input->GetMTime();
  }
  request.Workspace = this->Workspace.get();

  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  SetOutputExtent(output, request.Grid, request.Extent);
  const vtkdf::LinearFactorArrays arrays = this->AddArrays(output, n);
  vtkdf::LinearFactorReport report;
  std::string error;
  if (!vtkdf::ComputeLinearFactorField(
        std::move(mesh), request, gl, arrays, run.MakeExecution(), report, error))
  {
    return run.Fail(error);
  }
  if (report.NoUsableCell)
  {
    return run.Empty("The input has no usable cell: the output is an empty image.");
  }
  if (report.Aborted)
  {
    return run.Empty();
  }
  this->LastRoute =
    report.Route == vtkdf::FieldRoute::SampleQueries ? "sample queries" : "site scan";
  this->LastEvaluations = report.Evaluations;
  this->LastCullingFactor = report.Evaluations >= 0 ? double(report.Evaluations) / n : -1.0;
  this->LastWindingBlockSamples = report.WindingBlockSamples;
  this->LastWindingLineSamples = report.WindingLineSamples;
  this->LastWindingExactSamples = report.WindingExactSamples;
  this->LastWindingCPUSamples = report.WindingCPUSamples;
  this->LastSignBackend = !winding ? "none" : (report.WindingOnGPU ? "gpu" : "cpu");
  return vtkdf::RunStatus::Done;
}

vtkdf::LinearFactorArrays vtkLinearFactorDistanceField::AddArrays(vtkImageData* output,
  vtkIdType n) const
{
  // The arrays, in world units, on the requested extent.
  vtkPointData* pd = output->GetPointData();
  vtkdf::LinearFactorArrays arrays;
  if (this->ComputeDistance)
  {
    auto a = vtkdf::NewArray<vtkFloatArray>("Distance", n);
    arrays.Distance = a->GetPointer(0);
    pd->SetScalars(a);
  }
  if (this->ComputeClosestCellId)
  {
    auto a = vtkdf::NewArray<vtkIdTypeArray>("ClosestCellId", n);
    static_assert(sizeof(vtkIdType) == sizeof(int64_t), "vtkIdType is 64 bits");
    arrays.ClosestCellId = reinterpret_cast<int64_t*>(a->GetPointer(0));
    pd->AddArray(a);
  }
  if (this->ComputeClosestFeature)
  {
    auto a = vtkdf::NewArray<vtkUnsignedCharArray>("ClosestFeature", n);
    arrays.ClosestFeature = a->GetPointer(0);
    pd->AddArray(a);
  }
  if (this->ComputeClosestPoint)
  {
    auto a = vtkdf::NewArray<vtkFloatArray>("ClosestPoint", n, 3);
    arrays.ClosestPoint = a->GetPointer(0);
    pd->AddArray(a);
  }
  if (this->ComputeWindingNumber)
  {
    auto a = vtkdf::NewArray<vtkFloatArray>("WindingNumber", n);
    arrays.WindingNumber = a->GetPointer(0);
    pd->AddArray(a);
  }
  if (this->ComputeClosestBarycentric)
  {
    auto a = vtkdf::NewArray<vtkFloatArray>("ClosestBarycentric", n, 3);
    arrays.ClosestBarycentric = a->GetPointer(0);
    pd->AddArray(a);
    auto sub = vtkdf::NewArray<vtkIdTypeArray>("ClosestSubTriangle", n);
    arrays.ClosestSubTriangle = reinterpret_cast<int64_t*>(sub->GetPointer(0));
    pd->AddArray(sub);
  }
  if (this->ComputeGradient)
  {
    auto a = vtkdf::NewArray<vtkFloatArray>("Gradient", n, 3);
    arrays.Gradient = a->GetPointer(0);
    pd->AddArray(a);
  }
  return arrays;
}

std::string vtkLinearFactorDistanceField::PointCloudRefusal()
{
  if (this->SignMode != UNSIGNED || this->ComputeWindingNumber)
  {
    return "a sign (SignMode) and the winding number need a surface; with SignMode "
           "Unsigned the field is the distance to the points";
  }
  return std::string();
}

bool vtkLinearFactorDistanceField::CheckProperties()
{
  if (!this->Superclass::CheckProperties() ||
    !this->CheckEnum(this->SignMode, vtkdf::enums::LinearFactorSign) ||
    !this->CheckEnum(this->DomainShape, vtkdf::enums::DomainShape) ||
    !this->CheckEnum(this->Route, vtkdf::enums::Route))
  {
    return false;
  }
  if (!(this->MaximumDistance >= 0 && std::isfinite(this->MaximumDistance)))
  {
    vtkErrorMacro("MaximumDistance must be finite and >= 0 (0: no cap); it is "
      << this->MaximumDistance << ".");
    return false;
  }
  return true;
}

void vtkLinearFactorDistanceField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SignMode: " << vtkdf::enums::LinearFactorSign.Name(this->SignMode) << "\n";
  os << indent << "DomainShape: " << vtkdf::enums::DomainShape.Name(this->DomainShape) << "\n";
  os << indent << "Route: " << vtkdf::enums::Route.Name(this->Route) << "\n";
  os << indent << "LastRoute: " << this->LastRoute << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance << "\n";
  os << indent << "ComputeDistance: " << this->ComputeDistance << "\n";
  os << indent << "ComputeClosestCellId: " << this->ComputeClosestCellId << "\n";
  os << indent << "ComputeClosestFeature: " << this->ComputeClosestFeature << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "ComputeWindingNumber: " << this->ComputeWindingNumber << "\n";
  os << indent << "ComputeClosestBarycentric: " << this->ComputeClosestBarycentric << "\n";
  os << indent << "ComputeGradient: " << this->ComputeGradient << "\n";
  os << indent << "LastEvaluations: " << this->LastEvaluations << "\n";
  os << indent << "LastWindingBlockSamples: " << this->LastWindingBlockSamples << "\n";
  os << indent << "LastWindingLineSamples: " << this->LastWindingLineSamples << "\n";
  os << indent << "LastWindingExactSamples: " << this->LastWindingExactSamples << "\n";
  os << indent << "LastWindingCPUSamples: " << this->LastWindingCPUSamples << "\n";
  os << indent << "LastSignBackend: " << this->LastSignBackend << "\n";
  os << indent << "LastCullingFactor: " << this->LastCullingFactor << "\n";
  os << indent << "WorkBufferBytes: " << this->GetWorkBufferBytes() << "\n";
}
