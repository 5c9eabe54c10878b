#include "vtkChamferVoxelDistance.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArrayRange.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "Voxels/VoxelFields.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <utility>

vtkStandardNewMacro(vtkChamferVoxelDistance);

namespace
{
/// Non-zero values of a one-component array (x fastest over dims) into voxel lanes.
struct MaskToBits
{
  template<typename ArrayT>
  void operator()(ArrayT* array, vtkdf::BitVolume& bits) const
  {
    const auto values = vtk::DataArrayValueRange<1>(array);
    const int nx = bits.Size(0), ny = bits.Size(1), nz = bits.Size(2);
    const int64_t slice = int64_t(nx) * ny;
    vtkdf::SMPFor(slice,
      256,
      [&](int64_t begin, int64_t end)
      {
        // Lanes are consecutive in memory (x, then y): a chunk of lanes reads a run of
        // each slice, slice after slice, and sets bits in its own few words.
        uint64_t* words = bits.Lane(0, 0) + begin * bits.WordsPerLane();
        const int W = bits.WordsPerLane();
        for (int z = 0; z < nz; ++z)
        {
          const uint64_t bit = uint64_t(1) << (z & 63);
          const int64_t first = z * slice;
          uint64_t* word = words + (z >> 6);
          for (int64_t lane = begin; lane < end; ++lane, word += W)
          {
            *word |= values[first + lane] != 0 ? bit : 0;
          }
        }
      });
  }
};

/// The named mask of `image` as lanes; false with `error` when it is unusable.
bool ReadMask(vtkImageData* image,
  const char* name,
  bool required,
  vtkdf::BitVolume& bits,
  bool& found,
  std::string& error)
{
  found = false;
  if (!required && !image->GetPointData()->GetAbstractArray(name))
  {
    return true;
  }
  vtkDataArray* array = vtkdf::SampleArray(image, name, 1, error);
  if (!array)
  {
    return false;
  }
  MaskToBits worker;
  if (!vtkArrayDispatch::Dispatch::Execute(array, worker, bits))
  {
    worker(array, bits); // vtkDataArray fallback
  }
  found = true;
  return true;
}
} // namespace

vtkChamferVoxelDistance::vtkChamferVoxelDistance()
{
  this->AcceptsImageInput = true;
}

int vtkChamferVoxelDistance::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (!vtkImageData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    return this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
  }
  // A masks input: all of it without a limit on the layers; else the requested voxels
  // and MaximumLayers around them (see PieceVoxels).
  RequestGrownImage(inInfo,
    outputVector->GetInformationObject(0),
    this->MaximumLayers > 0 ? this->MaximumLayers : -1);
  return 1;
}

