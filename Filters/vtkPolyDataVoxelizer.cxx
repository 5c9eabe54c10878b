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
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

#include <utility>

vtkStandardNewMacro(vtkPolyDataVoxelizer);

vtkPolyDataVoxelizer::vtkPolyDataVoxelizer() = default;

vtkdf::RunStatus vtkPolyDataVoxelizer::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkPolyData* input = nullptr;
  vtkdf::SampleGrid grid;
  vtkdf::IndexBox extent;
  const vtkdf::RunStatus opened =
    this->OpenMeshRun(inputVector, outputVector, run, input, grid, extent);
  if (opened != vtkdf::RunStatus::Done)
  {
    return opened;
  }
  const bool wantBoundary = this->Mode != SOLID, wantSolid = this->Mode != BOUNDARY;
  // Lanes of three views (front and back for a solid), the combined masks, the arrays.
  const double voxels = double(grid.Whole.Count());
  const double bytes = voxels * ((wantSolid ? 6 : 3) / 8.0 + 2 / 8.0) +
    double(extent.Count()) * (wantBoundary + wantSolid);
  vtkdf::MeshInput mesh;
  if (!this->CheckMemory(bytes, grid.Whole) || !run.ResolveBackend(this->Backend) ||
    !this->ReadMesh(input, grid, mesh))
  {
    return vtkdf::RunStatus::Failed;
  }
  vtkdf::BitVolume boundary, solid;
  vtkdf::VoxelReport report;
  std::string error;
  if (!vtkdf::VoxelizeMesh(std::move(mesh),
        grid,
        run.Context(),
        wantBoundary ? &boundary : nullptr,
        wantSolid ? &solid : nullptr,
        run.MakeExecution(0, 0.8),
        report,
        error))
  {
    return run.Fail(error);
  }
  if (!report.Warning.empty())
  {
    vtkWarningMacro(<< report.Warning);
  }
  if (run.AbortRequested())
  {
    return run.Empty();
  }

  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
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
  run.Timer.End("voxelize");
  return vtkdf::RunStatus::Done;
}

bool vtkPolyDataVoxelizer::CheckProperties()
{
  return this->Superclass::CheckProperties() &&
    this->CheckEnum(this->Mode, vtkdf::enums::VoxelMode);
}

void vtkPolyDataVoxelizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << vtkdf::enums::VoxelMode.Name(this->Mode) << "\n";
}
