#include "vtkDistanceFieldPartitions.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>

namespace vtkdf
{
namespace
{
/// A fingerprint of a piece: its sizes and a hash of its points and cells, to tell
/// whether every rank holds the same mesh.
struct Fingerprint
{
  int64_t Points = 0, Cells = 0;
  uint64_t Hash = 1469598103934665603ull; // FNV-1a

  void Add(const void* data, size_t bytes)
  {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i)
    {
      this->Hash = (this->Hash ^ p[i]) * 1099511628211ull;
    }
  }
  explicit Fingerprint(vtkPolyData* mesh)
  {
    this->Points = mesh->GetNumberOfPoints();
    this->Cells = mesh->GetNumberOfCells();
    for (vtkIdType i = 0; i < this->Points; ++i)
    {
      double x[3];
      mesh->GetPoint(i, x);
      this->Add(x, sizeof(x));
    }
    for (vtkCellArray* cells :
      { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(), mesh->GetStrips() })
    {
      const vtkIdType count = cells ? cells->GetNumberOfCells() : 0;
      this->Add(&count, sizeof(count));
      for (vtkIdType c = 0; c < count; ++c)
      {
        vtkIdType n = 0;
        const vtkIdType* ids = nullptr;
        cells->GetCellAtId(c, n, ids);
        this->Add(&n, sizeof(n));
        this->Add(ids, sizeof(vtkIdType) * n);
      }
    }
  }
};

/// One cell of the whole mesh: its kind (the vtkPolyData cell array: 0 verts, 1 lines,
/// 2 polys, 3 strips) and its points' global ids.
struct GlobalCell
{
  int Kind = 0;
  std::vector<vtkIdType> Points;
};

/// The pieces as one mesh in global-id order: points sorted by global id (one per id),
/// cells sorted by global id (one per id) within each cell array.
void Assemble(const std::vector<vtkPolyData*>& pieces, WholeMesh& whole)
{
  std::map<vtkIdType, std::array<double, 3>> points;
  std::map<vtkIdType, GlobalCell> cells;
  int pointType = VTK_FLOAT;
  for (vtkPolyData* piece : pieces)
  {
    vtkDataArray* pointIds = piece->GetPointData()->GetGlobalIds();
    vtkDataArray* cellIds = piece->GetCellData()->GetGlobalIds();
    if (piece->GetPoints())
    {
      pointType = piece->GetPoints()->GetDataType();
    }
    for (vtkIdType i = 0; i < piece->GetNumberOfPoints(); ++i)
    {
      std::array<double, 3> x;
      piece->GetPoint(i, x.data());
      points.emplace(static_cast<vtkIdType>(pointIds->GetTuple1(i)), x);
    }
    vtkIdType cell = 0;
    int kind = 0;
    for (vtkCellArray* array :
      { piece->GetVerts(), piece->GetLines(), piece->GetPolys(), piece->GetStrips() })
    {
      const vtkIdType count = array ? array->GetNumberOfCells() : 0;
      for (vtkIdType c = 0; c < count; ++c, ++cell)
      {
        vtkIdType n = 0;
        const vtkIdType* ids = nullptr;
        array->GetCellAtId(c, n, ids);
        GlobalCell global;
        global.Kind = kind;
        for (vtkIdType k = 0; k < n; ++k)
        {
          global.Points.push_back(static_cast<vtkIdType>(pointIds->GetTuple1(ids[k])));
        }
        cells.emplace(static_cast<vtkIdType>(cellIds->GetTuple1(cell)), std::move(global));
      }
      ++kind;
    }
  }
  vtkNew<vtkPoints> wholePoints;
  wholePoints->SetDataType(pointType);
  wholePoints->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  std::map<vtkIdType, vtkIdType> pointIndex;
  vtkIdType next = 0;
  for (const auto& point : points)
  {
    wholePoints->SetPoint(next, point.second.data());
    pointIndex[point.first] = next++;
  }
  vtkNew<vtkCellArray> arrays[4];
  std::vector<vtkIdType> kindIds[4];
  std::vector<vtkIdType> connectivity;
  for (const auto& cell : cells)
  {
    connectivity.clear();
    for (vtkIdType id : cell.second.Points)
    {
      connectivity.push_back(pointIndex.at(id));
    }
    arrays[cell.second.Kind]->InsertNextCell(
      static_cast<vtkIdType>(connectivity.size()), connectivity.data());
    kindIds[cell.second.Kind].push_back(cell.first);
  }
  whole.Mesh = vtkSmartPointer<vtkPolyData>::New();
  whole.Mesh->SetPoints(wholePoints);
  whole.Mesh->SetVerts(arrays[0]);
  whole.Mesh->SetLines(arrays[1]);
  whole.Mesh->SetPolys(arrays[2]);
  whole.Mesh->SetStrips(arrays[3]);
  // vtkPolyData numbers verts, then lines, polys and strips.
  whole.CellIds.clear();
  for (const auto& ids : kindIds)
  {
    whole.CellIds.insert(whole.CellIds.end(), ids.begin(), ids.end());
  }
  bool identity = true;
  for (size_t i = 0; i < whole.CellIds.size() && identity; ++i)
  {
    identity = whole.CellIds[i] == static_cast<vtkIdType>(i);
  }
  if (identity)
  {
    whole.CellIds.clear();
  }
}

/// The geometry and global ids of a piece, what the ranks send each other.
vtkSmartPointer<vtkPolyData> Shipped(vtkPolyData* input)
{
  auto piece = vtkSmartPointer<vtkPolyData>::New();
  piece->CopyStructure(input);
  if (vtkDataArray* ids = input->GetPointData()->GetGlobalIds())
  {
    piece->GetPointData()->SetGlobalIds(ids);
  }
  if (vtkDataArray* ids = input->GetCellData()->GetGlobalIds())
  {
    piece->GetCellData()->SetGlobalIds(ids);
  }
  return piece;
}
} // namespace

