#include "vtkMedialAxisFilter.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "Medial/MedialAxisField.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldPartitions.h"

#include <utility>

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
  vtkPolyData* points = vtkPolyData::GetData(outputVector, 1);
  output->Initialize();
  points->Initialize();
  this->LastMedialCount = 0;
  if (mesh && (mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0))
  {
    vtkWarningMacro("The input mesh is empty: the outputs are empty.");
    return 1;
  }
  vtkdf::HeadlessGL* gl = nullptr;
  if (!this->ChooseBackend(gl))
  {
    return 0;
  }
  vtkdf::MedialInput field;
  field.SeparationAngle = this->SeparationAngle;
  field.Region = static_cast<vtkdf::MedialRegion>(this->Region);
  vtkSmartPointer<vtkFloatArray> distance, closest;
  vtkdf::MeshInput input;
  vtkdf::IndexBox unused;
  std::string error;
  if (mesh)
  {
    if (!GetOutputGrid(outInfo, field.Grid, unused))
    {
      vtkWarningMacro("The grid is empty: the outputs are empty.");
      return 1;
    }
    // The field (distances, closest points, nearest sites), the cosines, the outputs.
    if (!this->CheckMemory(
          double(field.Grid.Whole.Count()) * (8 + 8 + 1 + 4 + 4 + 16), field.Grid.Whole) ||
      !this->ReadMesh(mesh, field.Grid, input))
    {
      return 0;
    }
  }
  else if (!image || !GetImageGrid(image, field.Grid))
  {
    vtkWarningMacro("The input is empty: the outputs are empty.");
    return 1;
  }
  else if (!this->ReadField(image, field, distance, closest))
  {
    return 0;
  }
  const vtkIdType n = static_cast<vtkIdType>(field.Grid.Whole.Count());
  auto medial = vtkdf::NewArray<vtkUnsignedCharArray>("Medial", n);
  auto angle = vtkdf::NewArray<vtkFloatArray>("SeparationAngle", n);
  auto radius = vtkdf::NewArray<vtkFloatArray>("Radius", n);
  vtkdf::MedialArrays arrays;
  arrays.Medial = medial->GetPointer(0);
  arrays.SeparationAngle = angle->GetPointer(0);
  arrays.Radius = radius->GetPointer(0);
  const vtkdf::Execution execution = this->MakeExecution(timer);
  const bool ok = mesh ? vtkdf::ComputeMedialAxis(std::move(input),
                           this->SignMode == WINDING_NUMBER ? vtkdf::SignMode::WindingNumber
                                                            : vtkdf::SignMode::PseudoNormal,
                           field,
                           gl,
                           arrays,
                           execution,
                           error)
                       : vtkdf::ComputeMedialAxis(field, gl, arrays, execution, error);
  if (!ok)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (arrays.Aborted)
  {
    return 1; // empty outputs
  }

  // Port 0: the grid with Medial, SeparationAngle and Radius.
  SetOutputExtent(output, field.Grid, field.Grid.Whole);
  output->GetPointData()->AddArray(medial);
  output->GetPointData()->AddArray(angle);
  output->GetPointData()->AddArray(radius);
  output->GetPointData()->SetActiveScalars("Medial");
  // Port 1: one vertex per medial voxel.
  if (vtkdf::IsFirstRank())
  {
    // Every rank computes the whole grid: in a distributed run rank 0 alone outputs the
    // points, so that the ranks' outputs do not repeat them.
    this->WriteMedialPoints(field.Grid, medial, angle, radius, arrays.Count, points);
  }
  this->LastMedialCount = arrays.Count;
  this->FinishTiming(gl, timer);
  return 1;
}

bool vtkMedialAxisFilter::ReadField(vtkImageData* image,
  vtkdf::MedialInput& field,
  vtkSmartPointer<vtkFloatArray>& distance,
  vtkSmartPointer<vtkFloatArray>& closest)
{
  std::string error;
  distance = FloatArray(image, "Distance", 1, error);
  closest = distance ? FloatArray(image, "ClosestPoint", 3, error) : nullptr;
  if (!distance || !closest)
  {
    vtkErrorMacro(<< error);
    return false;
  }
  if (this->Region == INSIDE && distance->GetRange()[0] >= 0)
  {
    vtkErrorMacro("Region is Inside but the field is unsigned (no negative Distance): compute "
                  "it with SignMode PseudoNormal or WindingNumber, or use Region Outside or "
                  "Both.");
    return false;
  }
  // Cosines (double), the output arrays.
  if (!this->CheckMemory(double(image->GetNumberOfPoints()) * (8 + 1 + 4 + 4), field.Grid.Whole))
  {
    return false;
  }
  field.Distance = distance->GetPointer(0);
  field.ClosestPoint = closest->GetPointer(0);
  return true;
}

void vtkMedialAxisFilter::WriteMedialPoints(const vtkdf::SampleGrid& grid,
  vtkUnsignedCharArray* medial,
  vtkFloatArray* angle,
  vtkFloatArray* radius,
  vtkIdType count,
  vtkPolyData* points)
{
  vtkNew<vtkPoints> positions;
  positions->SetDataTypeToDouble();
  positions->SetNumberOfPoints(count);
  vtkNew<vtkCellArray> vertices;
  auto pointMedial = vtkdf::NewArray<vtkUnsignedCharArray>("Medial", count);
  auto pointAngle = vtkdf::NewArray<vtkFloatArray>("SeparationAngle", count);
  auto pointRadius = vtkdf::NewArray<vtkFloatArray>("Radius", count);
  const vtkdf::IndexBox& whole = grid.Whole;
  const int nx = whole.Size(0), ny = whole.Size(1);
  vtkIdType next = 0;
  for (vtkIdType v = 0; v < medial->GetNumberOfTuples(); ++v)
  {
    if (!medial->GetValue(v))
    {
      continue;
    }
    const int ijk[3] = { whole.Lo[0] + static_cast<int>(v % nx),
      whole.Lo[1] + static_cast<int>((v / nx) % ny),
      whole.Lo[2] + static_cast<int>(v / (vtkIdType(nx) * ny)) };
    positions->SetPoint(
      next, grid.Coordinate(0, ijk[0]), grid.Coordinate(1, ijk[1]), grid.Coordinate(2, ijk[2]));
    pointMedial->SetValue(next, 1);
    pointAngle->SetValue(next, angle->GetValue(v));
    pointRadius->SetValue(next, radius->GetValue(v));
    vertices->InsertNextCell(1, &next);
    ++next;
  }
  points->SetPoints(positions);
  points->SetVerts(vertices);
  points->GetPointData()->AddArray(pointMedial);
  points->GetPointData()->AddArray(pointAngle);
  points->GetPointData()->AddArray(pointRadius);
  points->GetPointData()->SetActiveScalars("Radius");
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
