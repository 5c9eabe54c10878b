#include "vtkMedialAxisFilter.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
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
#include "Medial/MedialAxis.h"
#include "Medial/MedialAxisGPU.h"
#include "LinearFactor/MeshSites.h"
#include "LinearFactor/RangeCulling.h"
#include "vtkDistanceFieldMesh.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkMedialAxisFilter);

namespace
{
/// The named array as float with `components` components; null and `error` otherwise.
vtkSmartPointer<vtkFloatArray> FloatArray(vtkImageData* image,
  const char* name,
  int components,
  std::string& error)
{
  vtkDataArray* array = vtkdf::SampleArray(image, name, components, error);
  if (!array)
  {
    error += " (vtkLinearFactorDistanceField makes Distance and ClosestPoint.)";
    return nullptr;
  }
  vtkSmartPointer<vtkFloatArray> values = vtkFloatArray::SafeDownCast(array);
  if (!values)
  {
    values = vtkSmartPointer<vtkFloatArray>::New();
    values->DeepCopy(array);
  }
  return values;
}
} // namespace

vtkMedialAxisFilter::vtkMedialAxisFilter()
{
  this->SetNumberOfOutputPorts(2);
  this->AcceptsImageInput = true;
  this->ProducesSubExtents = false; // a pair needs its neighbour: the whole grid
}

int vtkMedialAxisFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

