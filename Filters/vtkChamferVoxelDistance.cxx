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
#include "vtkDistanceFieldExecution.h"

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

namespace
{
/// The bits of `from` (over the box `box`) on the voxels of `part`, a box within it.
vtkdf::BitVolume ExtractBits(const vtkdf::BitVolume& from,
  const vtkdf::IndexBox& box,
  const vtkdf::IndexBox& part)
{
  vtkdf::BitVolume to(part.Size(0), part.Size(1), part.Size(2));
  const int dx = part.Lo[0] - box.Lo[0], dy = part.Lo[1] - box.Lo[1], dz = part.Lo[2] - box.Lo[2];
  vtkdf::SMPFor(int64_t(part.Size(0)) * part.Size(1),
    256,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t lane = begin; lane < end; ++lane)
      {
        const int x = static_cast<int>(lane % part.Size(0));
        const int y = static_cast<int>(lane / part.Size(0));
        // A word at a time: the part's lane is the source lane from voxel dz on.
        uint64_t* words = to.Lane(x, y);
        for (int w = 0; w < to.WordsPerLane(); ++w)
        {
          words[w] = from.Bits64(x + dx, y + dy, dz + 64 * w);
        }
        words[to.WordsPerLane() - 1] &= to.LastWordMask();
      }
    });
  return to;
}

/// Whether every voxel of `piece` holds a distance of at most `layers` in `distance`
/// (laid out over `box`).
bool AllReached(vtkIntArray* distance,
  const vtkdf::IndexBox& box,
  const vtkdf::IndexBox& piece,
  int layers)
{
  const int32_t* values = distance->GetPointer(0);
  const int64_t nx = box.Size(0), ny = box.Size(1);
  for (int k = piece.Lo[2]; k <= piece.Hi[2]; ++k)
  {
    for (int j = piece.Lo[1]; j <= piece.Hi[1]; ++j)
    {
      const int32_t* row =
        values + ((k - box.Lo[2]) * ny + (j - box.Lo[1])) * nx + (piece.Lo[0] - box.Lo[0]);
      for (int i = 0; i < piece.Size(0); ++i)
      {
        if (row[i] > layers || row[i] < -layers)
        {
          return false;
        }
      }
    }
  }
  return true;
}
} // namespace

