#include "vtkSegmentedDistanceField.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorScan.h"
#include "LinearFactor/MeshSites.h"
#include "LinearFactor/RangeCulling.h"
#include "Segment/SegmentFieldGPU.h"
#include "Segment/SegmentRegions.h"
#include "Segment/SelfIntersections.h"
#include "Segment/SurfacePatches.h"
#include "vtkDistanceFieldMesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkSegmentedDistanceField);

vtkSegmentedDistanceField::vtkSegmentedDistanceField()
{
  this->ProducesSubExtents = false; // regions are global: the whole grid
}

int vtkSegmentedDistanceField::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  this->StartTiming();
  vtkPolyData* mesh = vtkPolyData::GetData(inputVector[0], 0);
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
  vtkdf::SampleGrid grid;
  vtkdf::IndexBox unused;
  if (!GetOutputGrid(outInfo, grid, unused))
  {
    vtkWarningMacro("The grid is empty: the output is empty.");
    return 1;
  }
  const double largest = std::max({ grid.Spacing[0], grid.Spacing[1], grid.Spacing[2] });
  const double delta = this->Delta > 0 ? this->Delta : 2 * largest;
  const double offset = this->RegionOffset > 0 ? this->RegionOffset : 4 * largest;
  if (delta < largest || !(delta < offset))
  {
    vtkErrorMacro("Delta must be at least the largest grid spacing ("
      << largest << ") and below RegionOffset; they are " << delta << " and " << offset << ".");
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(grid.Whole.Count());
  if (!this->CheckMemory(double(n) * (4 + 8 + 1 + 12 + 24 + 8 + 4 + 4 + 4 + 4 + 8), grid.Whole))
  {
    return 0;
  }

  // The triangles, their patches, and a copy of the mesh with only those that have one.
  std::string error;
  vtkdf::MeshConversion conversion;
  if (!conversion.Run(mesh, grid, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const auto& mi = conversion.Mesh;
  if (!mi.Segments.empty() || !mi.Vertices.empty())
  {
    vtkWarningMacro("The segmented distance is that of the surface: "
      << mi.SegmentCells.size() << " line segments and " << mi.Vertices.size()
      << " vertices are ignored.");
  }
  // Cut along crossings in world coordinates (the cut's new points are rounded there, so
  // the inner field and the patches see the same points).
  const std::vector<double>* patchPoints = &mi.Points;
  const std::vector<int64_t>* patchTriangles = &mi.Triangles;
  vtkdf::SelfIntersectionCut cut;
  std::vector<double> cutLocal;
  vtkSmartPointer<vtkPoints> surfacePoints = mesh->GetPoints();
  if (this->CutSelfIntersections)
  {
    std::vector<double> world(3 * static_cast<size_t>(mesh->GetNumberOfPoints()));
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      mesh->GetPoint(p, &world[3 * p]);
    }
    std::string cutError;
    if (!vtkdf::CutSelfIntersections(world, mi.Triangles, cut, cutError))
    {
      vtkWarningMacro(<< cutError << ". The field is that of the uncut mesh.");
    }
    else if (cut.FailedGroups > 0)
    {
      vtkWarningMacro(<< cut.FailedGroups << " of " << cut.CrossingGroups
                      << " groups of crossing triangles (" << cut.FailedTriangles
                      << " triangles) could not be cut along their crossings (CGAL: "
                      << cut.FailedMessage << "); there the field is that of the uncut mesh.");
    }
    if (cut.Cut())
    {
      this->LastCrossedTriangles = cut.CutTriangles;
      cutLocal.resize(cut.Points.size());
      surfacePoints = vtkSmartPointer<vtkPoints>::New();
      surfacePoints->SetDataTypeToDouble();
      surfacePoints->SetNumberOfPoints(static_cast<vtkIdType>(cut.Points.size() / 3));
      for (size_t p = 0; p < cut.Points.size() / 3; ++p)
      {
        surfacePoints->SetPoint(static_cast<vtkIdType>(p), &cut.Points[3 * p]);
        for (int a = 0; a < 3; ++a)
        {
          cutLocal[3 * p + a] = conversion.Frame.ToLocal(a, cut.Points[3 * p + a]);
        }
      }
      patchPoints = &cutLocal;
      patchTriangles = &cut.Triangles;
    }
  }
  this->EndStage("crossings");
  vtkdf::SurfacePatches patches;
  patches.Build(*patchPoints, *patchTriangles);
  this->LastPatchCount = patches.PatchCount;
  this->LastCutEdges = patches.CutEdges;
  std::vector<int64_t> kept;
  vtkNew<vtkCellArray> polys;
  for (size_t t = 0; t < patches.Patch.size(); ++t)
  {
    if (patches.Patch[t] >= 0)
    {
      kept.push_back(static_cast<int64_t>(t));
      const vtkIdType ids[3] = {
        (*patchTriangles)[3 * t], (*patchTriangles)[3 * t + 1], (*patchTriangles)[3 * t + 2]
      };
      polys->InsertNextCell(3, ids);
    }
  }
  if (kept.empty())
  {
    vtkErrorMacro("The input has no triangle with an area: there is no surface to segment.");
    return 0;
  }
  if (patches.CutEdges > 0)
  {
    vtkWarningMacro(
      "Some patches are not orientable: they were cut along " << patches.CutEdges << " edges.");
  }
  this->EndStage("patches");

  // The exact unsigned field with closest features, and each sample's side label: on the
  // GPU the field stays there and the labels are computed where it lies (SegmentFieldGPU);
  // on the CPU from vtkLinearFactorDistanceField's arrays (SegmentRegions).
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(surfacePoints);
  surface->SetPolys(polys);
  const vtkdf::GridFrame& frame = conversion.Frame;
  vtkSmartPointer<vtkFloatArray> distance, points; // world units, for the output
  std::vector<float> localDistance(n);
  std::vector<int32_t> labels;
  std::vector<int64_t> triangle;
  std::vector<double> closest;
  vtkSmartPointer<vtkUnsignedCharArray> features;
  if (gl)
  {
    vtkdf::MeshConversion siteConversion; // the same local frame: it depends on the grid
    vtkdf::MeshSites sites;
    std::string warning;
    if (!vtkdf::BuildSites(
          surface, vtkdf::Culling::Auto, grid, siteConversion, sites, warning, error) ||
      sites.Sites.empty())
    {
      vtkErrorMacro(<< (error.empty() ? "Invalid input mesh: no usable cell." : error));
      return 0;
    }
    vtkdf::FieldRequest request;
    request.Grid = siteConversion.Grid;
    request.Extent = grid.Whole;
    vtkdf::RangeCulling culling;
    culling.ReachLevel = 0; // the GPU scan
    culling.Build(sites, request.Grid, request.Extent, HUGE_VAL, vtkdf::SMPFor);
    std::vector<int32_t> siteTriangle(2 * sites.Sites.size());
    for (size_t i = 0; i < sites.Sites.size(); ++i)
    {
      const int64_t c = sites.Sites[i].CellId;
      siteTriangle[2 * i] =
        c >= 0 && c < static_cast<int64_t>(kept.size()) ? static_cast<int32_t>(kept[c]) : -1;
      siteTriangle[2 * i + 1] = sites.Sites[i].Type;
    }
    std::vector<float> localClosest(3 * static_cast<size_t>(n));
    labels.resize(n);
    vtkdf::ScanStatistics stats;
    auto progress = [this](double fraction)
    {
      this->UpdateProgress(0.05 + 0.5 * fraction);
      return !this->GetAbortExecute();
    };
    if (!vtkdf::SegmentFieldGPU(*gl,
          sites,
          culling,
          request,
          patches,
          siteTriangle,
          localDistance.data(),
          localClosest.data(),
          labels.data(),
          stats,
          error,
          progress))
    {
      vtkErrorMacro("The GPU field and side labels failed: " << error);
      return 0;
    }
    if (stats.Aborted)
    {
      return 1; // aborted: the output stays empty
    }
    distance = vtkSmartPointer<vtkFloatArray>::New();
    distance->SetName("Distance");
    vtkdf::AllocateTuples(distance, n);
    points = vtkSmartPointer<vtkFloatArray>::New();
    points->SetName("ClosestPoint");
    points->SetNumberOfComponents(3);
    vtkdf::AllocateTuples(points, n);
    float* d = distance->GetPointer(0);
    float* x = points->GetPointer(0);
    vtkdf::SMPFor(n,
      4096,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t v = begin; v < end; ++v)
        {
          d[v] = static_cast<float>(localDistance[v] * frame.Scale);
          for (int a = 0; a < 3; ++a)
          {
            x[3 * v + a] = static_cast<float>(frame.ToWorld(a, localClosest[3 * v + a]));
          }
        }
      });
  }
  else
  {
    vtkNew<vtkLinearFactorDistanceField> exact;
    const vtkdf::InnerErrors innerErrors(exact);
    exact->SetInputData(surface);
    exact->ExplicitGridOn();
    exact->SetGridOrigin(grid.Origin.data());
    exact->SetGridSpacing(grid.Spacing.data());
    exact->SetGridDimensions(grid.Whole.Size(0), grid.Whole.Size(1), grid.Whole.Size(2));
    exact->SetBackendToCPU();
    exact->SetMemoryLimit(this->MemoryLimit);
    exact->SetSignModeToUnsigned();
    exact->ComputeClosestCellIdOn();
    exact->ComputeClosestFeatureOn();
    exact->ComputeClosestPointOn();
    exact->Update();
    vtkImageData* field = exact->GetOutput();
    auto* d =
      field ? vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("Distance")) : nullptr;
    auto* cells = field
      ? vtkIdTypeArray::SafeDownCast(field->GetPointData()->GetArray("ClosestCellId"))
      : nullptr;
    features = field
      ? vtkUnsignedCharArray::SafeDownCast(field->GetPointData()->GetArray("ClosestFeature"))
      : nullptr;
    auto* x = field ? vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("ClosestPoint"))
                    : nullptr;
    if (exact->GetErrorCode() || !field || field->GetNumberOfPoints() != n || !d || !cells ||
      !features || !x)
    {
      vtkErrorMacro("The distance field of the input could not be computed: "
        << innerErrors.Message("no output"));
      return 0;
    }
    distance = d; // the inner filter's arrays, named as the output's
    points = x;
    triangle.resize(n);
    closest.resize(3 * static_cast<size_t>(n));
    vtkdf::SMPFor(n,
      4096,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t v = begin; v < end; ++v)
        {
          localDistance[v] = static_cast<float>(d->GetValue(v) / frame.Scale);
          const vtkIdType c = cells->GetValue(v);
          triangle[v] = c >= 0 && c < static_cast<vtkIdType>(kept.size()) ? kept[c] : -1;
          for (int a = 0; a < 3; ++a)
          {
            closest[3 * v + a] = frame.ToLocal(a, x->GetValue(3 * v + a));
          }
        }
      });
  }
  this->EndStage("field");
  this->UpdateProgress(0.6);

  // Regions, in the grid's local frame.
  vtkdf::SegmentInput input;
  input.Patches = &patches;
  input.Grid = conversion.Grid;
  input.Distance = localDistance.data();
  if (gl)
  {
    input.Labels = labels.data();
  }
  else
  {
    input.ClosestTriangle = triangle.data();
    input.ClosestFeature = features->GetPointer(0);
    input.ClosestPoint = closest.data();
  }
  vtkdf::SegmentResult result;
  vtkdf::SegmentRegions(input, result, vtkdf::SMPFor);
  this->LastRegionCount = result.RegionCount;
  this->LastRefusedMerges = result.Refused;
  this->EndStage("regions");
  // SegmentedDistance is float: its largest value must exist, and distances near it keep
  // what float's resolution there leaves them.
  const double top = offset * std::max(0, result.RegionCount - 1) + delta;
  if (!(top <= std::numeric_limits<float>::max()))
  {
    vtkErrorMacro("RegionOffset (" << offset << ") times the " << result.RegionCount - 1
                                   << " regions after the first exceeds the float range of "
                                      "SegmentedDistance.");
    return 0;
  }
  const double resolution = top * std::numeric_limits<float>::epsilon();
  if (resolution > 1e-3 * std::min({ grid.Spacing[0], grid.Spacing[1], grid.Spacing[2] }))
  {
    vtkWarningMacro("SegmentedDistance is float: in region "
      << result.RegionCount - 1 << " it resolves distances only to " << resolution
      << " (a smaller RegionOffset keeps more).");
  }

  // Arrays.
  vtkNew<vtkFloatArray> segmented;
  segmented->SetName("SegmentedDistance");
  vtkdf::AllocateTuples(segmented, n);
  vtkNew<vtkIntArray> region, patch;
  region->SetName("RegionIndex");
  vtkdf::AllocateTuples(region, n);
  patch->SetName("PatchId");
  vtkdf::AllocateTuples(patch, n);
  float* f = segmented->GetPointer(0);
  int* r = region->GetPointer(0);
  int* pid = patch->GetPointer(0);
  vtkdf::SMPFor(n,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        r[v] = result.Region[v];
        pid[v] = result.Patch[v];
        f[v] = static_cast<float>(
          std::min(double(distance->GetValue(v)), delta) + offset * std::max(0, r[v]));
      }
    });
  SetOutputExtent(output, grid, grid.Whole);
  output->GetPointData()->SetScalars(segmented);
  output->GetPointData()->AddArray(region);
  output->GetPointData()->AddArray(distance);
  output->GetPointData()->AddArray(patch);
  if (this->ComputeClosestPoint)
  {
    output->GetPointData()->AddArray(points);
  }
  vtkFieldData* fd = output->GetFieldData();
  auto scalar = [fd](const char* name, double value)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  scalar("Delta", delta);
  scalar("RegionOffset", offset);
  scalar("RegionCount", result.RegionCount);
  vtkNew<vtkIntArray> sides;
  sides->SetName("RegionSides");
  sides->SetNumberOfComponents(3);
  for (int32_t g = 0; g < result.RegionCount; ++g)
  {
    for (const auto& s : result.Sides[g])
    {
      const int row[3] = { g, static_cast<int>(s.first), s.second };
      sides->InsertNextTypedTuple(row);
    }
  }
  fd->AddArray(sides);
  this->UpdateProgress(1.0);
  this->FinishTiming(gl);
  return 1;
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

void vtkSegmentedDistanceField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Delta: " << this->Delta << "\n";
  os << indent << "RegionOffset: " << this->RegionOffset << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "LastRegionCount: " << this->LastRegionCount << "\n";
  os << indent << "CutSelfIntersections: " << this->CutSelfIntersections << "\n";
  os << indent << "LastPatchCount: " << this->LastPatchCount << "\n";
  os << indent << "LastCrossedTriangles: " << this->LastCrossedTriangles << "\n";
  os << indent << "LastCutEdges: " << this->LastCutEdges << "\n";
  os << indent << "LastRefusedMerges: " << this->LastRefusedMerges << "\n";
}