vtkPolyData* vtkMedialAxisFilter::GetMedialPoints()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkMedialAxisFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  this->StartTiming();
  vtkPolyData* mesh = vtkPolyData::GetData(inputVector[0], 0);
  vtkImageData* image = vtkImageData::GetData(inputVector[0], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkPolyData* points = vtkPolyData::GetData(outputVector, 1);
  output->Initialize();
  points->Initialize();
  this->LastMedialCount = 0;
  if (mesh && (mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0))
  {
    vtkWarningMacro("The input mesh is empty: the outputs are empty.");
    return 1;
  }
  std::string error;
  vtkdf::HeadlessGL* gl = nullptr;
  if (!this->ChooseBackend(gl))
  {
    return 0;
  }

  vtkdf::MedialInput input;
  input.SeparationAngle = this->SeparationAngle;
  input.Region = this->Region == INSIDE
    ? vtkdf::MedialRegion::Inside
    : (this->Region == OUTSIDE ? vtkdf::MedialRegion::Outside : vtkdf::MedialRegion::Both);
  vtkSmartPointer<vtkFloatArray> distance;
  vtkNew<vtkUnsignedCharArray> medial;
  medial->SetName("Medial");
  std::vector<double> cosine;
  int64_t count = 0;
  // The world grid of the outputs, and what turns the distances into world units (the
  // GPU path from a mesh computes in the grid's local frame).
  vtkdf::SampleGrid outputGrid;
  double distanceScale = 1;

  if (mesh && gl && this->SignMode == PSEUDO_NORMAL)
  {
    // The field and the medial pass, all on the GPU (only distances and cosines return).
    vtkdf::FieldRequest request;
    vtkdf::SampleGrid grid;
    vtkdf::IndexBox unused;
    if (!GetOutputGrid(outInfo, grid, unused))
    {
      vtkWarningMacro("The grid is empty: the outputs are empty.");
      return 1;
    }
    request.Extent = grid.Whole;
    const double n = double(request.Extent.Count());
    if (!this->CheckMemory(n * (8 + 8 + 1 + 4 + 4 + 16), request.Extent))
    {
      return 0;
    }
    // The field and the pairs in the grid's local frame (scale-invariant); the output
    // keeps the world grid, and distances are mapped back below.
    vtkdf::MeshConversion conversion;
    vtkdf::MeshSites sites;
    std::string warning;
    const bool built =
      vtkdf::BuildSites(mesh, vtkdf::Culling::Auto, grid, conversion, sites, warning, error);
    request.Grid = conversion.Grid;
    input.Grid = request.Grid;
    outputGrid = grid;
    distanceScale = conversion.Frame.Scale;
    if (!warning.empty())
    {
      vtkWarningMacro(<< warning);
    }
    if (!built || sites.Sites.empty())
    {
      vtkErrorMacro(<< (built ? "Invalid input mesh: no usable cell." : error));
      return 0;
    }
    vtkdf::RangeCulling culling;
    culling.ReachLevel = 0; // the GPU scan
    culling.Build(sites, request.Grid, request.Extent, HUGE_VAL, vtkdf::SMPFor);
    distance = vtkSmartPointer<vtkFloatArray>::New();
    vtkdf::AllocateTuples(distance, request.Extent.Count());
    vtkdf::AllocateTuples(medial, request.Extent.Count());
    cosine.resize(request.Extent.Count());
    vtkdf::ScanStatistics stats;
    if (!vtkdf::MedialAxisFromSitesGPU(*gl,
          sites,
          culling,
          request,
          input,
          distance->GetPointer(0),
          medial->GetPointer(0),
          cosine.data(),
          count,
          stats,
          error))
    {
      vtkErrorMacro("The GPU backend (" << gl->Renderer() << ") failed: " << error << ".");
      return 0;
    }
    this->EndStage("field+medial");
  }
  else
  {
    // The field: the input image, or the signed field of the input mesh (on this
    // filter's backend; the winding-number sign is computed on the CPU).
    vtkSmartPointer<vtkImageData> field = image;
    if (mesh)
    {
      vtkNew<vtkLinearFactorDistanceField> exact;
      exact->SetInputData(mesh);
      exact->SetResolution(this->Resolution);
      exact->SetPadding(this->Padding);
      exact->SetExplicitGrid(this->ExplicitGrid);
      exact->SetGridOrigin(this->GridOrigin);
      exact->SetGridSpacing(this->GridSpacing);
      exact->SetGridDimensions(this->GridDimensions);
      exact->SetBackend(gl ? BACKEND_GPU : BACKEND_CPU);
      exact->SetMemoryLimit(this->MemoryLimit);
      exact->SetSignMode(this->SignMode == WINDING_NUMBER
          ? vtkLinearFactorDistanceField::WINDING_NUMBER
          : vtkLinearFactorDistanceField::PSEUDO_NORMAL);
      // Its errors become this filter's (a caller observes this filter, not the inner one).
      const vtkdf::InnerErrors innerErrors(exact);
      exact->ComputeClosestPointOn();
      exact->ComputeClosestCellIdOff();
      exact->ComputeClosestFeatureOff();
      exact->Update();
      field = exact->GetOutput();
      if (exact->GetErrorCode() || !field || field->GetNumberOfPoints() == 0)
      {
        vtkErrorMacro("The distance field of the input mesh could not be computed: "
          << innerErrors.Message("no output"));
        return 0;
      }
    }
    this->EndStage("field");
    if (!field || !GetImageGrid(field, input.Grid))
    {
      vtkWarningMacro("The input is empty: the outputs are empty.");
      return 1;
    }
    outputGrid = input.Grid;
    distance = FloatArray(field, "Distance", 1, error);
    vtkSmartPointer<vtkFloatArray> closest =
      distance ? FloatArray(field, "ClosestPoint", 3, error) : nullptr;
    if (!distance || !closest)
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    const vtkIdType n = field->GetNumberOfPoints();
    if (this->Region == INSIDE && distance->GetRange()[0] >= 0)
    {
      vtkErrorMacro("Region is Inside but the field is unsigned (no negative Distance): compute "
                    "it with SignMode PseudoNormal or WindingNumber, or use Region Outside or "
                    "Both.");
      return 0;
    }
    // Cosines (double), the output arrays.
    if (!this->CheckMemory(double(n) * (8 + 1 + 4 + 4), input.Grid.Whole))
    {
      return 0;
    }
    input.Distance = distance->GetPointer(0);
    input.ClosestPoint = closest->GetPointer(0);
    vtkdf::AllocateTuples(medial, n);
    cosine.resize(n);
    if (gl)
    {
      if (!vtkdf::MedialAxisGPU(*gl, input, medial->GetPointer(0), cosine.data(), count, error))
      {
        vtkErrorMacro("The GPU backend (" << gl->Renderer() << ") failed: " << error << ".");
        return 0;
      }
    }
    else
    {
      count = vtkdf::MedialAxisCPU(input, medial->GetPointer(0), cosine.data(), vtkdf::SMPFor);
    }
  }
  const vtkIdType n = medial->GetNumberOfTuples();

  // Port 0: the grid with Medial, SeparationAngle and Radius.
  vtkNew<vtkFloatArray> angle, radius;
  angle->SetName("SeparationAngle");
  vtkdf::AllocateTuples(angle, n);
  radius->SetName("Radius");
  vtkdf::AllocateTuples(radius, n);
  float* a = angle->GetPointer(0);
  float* r = radius->GetPointer(0);
  const float* d = distance->GetPointer(0);
  vtkdf::SMPFor(n,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        a[v] = cosine[v] <= 1
          ? static_cast<float>(std::acos(std::max(-1.0, cosine[v])) * 180.0 / M_PI)
          : 0.0f;
        r[v] = static_cast<float>(std::fabs(d[v]) * distanceScale);
      }
    });
  SetOutputExtent(output, outputGrid, outputGrid.Whole);
  output->GetPointData()->AddArray(medial);
  output->GetPointData()->AddArray(angle);
  output->GetPointData()->AddArray(radius);
  output->GetPointData()->SetActiveScalars("Medial");

  // Port 1: one vertex per medial voxel.
  vtkNew<vtkPoints> positions;
  positions->SetDataTypeToDouble();
  positions->SetNumberOfPoints(count);
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkUnsignedCharArray> pointMedial;
  vtkNew<vtkFloatArray> pointAngle, pointRadius;
  pointMedial->SetName("Medial");
  pointAngle->SetName("SeparationAngle");
  pointRadius->SetName("Radius");
  vtkdf::AllocateTuples(pointMedial, count);
  vtkdf::AllocateTuples(pointAngle, count);
  vtkdf::AllocateTuples(pointRadius, count);
  const vtkdf::IndexBox& whole = outputGrid.Whole;
  const int nx = whole.Size(0), ny = whole.Size(1);
  vtkIdType next = 0;
  for (vtkIdType v = 0; v < n; ++v)
  {
    if (!medial->GetValue(v))
    {
      continue;
    }
    const int ijk[3] = { whole.Lo[0] + static_cast<int>(v % nx),
      whole.Lo[1] + static_cast<int>((v / nx) % ny),
      whole.Lo[2] + static_cast<int>(v / (vtkIdType(nx) * ny)) };
    positions->SetPoint(next,
      outputGrid.Coordinate(0, ijk[0]),
      outputGrid.Coordinate(1, ijk[1]),
      outputGrid.Coordinate(2, ijk[2]));
    pointMedial->SetValue(next, 1);
    pointAngle->SetValue(next, a[v]);
    pointRadius->SetValue(next, r[v]);
    vertices->InsertNextCell(1, &next);
    ++next;
  }
  points->SetPoints(positions);
  points->SetVerts(vertices);
  points->GetPointData()->AddArray(pointMedial);
  points->GetPointData()->AddArray(pointAngle);
  points->GetPointData()->AddArray(pointRadius);
  points->GetPointData()->SetActiveScalars("Radius");

  this->LastMedialCount = count;
  this->EndStage(mesh && gl ? "outputs" : "medial");
  this->FinishTiming(gl);
  return 1;
}

bool vtkMedialAxisFilter::CheckProperties()
{
  if (!this->Superclass::CheckProperties() ||
    !this->CheckEnum("Region", this->Region, { "Inside", "Outside", "Both" }) ||
    !this->CheckEnum("SignMode", this->SignMode, { "PseudoNormal", "WindingNumber" }))
  {
    return false;
  }
  if (!(this->SeparationAngle > 0 && this->SeparationAngle < 180))
  {
    vtkErrorMacro(
      "SeparationAngle must lie in (0, 180) degrees; it is " << this->SeparationAngle << ".");
    return false;
  }
  return true;
}

void vtkMedialAxisFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SeparationAngle: " << this->SeparationAngle << "\n";
  os << indent << "Region: " << EnumName(this->Region, { "Inside", "Outside", "Both" }) << "\n";
  os << indent << "SignMode: " << EnumName(this->SignMode, { "PseudoNormal", "WindingNumber" })
     << "\n";
  os << indent << "LastMedialCount: " << this->LastMedialCount << "\n";
}
