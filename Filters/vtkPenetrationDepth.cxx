#include "vtkPenetrationDepth.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "GL/HeadlessGL.h"
#include "Union/PenetrationDepth.h"
#include "vtkConvexPieces.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldPartitions.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkPenetrationDepth);

vtkPenetrationDepth::vtkPenetrationDepth()
{
  this->SetNumberOfInputPorts(2);
}

int vtkPenetrationDepth::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  this->LastPenetrationDepth = this->LastSeparationDistance = 0;
  this->LastDirection[0] = this->LastDirection[1] = this->LastDirection[2] = 0;
  this->LastIntersecting = false;
  this->LastErrorBound = 0;
  this->LastPasses = 0;
  this->LastPairsTotal = this->LastPairsKept = this->LastFacesVisited = 0;
  vtkdf::ConvexPieceInput solids[2];
  vtkdf::HeadlessGL* gl = nullptr;
  if (!this->ReadPieces(vtkDataObject::GetData(inputVector[0], 0), "P", 0, solids[0]) ||
    !this->ReadPieces(vtkDataObject::GetData(inputVector[1], 0), "Q", 1, solids[1]) ||
    !this->ChooseBackend(gl))
  {
    return 0;
  }
  if (!vtkdf::IsFirstRank())
  {
    return 1; // in a distributed run, rank 0 gives the one answer
  }
  this->UpdateProgress(0.1);

  vtkdf::PenetrationDepth depth;
  depth.Tolerance = 1e-9 * (solids[0].Diagonal + solids[1].Diagonal);
  depth.For = vtkdf::SMPFor;
  const double origin[3] = { 0, 0, 0 };
  vtkdf::PenetrationAnswer answer;
  std::string error;
  vtkdf::UnionGPUSettings settings;
  settings.Resolution = this->ViewResolution;
  settings.Certify = this->Certify;
  if (!depth.Compute(solids[0].Pieces, solids[1].Pieces, origin, answer, error, gl, settings))
  {
    vtkErrorMacro(<< (gl ? "The GPU query failed: " : "No Minkowski sum: ") << error << ".");
    return 0;
  }
  this->UpdateProgress(0.9);
  this->WriteAnswer(answer, solids[1], output);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPenetrationDepth::WriteAnswer(const vtkdf::PenetrationAnswer& answer,
  const vtkdf::ConvexPieceInput& q,
  vtkPolyData* output)
{
  this->LastPasses = answer.Passes;
  this->LastErrorBound = answer.ErrorBound;
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
  scalar("ErrorBound", answer.ErrorBound);
  scalar("Certified", answer.Certified ? 1 : 0);
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
  os << indent << "LastErrorBound: " << this->LastErrorBound << "\n";
  os << indent << "LastPenetrationDepth: " << this->LastPenetrationDepth << "\n";
  os << indent << "LastSeparationDistance: " << this->LastSeparationDistance << "\n";
  os << indent << "LastDirection: " << this->LastDirection[0] << " " << this->LastDirection[1]
     << " " << this->LastDirection[2] << "\n";
  os << indent << "LastIntersecting: " << this->LastIntersecting << "\n";
  os << indent << "LastPairsTotal: " << this->LastPairsTotal << "\n";
  os << indent << "LastPairsKept: " << this->LastPairsKept << "\n";
}
