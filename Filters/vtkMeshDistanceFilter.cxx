#include "vtkMeshDistanceFilter.h"

#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "LinearFactor/PointDistance.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldMeshInput.h"
#include "vtkDistanceFieldRun.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkMeshDistanceFilter);

namespace
{
/// The points of `input` as xyz doubles: its own array when it is one, else `copy`.
const double* PointCoordinates(vtkDataSet* input, std::vector<double>& copy)
{
  vtkPointSet* pointSet = vtkPointSet::SafeDownCast(input);
  vtkDoubleArray* doubles = pointSet && pointSet->GetPoints()
    ? vtkDoubleArray::FastDownCast(pointSet->GetPoints()->GetData())
    : nullptr;
  if (doubles && doubles->GetNumberOfComponents() == 3)
  {
    return doubles->GetPointer(0);
  }
  const vtkIdType count = input->GetNumberOfPoints();
  copy.resize(3 * static_cast<size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    input->GetPoint(i, copy.data() + 3 * i);
  }
  return copy.data();
}

template<typename T>
void AddValue(vtkFieldData* data, const char* name, T value)
{
  auto array = vtkdf::NewArray<vtkDoubleArray>(name, 1);
  array->SetValue(0, static_cast<double>(value));
  data->AddArray(array);
}
} // namespace

static_assert(sizeof(vtkIdType) == sizeof(int64_t), "vtkIdType must be 64 bits");

vtkMeshDistanceFilter::vtkMeshDistanceFilter()
{
  this->SetNumberOfInputPorts(2);
}

vtkMeshDistanceFilter::~vtkMeshDistanceFilter() = default;

int vtkMeshDistanceFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkDataSet" : "vtkPolyData");
  return 1;
}

bool vtkMeshDistanceFilter::CheckProperties()
{
  std::string error;
  if (!vtkdf::enums::LinearFactorSign.Check(this->SignMode, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  if (!(this->MaximumDistance >= 0) || !std::isfinite(this->MaximumDistance))
  {
    vtkErrorMacro("MaximumDistance must be finite and at least 0 (0: no limit); it is "
      << this->MaximumDistance << ".");
    return false;
  }
  return true;
}

int vtkMeshDistanceFilter::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return this->CheckProperties() ? 1 : 0;
}

int vtkMeshDistanceFilter::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // The surface whole, whatever piece of the points is asked for.
  if (vtkInformation* in = inputVector[1]->GetInformationObject(0))
  {
    vtkdf::RequestWholeInput(in);
  }
  return 1;
}

bool vtkMeshDistanceFilter::PrepareQueries(vtkPolyData* surface, vtkdf::FilterRun& run)
{
  this->LastBuiltHierarchy = false;
  if (this->Queries && this->QueriesSurface == surface &&
    this->QueriesTime == surface->GetMTime() && this->QueriesSign == this->SignMode &&
    this->QueriesWinding == this->ComputeWindingNumber)
  {
    return true;
  }
  this->Queries.reset();
  std::string error;
  double bounds[6];
  vtkdf::MeshInput mesh;
  vtkdf::MeshCopyReport report;
  // The queries scale the mesh themselves (by a power of two): the identity frame here.
  if (!vtkdf::UsedPointBounds(surface, bounds, error) ||
    !vtkdf::CopyMesh(surface, bounds, vtkdf::GridFrame(), mesh, report, error))
  {
    vtkErrorMacro("The surface (input 1): " << error << ".");
    return false;
  }
  const std::string warning = report.Warnings();
  if (!warning.empty())
  {
    vtkWarningMacro("The surface (input 1): " << warning);
  }
  run.Timer.End("input");
  auto queries = std::make_unique<vtkdf::PointDistanceQueries>();
  if (!queries->Build(std::move(mesh),
        static_cast<vtkdf::SignMode>(this->SignMode),
        this->ComputeWindingNumber,
        vtkdf::SMPFor,
        error))
  {
    vtkErrorMacro("The surface (input 1): " << error << ".");
    return false;
  }
  run.Timer.End("tree");
  this->Queries = std::move(queries);
  this->QueriesSurface = surface;
  this->QueriesTime = surface->GetMTime();
  this->QueriesSign = this->SignMode;
  this->QueriesWinding = this->ComputeWindingNumber;
  this->LastBuiltHierarchy = true;
  return true;
}

