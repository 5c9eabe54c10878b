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
        for (int64_t lane = begin; lane < end; ++lane)
        {
          uint64_t* words = bits.Lane(static_cast<int>(lane % nx), static_cast<int>(lane / nx));
          for (int z = 0; z < nz; ++z)
          {
            if (values[lane + z * slice] != 0)
            {
              words[z >> 6] |= uint64_t(1) << (z & 63);
            }
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
  this->ProducesSubExtents = false; // every voxel depends on the whole zero set
}

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
  // The grid.
  vtkdf::ChamferRequest request;
  vtkdf::SampleGrid& grid = request.Grid;
  vtkdf::IndexBox unused;
  if (image)
  {
    if (!GetImageGrid(image, grid))
    {
      vtkWarningMacro("The input image is empty: the output is an empty image.");
      return 1;
    }
  }
  else if (!mesh || mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0 ||
    !GetOutputGrid(outInfo, grid, unused))
  {
    vtkWarningMacro("The input mesh is empty: the output is an empty image.");
    return 1;
  }
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
  // voxelized (on the GPU, the voxelization stays there for the propagation).
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
  auto distance = vtkdf::NewArray<vtkIntArray>("ChamferDistance", grid.Whole.Count());
  vtkdf::ChamferReport report;
  const vtkdf::Execution execution = this->MakeExecution(timer);
  const bool ok = image ? vtkdf::ComputeChamferField(boundary,
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
  SetOutputExtent(output, grid, grid.Whole);
  output->GetPointData()->SetScalars(distance);
  vtkNew<vtkIntArray> unreachedValue;
  unreachedValue->SetName("UnreachedValue");
  unreachedValue->InsertNextValue(request.Unreached());
  output->GetFieldData()->AddArray(unreachedValue);
  if (this->OutputMasks)
  {
    for (int m = 0; m < (haveSolid ? 2 : 1); ++m)
    {
      auto mask =
        vtkdf::NewArray<vtkUnsignedCharArray>(m == 0 ? "Boundary" : "Solid", grid.Whole.Count());
      vtkdf::BitsToBytes(
        m == 0 ? boundary : solid, grid, grid.Whole, mask->GetPointer(0), vtkdf::SMPFor);
      output->GetPointData()->AddArray(mask);
    }
  }
  this->LastLayers = report.Result.Layers;
  timer.End("arrays");
  this->FinishTiming(gl, timer);
  this->UpdateProgress(1.0);
  return 1;
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
