#include "vtkSegmentedDistanceField.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "Segment/SegmentedField.h"
#include "vtkDistanceFieldArrays.h"

#include <cmath>
#include <utility>

vtkStandardNewMacro(vtkSegmentedDistanceField);

vtkSegmentedDistanceField::vtkSegmentedDistanceField()
{
  this->ProducesSubExtents = false; // regions are global: the whole grid
}

int vtkSegmentedDistanceField::RequestData(vtkInformation*,
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
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  this->LastRegionCount = 0;
  this->LastPatchCount = this->LastCutEdges = this->LastRefusedMerges = 0;
  this->LastCrossedTriangles = 0;
  if (!mesh || mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro("The input mesh is empty: the output is empty.");
    return 1;
  }
  vtkdf::HeadlessGL* gl = nullptr;
  if (!this->ChooseBackend(gl))
  {
    return 0;
  }
  vtkdf::SegmentedFieldRequest request;
  vtkdf::IndexBox unused;
  if (!GetOutputGrid(outInfo, request.Grid, unused))
  {
    vtkWarningMacro("The grid is empty: the output is empty.");
    return 1;
  }
  request.Delta = this->Delta;
  request.RegionOffset = this->RegionOffset;
  request.CutSelfIntersections = this->CutSelfIntersections;
  const vtkIdType n = static_cast<vtkIdType>(request.Grid.Whole.Count());
  vtkdf::MeshInput input;
  if (!this->CheckMemory(
        double(n) * (4 + 8 + 1 + 12 + 24 + 8 + 4 + 4 + 4 + 4 + 8), request.Grid.Whole) ||
    !this->ReadMesh(mesh, request.Grid, input))
  {
    return 0;
  }

  auto segmented = vtkdf::NewArray<vtkFloatArray>("SegmentedDistance", n);
  auto region = vtkdf::NewArray<vtkIntArray>("RegionIndex", n);
  auto distance = vtkdf::NewArray<vtkFloatArray>("Distance", n);
  auto patch = vtkdf::NewArray<vtkIntArray>("PatchId", n);
  vtkSmartPointer<vtkFloatArray> points;
  vtkdf::SegmentedFieldArrays arrays;
  arrays.SegmentedDistance = segmented->GetPointer(0);
  arrays.RegionIndex = region->GetPointer(0);
  arrays.Distance = distance->GetPointer(0);
  arrays.PatchId = patch->GetPointer(0);
  if (this->ComputeClosestPoint)
  {
    points = vtkdf::NewArray<vtkFloatArray>("ClosestPoint", n, 3);
    arrays.ClosestPoint = points->GetPointer(0);
  }
  vtkdf::SegmentedFieldReport report;
  std::string error;
  const bool ok = vtkdf::ComputeSegmentedField(
    std::move(input), request, gl, arrays, this->MakeExecution(timer), report, error);
  for (const std::string& warning : report.Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  this->LastCrossedTriangles = report.CrossedTriangles;
  this->LastPatchCount = report.PatchCount;
  this->LastCutEdges = report.CutEdges;
  if (!ok)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (report.Aborted)
  {
    return 1; // the output stays empty
  }
  this->LastRegionCount = report.RegionCount;
  this->LastRefusedMerges = report.RefusedMerges;

  SetOutputExtent(output, request.Grid, request.Grid.Whole);
  output->GetPointData()->SetScalars(segmented);
  output->GetPointData()->AddArray(region);
  output->GetPointData()->AddArray(distance);
  output->GetPointData()->AddArray(patch);
  if (points)
  {
    output->GetPointData()->AddArray(points);
  }
  this->WriteFieldData(report, output->GetFieldData());
  this->UpdateProgress(1.0);
  this->FinishTiming(gl, timer);
  return 1;
}

void vtkSegmentedDistanceField::WriteFieldData(const vtkdf::SegmentedFieldReport& report,
  vtkFieldData* fd)
{
  auto scalar = [fd](const char* name, double value)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  scalar("Delta", report.Delta);
  scalar("RegionOffset", report.RegionOffset);
  scalar("RegionCount", report.RegionCount);
  vtkNew<vtkIntArray> sides;
  sides->SetName("RegionSides");
  sides->SetNumberOfComponents(3);
  for (int32_t g = 0; g < report.RegionCount; ++g)
  {
    for (const auto& s : report.Sides[g])
    {
      const int row[3] = { g, static_cast<int>(s.first), s.second };
      sides->InsertNextTypedTuple(row);
    }
  }
  fd->AddArray(sides);
}

bool vtkSegmentedDistanceField::CheckProperties()
{
  if (!this->Superclass::CheckProperties())
  {
    return false;
  }
  if (!(this->Delta >= 0 && std::isfinite(this->Delta)) ||
    !(this->RegionOffset >= 0 && std::isfinite(this->RegionOffset)))
  {
    vtkErrorMacro("Delta and RegionOffset must be finite and >= 0 (0: the default); they are "
      << this->Delta << " and " << this->RegionOffset << ".");
    return false;
  }
  if (this->Delta > 0 && this->RegionOffset > 0 && !(this->Delta < this->RegionOffset))
  {
    vtkErrorMacro(
      "Delta (" << this->Delta << ") must be below RegionOffset (" << this->RegionOffset << ").");
    return false;
  }
  return true;
}

bool vtkSegmentedDistanceField::IsSelfIntersectionCutAvailable()
{
  return vtkdf::SelfIntersectionCutAvailable();
}

void vtkSegmentedDistanceField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Delta: " << this->Delta << "\n";
  os << indent << "RegionOffset: " << this->RegionOffset << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "LastRegionCount: " << this->LastRegionCount << "\n";
  os << indent << "CutSelfIntersections: " << this->CutSelfIntersections
     << " (cut available in this build: " << IsSelfIntersectionCutAvailable() << ")\n";
  os << indent << "LastPatchCount: " << this->LastPatchCount << "\n";
  os << indent << "LastCrossedTriangles: " << this->LastCrossedTriangles << "\n";
  os << indent << "LastCutEdges: " << this->LastCutEdges << "\n";
  os << indent << "LastRefusedMerges: " << this->LastRefusedMerges << "\n";
}
