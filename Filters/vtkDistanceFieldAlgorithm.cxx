#include "vtkDistanceFieldAlgorithm.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCellArray.h"
#include "vtkDataSet.h"
#include "vtkErrorCode.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "GL/HeadlessGL.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldMeshInput.h"
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

#include <vtksys/SystemInformation.hxx>

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>

static_assert(vtkdf::SameBackendValues<vtkDistanceFieldAlgorithm>(),
  "Backend values differ from BackendChoice");

vtkDistanceFieldAlgorithm::vtkDistanceFieldAlgorithm()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

int vtkDistanceFieldAlgorithm::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (this->AcceptsImageInput)
  {
    info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  }
  return 1;
}

void vtkDistanceFieldAlgorithm::ComputeDefaultGrid(const double bounds[6],
  int resolution,
  double padding,
  double origin[3],
  double spacing[3],
  int dimensions[3])
{
  const vtkdf::SampleGrid grid = vtkdf::SampleGrid::FromBounds(bounds, resolution, padding);
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = grid.Origin[a];
    spacing[a] = grid.Spacing[a];
    dimensions[a] = grid.Whole.Hi[a] + 1;
  }
}

bool vtkDistanceFieldAlgorithm::MeshBounds(vtkPolyData* mesh, double bounds[6], std::string& error)
{
  if (!(this->BoundsMesh == mesh && this->BoundsTime == mesh->GetMTime()))
  {
    this->BoundsMesh = mesh;
    this->BoundsTime = mesh->GetMTime();
    this->BoundsError.clear();
    this->BoundsValid = vtkdf::UsedPointBounds(mesh, this->Bounds, this->BoundsError);
  }
  std::copy(this->Bounds, this->Bounds + 6, bounds);
  error = this->BoundsError;
  return this->BoundsValid;
}

bool vtkDistanceFieldAlgorithm::InputMesh(vtkPolyData*& mesh)
{
  if (!mesh)
  {
    return true;
  }
  if (!(this->WholeInput == mesh && this->WholeInputTime == mesh->GetMTime()))
  {
    this->WholeInput = mesh;
    this->WholeInputTime = mesh->GetMTime();
    vtkdf::WholeMesh whole;
    this->WholeError.clear();
    vtkdf::AssembleWholeMesh(mesh, whole, this->WholeError);
    this->WholeMesh = whole.Mesh;
    this->WholeCellIds = std::move(whole.CellIds);
    this->WholeParts = whole.Parts;
    if (this->WholeParts > 1)
    {
      vtkDebugMacro("Gathered the mesh from " << this->WholeParts << " ranks.");
    }
  }
  if (!this->WholeError.empty())
  {
    vtkErrorMacro(<< this->WholeError << ".");
    mesh = nullptr;
    return false;
  }
  mesh = this->WholeMesh;
  if (mesh && mesh->GetNumberOfCells() == 0 && mesh->GetNumberOfPoints() > 0)
  {
    const std::string refusal = this->PointCloudRefusal();
    if (!refusal.empty())
    {
      vtkErrorMacro("The input has " << mesh->GetNumberOfPoints()
                                     << " points but no polygons: " << refusal << ".");
      mesh = nullptr;
      return false;
    }
    if (!(this->PointSitesInput == mesh && this->PointSitesTime == mesh->GetMTime()))
    {
      this->PointSitesInput = mesh;
      this->PointSitesTime = mesh->GetMTime();
      const vtkIdType count = mesh->GetNumberOfPoints();
      vtkNew<vtkIdTypeArray> offsets, connectivity;
      offsets->SetNumberOfValues(count + 1);
      connectivity->SetNumberOfValues(count);
      for (vtkIdType i = 0; i < count; ++i)
      {
        offsets->SetValue(i, i);
        connectivity->SetValue(i, i);
      }
      offsets->SetValue(count, count);
      vtkNew<vtkCellArray> vertices;
      vertices->SetData(offsets, connectivity);
      this->PointSites = vtkSmartPointer<vtkPolyData>::New();
      this->PointSites->SetPoints(mesh->GetPoints());
      this->PointSites->SetVerts(vertices);
      vtkWarningMacro("The input has " << count
                                       << " points and no cells: each point is taken as a "
                                          "point site (the field is the distance to the "
                                          "nearest point; its id is the ClosestCellId).");
    }
    mesh = this->PointSites;
  }
  return true;
}

