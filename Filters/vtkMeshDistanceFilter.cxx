#include "vtkMeshDistanceFilter.h"

#include "vtkCommunicator.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
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

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
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

/// The statistics of every rank's points with global ids, each id once (the first rank's
/// copy): rank 0 gathers the ranks' (id, |d|) pairs and summarizes them as one process
/// summarizes its points (the farthest: the smallest id at the maximum), then tells the
/// others. Collective; with no controller, this process's points alone.
void SummarizeByGlobalIds(vtkMultiProcessController* controller,
  vtkDataSet* input,
  const uint8_t* excluded,
  const double* magnitude,
  vtkdf::PointDistanceStatistics& stats,
  vtkIdType& key,
  double farthest[3])
{
  vtkDataArray* ids = input->GetPointData()->GetGlobalIds();
  std::vector<vtkIdType> myIds;
  std::vector<double> myValues;
  for (vtkIdType i = 0; ids && i < input->GetNumberOfPoints(); ++i)
  {
    if (!excluded || !excluded[i])
    {
      myIds.push_back(static_cast<vtkIdType>(ids->GetTuple1(i)));
      myValues.push_back(magnitude[i]);
    }
  }
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  const bool root = !controller || controller->GetLocalProcessId() == 0;
  vtkIdType mine = static_cast<vtkIdType>(myIds.size());
  std::vector<vtkIdType> lengths(ranks, mine), offsets(ranks, 0);
  std::vector<vtkIdType> allIds;
  std::vector<double> allValues;
  if (controller)
  {
    controller->AllGather(&mine, lengths.data(), 1);
    for (int r = 1; r < ranks; ++r)
    {
      offsets[r] = offsets[r - 1] + lengths[r - 1];
    }
    const vtkIdType gathered = offsets[ranks - 1] + lengths[ranks - 1];
    allIds.resize(root ? gathered : 0);
    allValues.resize(root ? gathered : 0);
    controller->GatherV(myIds.data(), allIds.data(), mine, lengths.data(), offsets.data(), 0);
    controller->GatherV(myValues.data(), allValues.data(), mine, lengths.data(), offsets.data(), 0);
  }
  else
  {
    allIds = std::move(myIds);
    allValues = std::move(myValues);
  }
  const vtkIdType total = static_cast<vtkIdType>(allIds.size());
  // Points, beyond, maximum, the farthest id, mean, root mean square.
  double summary[6] = { 0, 0, 0, -1, 0, 0 };
  if (root)
  {
    std::vector<vtkIdType> order(total);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(
      order.begin(), order.end(), [&](vtkIdType a, vtkIdType b) { return allIds[a] < allIds[b]; });
    vtkdf::PointDistanceStatistics all;
    for (vtkIdType k = 0; k < total; ++k)
    {
      const vtkIdType at = order[k];
      // Another rank's copy of the same point counts once.
      if (k == 0 || allIds[at] != allIds[order[k - 1]])
      {
        all.Count(allValues[at], allIds[at]);
      }
    }
    all.Finish();
    summary[0] = static_cast<double>(all.Points);
    summary[1] = static_cast<double>(all.Beyond);
    summary[2] = all.Maximum;
    summary[3] = static_cast<double>(all.Farthest);
    summary[4] = all.Mean;
    summary[5] = all.RootMeanSquare;
  }
  if (controller)
  {
    controller->Broadcast(summary, 6, 0);
  }
  stats.Points = static_cast<int64_t>(summary[0]);
  stats.Beyond = static_cast<int64_t>(summary[1]);
  stats.Maximum = summary[2];
  key = static_cast<vtkIdType>(summary[3]);
  stats.Mean = summary[4];
  stats.RootMeanSquare = summary[5];
  // The farthest point's coordinates, from a rank that holds it.
  double point[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (vtkIdType i = 0; key >= 0 && ids && i < input->GetNumberOfPoints(); ++i)
  {
    if (static_cast<vtkIdType>(ids->GetTuple1(i)) == key)
    {
      input->GetPoint(i, point);
      break;
    }
  }
  if (controller)
  {
    controller->AllReduce(point, farthest, 3, vtkCommunicator::MAX_OP);
  }
  else
  {
    std::copy(point, point + 3, farthest);
  }
  if (key < 0)
  {
    std::fill(farthest, farthest + 3, NAN);
  }
}

/// In a distributed run (the global controller's ranks, each with its own points and the
/// same surface), the statistics of all the ranks' points, the same bits as one
/// process's over all of them. With global point ids (on every rank that holds points),
/// each id counts once (SummarizeByGlobalIds). Without them, the ranks' points (but
/// their ghost points, excluded from `stats` already) add up: the exact sums, the
/// largest distance, and as the farthest point the first rank's at the maximum, whose
/// index names it only where that rank alone holds points (else `key` is -1).
/// Collective: every rank calls it after its queries, whether they succeeded (`status`
/// 0), failed (1) or were aborted (2); returns the largest status of all the ranks.
/// `key` and `farthest` hold this process's farthest point and get the chosen one.
int CombineAcrossRanks(int status,
  vtkDataSet* input,
  const uint8_t* excluded,
  const double* magnitude,
  vtkdf::PointDistanceStatistics& stats,
  vtkIdType& key,
  double farthest[3])
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() < 2)
  {
    // One process: points that share a global id still count once.
    if (status == 0 && input->GetPointData()->GetGlobalIds())
    {
      SummarizeByGlobalIds(nullptr, input, excluded, magnitude, stats, key, farthest);
    }
    return status;
  }
  int worst = status;
  controller->AllReduce(&status, &worst, 1, vtkCommunicator::MAX_OP);
  if (worst != 0)
  {
    return worst;
  }
  vtkTypeInt64 evaluations = stats.Evaluations, allEvaluations = 0;
  controller->AllReduce(&evaluations, &allEvaluations, 1, vtkCommunicator::SUM_OP);
  stats.Evaluations = allEvaluations;
  const int withIds =
    input->GetPointData()->GetGlobalIds() != nullptr || input->GetNumberOfPoints() == 0;
  int everyRankWithIds = withIds;
  controller->AllReduce(&withIds, &everyRankWithIds, 1, vtkCommunicator::MIN_OP);
  if (everyRankWithIds)
  {
    SummarizeByGlobalIds(controller, input, excluded, magnitude, stats, key, farthest);
    return 0;
  }
  vtkTypeInt64 counts[3] = { stats.Points, stats.Beyond, stats.Points > 0 }, total[3];
  controller->AllReduce(counts, total, 3, vtkCommunicator::SUM_OP);
  for (vtkdf::ExactSum* sum : { &stats.Sum, &stats.Squares })
  {
    sum->Normalize();
    vtkTypeInt64 digits[vtkdf::ExactSum::Digits], summed[vtkdf::ExactSum::Digits];
    std::copy(sum->Digit, sum->Digit + vtkdf::ExactSum::Digits, digits);
    controller->AllReduce(digits, summed, vtkdf::ExactSum::Digits, vtkCommunicator::SUM_OP);
    std::copy(summed, summed + vtkdf::ExactSum::Digits, sum->Digit);
    sum->Normalize();
  }
  const bool any = stats.Farthest >= 0;
  double maximum = any ? stats.Maximum : -HUGE_VAL, largest = maximum;
  controller->AllReduce(&maximum, &largest, 1, vtkCommunicator::MAX_OP);
  // The owner: the first rank with a point at the maximum; its point and index.
  const int none = controller->GetNumberOfProcesses();
  const int mine = any && maximum == largest ? controller->GetLocalProcessId() : none;
  int owner = mine;
  controller->AllReduce(&mine, &owner, 1, vtkCommunicator::MIN_OP);
  double point[4] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -1 }, chosen[4];
  if (mine == owner && owner != none)
  {
    std::copy(farthest, farthest + 3, point);
    point[3] = static_cast<double>(key);
  }
  controller->AllReduce(point, chosen, 4, vtkCommunicator::MAX_OP);
  const bool found = owner != none;
  std::copy(chosen, chosen + 3, farthest);
  if (!found)
  {
    std::fill(farthest, farthest + 3, NAN);
  }
  stats.Points = total[0];
  stats.Beyond = total[1];
  stats.Maximum = found ? largest : 0;
  key = found && total[2] == 1 ? static_cast<vtkIdType>(chosen[3]) : -1;
  stats.Finish();
  return 0;
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

