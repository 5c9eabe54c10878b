#include "vtkPenetrationDepth.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "GL/HeadlessGL.h"
#include "Union/PenetrationDepth.h"
#include "vtkConvexPieces.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkPenetrationDepth);

vtkPenetrationDepth::vtkPenetrationDepth()
{
  this->SetNumberOfInputPorts(2);
}

vtkdf::RunStatus vtkPenetrationDepth::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastPenetrationDepth = this->LastSeparationDistance = 0;
  this->LastDirection[0] = this->LastDirection[1] = this->LastDirection[2] = 0;
  this->LastIntersecting = false;
  this->LastPairsTotal = this->LastPairsKept = this->LastPairsBuilt = this->LastFacesVisited = 0;
  vtkdf::ConvexPieceInput solids[2];
  // A distributed run: every rank builds its block of the sums, rank 0 gathers them all
  // (in one process's order) and answers: only rank 0 needs a GPU, and chooses it after
  // the gather (a rank that left before it would leave the others waiting).
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  const int rank = controller ? controller->GetLocalProcessId() : 0;
  if (!this->ReadPieces(vtkDataObject::GetData(inputVector[0], 0), "P", 0, solids[0]) ||
    !this->ReadPieces(vtkDataObject::GetData(inputVector[1], 0), "Q", 1, solids[1]) ||
    (ranks == 1 && !this->ChooseBackend(run)))
  {
    return vtkdf::RunStatus::Failed;
  }
  run.Progress(0.1);

  vtkdf::PenetrationDepth depth;
  depth.Tolerance = 1e-9 * (solids[0].Diagonal + solids[1].Diagonal);
  depth.For = vtkdf::SMPFor;
  depth.Share = rank;
  depth.Shares = ranks;
  const double origin[3] = { 0, 0, 0 };
  vtkdf::UnionClosestPoint sums;
  std::vector<std::pair<int64_t, int64_t>> pairs;
  int64_t total = 0;
  std::string error;
  const bool built =
    depth.BuildSums(solids[0].Pieces, solids[1].Pieces, origin, sums, pairs, total, error);
  this->LastPairsBuilt = built ? static_cast<vtkTypeInt64>(sums.Pieces.size()) : 0;
  if (ranks > 1)
  {
    // Every rank takes part in the gather, a failed one too: rank 0 reports it.
    std::vector<double> mine = vtkdf::PackSums(built, sums.Pieces, pairs);
    vtkNew<vtkDoubleArray> send, received;
    send->SetArray(mine.data(), static_cast<vtkIdType>(mine.size()), 1);
    controller->GatherV(send, received, 0);
    if (rank != 0)
    {
      return vtkdf::RunStatus::Done; // rank 0 answers for all
    }
    sums.Pieces.clear();
    pairs.clear();
    if (!vtkdf::UnpackSums(received->GetPointer(0),
          static_cast<size_t>(received->GetNumberOfValues()),
          ranks,
          sums.Pieces,
          pairs,
          error))
    {
      return run.Fail("No Minkowski sum: " + error + ".");
    }
    if (!this->ChooseBackend(run))
    {
      return vtkdf::RunStatus::Failed;
    }
  }
  else if (!built)
  {
    return run.Fail("No Minkowski sum: " + error + ".");
  }
  run.Progress(0.5);
  vtkdf::HeadlessGL* gl = run.Context();

  vtkdf::PenetrationAnswer answer;
  if (!depth.Query(sums, pairs, total, origin, answer, error, gl))
  {
    return run.Fail((gl ? "The GPU query failed: " : "No answer: ") + error + ".");
  }
  run.Progress(0.9);
  this->WriteAnswer(answer, solids[1], output);
  return vtkdf::RunStatus::Done;
}

void vtkPenetrationDepth::WriteAnswer(const vtkdf::PenetrationAnswer& answer,
  const vtkdf::ConvexPieceInput& q,
  vtkPolyData* output)
{
  const double length = answer.Distance;
  double n[3] = { 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    n[a] = length > 0 ? answer.Translation[a] / length : 0;
  }
  this->LastIntersecting = answer.Intersecting;
  this->LastPenetrationDepth = answer.Intersecting ? length : 0;
  this->LastSeparationDistance = answer.Intersecting ? 0 : length;
  std::copy(n, n + 3, this->LastDirection);
  this->LastPairsTotal = answer.PairsTotal;
  this->LastPairsKept = answer.PairsKept;
  this->LastFacesVisited = answer.FacesVisited;

  // The line: from the witness piece of Q's corner farthest against the direction (the
  // last to leave P), to where the translation takes it.
  double start[3] = { 0, 0, 0 };
  if (answer.PieceQ >= 0)
  {
    const std::vector<double> corners = q.Pieces[answer.PieceQ].Corners();
    double lowest = HUGE_VAL;
    for (size_t k = 0; k < corners.size(); k += 3)
    {
      const double s = n[0] * corners[k] + n[1] * corners[k + 1] + n[2] * corners[k + 2];
      if (s < lowest)
      {
        lowest = s;
        std::copy(&corners[k], &corners[k] + 3, start);
      }
    }
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->InsertNextPoint(start);
  points->InsertNextPoint(start[0] + answer.Translation[0],
    start[1] + answer.Translation[1],
    start[2] + answer.Translation[2]);
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 1 };
  lines->InsertNextCell(2, line);
  output->SetPoints(points);
  output->SetLines(lines);

  vtkFieldData* fields = output->GetFieldData();
  auto scalar = [&](const char* name, double value)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name);
    array->InsertNextValue(value);
    fields->AddArray(array);
  };
  scalar("PenetrationDepth", this->LastPenetrationDepth);
  if (!answer.Intersecting)
  {
    scalar("SeparationDistance", this->LastSeparationDistance);
  }
  vtkNew<vtkDoubleArray> direction;
  direction->SetName("Direction");
  direction->SetNumberOfComponents(3);
  direction->InsertNextTuple(n);
  fields->AddArray(direction);
  vtkNew<vtkUnsignedCharArray> intersecting;
  intersecting->SetName("Intersecting");
  intersecting->InsertNextValue(answer.Intersecting ? 1 : 0);
  fields->AddArray(intersecting);
  vtkNew<vtkIntArray> witness;
  witness->SetName("WitnessPieces");
  witness->SetNumberOfComponents(2);
  const int pair[2] = { static_cast<int>(answer.PieceP), static_cast<int>(answer.PieceQ) };
  witness->InsertNextTypedTuple(pair);
  fields->AddArray(witness);
}

void vtkPenetrationDepth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LastPenetrationDepth: " << this->LastPenetrationDepth << "\n";
  os << indent << "LastSeparationDistance: " << this->LastSeparationDistance << "\n";
  os << indent << "LastDirection: " << this->LastDirection[0] << " " << this->LastDirection[1]
     << " " << this->LastDirection[2] << "\n";
  os << indent << "LastIntersecting: " << this->LastIntersecting << "\n";
  os << indent << "LastPairsTotal: " << this->LastPairsTotal << "\n";
  os << indent << "LastPairsKept: " << this->LastPairsKept << "\n";
  os << indent << "LastPairsBuilt: " << this->LastPairsBuilt << "\n";
}