std::string vtkDistanceFieldAlgorithm::PointCloudRefusal()
{
  return std::string(this->GetClassName()) +
    " needs a surface (polygons or triangle strips); only vtkLinearFactorDistanceField "
    "with SignMode Unsigned takes points alone";
}

bool vtkDistanceFieldAlgorithm::ReadMesh(vtkPolyData* input,
  const vtkdf::SampleGrid& grid,
  vtkdf::MeshInput& mesh)
{
  double bounds[6];
  std::string error;
  if (!this->MeshBounds(input, bounds, error))
  {
    vtkErrorMacro("Invalid input: " << error << ".");
    return false;
  }
  vtkdf::MeshCopyReport report;
  if (!vtkdf::CopyMesh(input, bounds, vtkdf::GridFrame::For(grid), mesh, report, error))
  {
    vtkErrorMacro("Invalid input: " << error << ".");
    return false;
  }
  if (input == this->WholeMesh && !this->WholeCellIds.empty())
  {
    // The whole mesh's cells in global-id order: report their global ids.
    for (auto* cells : { &mesh.TriangleCells, &mesh.SegmentCells, &mesh.VertexCells })
    {
      for (int64_t& cell : *cells)
      {
        cell = this->WholeCellIds[cell];
      }
    }
  }
  const std::string warning = report.Warnings();
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }
  return true;
}

bool vtkDistanceFieldAlgorithm::CheckEnum(int value, const vtkdf::EnumTable& table)
{
  std::string error;
  if (!table.Check(value, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

bool vtkDistanceFieldAlgorithm::CheckProperties()
{
  if (!this->CheckEnum(this->Backend, vtkdf::enums::Backend))
  {
    return false;
  }
  if (!(this->MemoryLimit >= 0 && std::isfinite(this->MemoryLimit)))
  {
    vtkErrorMacro("MemoryLimit must be a finite number of bytes >= 0 (0: the default); it is "
      << this->MemoryLimit << ".");
    return false;
  }
  if (this->ExplicitGrid)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (!std::isfinite(this->GridOrigin[a]))
      {
        vtkErrorMacro("GridOrigin must be finite; it is ("
          << this->GridOrigin[0] << ", " << this->GridOrigin[1] << ", " << this->GridOrigin[2]
          << ").");
        return false;
      }
      if (!(this->GridSpacing[a] > 0 && std::isfinite(this->GridSpacing[a])))
      {
        vtkErrorMacro("GridSpacing must be finite and positive; it is ("
          << this->GridSpacing[0] << ", " << this->GridSpacing[1] << ", " << this->GridSpacing[2]
          << ").");
        return false;
      }
      if (this->GridDimensions[a] < 1)
      {
        vtkErrorMacro("GridDimensions must be >= 1; they are (" << this->GridDimensions[0] << ", "
                                                                << this->GridDimensions[1] << ", "
                                                                << this->GridDimensions[2] << ").");
        return false;
      }
    }
  }
  else
  {
    if (this->Resolution < 2)
    {
      vtkErrorMacro("Resolution must be at least 2 samples; it is " << this->Resolution << ".");
      return false;
    }
    if (!(this->Padding >= 0 && std::isfinite(this->Padding)))
    {
      vtkErrorMacro("Padding must be finite and >= 0; it is " << this->Padding << ".");
      return false;
    }
  }
  return true;
}

int vtkDistanceFieldAlgorithm::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (!this->CheckProperties())
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkdf::SampleGrid grid;
  const char* what = "The grid";
  const bool imageInput = this->AcceptsImageInput && inInfo &&
    vtkImageData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT()));
  vtkPolyData* input = nullptr;
  if (!imageInput)
  {
    // The default grid depends on the mesh's bounds, which are known only once the input
    // has executed (the grid must be known here for streaming requests to make sense),
    // and a distributed run assembles the whole mesh on every rank, collectively, here:
    // bring the input up to date now.
    if (vtkAlgorithm* upstream = this->GetInputAlgorithm(0, 0))
    {
      // The request RequestUpdateExtent makes next, so that the input is not made twice.
      const int port = this->GetInputConnection(0, 0)->GetIndex();
      int piece = 0, pieces = 1;
      vtkdf::MeshPiece(piece, pieces);
      vtkNew<vtkInformationVector> requests;
      requests->SetNumberOfInformationObjects(upstream->GetNumberOfOutputPorts());
      vtkInformation* request = requests->GetInformationObject(port);
      request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), piece);
      request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), pieces);
      request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
      upstream->Update(port, requests);
    }
    input = vtkPolyData::GetData(inputVector[0], 0);
    if (!this->InputMesh(input))
    {
      return 0;
    }
  }
  if (imageInput)
  {
    // An image input: the output has its grid.
    int whole[6] = { 0, -1, 0, -1, 0, -1 };
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    for (int a = 0; a < 3; ++a)
    {
      grid.Whole.Lo[a] = whole[2 * a];
      grid.Whole.Hi[a] = whole[2 * a + 1];
    }
    if (inInfo->Has(vtkDataObject::ORIGIN()))
    {
      inInfo->Get(vtkDataObject::ORIGIN(), grid.Origin.data());
    }
    if (inInfo->Has(vtkDataObject::SPACING()))
    {
      inInfo->Get(vtkDataObject::SPACING(), grid.Spacing.data());
    }
    what = "The input image's grid";
  }
  else if (this->ExplicitGrid)
  {
    for (int a = 0; a < 3; ++a)
    {
      grid.Origin[a] = this->GridOrigin[a];
      grid.Spacing[a] = this->GridSpacing[a];
      grid.Whole.Lo[a] = 0;
      grid.Whole.Hi[a] = this->GridDimensions[a] - 1;
    }
    what = "The explicit grid (GridOrigin, GridSpacing, GridDimensions)";
  }
  else
  {
    double bounds[6];
    std::string error;
    const bool empty = !input || input->GetNumberOfCells() == 0 || input->GetNumberOfPoints() == 0;
    if (!empty && !this->MeshBounds(input, bounds, error))
    {
      vtkErrorMacro("Invalid input mesh: " << error << ".");
      return 0;
    }
    if (!empty)
    {
      grid = vtkdf::SampleGrid::FromBounds(bounds, this->Resolution, this->Padding);
      what = "The default grid (from the mesh bounds, Resolution and Padding)";
    }
    // An empty mesh keeps the empty extent: RequestData warns and outputs nothing.
  }
  std::string error;
  if (!grid.Whole.Empty() && !vtkdf::CheckGrid(grid, nullptr, error))
  {
    vtkErrorMacro(<< what << " is unusable: " << error << ".");
    return 0;
  }
  int whole[6];
  for (int a = 0; a < 3; ++a)
  {
    whole[2 * a] = grid.Whole.Lo[a];
    whole[2 * a + 1] = grid.Whole.Hi[a];
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), grid.Origin.data(), 3);
  outInfo->Set(vtkDataObject::SPACING(), grid.Spacing.data(), 3);
  if (this->ProducesSubExtents)
  {
    outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  }
  return 1;
}

