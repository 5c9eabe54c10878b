#include "vtkUnionClosestPoint.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkErrorCode.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
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
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "ConvexHull.h"
#include "UnionClosestPoint.h"
#include "vtkDistanceFieldMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkUnionClosestPoint);

namespace
{
/// A piece: the points of its mesh and its polygons (point ids).
struct PieceCells
{
  vtkPolyData* Mesh;
  std::vector<std::vector<int64_t>> Faces;
};

/// Per point of `mesh`, the lowest id of a point at the same position.
std::vector<int64_t> SamePositions(vtkPolyData* mesh)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<int64_t> order(n), key(n);
  std::iota(order.begin(), order.end(), 0);
  std::iota(key.begin(), key.end(), 0);
  std::vector<std::array<double, 3>> x(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    mesh->GetPoint(i, x[i].data());
  }
  // NaN coordinates are refused before (UsedPointBounds): the order is strict here.
  std::sort(order.begin(),
    order.end(),
    [&](int64_t a, int64_t b) { return x[a] != x[b] ? x[a] < x[b] : a < b; });
  for (size_t i = 1; i < order.size(); ++i)
  {
    if (x[order[i]] == x[order[i - 1]])
    {
      key[order[i]] = key[order[i - 1]];
    }
  }
  return key;
}