vtkdf::RunStatus vtkChamferVoxelDistance::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  this->LastLayers = 0;
  vtkPolyData* mesh = vtkPolyData::GetData(inputVector[0], 0);
  // The whole mesh, gathered when a distributed run partitioned it (vtkDistanceFieldPartitions.h).
  if (!this->InputMesh(mesh))
  {
    return vtkdf::RunStatus::Failed;
  }
  vtkImageData* image = vtkImageData::GetData(inputVector[0], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // The grid of the masks: the input image's, or the whole grid for a mesh.
  vtkdf::ChamferRequest request;
  vtkdf::SampleGrid& grid = request.Grid;
  vtkdf::IndexBox piece;
  if (image && !GetImageGrid(image, grid))
  {
    return run.Empty("The input image is empty: the output is an empty image.");
  }
  if (!image &&
    (!mesh || mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0 ||
      !GetOutputGrid(outInfo, grid, piece)))
  {
    return run.Empty("The input mesh is empty: the output is an empty image.");
  }
  // The piece asked for (all of it in one process).
  vtkdf::SampleGrid whole;
  if (!GetOutputGrid(outInfo, whole, piece) || !grid.Whole.Contains(piece))
  {
    piece = grid.Whole;
  }
  request.Metric = static_cast<vtkdf::ChamferMetric>(this->Metric);
  request.MaximumLayers = this->MaximumLayers;
  request.Signed = this->Signed;
  vtkdf::MeshInput input;
  if (!this->CheckMemory(this->EstimateBytes(grid.Whole), grid.Whole) ||
    !run.ResolveBackend(this->Backend) || (mesh && !this->ReadMesh(mesh, grid, input)))
  {
    return vtkdf::RunStatus::Failed;
  }

  // The zero set, and the solid when a sign is wanted: read from the image, or
  // voxelized (on the GPU, for the whole grid, the voxelization stays there for the
  // propagation).
  vtkdf::BitVolume boundary(grid.Whole.Size(0), grid.Whole.Size(1), grid.Whole.Size(2)), solid;
  bool haveSolid = this->Signed;
  if (image)
  {
    if (!this->ReadMasks(image, boundary, solid, haveSolid))
    {
      return vtkdf::RunStatus::Failed;
    }
    run.Timer.End("masks");
  }
  std::string error;
  vtkdf::ChamferReport report;
  // The voxels computed: all of the masks' grid, or those that decide the piece.
  vtkdf::IndexBox computed = grid.Whole;
  vtkSmartPointer<vtkIntArray> distance;
  const bool ok = this->Propagate(mesh ? &input : nullptr,
    boundary,
    solid,
    haveSolid,
    request,
    piece,
    run,
    distance,
    computed,
    report,
    error);
  if (!ok)
  {
    return run.Fail(error);
  }
  if (report.Result.Aborted)
  {
    return run.Empty();
  }
  if (!report.Voxels.Warning.empty())
  {
    vtkWarningMacro(<< report.Voxels.Warning);
  }
  this->WriteOutput(grid,
    piece,
    computed,
    distance,
    boundary,
    haveSolid ? &solid : nullptr,
    vtkImageData::GetData(outputVector, 0));
  this->LastLayers = report.Result.Layers;
  run.Timer.End("arrays");
  return vtkdf::RunStatus::Done;
}

bool vtkChamferVoxelDistance::Propagate(vtkdf::MeshInput* mesh,
  vtkdf::BitVolume& boundary,
  vtkdf::BitVolume& solid,
  bool haveSolid,
  const vtkdf::ChamferRequest& request,
  const vtkdf::IndexBox& piece,
  vtkdf::FilterRun& run,
  vtkSmartPointer<vtkIntArray>& distance,
  vtkdf::IndexBox& computed,
  vtkdf::ChamferReport& report,
  std::string& error)
{
  const vtkdf::IndexBox& whole = request.Grid.Whole;
  const vtkdf::BitVolume* inside = haveSolid ? &solid : nullptr;
  vtkdf::HeadlessGL* gl = run.Context();
  const vtkdf::Execution execution = run.MakeExecution();
  const vtkdf::ChamferOutput output = [&distance](const vtkdf::IndexBox& box)
  {
    distance = vtkdf::NewArray<vtkIntArray>("ChamferDistance", box.Count());
    return distance->GetPointer(0);
  };
  computed = whole;
  if (!this->ComputesAlone(piece, whole))
  {
    return mesh ? vtkdf::ComputeChamferField(std::move(*mesh),
                    request,
                    gl,
                    output(whole),
                    boundary,
                    solid,
                    this->OutputMasks,
                    execution,
                    report,
                    error)
                : vtkdf::ComputeChamferField(
                    boundary, inside, request, gl, output(whole), execution, report, error);
  }
  // A piece of the grid: the masks of the whole, then the propagation over the voxels
  // that decide the piece.
  return (!mesh ||
           vtkdf::VoxelizeMesh(std::move(*mesh),
             request.Grid,
             gl,
             &boundary,
             this->Signed ? &solid : nullptr,
             execution,
             report.Voxels,
             error)) &&
    vtkdf::ComputeChamferPiece(
      boundary, inside, piece, request, gl, output, computed, execution, report, error);
}

bool vtkChamferVoxelDistance::ComputesAlone(const vtkdf::IndexBox& piece,
  const vtkdf::IndexBox& grid) const
{
  // A piece smaller than the masks' grid whose deciding voxels are fewer too.
  return !(piece == grid) && !(this->MaximumLayers > 0 && this->PieceVoxels(piece, grid) == grid);
}