int vtkDistanceFieldAlgorithm::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Every voxel may depend on every other voxel of an image: ask for all of it. Every
  // sample may depend on every cell of a mesh: ask for the whole mesh, or, in a
  // distributed run, for this rank's piece, which InputMesh gathers with the others'.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkdf::RequestWholeInput(inInfo);
  if (!vtkImageData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    int piece = 0, pieces = 1;
    vtkdf::MeshPiece(piece, pieces);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), piece);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), pieces);
  }
  return 1;
}

vtkdf::RunStatus vtkDistanceFieldAlgorithm::OpenMeshRun(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run,
  vtkPolyData*& mesh,
  vtkdf::SampleGrid& grid,
  vtkdf::IndexBox& extent)
{
  mesh = vtkPolyData::GetData(inputVector[0], 0);
  // The whole mesh, gathered when a distributed run partitioned it (vtkDistanceFieldPartitions.h).
  if (!this->InputMesh(mesh))
  {
    return vtkdf::RunStatus::Failed;
  }
  if (!mesh || mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0)
  {
    return run.Empty("The input mesh is empty: the output is an empty image.");
  }
  // The grid (RequestInformation) and the part of it requested (streaming).
  if (!GetOutputGrid(outputVector->GetInformationObject(0), grid, extent))
  {
    return run.Empty("The requested extent is empty: the output is an empty image.");
  }
  return vtkdf::RunStatus::Done;
}

