#include "vtkDistanceFieldAlgorithm.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCellArray.h"
#include "vtkDataSet.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "HeadlessGL.h"
#include "SampleGrid.h"

#include <vtksys/SystemInformation.hxx>

#include <chrono>
#include <cmath>
#include <sstream>

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

bool vtkDistanceFieldAlgorithm::CellBounds(vtkDataSet* input, double bounds[6])
{
  vtkPolyData* mesh = vtkPolyData::SafeDownCast(input);
  if (!mesh || !mesh->GetPoints())
  {
    return false;
  }
  bool any = false;
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = VTK_DOUBLE_MAX;
    bounds[2 * a + 1] = -VTK_DOUBLE_MAX;
  }
  for (vtkCellArray* cells :
    { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(), mesh->GetStrips() })
  {
    if (!cells)
    {
      continue;
    }
    vtkIdType count;
    const vtkIdType* ids;
    for (cells->InitTraversal(); cells->GetNextCell(count, ids);)
    {
      for (vtkIdType i = 0; i < count; ++i)
      {
        double x[3];
        mesh->GetPoint(ids[i], x);
        for (int a = 0; a < 3; ++a)
        {
          bounds[2 * a] = std::min(bounds[2 * a], x[a]);
          bounds[2 * a + 1] = std::max(bounds[2 * a + 1], x[a]);
        }
        any = true;
      }
    }
  }
  return any;
}

int vtkDistanceFieldAlgorithm::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  int whole[6] = { 0, -1, 0, -1, 0, -1 };
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  if (this->AcceptsImageInput && inInfo &&
    vtkImageData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    // An image input: the output has its grid.
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    if (inInfo->Has(vtkDataObject::ORIGIN()))
    {
      inInfo->Get(vtkDataObject::ORIGIN(), origin);
    }
    if (inInfo->Has(vtkDataObject::SPACING()))
    {
      inInfo->Get(vtkDataObject::SPACING(), spacing);
    }
  }
  else if (this->ExplicitGrid)
  {
    for (int a = 0; a < 3; ++a)
    {
      origin[a] = this->GridOrigin[a];
      spacing[a] = this->GridSpacing[a];
      whole[2 * a + 1] = this->GridDimensions[a] - 1;
      if (!(spacing[a] > 0) || this->GridDimensions[a] < 1)
      {
        vtkErrorMacro("Explicit grid needs positive spacing and dimensions, got spacing "
          << spacing[a] << " and dimension " << this->GridDimensions[a] << " on axis " << a);
        return 0;
      }
    }
  }
  else
  {
    // The default grid depends on the input's bounds, which are known only once the
    // input has executed: bring it up to date now (as the grid must be known here for
    // streaming requests to make sense).
    if (vtkAlgorithm* upstream = this->GetInputAlgorithm(0, 0))
    {
      upstream->Update(this->GetInputConnection(0, 0)->GetIndex());
    }
    vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
    double bounds[6];
    int dims[3];
    if (input && CellBounds(input, bounds) &&
      std::isfinite(bounds[0] + bounds[1] + bounds[2] + bounds[3] + bounds[4] + bounds[5]))
    {
      ComputeDefaultGrid(bounds, this->Resolution, this->Padding, origin, spacing, dims);
      for (int a = 0; a < 3; ++a)
      {
        whole[2 * a + 1] = dims[a] - 1;
      }
    }
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
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
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (vtkImageData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    // Every voxel may depend on every other: ask for the whole image.
    int whole[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), whole, 6);
    return 1;
  }
  // Every sample may depend on every cell: ask for the whole mesh.
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

namespace
{
double SteadySeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace

void vtkDistanceFieldAlgorithm::StartTiming()
{
  this->TimingStart = this->StageStart = SteadySeconds();
  this->LastStageTimes.clear();
}

void vtkDistanceFieldAlgorithm::EndStage(const char* name)
{
  const double now = SteadySeconds();
  std::ostringstream text;
  text << (this->LastStageTimes.empty() ? "" : ",") << name << ":" << now - this->StageStart;
  this->LastStageTimes += text.str();
  this->StageStart = now;
}

void vtkDistanceFieldAlgorithm::FinishTiming(vtkdf::HeadlessGL* gl)
{
  this->LastTime = SteadySeconds() - this->TimingStart;
  this->LastBackend = gl ? "gpu" : "cpu";
  this->LastRenderer = gl ? gl->Renderer() : "cpu";
}

bool vtkDistanceFieldAlgorithm::ChooseBackend(vtkdf::HeadlessGL*& gl)
{
  gl = nullptr;
  if (this->Backend == BACKEND_CPU)
  {
    return true;
  }
  std::string why;
  vtkdf::HeadlessGL* context = vtkdf::HeadlessGL::Get(why);
  if (this->Backend == BACKEND_GPU && !context)
  {
    vtkErrorMacro("Backend is GPU but " << why);
    return false;
  }
  // Auto: a hardware-accelerated context only.
  gl = this->Backend == BACKEND_GPU || (context && !context->IsSoftware()) ? context : nullptr;
  return true;
}

bool vtkDistanceFieldAlgorithm::CheckMemory(double bytes, const vtkdf::IndexBox& grid)
{
  const double samples = double(grid.Size(0)) * grid.Size(1) * grid.Size(2);
  if (samples > static_cast<double>(VTK_ID_MAX) || samples > 4.0e18)
  {
    vtkErrorMacro("The grid has " << samples << " samples, more than vtkIdType can index.");
    return false;
  }
  const double limit = this->EffectiveMemoryLimit();
  if (bytes > limit)
  {
    vtkErrorMacro("The grid (" << grid.Size(0) << " x " << grid.Size(1) << " x " << grid.Size(2)
                               << ") needs " << bytes / 1048576.0 << " MiB, above MemoryLimit ("
                               << limit / 1048576.0 << " MiB).");
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

double vtkDistanceFieldAlgorithm::EffectiveMemoryLimit() const
{
  if (this->MemoryLimit > 0)
  {
    return this->MemoryLimit;
  }
  vtksys::SystemInformation info;
  info.RunMemoryCheck();
  return 0.5 * static_cast<double>(info.GetTotalPhysicalMemory()) * 1024.0 * 1024.0;
}

void vtkDistanceFieldAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const char* backends[] = { "Auto", "GPU", "CPU" };
  os << indent << "Backend: " << backends[this->Backend] << "\n";
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
  os << indent << "LastBackend: " << this->LastBackend << "\n";
  os << indent << "LastRenderer: " << this->LastRenderer << "\n";
  os << indent << "LastTime: " << this->LastTime << "\n";
  os << indent << "LastStageTimes: " << this->LastStageTimes << "\n";
}