void vtkChamferVoxelDistance::WriteOutput(const vtkdf::SampleGrid& grid,
  const vtkdf::IndexBox& piece,
  const vtkdf::IndexBox& computed,
  vtkIntArray* distance,
  const vtkdf::BitVolume& boundary,
  const vtkdf::BitVolume* solid,
  vtkImageData* output) const
{
  SetOutputExtent(output, grid, piece);
  if (computed == piece)
  {
    output->GetPointData()->SetScalars(distance);
  }
  else
  {
    output->GetPointData()->SetScalars(vtkdf::CropArray(distance, computed, piece));
  }
  vtkNew<vtkIntArray> unreachedValue;
  unreachedValue->SetName("UnreachedValue");
  vtkdf::ChamferRequest request;
  request.MaximumLayers = this->MaximumLayers;
  unreachedValue->InsertNextValue(request.Unreached());
  output->GetFieldData()->AddArray(unreachedValue);
  if (this->OutputMasks)
  {
    for (int m = 0; m < (solid ? 2 : 1); ++m)
    {
      auto mask =
        vtkdf::NewArray<vtkUnsignedCharArray>(m == 0 ? "Boundary" : "Solid", piece.Count());
      vtkdf::BitsToBytes(
        m == 0 ? boundary : *solid, grid, piece, mask->GetPointer(0), vtkdf::SMPFor);
      output->GetPointData()->AddArray(mask);
    }
  }
}

vtkdf::IndexBox vtkChamferVoxelDistance::PieceVoxels(const vtkdf::IndexBox& piece,
  const vtkdf::IndexBox& grid) const
{
  // A voxel at distance d <= MaximumLayers from the zero set has a shortest path to it
  // inside the box its distance spans (every step of every metric moves each coordinate
  // by at most one, and the steps of a path can be reordered to move monotonically), so
  // MaximumLayers voxels around the piece decide it; without a limit, all of them.
  return this->MaximumLayers > 0 ? piece.Grown(this->MaximumLayers, grid) : grid;
}

double vtkChamferVoxelDistance::EstimateBytes(const vtkdf::IndexBox& voxels) const
{
  // Three views of lanes (voxelizing), three lane grids and one bit plane per bit of the
  // largest layer index (propagating; no metric needs more than nx + ny + nz layers),
  // the int32 field.
  int64_t largestLayer = int64_t(voxels.Size(0)) + voxels.Size(1) + voxels.Size(2);
  largestLayer =
    this->MaximumLayers > 0 ? std::min<int64_t>(largestLayer, this->MaximumLayers) : largestLayer;
  int planes = 0;
  while ((int64_t(1) << planes) <= largestLayer)
  {
    ++planes;
  }
  return double(voxels.Count()) * (6 / 8.0 + (3 + planes) / 8.0 + 4 + (this->OutputMasks ? 2 : 0));
}

bool vtkChamferVoxelDistance::ReadMasks(vtkImageData* image,
  vtkdf::BitVolume& boundary,
  vtkdf::BitVolume& solid,
  bool& haveSolid)
{
  std::string error;
  bool found = false;
  solid.Resize(boundary.Size(0), boundary.Size(1), boundary.Size(2));
  if (!ReadMask(image, "Boundary", true, boundary, found, error) ||
    !ReadMask(image, "Solid", false, solid, haveSolid, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  if (this->Signed && !haveSolid)
  {
    vtkWarningMacro("Signed is on but the input image has no Solid array: the distances are "
                    "unsigned.");
  }
  return true;
}

bool vtkChamferVoxelDistance::CheckProperties()
{
  if (!this->Superclass::CheckProperties() || !this->CheckEnum(this->Metric, vtkdf::enums::Metric))
  {
    return false;
  }
  if (this->MaximumLayers < 0 || this->MaximumLayers > VTK_INT_MAX - 1)
  {
    vtkErrorMacro("MaximumLayers must lie in [0, " << VTK_INT_MAX - 1 << "] (0: no limit); it is "
                                                   << this->MaximumLayers << ".");
    return false;
  }
  return true;
}

void vtkChamferVoxelDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Metric: " << vtkdf::enums::Metric.Name(this->Metric) << "\n";
  os << indent << "MaximumLayers: " << this->MaximumLayers << "\n";
  os << indent << "Signed: " << this->Signed << "\n";
  os << indent << "OutputMasks: " << this->OutputMasks << "\n";
  os << indent << "LastLayers: " << this->LastLayers << "\n";
}