bool vtkDistanceFieldAlgorithm::CheckMemory(double bytes, const vtkdf::IndexBox& grid)
{
  const double samples = double(grid.Size(0)) * grid.Size(1) * grid.Size(2);
  if (samples > static_cast<double>(VTK_ID_MAX) || samples > 4.0e18)
  {
    vtkErrorMacro("The grid has " << samples << " samples, more than vtkIdType can index.");
    return false;
  }
  std::string source;
  const double limit = this->EffectiveMemoryLimit(&source);
  if (bytes > limit)
  {
    vtkErrorMacro("The grid (" << grid.Size(0) << " x " << grid.Size(1) << " x " << grid.Size(2)
                               << ") needs " << bytes / 1048576.0 << " MiB, above "
                               << (source == "MemoryLimit" ? "MemoryLimit" : "the memory limit")
                               << " (" << limit / 1048576.0 << " MiB"
                               << (source == "MemoryLimit" ? "" : ": " + source) << ").");
    return false;
  }
  return true;
}

bool vtkDistanceFieldAlgorithm::GetOutputGrid(vtkInformation* outInfo,
  vtkdf::SampleGrid& grid,
  vtkdf::IndexBox& extent)
{
  int whole[6], update[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), update);
  }
  else
  {
    std::copy(whole, whole + 6, update);
  }
  double origin[3], spacing[3];
  outInfo->Get(vtkDataObject::ORIGIN(), origin);
  outInfo->Get(vtkDataObject::SPACING(), spacing);
  for (int a = 0; a < 3; ++a)
  {
    grid.Origin[a] = origin[a];
    grid.Spacing[a] = spacing[a];
    grid.Whole.Lo[a] = whole[2 * a];
    grid.Whole.Hi[a] = whole[2 * a + 1];
    extent.Lo[a] = update[2 * a];
    extent.Hi[a] = update[2 * a + 1];
  }
  extent = extent.Intersect(grid.Whole);
  return !extent.Empty() && !grid.Whole.Empty();
}

void vtkDistanceFieldAlgorithm::SetOutputExtent(vtkImageData* output,
  const vtkdf::SampleGrid& grid,
  const vtkdf::IndexBox& extent)
{
  output->SetExtent(
    extent.Lo[0], extent.Hi[0], extent.Lo[1], extent.Hi[1], extent.Lo[2], extent.Hi[2]);
  output->SetOrigin(grid.Origin.data());
  output->SetSpacing(grid.Spacing.data());
}

void vtkDistanceFieldAlgorithm::RequestGrownImage(vtkInformation* inInfo,
  vtkInformation* outInfo,
  int layers)
{
  vtkdf::RequestWholeInput(inInfo);
  vtkdf::SampleGrid grid;
  vtkdf::IndexBox piece;
  if (layers >= 0 && GetOutputGrid(outInfo, grid, piece))
  {
    const vtkdf::IndexBox grown = piece.Grown(layers, grid.Whole);
    const int update[6] = {
      grown.Lo[0], grown.Hi[0], grown.Lo[1], grown.Hi[1], grown.Lo[2], grown.Hi[2]
    };
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), update, 6);
    // A request by pieces (a distributed run): VTK's executive turns the piece numbers
    // that come with it into the piece's extent (piece 0 of 1: the whole grid), so the
    // voxels around the piece are asked for as ghost levels of this rank's piece, which
    // it grows the piece's extent by.
    using SDDP = vtkStreamingDemandDrivenPipeline;
    if (outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) &&
      outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) > 1)
    {
      inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()));
      inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()));
      inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), layers);
    }
  }
}

bool vtkDistanceFieldAlgorithm::GetImageGrid(vtkImageData* image, vtkdf::SampleGrid& grid)
{
  int extent[6];
  image->GetExtent(extent);
  for (int a = 0; a < 3; ++a)
  {
    grid.Origin[a] = image->GetOrigin()[a];
    grid.Spacing[a] = image->GetSpacing()[a];
    grid.Whole.Lo[a] = extent[2 * a];
    grid.Whole.Hi[a] = extent[2 * a + 1];
  }
  return !grid.Whole.Empty();
}

