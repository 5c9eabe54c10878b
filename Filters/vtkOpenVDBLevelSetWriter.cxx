#include "vtkOpenVDBLevelSetWriter.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include "LevelSet/OpenVDBLevelSet.h"

#include <dlfcn.h>

#include <cmath>
#include <mutex>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkOpenVDBLevelSetWriter);

namespace
{
/// The level set's writer, from the module beside this library (DF_LEVELSET_MODULE,
/// loaded once, never unloaded: OpenVDB keeps its registries for the process); null and
/// `error` when it cannot be loaded.
vtkdf::WriteOpenVDBLevelSetFunction LoadLevelSetWriter(std::string& error)
{
  static std::mutex mutex;
  static vtkdf::WriteOpenVDBLevelSetFunction function = nullptr;
  const std::lock_guard<std::mutex> lock(mutex);
  if (function)
  {
    return function;
  }
  Dl_info self;
  if (!dladdr(reinterpret_cast<void*>(&LoadLevelSetWriter), &self) || !self.dli_fname)
  {
    error = "Cannot find the folder of the library that holds the .vdb writer.";
    return nullptr;
  }
  std::string path = self.dli_fname;
  path = path.substr(0, path.rfind('/') + 1) + DF_LEVELSET_MODULE;
  void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  void* symbol = module ? dlsym(module, vtkdf::WriteOpenVDBLevelSetSymbol) : nullptr;
  if (!symbol)
  {
    const char* why = dlerror();
    error = "Cannot load OpenVDB's writer " + path + " (" + (why ? why : "no entry point") + ").";
    return nullptr;
  }
  function = reinterpret_cast<vtkdf::WriteOpenVDBLevelSetFunction>(symbol);
  return function;
}

/// A piece as the core reads it; false and `error` when it lacks what a level set needs.
bool PieceBrick(vtkImageData* piece,
  unsigned index,
  vtkdf::LevelSetBrick& brick,
  std::string& error)
{
  const std::string which = "Piece " + std::to_string(index);
  if (!piece)
  {
    error = which + " is not a vtkImageData.";
    return false;
  }
  vtkPointData* pd = piece->GetPointData();
  auto* distance = vtkFloatArray::SafeDownCast(pd->GetArray("Distance"));
  auto* hidden =
    vtkUnsignedCharArray::SafeDownCast(pd->GetArray(vtkDataSetAttributes::GhostArrayName()));
  const vtkIdType n = piece->GetNumberOfPoints();
  if (!distance || !hidden || distance->GetNumberOfTuples() != n ||
    hidden->GetNumberOfTuples() != n || distance->GetNumberOfComponents() != 1)
  {
    error = which + " has no float Distance and ghost array of a value a sample.";
    return false;
  }
  int e[6];
  piece->GetExtent(e);
  for (int a = 0; a < 3; ++a)
  {
    brick.Extent.Lo[a] = e[2 * a];
    brick.Extent.Hi[a] = e[2 * a + 1];
  }
  brick.Distance = distance->GetPointer(0);
  brick.Hidden = hidden->GetPointer(0);
  auto* closest = vtkFloatArray::SafeDownCast(pd->GetArray("ClosestPoint"));
  if (closest && closest->GetNumberOfComponents() == 3 && closest->GetNumberOfTuples() == n)
  {
    brick.ClosestPoint = closest->GetPointer(0);
  }
  return true;
}

/// The grid's origin and cubic voxel from a piece; false and `error` when its spacings differ.
bool VoxelGrid(vtkImageData* piece, vtkdf::LevelSetGrid& grid, std::string& error)
{
  const double* spacing = piece->GetSpacing();
  const double* origin = piece->GetOrigin();
  if (!(spacing[0] > 0) || spacing[1] != spacing[0] || spacing[2] != spacing[0])
  {
    error = "A level set's voxels are cubes: the grid's spacings (" + std::to_string(spacing[0]) +
      ", " + std::to_string(spacing[1]) + ", " + std::to_string(spacing[2]) +
      ") must be equal and positive.";
    return false;
  }
  grid.VoxelSize = spacing[0];
  grid.Origin = { { origin[0], origin[1], origin[2] } };
  return true;
}

/// The sides of the bricks without pieces, from vtkSparseDistanceField's output 1.
bool BrickSides(vtkImageData* sides, double voxel, vtkdf::LevelSetGrid& grid, std::string& error)
{
  vtkDataArray* side = sides->GetCellData()->GetArray("Side");
  int dims[3];
  sides->GetDimensions(dims);
  const double brick = sides->GetSpacing()[0] / voxel;
  grid.BrickSize = static_cast<int>(std::lround(brick));
  if (!side || side->GetNumberOfTuples() != sides->GetNumberOfCells() || grid.BrickSize < 1 ||
    std::fabs(brick - grid.BrickSize) > 1e-6 * brick)
  {
    error = "The sides (input 1) are not vtkSparseDistanceField's: a Side cell array, a cell "
            "per brick of a whole number of samples.";
    return false;
  }
  grid.BrickCounts = { { dims[0] - 1, dims[1] - 1, dims[2] - 1 } };
  grid.Sides.resize(static_cast<size_t>(side->GetNumberOfTuples()));
  for (vtkIdType c = 0; c < side->GetNumberOfTuples(); ++c)
  {
    grid.Sides[c] = static_cast<int8_t>(side->GetTuple1(c));
  }
  return true;
}
} // namespace

