#include "vtkUnionClosestPoint.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
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

#include "Union/UnionClosestPoint.h"
#include "Union/UnionClosestPointGPU.h"
#include "vtkConvexPieces.h"
#include "vtkDistanceFieldMesh.h"

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

void vtkUnionClosestPoint::WriteViewImages(const std::vector<float>& images,
  const std::vector<double>& frames,
  const double query[3],
  vtkInformationVector* outputVector)
{
  auto* views = vtkPartitionedDataSet::GetData(outputVector, 1);
  if (!views)
  {
    return;
  }
  const int n = this->ViewResolution;
  views->SetNumberOfPartitions(6);
  for (int v = 0; v < 6; ++v)
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(n, n, 1);
    image->SetOrigin(-1 + 1.0 / n, -1 + 1.0 / n, 0);
    image->SetSpacing(2.0 / n, 2.0 / n, 1);
    vtkNew<vtkFloatArray> distance;
    distance->SetName("Distance");
    distance->SetNumberOfTuples(static_cast<vtkIdType>(n) * n);
    std::copy(images.begin() + static_cast<size_t>(v) * n * n,
      images.begin() + static_cast<size_t>(v + 1) * n * n,
      distance->GetPointer(0));
    image->GetPointData()->SetScalars(distance);
    vtkNew<vtkDoubleArray> frame;
    frame->SetName("ViewFrame");
    frame->SetNumberOfComponents(3);
    for (int k = 0; k < 3; ++k)
    {
      frame->InsertNextTuple(&frames[9 * v + 3 * k]);
    }
    image->GetFieldData()->AddArray(frame);
    vtkNew<vtkDoubleArray> origin;
    origin->SetName("QueryPoint");
    origin->SetNumberOfComponents(3);
    origin->InsertNextTuple(query);
    image->GetFieldData()->AddArray(origin);
    views->SetPartition(v, image);
  }
}

int vtkUnionClosestPoint::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
    info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkUnionClosestPoint::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vtkdf::RunOrEmpty(
    vtkPolyData::GetData(outputVector, 0),
    [&] { return this->Compute(request, inputVector, outputVector); },
    [this](unsigned long code) { this->SetErrorCode(code); });
}

