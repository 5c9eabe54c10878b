#include "vtkMeshDistanceFunction.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include "Common/LargeVector.h"
#include "LinearFactor/PointDistance.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldMeshInput.h"

#include <atomic>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkMeshDistanceFunction);

namespace
{
/// Each build's number, unique across functions (an address may be reused).
std::atomic<uint64_t> Builds{ 0 };

/// A thread's last answer, which seeds its next query of the same build: VTK's filters
/// evaluate neighbouring points in turn, and the previous closest point bounds the next
/// search (and a closed surface's side carries over), with no change to the answer.
struct LastAnswer
{
  const void* Owner = nullptr;
  uint64_t Build = 0;
  vtkdf::PointAnswer Answer;
};
thread_local LastAnswer Last;
} // namespace

vtkMeshDistanceFunction::vtkMeshDistanceFunction() = default;

vtkMeshDistanceFunction::~vtkMeshDistanceFunction() = default;

void vtkMeshDistanceFunction::SetInput(vtkPolyData* surface)
{
  if (this->Input != surface)
  {
    this->Input = surface;
    this->BuiltTime = 0;
    this->Modified();
  }
}

vtkPolyData* vtkMeshDistanceFunction::GetInput()
{
  return this->Input;
}

vtkMTimeType vtkMeshDistanceFunction::GetMTime()
{
  const vtkMTimeType own = this->Superclass::GetMTime();
  return this->Input ? std::max(own, this->Input->GetMTime()) : own;
}

bool vtkMeshDistanceFunction::Prepare()
{
  vtkPolyData* input = this->Input;
  const vtkMTimeType time = input ? input->GetMTime() : 0;
  if (this->BuiltTime == time && this->BuiltSign == this->SignMode)
  {
    return this->Valid;
  }
  std::lock_guard<std::mutex> lock(this->Building);
  if (this->BuiltTime == time && this->BuiltSign == this->SignMode)
  {
    return this->Valid; // another thread built it meanwhile
  }
  this->Valid = false;
  this->Queries.reset();
  std::string error;
  double bounds[6];
  vtkdf::MeshInput mesh;
  vtkdf::MeshCopyReport report;
  auto queries = std::make_unique<vtkdf::PointDistanceQueries>();
  if (!input)
  {
    error = "no input surface (SetInput)";
  }
  else if (!vtkdf::enums::LinearFactorSign.Check(this->SignMode, error))
  {
  }
  else if (vtkdf::UsedPointBounds(input, bounds, error) &&
    vtkdf::CopyMesh(input, bounds, vtkdf::GridFrame(), mesh, report, error) &&
    queries->Build(
      std::move(mesh), static_cast<vtkdf::SignMode>(this->SignMode), false, vtkdf::SMPFor, error))
  {
    this->Queries = std::move(queries);
    this->Build = ++Builds;
    this->Valid = true;
  }
  if (!this->Valid)
  {
    vtkErrorMacro(
      "No distances: " << error << "; every value is NoValue (" << this->NoValue << ").");
  }
  this->BuiltSign = this->SignMode;
  this->BuiltTime = time;
  return this->Valid;
}

void vtkMeshDistanceFunction::Query(const double x[3],
  const vtkdf::PointQueryParts& parts,
  vtkdf::PointAnswer& answer)
{
  const bool seeded = Last.Owner == this && Last.Build == this->Build && !Last.Answer.Beyond;
  this->Queries->Query(x,
    HUGE_VAL,
    seeded ? Last.Answer.Closest : nullptr,
    parts,
    answer,
    seeded ? &Last.Answer : nullptr);
  std::copy(x, x + 3, answer.Point);
  Last.Owner = this;
  Last.Build = this->Build;
  Last.Answer = answer;
}

double vtkMeshDistanceFunction::EvaluateFunction(double x[3])
{
  double closest[3];
  return this->EvaluateFunctionAndGetClosestPoint(x, closest);
}

double vtkMeshDistanceFunction::EvaluateFunctionAndGetClosestPoint(double x[3],
  double closestPoint[3])
{
  vtkdf::PointAnswer answer;
  vtkdf::PointQueryParts parts;
  parts.Closest = false;
  parts.Gradient = false;
  if (!this->Prepare() || !std::isfinite(x[0] + x[1] + x[2]))
  {
    std::copy(this->NoClosestPoint, this->NoClosestPoint + 3, closestPoint);
    return this->NoValue;
  }
  this->Query(x, parts, answer);
  std::copy(answer.Closest, answer.Closest + 3, closestPoint);
  return answer.Distance;
}

void vtkMeshDistanceFunction::EvaluateGradient(double x[3], double g[3])
{
  vtkdf::PointAnswer answer;
  vtkdf::PointQueryParts parts;
  parts.Closest = false;
  if (!this->Prepare() || !std::isfinite(x[0] + x[1] + x[2]))
  {
    g[0] = g[1] = g[2] = 0;
    return;
  }
  this->Query(x, parts, answer);
  std::copy(answer.Gradient, answer.Gradient + 3, g);
}

void vtkMeshDistanceFunction::EvaluateFunction(vtkDataArray* input, vtkDataArray* output)
{
  const vtkIdType count = input->GetNumberOfTuples();
  output->SetNumberOfComponents(1);
  output->SetNumberOfTuples(count);
  if (!this->Prepare() || input->GetNumberOfComponents() != 3)
  {
    output->Fill(this->NoValue);
    return;
  }
  // The points as xyz doubles (the array itself when it is one), the distances into a
  // double buffer (the output itself when it is one).
  vtkdf::LargeVector<double> xyz, values;
  vtkDoubleArray* doubles = vtkDoubleArray::FastDownCast(input);
  const double* points = doubles ? doubles->GetPointer(0) : nullptr;
  if (!points)
  {
    xyz.resize(3 * static_cast<size_t>(count));
    for (vtkIdType i = 0; i < count; ++i)
    {
      input->GetTuple(i, xyz.data() + 3 * i);
    }
    points = xyz.data();
  }
  vtkDoubleArray* doubleOutput = vtkDoubleArray::FastDownCast(output);
  if (!doubleOutput)
  {
    values.resize(static_cast<size_t>(count));
  }
  vtkdf::PointDistanceArrays arrays;
  arrays.Distance = doubleOutput ? doubleOutput->GetPointer(0) : values.data();
  vtkdf::Execution execution;
  execution.For = vtkdf::SMPFor;
  vtkdf::PointDistanceStatistics stats;
  std::string error;
  if (!this->Queries->QueryPoints(points, count, HUGE_VAL, arrays, execution, stats, error))
  {
    // A point with a NaN or infinite coordinate.
    vtkErrorMacro("No distances: " << error << "; every value is NoValue.");
    output->Fill(this->NoValue);
    return;
  }
  if (!doubleOutput)
  {
    for (vtkIdType i = 0; i < count; ++i)
    {
      output->SetTuple1(i, values[i]);
    }
  }
}

void vtkMeshDistanceFunction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Input: " << this->Input.Get() << "\n";
  os << indent << "SignMode: " << vtkdf::enums::LinearFactorSign.Name(this->SignMode) << "\n";
  os << indent << "NoValue: " << this->NoValue << "\n";
  os << indent << "NoClosestPoint: (" << this->NoClosestPoint[0] << ", " << this->NoClosestPoint[1]
     << ", " << this->NoClosestPoint[2] << ")\n";
}