vtkOpenVDBLevelSetWriter::vtkOpenVDBLevelSetWriter()
{
  this->SetNumberOfInputPorts(2);
}

int vtkOpenVDBLevelSetWriter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(
    vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPartitionedDataSet" : "vtkImageData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

void vtkOpenVDBLevelSetWriter::WriteData()
{
  this->LastActiveVoxels = this->LastLeafNodes = 0;
  auto fail = [this](const std::string& error)
  {
    vtkErrorMacro(<< error);
    this->SetErrorCode(vtkErrorCode::UserError);
  };
  auto* pieces = vtkPartitionedDataSet::SafeDownCast(this->GetInputDataObject(0, 0));
  if (this->FileName.empty())
  {
    return fail("No FileName: set the .vdb file to write.");
  }
  vtkDataArray* bandWidth = pieces ? pieces->GetFieldData()->GetArray("BandWidth") : nullptr;
  if (!pieces || !bandWidth || bandWidth->GetNumberOfTuples() < 1 || !(bandWidth->GetTuple1(0) > 0))
  {
    return fail("The input is not vtkSparseDistanceField's pieces: no BandWidth field data.");
  }
  if (pieces->GetNumberOfPartitions() == 0)
  {
    return fail("The input has no pieces: no sample lies within the band.");
  }
  vtkdf::LevelSetGrid grid;
  grid.Name = this->GridName;
  grid.Background = static_cast<float>(bandWidth->GetTuple1(0));
  std::vector<vtkdf::LevelSetBrick> bricks(pieces->GetNumberOfPartitions());
  std::string error;
  for (unsigned p = 0; p < pieces->GetNumberOfPartitions(); ++p)
  {
    auto* piece = vtkImageData::SafeDownCast(pieces->GetPartition(p));
    if (!PieceBrick(piece, p, bricks[p], error) || (p == 0 && !VoxelGrid(piece, grid, error)))
    {
      return fail(error);
    }
  }
  auto* sides = vtkImageData::SafeDownCast(this->GetInputDataObject(1, 0));
  if (sides && !BrickSides(sides, grid.VoxelSize, grid, error))
  {
    return fail(error);
  }
  const vtkdf::WriteOpenVDBLevelSetFunction writeLevelSet = LoadLevelSetWriter(error);
  if (!writeLevelSet)
  {
    return fail(error);
  }
  vtkdf::LevelSetSummary summary;
  if (!writeLevelSet(this->FileName, grid, bricks, summary, error))
  {
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    vtkErrorMacro(<< error);
    return;
  }
  this->LastActiveVoxels = summary.ActiveVoxels;
  this->LastLeafNodes = summary.LeafNodes;
}

void vtkOpenVDBLevelSetWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "LastActiveVoxels: " << this->LastActiveVoxels << "\n";
  os << indent << "LastLeafNodes: " << this->LastLeafNodes << "\n";
}