vtkdf::RunStatus vtkMeshDistanceFilter::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkPolyData* surface = vtkPolyData::GetData(inputVector[1], 0);
  vtkDataSet* output = vtkDataSet::GetData(outputVector, 0);
  if (!input || !output)
  {
    return run.Fail("No points to measure from (input 0).");
  }
  if (!surface)
  {
    return run.Fail("No surface to measure distances to (input 1).");
  }
  if (!this->CheckProperties())
  {
    return vtkdf::RunStatus::Failed;
  }
  if (!this->PrepareQueries(surface, run))
  {
    return vtkdf::RunStatus::Failed;
  }

  const vtkIdType count = input->GetNumberOfPoints();
  std::vector<double> copy;
  const double* points = PointCoordinates(input, copy);

  output->ShallowCopy(input);
  vtkPointData* pd = output->GetPointData();
  vtkdf::PointDistanceArrays arrays;
  auto distance = vtkdf::NewArray<vtkDoubleArray>("Distance", count, 1);
  arrays.Distance = distance->GetPointer(0);
  pd->AddArray(distance);
  pd->SetActiveScalars("Distance");
  if (this->ComputeClosestPoint)
  {
    auto closest = vtkdf::NewArray<vtkDoubleArray>("ClosestPoint", count, 3);
    arrays.ClosestPoint = closest->GetPointer(0);
    pd->AddArray(closest);
  }
  if (this->ComputeClosestCellId)
  {
    auto cells = vtkdf::NewArray<vtkIdTypeArray>("ClosestCellId", count);
    arrays.ClosestCellId = reinterpret_cast<int64_t*>(cells->GetPointer(0));
    pd->AddArray(cells);
  }
  if (this->ComputeBarycentric)
  {
    auto barycentric = vtkdf::NewArray<vtkDoubleArray>("ClosestBarycentric", count, 3);
    auto sub = vtkdf::NewArray<vtkIdTypeArray>("ClosestSubTriangle", count);
    arrays.ClosestBarycentric = barycentric->GetPointer(0);
    arrays.ClosestSubTriangle = reinterpret_cast<int64_t*>(sub->GetPointer(0));
    pd->AddArray(barycentric);
    pd->AddArray(sub);
  }
  if (this->ComputeGradient)
  {
    auto gradient = vtkdf::NewArray<vtkDoubleArray>("Gradient", count, 3);
    arrays.Gradient = gradient->GetPointer(0);
    pd->AddArray(gradient);
  }
  if (this->ComputeClosestFeature)
  {
    auto feature = vtkdf::NewArray<vtkUnsignedCharArray>("ClosestFeature", count);
    arrays.ClosestFeature = feature->GetPointer(0);
    pd->AddArray(feature);
  }
  if (this->ComputeWindingNumber)
  {
    auto winding = vtkdf::NewArray<vtkDoubleArray>("WindingNumber", count, 1);
    arrays.WindingNumber = winding->GetPointer(0);
    pd->AddArray(winding);
  }

  vtkdf::PointDistanceStatistics stats;
  std::string error;
  const double cap = this->MaximumDistance > 0 ? this->MaximumDistance : HUGE_VAL;
  if (!this->Queries->QueryPoints(
        points, count, cap, arrays, run.MakeExecution(0.05, 1), stats, error))
  {
    return run.Fail("The points (input 0): " + error + ".");
  }
  if (stats.Aborted)
  {
    return run.Empty();
  }
  this->LastEvaluations = stats.Evaluations;
  this->LastPointsBeyond = stats.Beyond;

  vtkFieldData* fd = output->GetFieldData();
  AddValue(fd, "MaximumAbsoluteDistance", stats.Maximum);
  AddValue(fd, "MeanAbsoluteDistance", stats.Mean);
  AddValue(fd, "RootMeanSquareDistance", stats.RootMeanSquare);
  AddValue(fd, "FarthestPointId", stats.Farthest);
  AddValue(fd, "PointsBeyond", stats.Beyond);
  auto farthest = vtkdf::NewArray<vtkDoubleArray>("FarthestPoint", 1, 3);
  for (int a = 0; a < 3; ++a)
  {
    farthest->SetValue(a, stats.Farthest >= 0 ? points[3 * stats.Farthest + a] : NAN);
  }
  fd->AddArray(farthest);
  return vtkdf::RunStatus::Done;
}

void vtkMeshDistanceFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SignMode: " << vtkdf::enums::LinearFactorSign.Name(this->SignMode) << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "ComputeClosestCellId: " << this->ComputeClosestCellId << "\n";
  os << indent << "ComputeBarycentric: " << this->ComputeBarycentric << "\n";
  os << indent << "ComputeGradient: " << this->ComputeGradient << "\n";
  os << indent << "ComputeClosestFeature: " << this->ComputeClosestFeature << "\n";
  os << indent << "ComputeWindingNumber: " << this->ComputeWindingNumber << "\n";
  os << indent << "LastEvaluations: " << this->LastEvaluations << "\n";
  os << indent << "LastPointsBeyond: " << this->LastPointsBeyond << "\n";
  os << indent << "LastBuiltHierarchy: " << this->LastBuiltHierarchy << "\n";
}