vtkdf::PointDistanceArrays vtkMeshDistanceFilter::AddArrays(vtkPointData* pd, vtkIdType count) const
{
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

  return arrays;
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
  vtkdf::PointDistanceArrays arrays = this->AddArrays(output->GetPointData(), count);
  vtkdf::PointDistanceStatistics stats;
  std::string error;
  const double cap = this->MaximumDistance > 0 ? this->MaximumDistance : HUGE_VAL;
  // A distributed run's copies of points that another rank owns (VTK's ghost points)
  // are measured but left out of the statistics, so that each point counts once.
  vtkUnsignedCharArray* ghosts = input->GetPointGhostArray();
  const uint8_t* excluded = nullptr;
  std::vector<uint8_t> duplicates;
  if (ghosts && ghosts->GetNumberOfTuples() == count)
  {
    duplicates.resize(count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      duplicates[i] = (ghosts->GetValue(i) & vtkDataSetAttributes::DUPLICATEPOINT) != 0;
    }
    excluded = duplicates.data();
  }
  // |d| (NaN beyond the cap) of every point, for the statistics of a distributed run.
  std::vector<double> magnitude(count);
  arrays.Magnitude = magnitude.data();
  const bool ok = this->Queries->QueryPoints(
    points, count, cap, arrays, run.MakeExecution(0.05, 1), stats, error, excluded);
  // Every rank of a distributed run reaches the combination, whatever its queries did.
  vtkIdType key = -1;
  double farthest[3] = { NAN, NAN, NAN };
  if (ok && !stats.Aborted && stats.Farthest >= 0)
  {
    key = stats.Farthest;
    std::copy(points + 3 * key, points + 3 * key + 3, farthest);
  }
  const int status = CombineAcrossRanks(
    !ok ? 1 : (stats.Aborted ? 2 : 0), input, excluded, magnitude.data(), stats, key, farthest);
  if (!ok)
  {
    return run.Fail("The points (input 0): " + error + ".");
  }
  if (status == 1)
  {
    return run.Fail("The points of another rank could not be measured (its error says why).");
  }
  if (status == 2)
  {
    return run.Empty();
  }
  this->LastEvaluations = stats.Evaluations;
  this->LastPointsBeyond = stats.Beyond;

  vtkFieldData* fd = output->GetFieldData();
  AddValue(fd, "MaximumAbsoluteDistance", stats.Maximum);
  AddValue(fd, "MeanAbsoluteDistance", stats.Mean);
  AddValue(fd, "RootMeanSquareDistance", stats.RootMeanSquare);
  AddValue(fd, "FarthestPointId", key);
  AddValue(fd, "PointsBeyond", stats.Beyond);
  auto farthestPoint = vtkdf::NewArray<vtkDoubleArray>("FarthestPoint", 1, 3);
  for (int a = 0; a < 3; ++a)
  {
    farthestPoint->SetValue(a, farthest[a]);
  }
  fd->AddArray(farthestPoint);
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