int vtkUnionClosestPoint::Compute(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  this->LastPieceCount = 0;
  this->LastFacesVisited = 0;
  this->LastPasses = 0;
  this->LastBackend = BACKEND_CPU;
  this->LastRenderer.clear();
  if (auto* views = vtkPartitionedDataSet::GetData(outputVector, 1))
  {
    views->Initialize();
  }
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);

  // The pieces, checked (or replaced by their hulls).
  vtkdf::ConvexPieceInput pieces;
  std::string error;
  if (!pieces.Read(input, this->PieceArray, this->UseConvexHulls, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (pieces.Hulls > 0)
  {
    vtkWarningMacro("UseConvexHulls: " << pieces.Hulls << " of " << pieces.Pieces.size()
                                       << " pieces were not closed and convex and were "
                                          "replaced by their convex hulls.");
  }
  vtkdf::UnionClosestPoint query;
  query.Tolerance = pieces.Tolerance;
  query.Pieces = std::move(pieces.Pieces);
  this->LastPieceCount = static_cast<int>(query.Pieces.size());

  // The queries.
  std::vector<double> o;
  if (auto* queries = vtkPointSet::GetData(inputVector[1], 0))
  {
    o.resize(3 * queries->GetNumberOfPoints());
    for (vtkIdType i = 0; i < queries->GetNumberOfPoints(); ++i)
    {
      queries->GetPoint(i, &o[3 * i]);
    }
  }
  else
  {
    o.assign(this->QueryPoint, this->QueryPoint + 3);
  }
  for (size_t i = 0; i < o.size(); ++i)
  {
    if (!std::isfinite(o[i]))
    {
      vtkErrorMacro("Query " << i / 3 << " has a coordinate that is not finite.");
      return 0;
    }
  }
  const vtkIdType n = static_cast<vtkIdType>(o.size() / 3);
  vtkdf::HeadlessGL* gl = nullptr;
  if (!vtkdf::ChooseContext(this->Backend, gl, error))
  {
    vtkErrorMacro(<< error << ".");
    return 0;
  }
  if (this->GenerateViewImages && !gl)
  {
    vtkWarningMacro("GenerateViewImages: the views come from the GPU backend, which this run "
                    "does not use (Backend "
      << (this->Backend == BACKEND_CPU ? "CPU" : "Auto without a hardware GPU")
      << "): output 1 is empty.");
  }
  std::vector<vtkdf::UnionGPUAnswer> answers(n);
  this->UpdateProgress(0.1);
  // Parallel over the queries (or their certification), or over each query's faces when
  // there are too few queries to keep the threads busy.
  const bool fewQueries = n < 4 * vtkSMPTools::GetEstimatedNumberOfThreads();
  if (fewQueries)
  {
    query.For = vtkdf::SMPFor;
  }
  if (gl)
  {
    vtkdf::UnionGPUSettings settings;
    settings.Resolution = this->ViewResolution;
    settings.Certify = this->Certify;
    if (!fewQueries)
    {
      settings.For = vtkdf::SMPFor;
    }
    settings.Progress = [this](double fraction)
    {
      this->UpdateProgress(0.1 + 0.8 * fraction);
      return !this->GetAbortExecute();
    };
    std::vector<float> images;
    std::vector<double> frames;
    const bool views = this->GenerateViewImages && n > 0;
    if (!vtkdf::QueryUnionGPU(*gl,
          query,
          o,
          settings,
          answers,
          error,
          views ? &images : nullptr,
          views ? &frames : nullptr))
    {
      if (this->GetAbortExecute())
      {
        return 1; // aborted: an empty output, no error
      }
      vtkErrorMacro("The GPU query failed: " << error << ".");
      return 0;
    }
    this->LastBackend = BACKEND_GPU;
    this->LastRenderer = gl->Renderer();
    for (const auto& answer : answers)
    {
      this->LastPasses += answer.Passes;
    }
    if (views)
    {
      this->WriteViewImages(images, frames, &o[3 * (n - 1)], outputVector);
    }
  }
  else
  {
    // In twenty blocks, between which progress is told and an abort heard.
    const vtkIdType block = std::max<vtkIdType>(1, (n + 19) / 20);
    for (vtkIdType first = 0; first < n; first += block)
    {
      vtkSMPTools::For(first,
        std::min(n, first + block),
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType i = begin; i < end; ++i)
          {
            answers[i].Answer = query.Query(&o[3 * i]);
            answers[i].Certified = true;
          }
        });
      this->UpdateProgress(0.1 + 0.8 * std::min(n, first + block) / n);
      if (this->GetAbortExecute())
      {
        return 1; // aborted: an empty output, no error
      }
    }
    this->LastBackend = BACKEND_CPU;
    this->LastRenderer = "cpu";
  }
  this->UpdateProgress(0.9);

  vtkNew<vtkPoints> out;
  out->SetDataTypeToDouble();
  out->SetNumberOfPoints(2 * n);
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkFloatArray> distance, closest, direction, bound;
  vtkNew<vtkUnsignedCharArray> inside, certified;
  vtkNew<vtkIntArray> piece;
  certified->SetName("Certified");
  distance->SetName("Distance");
  closest->SetName("ClosestPoint");
  closest->SetNumberOfComponents(3);
  direction->SetName("Direction");
  direction->SetNumberOfComponents(3);
  bound->SetName("ErrorBound");
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
    bound->InsertNextValue(static_cast<float>(answers[i].ErrorBound));
    certified->InsertNextValue(answers[i].Certified ? 1 : 0);
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
  pd->AddArray(bound);
  pd->AddArray(certified);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkUnionClosestPoint::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "QueryPoint: " << this->QueryPoint[0] << " " << this->QueryPoint[1] << " "
     << this->QueryPoint[2] << "\n";
  os << indent << "PieceArray: " << (this->PieceArray.empty() ? "(none)" : this->PieceArray)
     << "\n";
  os << indent << "UseConvexHulls: " << this->UseConvexHulls << "\n";
  os << indent << "Backend: " << this->Backend << "\n";
  os << indent << "ViewResolution: " << this->ViewResolution << "\n";
  os << indent << "Certify: " << this->Certify << "\n";
  os << indent << "GenerateViewImages: " << this->GenerateViewImages << "\n";
  os << indent << "LastBackend: " << this->LastBackend << "\n";
  os << indent << "LastRenderer: " << this->LastRenderer << "\n";
  os << indent << "LastPasses: " << this->LastPasses << "\n";
  os << indent << "LastPieceCount: " << this->LastPieceCount << "\n";
  os << indent << "LastFacesVisited: " << this->LastFacesVisited << "\n";
}
