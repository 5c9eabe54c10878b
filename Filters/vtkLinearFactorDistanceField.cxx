#include "vtkLinearFactorDistanceField.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "HeadlessGL.h"
#include "LinearFactorField.h"
#include "LinearFactorGPU.h"
#include "vtkDistanceFieldMesh.h"

#include <cmath>

vtkStandardNewMacro(vtkLinearFactorDistanceField);

vtkLinearFactorDistanceField::vtkLinearFactorDistanceField() = default;

int vtkLinearFactorDistanceField::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  this->StartTiming();
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  this->LastEvaluations = 0;
  this->LastCullingFactor = 0;

  if (!input || input->GetNumberOfCells() == 0 || input->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro("The input mesh is empty: the output is an empty image.");
    return 1;
  }

  // The grid (RequestInformation) and the part of it requested (streaming).
  vtkdf::FieldRequest request;
  if (!GetOutputGrid(outInfo, request.Grid, request.Extent))
  {
    vtkWarningMacro("The input mesh uses no point, or the requested extent is empty: the output is "
                    "an empty image.");
    return 1;
  }
  double origin[3], spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = request.Grid.Origin[a];
    spacing[a] = request.Grid.Spacing[a];
  }
  const double samples = double(request.Extent.Count());

  // Refuse grids that overflow indices or memory before allocating anything.
  const double bytesPerSample = 8.0 /* nearest-site buffer */ + (this->ComputeDistance ? 4 : 0) +
    (this->ComputeClosestCellId ? sizeof(vtkIdType) : 0) + (this->ComputeClosestFeature ? 1 : 0) +
    (this->ComputeClosestPoint ? 12 : 0);
  if (!this->CheckMemory(samples * bytesPerSample, request.Extent))
  {
    return 0;
  }

  if (this->MaximumDistance > 0)
  {
    request.MaximumDistance = this->MaximumDistance;
  }
  const vtkdf::Culling culling = this->Culling == CULLING_NON_MANIFOLD
    ? vtkdf::Culling::NonManifold
    : (this->Culling == CULLING_MANIFOLD ? vtkdf::Culling::Manifold : vtkdf::Culling::Auto);
  vtkdf::MeshSites sites;
  std::string error, warning;
  const bool built = vtkdf::BuildSites(input, culling, request.Grid, sites, warning, error);
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }
  if (!built)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (sites.Sites.empty())
  {
    vtkWarningMacro("The input has no usable cell: the output is an empty image.");
    return 1;
  }

  this->EndStage("sites");
  vtkdf::HeadlessGL* gl = nullptr;
  if (!this->ChooseBackend(gl))
  {
    return 0;
  }

  this->UpdateProgress(0.0);
  vtkdf::RangeCulling range;
  range.ReachLevel = gl ? 0 : 1;
  range.Build(sites, request.Grid, request.Extent, request.MaximumDistance, vtkdf::SMPFor);
  this->EndStage("culling");
  this->UpdateProgress(0.1);

  vtkdf::NearestSiteBuffer nearest;
  nearest.Reset(request.Extent.Count(), vtkdf::SMPFor);
  auto progress = [this](double fraction)
  {
    this->UpdateProgress(0.1 + 0.8 * fraction);
    return !this->GetAbortExecute();
  };
  vtkdf::ScanStatistics stats;
  if (gl)
  {
    if (!vtkdf::ScanSitesGPU(*gl, sites, range, request, nearest, progress, stats, error))
    {
      vtkErrorMacro("The GPU backend (" << gl->Renderer() << ") failed: " << error);
      return 0;
    }
  }
  else
  {
    stats = vtkdf::ScanSitesCPU(sites, range, request, nearest, vtkdf::SMPFor, progress);
  }
  if (stats.Aborted)
  {
    this->FinishTiming(gl);
    output->Initialize();
    return 1;
  }
  this->EndStage("scan");
  this->LastEvaluations = stats.Evaluations;
  this->LastCullingFactor = stats.Evaluations >= 0 ? double(stats.Evaluations) / samples : -1.0;

  // Arrays on the requested extent.
  output->SetExtent(request.Extent.Lo[0],
    request.Extent.Hi[0],
    request.Extent.Lo[1],
    request.Extent.Hi[1],
    request.Extent.Lo[2],
    request.Extent.Hi[2]);
  output->SetOrigin(origin);
  output->SetSpacing(spacing);
  const vtkIdType n = static_cast<vtkIdType>(request.Extent.Count());
  vtkdf::FieldArrays arrays;
  vtkPointData* pd = output->GetPointData();
  if (this->ComputeDistance)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName("Distance");
    a->SetNumberOfTuples(n);
    arrays.Distance = a->GetPointer(0);
    arrays.Signed = this->SignMode == PSEUDO_NORMAL;
    pd->SetScalars(a);
  }
  if (this->ComputeClosestCellId)
  {
    vtkNew<vtkIdTypeArray> a;
    a->SetName("ClosestCellId");
    a->SetNumberOfTuples(n);
    static_assert(sizeof(vtkIdType) == sizeof(int64_t), "vtkIdType is 64 bits");
    arrays.ClosestCellId = reinterpret_cast<int64_t*>(a->GetPointer(0));
    pd->AddArray(a);
  }
  if (this->ComputeClosestFeature)
  {
    vtkNew<vtkUnsignedCharArray> a;
    a->SetName("ClosestFeature");
    a->SetNumberOfTuples(n);
    arrays.ClosestFeature = a->GetPointer(0);
    pd->AddArray(a);
  }
  if (this->ComputeClosestPoint)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName("ClosestPoint");
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(n);
    arrays.ClosestPoint = a->GetPointer(0);
    pd->AddArray(a);
  }
  vtkdf::Finalize(sites, request, nearest, arrays, vtkdf::SMPFor);
  this->EndStage("finalize");
  this->UpdateProgress(1.0);
  this->FinishTiming(gl);
  return 1;
}

void vtkLinearFactorDistanceField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const char* cullings[] = { "Auto", "NonManifold", "Manifold" };
  os << indent << "SignMode: " << (this->SignMode == PSEUDO_NORMAL ? "PseudoNormal" : "Unsigned")
     << "\n";
  os << indent << "Culling: " << cullings[this->Culling] << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance << "\n";
  os << indent << "ComputeDistance: " << this->ComputeDistance << "\n";
  os << indent << "ComputeClosestCellId: " << this->ComputeClosestCellId << "\n";
  os << indent << "ComputeClosestFeature: " << this->ComputeClosestFeature << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "LastEvaluations: " << this->LastEvaluations << "\n";
  os << indent << "LastCullingFactor: " << this->LastCullingFactor << "\n";
}