void MeshPiece(int& piece, int& pieces)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  piece = controller ? controller->GetLocalProcessId() : 0;
  pieces = controller ? controller->GetNumberOfProcesses() : 1;
}

bool SameMeshOnEveryRank(vtkPolyData* mesh)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  if (ranks < 2)
  {
    return true;
  }
  const Fingerprint mine(mesh);
  int64_t local[3] = { mine.Points, mine.Cells, static_cast<int64_t>(mine.Hash) };
  std::vector<int64_t> all(3 * static_cast<size_t>(ranks));
  controller->AllGather(local, all.data(), 3);
  for (int r = 0; r < ranks; ++r)
  {
    if (!std::equal(local, local + 3, &all[3 * r]))
    {
      return false;
    }
  }
  return true;
}

bool IsFirstRank()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return !controller || controller->GetLocalProcessId() == 0;
}

bool AssembleWholeMesh(vtkPolyData* input, WholeMesh& whole, std::string& error)
{
  whole = WholeMesh();
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  const bool hasIds = input->GetPointData()->GetGlobalIds() && input->GetCellData()->GetGlobalIds();
  // Whether the ranks hold different pieces (an all-gather of fingerprints).
  bool partitioned = false;
  if (ranks > 1)
  {
    const Fingerprint mine(input);
    int64_t local[4] = { mine.Points, mine.Cells, static_cast<int64_t>(mine.Hash), hasIds };
    std::vector<int64_t> all(4 * static_cast<size_t>(ranks));
    controller->AllGather(local, all.data(), 4);
    int withCells = 0, withCellsAndIds = 0;
    for (int r = 0; r < ranks; ++r)
    {
      partitioned = partitioned || !std::equal(local, local + 3, &all[4 * r]);
      withCells += all[4 * r + 1] > 0 ? 1 : 0;
      withCellsAndIds += (all[4 * r + 1] > 0 && all[4 * r + 3] != 0) ? 1 : 0;
    }
    if (partitioned && withCells > 1 && withCellsAndIds != withCells)
    {
      error = "The input mesh is partitioned across the " + std::to_string(ranks) +
        " ranks (their pieces differ) and has no global point and cell ids on every rank: "
        "the pieces cannot be put back together in one order. Generate them where the mesh "
        "is still whole (ParaView: Generate Global Ids; VTK: vtkGenerateGlobalIds), or "
        "give every rank the whole mesh";
      return false;
    }
    whole.Parts = partitioned ? withCells : 1;
  }
  if (partitioned)
  {
    std::vector<vtkSmartPointer<vtkDataObject>> gathered;
    controller->AllGather(Shipped(input), gathered);
    std::vector<vtkPolyData*> pieces;
    for (const auto& object : gathered)
    {
      vtkPolyData* piece = vtkPolyData::SafeDownCast(object);
      if (piece && piece->GetNumberOfCells() > 0)
      {
        pieces.push_back(piece);
      }
    }
    if (pieces.size() == 1 &&
      !(pieces[0]->GetPointData()->GetGlobalIds() && pieces[0]->GetCellData()->GetGlobalIds()))
    {
      // One rank holds the whole mesh (a reader of a one-piece file gives the others
      // nothing), without ids: every rank takes it as it is.
      whole.Mesh = pieces[0];
      whole.Parts = 1;
      return true;
    }
    Assemble(pieces, whole);
    return true;
  }
  if (hasIds)
  {
    Assemble({ input }, whole);
    return true;
  }
  whole.Mesh = input;
  return true;
}

} // namespace vtkdf
