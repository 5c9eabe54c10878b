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

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorScan.h"
#include "LinearFactor/LinearFactorGPU.h"
#include "Winding/WindingSigns.h"
#include "Winding/WindingSignsGPU.h"
#include "vtkDistanceFieldMesh.h"

#include <cmath>
#include <vector>

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
  vtkdf::SampleGrid grid;
  vtkdf::FieldRequest request;
  if (!GetOutputGrid(outInfo, grid, request.Extent))
  {
    vtkWarningMacro("The requested extent is empty: the output is an empty image.");
    return 1;
  }
  if (this->MaximumDistance > 0 && this->MaximumDistance < 1e-3 * grid.MinSpacing())
  {
    vtkErrorMacro("MaximumDistance (" << this->MaximumDistance
                                      << ") is below the field's accuracy, 1e-3 of the smallest "
                                         "spacing ("
                                      << 1e-3 * grid.MinSpacing()
                                      << "): use 0 for no cap, or a larger one.");
    return 0;
  }
  const double samples = double(request.Extent.Count());

  // Refuse grids that overflow indices or memory before allocating anything.
  const double bytesPerSample = 8.0 /* nearest-site buffer */ + (this->ComputeDistance ? 4 : 0) +
    (this->ComputeClosestCellId ? sizeof(vtkIdType) : 0) + (this->ComputeClosestFeature ? 1 : 0) +
    (this->ComputeClosestPoint ? 12 : 0) + (this->ComputeWindingNumber ? 4 : 0) +
    (this->SignMode == WINDING_NUMBER || this->ComputeWindingNumber ? 1 : 0);
  if (!this->CheckMemory(samples * bytesPerSample, request.Extent))
  {
    return 0;
  }

  const vtkdf::Culling culling = this->Culling == CULLING_NON_MANIFOLD
    ? vtkdf::Culling::NonManifold
    : (this->Culling == CULLING_MANIFOLD ? vtkdf::Culling::Manifold : vtkdf::Culling::Auto);
  // The cores work in the grid's local frame (scale-invariant); Finalize maps back.
  vtkdf::MeshConversion conversion;
  vtkdf::MeshSites sites;
  std::string error, warning;
  const bool built = vtkdf::BuildSites(input, culling, grid, conversion, sites, warning, error);
  request.Grid = conversion.Grid;
  if (this->MaximumDistance > 0)
  {
    request.MaximumDistance = this->MaximumDistance / conversion.Frame.Scale;
  }
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

  // Arrays on the requested extent, in world coordinates.
  SetOutputExtent(output, grid, request.Extent);
  const vtkIdType n = static_cast<vtkIdType>(request.Extent.Count());
  vtkdf::FieldArrays arrays;
  arrays.Frame = conversion.Frame;
  vtkPointData* pd = output->GetPointData();
  if (this->ComputeDistance)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName("Distance");
    vtkdf::AllocateTuples(a, n);
    arrays.Distance = a->GetPointer(0);
    arrays.Signed = this->SignMode == PSEUDO_NORMAL;
    pd->SetScalars(a);
  }
  if (this->ComputeClosestCellId)
  {
    vtkNew<vtkIdTypeArray> a;
    a->SetName("ClosestCellId");
    vtkdf::AllocateTuples(a, n);
    static_assert(sizeof(vtkIdType) == sizeof(int64_t), "vtkIdType is 64 bits");
    arrays.ClosestCellId = reinterpret_cast<int64_t*>(a->GetPointer(0));
    pd->AddArray(a);
  }
  if (this->ComputeClosestFeature)
  {
    vtkNew<vtkUnsignedCharArray> a;
    a->SetName("ClosestFeature");
    vtkdf::AllocateTuples(a, n);
    arrays.ClosestFeature = a->GetPointer(0);
    pd->AddArray(a);
  }
  if (this->ComputeClosestPoint)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName("ClosestPoint");
    a->SetNumberOfComponents(3);
    vtkdf::AllocateTuples(a, n);
    arrays.ClosestPoint = a->GetPointer(0);
    pd->AddArray(a);
  }
  vtkdf::Finalize(sites, request, nearest, arrays, vtkdf::SMPFor);
  this->EndStage("finalize");
  if ((this->SignMode == WINDING_NUMBER && this->ComputeDistance) || this->ComputeWindingNumber)
  {
    // Inside where |w| > 1/2, on the filter's backend: the GPU decides every sample in a
    // compute shader and returns only the answers (and w when asked for).
    vtkdf::WindingNumber winding;
    winding.Build(conversion.Mesh.Points, conversion.Mesh.Triangles);
    std::vector<uint8_t> inside(n);
    vtkFloatArray* values = nullptr;
    if (this->ComputeWindingNumber)
    {
      vtkNew<vtkFloatArray> a;
      a->SetName("WindingNumber");
      vtkdf::AllocateTuples(a, n);
      pd->AddArray(a);
      values = a;
    }
    vtkdf::WindingSignOptions options;
    options.Value = values ? values->GetPointer(0) : nullptr;
    // Unsigned still, in world units: blocks near the surface split without trying.
    options.Distance = arrays.Distance;
    options.DistanceScale = 1 / conversion.Frame.Scale;
    vtkdf::WindingSignStatistics stats;
    if (gl)
    {
      if (!vtkdf::WindingSignsGPU(
            *gl, winding, request.Grid, request.Extent, inside.data(), options, stats, error))
      {
        vtkErrorMacro("The GPU backend (" << gl->Renderer() << ") failed: " << error);
        output->Initialize();
        return 0;
      }
    }
    else
    {
      stats = vtkdf::WindingSigns(
        winding, request.Grid, request.Extent, inside.data(), options, vtkdf::SMPFor);
    }
    this->LastWindingBlockSamples = stats.BlockSamples;
    this->LastWindingExactSamples = stats.Exact;
    if (this->SignMode == WINDING_NUMBER && arrays.Distance)
    {
      float* d = arrays.Distance;
      vtkSMPTools::For(0,
        n,
        [d, &inside](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType v = begin; v < end; ++v)
          {
            d[v] = inside[v] ? -std::fabs(d[v]) : std::fabs(d[v]);
          }
        });
    }
    this->EndStage("sign");
  }
  this->UpdateProgress(1.0);
  this->FinishTiming(gl);
  return 1;
}