int vtkChamferVoxelDistance::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkdf::StageTimer timer;
  vtkPolyData* mesh = vtkPolyData::GetData(inputVector[0], 0);
  // The whole mesh, gathered when a distributed run partitioned it (vtkDistanceFieldPartitions.h).
  if (!this->InputMesh(mesh))
  {
    return 0;
  }
  vtkImageData* image = vtkImageData::GetData(inputVector[0], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  this->LastLayers = 0;
  // The grid of the masks: the input image's, or the whole grid for a mesh.
  vtkdf::ChamferRequest request;
  vtkdf::SampleGrid& grid = request.Grid;
  vtkdf::IndexBox piece;
  if (image)
  {
    if (!GetImageGrid(image, grid))
    {
      vtkWarningMacro("The input image is empty: the output is an empty image.");
      return 1;
    }
  }
  else if (!mesh || mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0 ||
    !GetOutputGrid(outInfo, grid, piece))
  {
    vtkWarningMacro("The input mesh is empty: the output is an empty image.");
    return 1;
  }
  // The piece asked for (all of it in one process), and the voxels that decide it.
  vtkdf::SampleGrid whole;
  if (!GetOutputGrid(outInfo, whole, piece) || !grid.Whole.Contains(piece))
  {
    piece = grid.Whole;
  }
  const vtkdf::IndexBox needed = this->PieceVoxels(piece, grid.Whole);
  request.Metric = static_cast<vtkdf::ChamferMetric>(this->Metric);
  request.MaximumLayers = this->MaximumLayers;
  request.Signed = this->Signed;
  vtkdf::HeadlessGL* gl = nullptr;
  vtkdf::MeshInput input;
  if (!this->CheckMemory(this->EstimateBytes(grid.Whole), grid.Whole) || !this->ChooseBackend(gl) ||
    (mesh && !this->ReadMesh(mesh, grid, input)))
  {
    return 0;
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
      return 0;
    }
    timer.End("masks");
  }
  std::string error;
  vtkdf::ChamferReport report;
  const vtkdf::Execution execution = this->MakeExecution(timer);
  // The voxels computed: all of the masks' grid, or those that decide the piece.
  vtkdf::SampleGrid computed = grid;
  vtkSmartPointer<vtkIntArray> distance;
  bool ok = true;
  // Alone: a piece smaller than the masks' grid whose deciding voxels are fewer too.
  const bool alone = !(piece == grid.Whole) && !(this->MaximumLayers > 0 && needed == grid.Whole);
  if (!alone)
  {
    distance = vtkdf::NewArray<vtkIntArray>("ChamferDistance", grid.Whole.Count());
    ok = image ? vtkdf::ComputeChamferField(boundary,
                   haveSolid ? &solid : nullptr,
                   request,
                   gl,
                   distance->GetPointer(0),
                   execution,
                   report,
                   error)
               : vtkdf::ComputeChamferField(std::move(input),
                   request,
                   gl,
                   distance->GetPointer(0),
                   boundary,
                   solid,
                   this->OutputMasks,
                   execution,
                   report,
                   error);
  }
  else
  {
    // A piece of the grid: the masks of the whole, then the propagation over the voxels
    // that decide the piece.
    if (mesh &&
      !vtkdf::VoxelizeMesh(std::move(input),
        grid,
        gl,
        &boundary,
        this->Signed ? &solid : nullptr,
        execution,
        report.Voxels,
        error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    if (this->MaximumLayers > 0)
    {
      ok = this->PropagatePiece(boundary,
        haveSolid ? &solid : nullptr,
        needed,
        gl,
        request,
        execution,
        distance,
        report,
        error);
      computed.Whole = needed;
    }
    else
    {
      // Without a limit, the piece's farthest voxel says how many voxels around it
      // decide it: propagate `margin` layers over the piece and `margin` voxels around
      // it; when every voxel of the piece is reached, each is exact (see PieceVoxels);
      // else double the margin. A box over a quarter of the grid is not tried: the
      // whole grid then (without a limit), so that the tries cost at most half of it.
      for (int margin = 16;; margin *= 2)
      {
        vtkdf::ChamferRequest bounded = request;
        computed.Whole = piece.Grown(margin, grid.Whole);
        if (computed.Whole.Count() > grid.Whole.Count() / 4)
        {
          computed.Whole = grid.Whole;
        }
        bounded.MaximumLayers = computed.Whole == grid.Whole ? 0 : margin;
        ok = this->PropagatePiece(boundary,
          haveSolid ? &solid : nullptr,
          computed.Whole,
          gl,
          bounded,
          execution,
          distance,
          report,
          error);
        if (!ok || report.Result.Aborted || bounded.MaximumLayers == 0 ||
          AllReached(distance, computed.Whole, piece, margin))
        {
          break;
        }
      }
    }
  }
  if (!ok)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (report.Result.Aborted)
  {
    return 1; // an empty output
  }
  if (!report.Voxels.Warning.empty())
  {
    vtkWarningMacro(<< report.Voxels.Warning);
  }
  SetOutputExtent(output, grid, piece);
  if (computed.Whole == piece)
  {
    output->GetPointData()->SetScalars(distance);
  }
  else
  {
    output->GetPointData()->SetScalars(vtkdf::CropArray(distance.Get(), computed.Whole, piece));
  }
  vtkNew<vtkIntArray> unreachedValue;
  unreachedValue->SetName("UnreachedValue");
  unreachedValue->InsertNextValue(request.Unreached());
  output->GetFieldData()->AddArray(unreachedValue);
  if (this->OutputMasks)
  {
    for (int m = 0; m < (haveSolid ? 2 : 1); ++m)
    {
      auto mask =
        vtkdf::NewArray<vtkUnsignedCharArray>(m == 0 ? "Boundary" : "Solid", piece.Count());
      vtkdf::BitsToBytes(
        m == 0 ? boundary : solid, grid, piece, mask->GetPointer(0), vtkdf::SMPFor);
      output->GetPointData()->AddArray(mask);
    }
  }
  this->LastLayers = report.Result.Layers;
  timer.End("arrays");
  this->FinishTiming(gl, timer);
  this->UpdateProgress(1.0);
  return 1;
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

bool vtkChamferVoxelDistance::PropagatePiece(const vtkdf::BitVolume& boundary,
  const vtkdf::BitVolume* solid,
  const vtkdf::IndexBox& needed,
  vtkdf::HeadlessGL* gl,
  const vtkdf::ChamferRequest& request,
  const vtkdf::Execution& execution,
  vtkSmartPointer<vtkIntArray>& distance,
  vtkdf::ChamferReport& report,
  std::string& error)
{
  if (!boundary.Any())
  {
    error = "The zero set is empty: no Boundary voxel is set, so no distance can be propagated.";
    return false;
  }
  const vtkdf::BitVolume partBoundary = ExtractBits(boundary, request.Grid.Whole, needed);
  vtkdf::BitVolume partSolid;
  if (solid)
  {
    partSolid = ExtractBits(*solid, request.Grid.Whole, needed);
  }
  distance = vtkdf::NewArray<vtkIntArray>("ChamferDistance", needed.Count());
  vtkdf::ChamferRequest part = request;
  part.Grid.Whole = needed;
  if (partBoundary.Any())
  {
    const vtkdf::VoxelReport voxels = report.Voxels;
    const bool ok = vtkdf::ComputeChamferField(partBoundary,
      solid ? &partSolid : nullptr,
      part,
      gl,
      distance->GetPointer(0),
      execution,
      report,
      error);
    report.Voxels = voxels;
    return ok;
  }
  // No zero-set voxel within MaximumLayers of the piece: none is reached.
  const int32_t unreached = request.Unreached();
  int32_t* values = distance->GetPointer(0);
  const int nx = needed.Size(0), ny = needed.Size(1), nz = needed.Size(2);
  for (int z = 0; z < nz; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int x = 0; x < nx; ++x)
      {
        const bool inside = request.Signed && solid && partSolid.Get(x, y, z);
        *values++ = inside ? -unreached : unreached;
      }
    }
  }
  return true;
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
  if (!this->Superclass::CheckProperties() ||
    !this->CheckEnum("Metric", this->Metric, { "Manhattan", "Chessboard18", "Chessboard26" }))
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
  os << indent
     << "Metric: " << EnumName(this->Metric, { "Manhattan", "Chessboard18", "Chessboard26" })
     << "\n";
  os << indent << "MaximumLayers: " << this->MaximumLayers << "\n";
  os << indent << "Signed: " << this->Signed << "\n";
  os << indent << "OutputMasks: " << this->OutputMasks << "\n";
  os << indent << "LastLayers: " << this->LastLayers << "\n";
}
