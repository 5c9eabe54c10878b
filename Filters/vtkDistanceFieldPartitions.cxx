#include "vtkDistanceFieldPartitions.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace vtkdf
{
namespace
{
/// The field-data arrays that carry a piece's extent, origin and spacing through
/// GatherWholeImage.
const char* const PieceExtentName = "vtkdfPieceExtent";
const char* const PieceGridName = "vtkdfPieceGrid";

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

bool BothMeshesOnEveryRank(vtkPolyData* const meshes[2], const char* noun, std::string& error)
{
  for (int port = 0; port < 2; ++port)
  {
    if (meshes[port] && !SameMeshOnEveryRank(meshes[port]))
    {
      error = std::string(noun) + (port == 0 ? " A" : " B") + " (input " + std::to_string(port) +
        ") differs between the ranks of this distributed run (it was partitioned upstream): "
        "every rank needs both inputs whole.";
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

namespace
{
/// A piece of an image as it travels between ranks: the named arrays only, its extent
/// and its grid (origin, spacing) in binary field data (an image is sent as dimensions
/// and origin, from extent 0; as text the grid would be rounded).
vtkSmartPointer<vtkImageData> PieceToSend(vtkImageData* piece,
  const std::vector<std::string>& arrays)
{
  vtkNew<vtkImageData> send;
  if (!piece)
  {
    return send.Get();
  }
  send->SetExtent(piece->GetExtent());
  send->SetOrigin(piece->GetOrigin());
  send->SetSpacing(piece->GetSpacing());
  send->GetFieldData()->ShallowCopy(piece->GetFieldData());
  vtkNew<vtkIntArray> extent;
  extent->SetName(PieceExtentName);
  extent->SetNumberOfValues(6);
  for (int a = 0; a < 6; ++a)
  {
    extent->SetValue(a, piece->GetExtent()[a]);
  }
  send->GetFieldData()->AddArray(extent);
  vtkNew<vtkDoubleArray> grid;
  grid->SetName(PieceGridName);
  grid->SetNumberOfValues(6);
  for (int a = 0; a < 3; ++a)
  {
    grid->SetValue(a, piece->GetOrigin()[a]);
    grid->SetValue(3 + a, piece->GetSpacing()[a]);
  }
  send->GetFieldData()->AddArray(grid);
  for (const std::string& name : arrays)
  {
    if (vtkDataArray* array = piece->GetPointData()->GetArray(name.c_str()))
    {
      send->GetPointData()->AddArray(array);
    }
  }
  return send.Get();
}

/// The extent `e` and grid (origin, spacing) a received piece came with; false with
/// `error` when it lacks them or lies outside `wholeExtent`.
bool ReceivedExtent(vtkImageData* part,
  const int wholeExtent[6],
  int e[6],
  vtkDoubleArray*& grid,
  std::string& error)
{
  vtkIntArray* extent = vtkIntArray::SafeDownCast(part->GetFieldData()->GetArray(PieceExtentName));
  if (!extent || extent->GetNumberOfValues() != 6)
  {
    error = "a rank's piece of the image came without its extent";
    return false;
  }
  for (int a = 0; a < 6; ++a)
  {
    e[a] = extent->GetValue(a);
  }
  grid = vtkDoubleArray::SafeDownCast(part->GetFieldData()->GetArray(PieceGridName));
  if (!grid || grid->GetNumberOfValues() != 6)
  {
    error = "a rank's piece of the image came without its grid";
    return false;
  }
  if (e[0] < wholeExtent[0] || e[1] > wholeExtent[1] || e[2] < wholeExtent[2] ||
    e[3] > wholeExtent[3] || e[4] < wholeExtent[4] || e[5] > wholeExtent[5])
  {
    error = "a rank's piece of the image lies outside its whole extent";
    return false;
  }
  return true;
}

/// The point arrays of `part` (extent `e`) copied into `image` (extent `wholeExtent`),
/// row by row, the arrays made at their first piece; `filled` marks the samples written.
void CopyPiece(vtkImageData* part,
  const int e[6],
  const int wholeExtent[6],
  vtkImageData* image,
  std::vector<uint8_t>& filled)
{
  const vtkIdType n = image->GetNumberOfPoints();
  const int nx = wholeExtent[1] - wholeExtent[0] + 1, ny = wholeExtent[3] - wholeExtent[2] + 1;
  vtkPointData* from = part->GetPointData();
  for (int a = 0; a < from->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* source = from->GetArray(a);
    vtkDataArray* target = image->GetPointData()->GetArray(source->GetName());
    if (!target)
    {
      vtkSmartPointer<vtkDataArray> created;
      created.TakeReference(source->NewInstance());
      created->SetName(source->GetName());
      created->SetNumberOfComponents(source->GetNumberOfComponents());
      created->SetNumberOfTuples(n);
      image->GetPointData()->AddArray(created);
      target = created;
    }
    const bool sameType = target->GetDataType() == source->GetDataType() &&
      target->GetNumberOfComponents() == source->GetNumberOfComponents();
    const int row = e[1] - e[0] + 1;
    const size_t rowBytes = static_cast<size_t>(row) * source->GetNumberOfComponents() *
      static_cast<size_t>(source->GetDataTypeSize());
    vtkIdType at = 0;
    for (int k = e[4]; k <= e[5]; ++k)
    {
      for (int j = e[2]; j <= e[3]; ++j, at += row)
      {
        const vtkIdType v = (vtkIdType(k - wholeExtent[4]) * ny + (j - wholeExtent[2])) * nx +
          (e[0] - wholeExtent[0]);
        if (sameType)
        {
          std::memcpy(target->GetVoidPointer(v * target->GetNumberOfComponents()),
            source->GetVoidPointer(at * source->GetNumberOfComponents()),
            rowBytes);
        }
        else
        {
          for (int i = 0; i < row; ++i)
          {
            target->SetTuple(v + i, at + i, source);
          }
        }
        std::fill(filled.begin() + v, filled.begin() + v + row, uint8_t(1));
      }
    }
  }
}
} // namespace

bool GatherWholeImage(vtkImageData* piece,
  const int wholeExtent[6],
  const std::vector<std::string>& arrays,
  vtkSmartPointer<vtkImageData>& whole,
  std::string& error,
  bool everyRank)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() < 2)
  {
    whole = piece;
    return true;
  }
  // Only the named arrays travel.
  const vtkSmartPointer<vtkImageData> send = PieceToSend(piece, arrays);
  std::vector<vtkSmartPointer<vtkDataObject>> received;
  if (everyRank)
  {
    controller->AllGather(send, received);
  }
  else
  {
    controller->Gather(send, received, 0);
  }
  whole = nullptr;
  if (!everyRank && controller->GetLocalProcessId() != 0)
  {
    return true;
  }
  vtkNew<vtkImageData> image;
  image->SetExtent(const_cast<int*>(wholeExtent));
  bool described = false; // origin, spacing and field data from the first piece
  std::vector<uint8_t> filled(static_cast<size_t>(image->GetNumberOfPoints()), 0);
  for (const auto& object : received)
  {
    vtkImageData* part = vtkImageData::SafeDownCast(object);
    if (!part || part->GetNumberOfPoints() == 0)
    {
      continue;
    }
    int e[6];
    vtkDoubleArray* grid = nullptr;
    if (!ReceivedExtent(part, wholeExtent, e, grid, error))
    {
      return false;
    }
    if (!described)
    {
      image->SetOrigin(grid->GetValue(0), grid->GetValue(1), grid->GetValue(2));
      image->SetSpacing(grid->GetValue(3), grid->GetValue(4), grid->GetValue(5));
      image->GetFieldData()->ShallowCopy(part->GetFieldData());
      image->GetFieldData()->RemoveArray(PieceExtentName);
      image->GetFieldData()->RemoveArray(PieceGridName);
      described = true;
    }
    CopyPiece(part, e, wholeExtent, image, filled);
  }
  if (std::find(filled.begin(), filled.end(), 0) != filled.end())
  {
    error = "the ranks' pieces of the image leave samples of its whole extent out";
    return false;
  }
  whole = image;
  return true;
}

} // namespace vtkdf
