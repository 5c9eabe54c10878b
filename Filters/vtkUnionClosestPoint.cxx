#include "vtkUnionClosestPoint.h"

#include "vtkCellArray.h"
#include "vtkErrorCode.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include "UnionClosestPoint.h"
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
  // A failure leaves the output empty and says so in the error code (as the module's
  // other filters do), for callers that do not observe ErrorEvent.
  this->SetErrorCode(vtkErrorCode::NoError);
  const int ok = this->Compute(request, inputVector, outputVector);
  if (!ok)
  {
    vtkPolyData::GetData(outputVector, 0)->Initialize();
    this->SetErrorCode(vtkErrorCode::UserError);
  }
  return ok;
}

int vtkUnionClosestPoint::Compute(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  this->LastPieceCount = 0;
  this->LastFacesVisited = 0;
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
  std::vector<vtkdf::UnionAnswer> answers(n);
  // Parallel over the queries, or over each query's faces when there are too few queries
  // to keep the threads busy.
  if (n < 4 * vtkSMPTools::GetEstimatedNumberOfThreads())
  {
    query.For = vtkdf::SMPFor;
  }
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        answers[i] = query.Query(&o[3 * i]);
      }
    });

  vtkNew<vtkPoints> out;
  out->SetDataTypeToDouble();
  out->SetNumberOfPoints(2 * n);
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkFloatArray> distance, closest, direction, bound;
  vtkNew<vtkUnsignedCharArray> inside;
  vtkNew<vtkIntArray> piece;
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
    const vtkdf::UnionAnswer& a = answers[i];
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
    bound->InsertNextValue(0);
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
  os << indent << "LastPieceCount: " << this->LastPieceCount << "\n";
  os << indent << "LastFacesVisited: " << this->LastFacesVisited << "\n";
}
