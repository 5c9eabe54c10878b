#include "vtkPolyDataVoxelizer.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
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

#include <utility>

vtkStandardNewMacro(vtkPolyDataVoxelizer);

vtkPolyDataVoxelizer::vtkPolyDataVoxelizer() = default;

int vtkPolyDataVoxelizer::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkdf::StageTimer timer;
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  // The whole mesh, gathered when a distributed run partitioned it (vtkDistanceFieldPartitions.h).
  if (!this->InputMesh(input))
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  if (!input || input->GetNumberOfCells() == 0 || input->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro("The input mesh is empty: the output is an empty image.");
    return 1;
  }

  vtkdf::SampleGrid grid;
  vtkdf::IndexBox extent;
  if (!this->GetOutputGrid(outInfo, grid, extent))
  {
    vtkWarningMacro("The requested extent is empty: the output is an empty image.");
    return 1;
  }
  const bool wantBoundary = this->Mode != SOLID, wantSolid = this->Mode != BOUNDARY;
  // Lanes of three views (front and back for a solid), the combined masks, the arrays.
  const double voxels = double(grid.Whole.Count());
  const double bytes = voxels * ((wantSolid ? 6 : 3) / 8.0 + 2 / 8.0) +
    double(extent.Count()) * (wantBoundary + wantSolid);
  vtkdf::HeadlessGL* gl = nullptr;
  vtkdf::MeshInput mesh;
  if (!this->CheckMemory(bytes, grid.Whole) || !this->ChooseBackend(gl) ||
    !this->ReadMesh(input, grid, mesh))
  {
    return 0;
  }
  vtkdf::BitVolume boundary, solid;
  vtkdf::VoxelReport report;
  std::string error;
  if (!vtkdf::VoxelizeMesh(std::move(mesh),
        grid,
        gl,
        wantBoundary ? &boundary : nullptr,
        wantSolid ? &solid : nullptr,
        this->MakeExecution(timer),
        report,
        error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (!report.Warning.empty())
  {
    vtkWarningMacro(<< report.Warning);
  }
  this->UpdateProgress(0.8);

  this->SetOutputExtent(output, grid, extent);
  for (int mask = 0; mask < 2; ++mask)
  {
    if (!(mask == 0 ? wantBoundary : wantSolid))
    {
      continue;
    }
    auto array =
      vtkdf::NewArray<vtkUnsignedCharArray>(mask == 0 ? "Boundary" : "Solid", extent.Count());
    vtkdf::BitsToBytes(
      mask == 0 ? boundary : solid, grid, extent, array->GetPointer(0), vtkdf::SMPFor);
    output->GetPointData()->AddArray(array);
  }
  output->GetPointData()->SetActiveScalars(wantBoundary ? "Boundary" : "Solid");
  timer.End("voxelize");
  this->FinishTiming(gl, timer);
  this->UpdateProgress(1.0);
  return 1;
}

bool vtkPolyDataVoxelizer::CheckProperties()
{
  return this->Superclass::CheckProperties() &&
    this->CheckEnum("Mode", this->Mode, { "Boundary", "Solid", "Both" });
}

void vtkPolyDataVoxelizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << EnumName(this->Mode, { "Boundary", "Solid", "Both" }) << "\n";
}