namespace
{
/// A number of bytes from a cgroup file ("max" or missing: -1).
double ReadBytes(const std::string& path)
{
  std::ifstream file(path);
  std::string word;
  if (!(file >> word) || word == "max")
  {
    return -1;
  }
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  return end && *end == '\0' && value >= 0 ? value : -1;
}

/// What the process's cgroup still allows (limit less usage; the tightest along the
/// cgroup v2 hierarchy, or cgroup v1's memory controller), or -1 when unlimited.
double CgroupAvailable()
{
  std::ifstream self("/proc/self/cgroup");
  std::string line;
  double available = -1;
  while (std::getline(self, line))
  {
    const size_t colon1 = line.find(':'), colon2 = line.find(':', colon1 + 1);
    if (colon1 == std::string::npos || colon2 == std::string::npos)
    {
      continue;
    }
    const std::string controllers = line.substr(colon1 + 1, colon2 - colon1 - 1);
    std::string path = line.substr(colon2 + 1);
    const bool v2 = line.compare(0, colon1, "0") == 0 && controllers.empty();
    const bool v1 = controllers.find("memory") != std::string::npos;
    if (!v2 && !v1)
    {
      continue;
    }
    const std::string root = v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
    const char* limitFile = v2 ? "/memory.max" : "/memory.limit_in_bytes";
    const char* usageFile = v2 ? "/memory.current" : "/memory.usage_in_bytes";
    for (;;)
    {
      const std::string dir = root + (path == "/" ? "" : path);
      const double limit = ReadBytes(dir + limitFile);
      // cgroup v1 writes "no limit" as a huge number.
      if (limit >= 0 && limit < 1e18)
      {
        const double usage = std::max(0.0, ReadBytes(dir + usageFile));
        const double left = std::max(0.0, limit - usage);
        available = available < 0 ? left : std::min(available, left);
      }
      if (path.empty() || path == "/")
      {
        break;
      }
      const size_t slash = path.find_last_of('/');
      path = slash == 0 || slash == std::string::npos ? "/" : path.substr(0, slash);
    }
  }
  return available;
}

/// What RLIMIT_AS still allows (limit less the address space in use), or -1.
double AddressSpaceAvailable()
{
  struct rlimit limit;
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
  {
    return -1;
  }
  std::ifstream statm("/proc/self/statm");
  double pages = 0;
  statm >> pages;
  const double used = pages * static_cast<double>(sysconf(_SC_PAGESIZE));
  return std::max(0.0, static_cast<double>(limit.rlim_cur) - used);
}
} // namespace

double vtkDistanceFieldAlgorithm::EffectiveMemoryLimit(std::string* source) const
{
  vtksys::SystemInformation info;
  info.RunMemoryCheck();
  const double physical = static_cast<double>(info.GetTotalPhysicalMemory()) * 1024.0 * 1024.0;
  double limit = this->MemoryLimit;
  std::string from = "MemoryLimit";
  if (!(limit > 0))
  {
    limit = 0.5 * physical;
    from = "half the physical memory";
  }
  else if (limit > physical)
  {
    limit = physical; // more would be paged out, or end in the OOM killer
    from = "the physical memory";
  }
  // Whatever was asked, never more than the process can still get. What the estimate
  // leaves out (the mesh, the pipeline's other data) takes some of that: keep 3/4.
  const double addressSpace = AddressSpaceAvailable();
  if (addressSpace >= 0 && 0.75 * addressSpace < limit)
  {
    limit = 0.75 * addressSpace;
    from = "3/4 of the address space RLIMIT_AS leaves";
  }
  const double cgroup = CgroupAvailable();
  if (cgroup >= 0 && 0.75 * cgroup < limit)
  {
    limit = 0.75 * cgroup;
    from = "3/4 of the memory the cgroup leaves";
  }
  if (source)
  {
    *source = from;
  }
  return limit;
}

void vtkDistanceFieldAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Backend: " << vtkdf::enums::Backend.Name(this->Backend) << "\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "Padding: " << this->Padding << "\n";
  os << indent << "ExplicitGrid: " << (this->ExplicitGrid ? "On" : "Off") << "\n";
  os << indent << "GridOrigin: " << this->GridOrigin[0] << " " << this->GridOrigin[1] << " "
     << this->GridOrigin[2] << "\n";
  os << indent << "GridSpacing: " << this->GridSpacing[0] << " " << this->GridSpacing[1] << " "
     << this->GridSpacing[2] << "\n";
  os << indent << "GridDimensions: " << this->GridDimensions[0] << " " << this->GridDimensions[1]
     << " " << this->GridDimensions[2] << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit
     << (this->MemoryLimit > 0 ? "" : " (half of physical memory)") << "\n";
}
