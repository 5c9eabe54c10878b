#include "vtkUnionClosestPoint.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "Union/UnionQuery.h"
#include "vtkConvexPieces.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkUnionClosestPoint);

vtkUnionClosestPoint::vtkUnionClosestPoint()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

int vtkUnionClosestPoint::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPartitionedDataSet");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

void vtkUnionClosestPoint::ChangeGenerateViewImages(bool value)
{
  if (this->GenerateViewImages != value)
  {
    this->GenerateViewImages = value;
    this->Modified();
  }
}

void vtkUnionClosestPoint::SetGenerateViewImages(bool value)
{
  this->ChangeGenerateViewImages(value);
}

void vtkUnionClosestPoint::GenerateViewImagesOn()
{
  this->ChangeGenerateViewImages(true);
}

void vtkUnionClosestPoint::GenerateViewImagesOff()
{
  this->ChangeGenerateViewImages(false);
}

int vtkUnionClosestPoint::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    return this->Superclass::FillInputPortInformation(port, info);
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

bool vtkUnionClosestPoint::ReadQueries(vtkInformationVector* queryInput,
  std::vector<double>& queries)
{
  if (auto* points = vtkPointSet::GetData(queryInput, 0))
  {
    queries.resize(3 * points->GetNumberOfPoints());
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      points->GetPoint(i, &queries[3 * i]);
    }
  }
  else
  {
    queries.assign(this->QueryPoint, this->QueryPoint + 3);
  }
  for (size_t i = 0; i < queries.size(); ++i)
  {
    if (!std::isfinite(queries[i]))
    {
      vtkErrorMacro("Query " << i / 3 << " has a coordinate that is not finite.");
      return false;
    }
  }
  return true;
}

vtkdf::RunStatus vtkUnionClosestPoint::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastPieceCount = 0;
  this->LastFacesVisited = 0;
  vtkdf::ConvexPieceInput pieces;
  std::vector<double> o;
  if (!this->ReadPieces(vtkDataObject::GetData(inputVector[0], 0), nullptr, 0, pieces) ||
    !this->ReadQueries(inputVector[1], o) || !this->ChooseBackend(run))
  {
    return vtkdf::RunStatus::Failed;
  }
  if (!vtkPointSet::GetData(inputVector[1], 0) && !vtkdf::IsFirstRank())
  {
    return vtkdf::RunStatus::Done; // QueryPoint in a distributed run: rank 0 answers it, once
  }
  vtkdf::HeadlessGL* gl = run.Context();
  vtkdf::UnionClosestPoint query;
  query.Tolerance = pieces.Tolerance;
  query.Pieces = std::move(pieces.Pieces);
  this->LastPieceCount = static_cast<int>(query.Pieces.size());
  if (this->GenerateViewImages)
  {
    vtkWarningMacro("GenerateViewImages is deprecated: the GPU backend renders no views, "
                    "so output 1 is empty.");
  }
  run.Progress(0.1);
  vtkdf::UnionQueryOptions options;
  options.Threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  std::vector<vtkdf::UnionGPUAnswer> answers;
  bool aborted = false;
  std::string error;
  if (!vtkdf::QueryUnion(query, o, gl, options, run.MakeExecution(), answers, aborted, error))
  {
    return run.Fail("The GPU query failed: " + error + ".");
  }
  if (aborted)
  {
    return run.Empty();
  }
  run.Progress(0.9);
  this->WriteAnswers(o, answers, output);
  return vtkdf::RunStatus::Done;
}

void vtkUnionClosestPoint::WriteAnswers(const std::vector<double>& o,
  const std::vector<vtkdf::UnionGPUAnswer>& answers,
  vtkPolyData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(answers.size());
  vtkNew<vtkPoints> out;
  out->SetDataTypeToDouble();
  out->SetNumberOfPoints(2 * n);
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkFloatArray> distance, closest, direction;
  vtkNew<vtkUnsignedCharArray> inside;
  vtkNew<vtkIntArray> piece;
  distance->SetName("Distance");
  closest->SetName("ClosestPoint");
  closest->SetNumberOfComponents(3);
  direction->SetName("Direction");
  direction->SetNumberOfComponents(3);
  inside->SetName("Inside");
  piece->SetName("ClosestPiece");
  for (vtkIdType k = 0; k < 2 * n; ++k)
  {
    const vtkIdType i = k % n;
    const vtkdf::UnionAnswer& a = answers[i].Answer;
    out->SetPoint(k, k < n ? &o[3 * i] : a.Closest);
    const double length = std::fabs(a.Distance);
    double d[3];
    for (int c = 0; c < 3; ++c)
    {
      d[c] = length > 0 ? (a.Closest[c] - o[3 * i + c]) / length : 0;
    }
    distance->InsertNextValue(static_cast<float>(a.Distance));
    closest->InsertNextTuple(a.Closest);
    direction->InsertNextTuple(d);
    inside->InsertNextValue(a.Inside ? 1 : 0);
    piece->InsertNextValue(static_cast<int>(a.Piece));
    if (k < n)
    {
      const vtkIdType line[2] = { k, k + n };
      lines->InsertNextCell(2, line);
      this->LastFacesVisited += a.FacesVisited;
    }
  }
  output->SetPoints(out);
  output->SetLines(lines);
  vtkPointData* pd = output->GetPointData();
  pd->SetScalars(distance);
  pd->AddArray(closest);
  pd->AddArray(direction);
  pd->AddArray(inside);
  pd->AddArray(piece);
}

void vtkUnionClosestPoint::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "QueryPoint: " << this->QueryPoint[0] << " " << this->QueryPoint[1] << " "
     << this->QueryPoint[2] << "\n";
  os << indent << "GenerateViewImages: " << this->GenerateViewImages << "\n";
  os << indent << "LastPieceCount: " << this->LastPieceCount << "\n";
}