bool vtkLinearFactorDistanceField::CheckProperties()
{
  if (!this->Superclass::CheckProperties() ||
    !this->CheckEnum("SignMode", this->SignMode, { "Unsigned", "PseudoNormal", "WindingNumber" }) ||
    !this->CheckEnum("Culling", this->Culling, { "Auto", "NonManifold", "Manifold" }))
  {
    return false;
  }
  if (!(this->MaximumDistance >= 0 && std::isfinite(this->MaximumDistance)))
  {
    vtkErrorMacro("MaximumDistance must be finite and >= 0 (0: no cap); it is "
      << this->MaximumDistance << ".");
    return false;
  }
  return true;
}

void vtkLinearFactorDistanceField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "SignMode: " << EnumName(this->SignMode, { "Unsigned", "PseudoNormal", "WindingNumber" })
     << "\n";
  os << indent << "Culling: " << EnumName(this->Culling, { "Auto", "NonManifold", "Manifold" })
     << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance << "\n";
  os << indent << "ComputeDistance: " << this->ComputeDistance << "\n";
  os << indent << "ComputeClosestCellId: " << this->ComputeClosestCellId << "\n";
  os << indent << "ComputeClosestFeature: " << this->ComputeClosestFeature << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "ComputeWindingNumber: " << this->ComputeWindingNumber << "\n";
  os << indent << "LastEvaluations: " << this->LastEvaluations << "\n";
  os << indent << "LastWindingBlockSamples: " << this->LastWindingBlockSamples << "\n";
  os << indent << "LastWindingExactSamples: " << this->LastWindingExactSamples << "\n";
  os << indent << "LastCullingFactor: " << this->LastCullingFactor << "\n";
}
