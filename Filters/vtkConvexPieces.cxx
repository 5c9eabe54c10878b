#include "vtkConvexPieces.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include "Union/ConvexHull.h"
#include "vtkDistanceFieldMeshInput.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

namespace vtkdf
{

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
/// The diagonal of the box of the points the faces use (xyz triples in `points`).
double FacesDiagonal(const std::vector<double>& points,
  const std::vector<std::vector<int64_t>>& faces)
{
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const auto& face : faces)
  {
    for (const int64_t id : face)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], points[3 * id + a]);
        hi[a] = std::max(hi[a], points[3 * id + a]);
      }
    }
  }
  return faces.empty() ? 0
                       : std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
                           (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/// The pieces' cells: the connected components of one mesh (or its cells by piece id,
/// `pieceArray`), or the leaves of a composite. False with `error`.
bool ReadPieceCells(vtkDataObject* input,
  const std::string& pieceArray,
  std::vector<PieceCells>& cells,
  std::string& error)
{
  if (auto* mesh = vtkPolyData::SafeDownCast(input))
  {
    double bounds[6];
    if (mesh->GetNumberOfPolys() > 0 && !UsedPointBounds(mesh, bounds, error))
    {
      return false;
    }
    std::vector<std::vector<std::vector<int64_t>>> pieces;
    if (!pieceArray.empty())
    {
      if (!PiecesByArray(mesh, pieceArray, pieces, error))
      {
        error += ".";
        return false;
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
        error = "Leaf " + std::to_string(cells.size()) + " of the input is not a vtkPolyData.";
        return false;
      }
      double bounds[6];
      if (leaf->GetNumberOfPolys() > 0 && !UsedPointBounds(leaf, bounds, error))
      {
        error = "Leaf " + std::to_string(cells.size()) + ": " + error;
        return false;
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
    auto* mesh = vtkPolyData::SafeDownCast(input);
    error = mesh && mesh->GetNumberOfPoints() > 0
      ? "The input has " + std::to_string(mesh->GetNumberOfPoints()) +
        " points but no polygons: there is no union of convex pieces (UseConvexHulls takes "
        "the hull of each piece's polygons, not of points alone)."
      : std::string("The input has no polygons: there is no union of convex pieces.");
    return false;
  }
  return true;
}

/// The convex hull (qhull) of the points that `faces` use, as `piece`; false with `error`.
bool BuildHull(const std::vector<double>& points,
  const std::vector<std::vector<int64_t>>& faces,
  double tolerance,
  ConvexPiece& piece,
  std::string& error)
{
  std::vector<int64_t> used;
  for (const auto& face : faces)
  {
    used.insert(used.end(), face.begin(), face.end());
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<double> corners;
  for (const int64_t id : used)
  {
    corners.insert(corners.end(), &points[3 * id], &points[3 * id] + 3);
  }
  std::vector<std::vector<int64_t>> hull;
  int64_t onHull = 0;
  return ConvexHull(corners, hull, onHull, error) && piece.Build(corners, hull, tolerance, error);
}
} // namespace

bool ConvexPieceInput::Read(vtkDataObject* input,
  const std::string& pieceArray,
  bool useHulls,
  std::string& error)
{
  this->Pieces.clear();
  this->Diagonal = 0;
  this->Tolerance = 0;
  this->ConvexityTolerance = 0;
  this->Hulls = 0;
  std::vector<PieceCells> cells;
  if (!ReadPieceCells(input, pieceArray, cells, error))
  {
    return false;
  }
  // Coordinates checked, and the tolerance from the pieces' size.
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  std::vector<std::vector<double>> points(cells.size());
  for (size_t p = 0; p < cells.size(); ++p)
  {
    double bounds[6];
    if (!UsedPointBounds(cells[p].Mesh, bounds, error))
    {
      error = "Piece " + std::to_string(p) + ": " + error;
      return false;
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
  this->Diagonal = diagonal;
  this->Tolerance = 1e-9 * diagonal;
  bool single = false;
  for (const PieceCells& piece : cells)
  {
    single = single || piece.Mesh->GetPoints()->GetDataType() != VTK_DOUBLE;
  }
  const double relativeTolerance = single ? 1e-6 : 1e-9;
  this->ConvexityTolerance = relativeTolerance * diagonal;
  for (size_t p = 0; p < cells.size(); ++p)
  {
    // Points repeated a rounding apart (an exported hull's unshared points) made one,
    // within the convexity tolerance relative to the piece's own size; the slivers
    // between them dropped.
    MergeNearCorners(
      points[p], cells[p].Faces, relativeTolerance * FacesDiagonal(points[p], cells[p].Faces));
    ConvexPiece piece;
    std::string why;
    if (piece.Build(points[p], cells[p].Faces, this->ConvexityTolerance, why))
    {
      this->Pieces.push_back(std::move(piece));
      continue;
    }
    if (!useHulls)
    {
      error = "Piece " + std::to_string(p) + " is not a closed convex polytope: " + why +
        " (UseConvexHulls would take its convex hull).";
      return false;
    }
    // Its convex hull instead: of the points its polygons use.
    std::string hullError;
    if (!BuildHull(points[p], cells[p].Faces, this->ConvexityTolerance, piece, hullError))
    {
      error = "Piece " + std::to_string(p) + " is not a closed convex polytope (" + why +
        ") and has no convex hull: " + hullError + ".";
      return false;
    }
    this->Pieces.push_back(std::move(piece));
    ++this->Hulls;
  }
  return true;
}

} // namespace vtkdf