/// The polygons of `mesh`, grouped by connected component (cells sharing a point id: so
/// touching pieces stay apart), in the order of each component's lowest cell id; within
/// a piece, ids of one position are made one (for the closedness check).
std::vector<std::vector<std::vector<int64_t>>> Components(vtkPolyData* mesh)
{
  const std::vector<int64_t> key = SamePositions(mesh);
  std::vector<std::vector<int64_t>> polygons;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType count;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(count, ids);)
  {
    polygons.emplace_back(ids, ids + count);
  }
  std::vector<int64_t> parent(mesh->GetNumberOfPoints());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int64_t x)
  {
    while (parent[x] != x)
    {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  };
  for (const auto& polygon : polygons)
  {
    for (size_t k = 1; k < polygon.size(); ++k)
    {
      const int64_t a = find(polygon[0]), b = find(polygon[k]);
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::vector<std::vector<int64_t>>> pieces;
  std::vector<int64_t> pieceOfRoot(parent.size(), -1);
  for (const auto& polygon : polygons)
  {
    if (polygon.empty())
    {
      continue;
    }
    const int64_t root = find(polygon[0]);
    if (pieceOfRoot[root] < 0)
    {
      pieceOfRoot[root] = static_cast<int64_t>(pieces.size());
      pieces.emplace_back();
    }
    std::vector<int64_t> merged(polygon.size());
    for (size_t k = 0; k < polygon.size(); ++k)
    {
      merged[k] = key[polygon[k]];
    }
    pieces[pieceOfRoot[root]].push_back(merged);
  }
  return pieces;
}
/// The polygons of `mesh` grouped by the value of the cell-data array `ids` (pieces in the
/// order of their lowest cell id), position-merged like Components; false with `error`
/// when the array is missing, not one component, or not integral.
bool PiecesByArray(vtkPolyData* mesh,
  const std::string& name,
  std::vector<std::vector<std::vector<int64_t>>>& pieces,
  std::string& error)
{
  vtkDataArray* ids = mesh->GetCellData()->GetArray(name.c_str());
  if (!ids || ids->GetNumberOfComponents() != 1 ||
    ids->GetNumberOfTuples() != mesh->GetNumberOfCells())
  {
    error = "PieceArray '" + name + "' is not a one-component cell-data array of the input";
    return false;
  }
  const std::vector<int64_t> key = SamePositions(mesh);
  std::map<double, size_t> pieceOfId;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    const int type = mesh->GetCellType(c);
    if (type != VTK_TRIANGLE && type != VTK_POLYGON && type != VTK_QUAD)
    {
      continue;
    }
    const double id = ids->GetTuple1(c);
    if (!std::isfinite(id) || id != std::floor(id))
    {
      error = "PieceArray '" + name + "' holds a value that is not an integer (cell " +
        std::to_string(c) + ")";
      return false;
    }
    const auto found = pieceOfId.emplace(id, pieces.size());
    if (found.second)
    {
      pieces.emplace_back();
    }
    mesh->GetCellPoints(c, cell);
    std::vector<int64_t> polygon(cell->GetNumberOfIds());
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
    {
      polygon[k] = key[cell->GetId(k)];
    }
    pieces[found.first->second].push_back(std::move(polygon));
  }
  return true;
}
} // namespace

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

  // The pieces: connected components of one mesh, or the leaves of a composite.
  std::vector<PieceCells> cells;
  if (auto* mesh = vtkPolyData::SafeDownCast(input))
  {
    double bounds[6];
    std::string error;
    if (mesh->GetNumberOfPolys() > 0 && !vtkdf::UsedPointBounds(mesh, bounds, error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    std::vector<std::vector<std::vector<int64_t>>> pieces;
    if (!this->PieceArray.empty())
    {
      if (!PiecesByArray(mesh, this->PieceArray, pieces, error))
      {
        vtkErrorMacro(<< error << ".");
        return 0;
      }
    }
    else
    {
      pieces = Components(mesh);
    }
    for (auto& faces : pieces)
    {
      cells.push_back({ mesh, std::move(faces) });
    }
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      auto* leaf = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
      if (!leaf)
      {
        vtkErrorMacro("Leaf " << cells.size() << " of the input is not a vtkPolyData.");
        return 0;
      }
      double bounds[6];
      std::string error;
      if (leaf->GetNumberOfPolys() > 0 && !vtkdf::UsedPointBounds(leaf, bounds, error))
      {
        vtkErrorMacro("Leaf " << cells.size() << ": " << error);
        return 0;
      }
      PieceCells piece{ leaf, {} };
      for (auto& faces : Components(leaf))
      {
        piece.Faces.insert(piece.Faces.end(), faces.begin(), faces.end());
      }
      cells.push_back(std::move(piece));
    }
  }
  if (cells.empty())
  {
    vtkErrorMacro("The input has no polygons: there is no union of convex pieces.");
    return 0;
  }

  // Coordinates checked, and the tolerance from the pieces' size.
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  std::vector<std::vector<double>> points(cells.size());
  for (size_t p = 0; p < cells.size(); ++p)
  {
    double bounds[6];
    std::string error;
    if (!vtkdf::UsedPointBounds(cells[p].Mesh, bounds, error))
    {
      vtkErrorMacro("Piece " << p << ": " << error);
      return 0;
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], bounds[2 * a]);
      hi[a] = std::max(hi[a], bounds[2 * a + 1]);
    }
    vtkPoints* pts = cells[p].Mesh->GetPoints();
    points[p].resize(3 * pts->GetNumberOfPoints());
    for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
    {
      pts->GetPoint(i, &points[p][3 * i]);
    }
  }
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  vtkdf::UnionClosestPoint query;
  query.Tolerance = 1e-9 * diagonal;
  int hulls = 0;
  for (size_t p = 0; p < cells.size(); ++p)
  {
    vtkdf::ConvexPiece piece;
    std::string error;
    if (piece.Build(points[p], cells[p].Faces, query.Tolerance, error))
    {
      query.Pieces.push_back(std::move(piece));
      continue;
    }
    if (!this->UseConvexHulls)
    {
      vtkErrorMacro("Piece " << p << " is not a closed convex polytope: " << error
                             << " (UseConvexHulls would take its convex hull).");
      return 0;
    }
    // Its convex hull instead: of the points its polygons use.
    std::vector<int64_t> used;
    for (const auto& face : cells[p].Faces)
    {
      used.insert(used.end(), face.begin(), face.end());
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::vector<double> corners;
    for (const int64_t id : used)
    {
      corners.insert(corners.end(), &points[p][3 * id], &points[p][3 * id] + 3);
    }
    std::vector<std::vector<int64_t>> hull;
    int64_t onHull = 0;
    std::string hullError;
    if (!vtkdf::ConvexHull(corners, hull, onHull, hullError) ||
      !piece.Build(corners, hull, query.Tolerance, hullError))
    {
      vtkErrorMacro("Piece " << p << " is not a closed convex polytope (" << error
                             << ") and has no convex hull: " << hullError << ".");
      return 0;
    }
    query.Pieces.push_back(std::move(piece));
    ++hulls;
  }
  if (hulls > 0)
  {
    vtkWarningMacro("UseConvexHulls: " << hulls << " of " << cells.size()
                                       << " pieces were not closed and convex and were "
                                          "replaced by their convex hulls.");
  }
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
