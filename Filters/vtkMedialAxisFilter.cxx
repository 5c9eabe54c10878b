#include "vtkMedialAxisFilter.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "Medial/MedialAxisField.h"
#include "Winding/WindingCrossings.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <array>
#include <utility>
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
  // A piece of the grid is computed alone, from the field on it and one voxel around
  // (a voxel's answer depends on the cells it is a corner of).
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

struct vtkMedialAxisFilter::MedialPart
{
  bool Ok = false;
  bool Aborted = false;
  vtkdf::HeadlessGL* GL = nullptr;
  vtkdf::SampleGrid Grid; // Grid.Whole: the voxels computed
  vtkdf::IndexBox Box;
  vtkSmartPointer<vtkUnsignedCharArray> Medial;
  vtkSmartPointer<vtkFloatArray> Angle, Radius;
};

int vtkMedialAxisFilter::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (!vtkImageData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    return this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
  }
  // A field input: the requested voxels and their neighbours (one voxel around).
  RequestGrownImage(inInfo, outputVector->GetInformationObject(0), 1);
  return 1;
}

vtkdf::RunStatus vtkMedialAxisFilter::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkPolyData* mesh = vtkPolyData::GetData(inputVector[0], 0);
  // The whole mesh, gathered when a distributed run partitioned it (vtkDistanceFieldPartitions.h).
  if (!this->InputMesh(mesh))
  {
    return vtkdf::RunStatus::Failed;
  }
  vtkImageData* image = vtkImageData::GetData(inputVector[0], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkPolyData* points = vtkPolyData::GetData(outputVector, 1);
  this->LastMedialCount = 0;
  // Nothing to compute: an empty input or grid, or an empty piece (more ranks than the
  // grid has slabs). Every rank goes on to the gather all the same (a rank leaving early
  // would leave the others waiting there).
  bool nothing = true, empty = true; // empty: the input or the whole grid
  vtkdf::SampleGrid whole;
  vtkdf::IndexBox piece;
  if (mesh && (mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0))
  {
    vtkWarningMacro("The input mesh is empty: the outputs are empty.");
  }
  else if (!GetOutputGrid(outInfo, whole, piece) && whole.Whole.Empty())
  {
    vtkWarningMacro("The grid is empty: the outputs are empty.");
  }
  else if (!mesh && (!image || image->GetNumberOfPoints() == 0) && !piece.Empty())
  {
    vtkWarningMacro("The input is empty: the outputs are empty.");
  }
  else
  {
    empty = false;
    nothing = piece.Empty() || (!mesh && (!image || image->GetNumberOfPoints() == 0));
  }
  // This piece of the grid (all of it in one process) and the voxels that decide it.
  MedialPart part;
  part.Ok =
    nothing || this->ComputePart(mesh, image, whole, piece.Grown(1, whole.Whole), run, part);
  if (part.Ok && !part.Aborted && !nothing)
  {
    // Port 0: this piece of the grid with Medial, SeparationAngle and Radius.
    if (!part.Box.Contains(piece))
    {
      vtkErrorMacro("The input field covers " << part.Box.Lo[0] << ".." << part.Box.Hi[0] << ", "
                                              << part.Box.Lo[1] << ".." << part.Box.Hi[1] << ", "
                                              << part.Box.Lo[2] << ".." << part.Box.Hi[2]
                                              << ", less than the voxels requested.");
      part.Ok = false;
    }
    else
    {
      SetOutputExtent(output, part.Grid, piece);
      if (part.Box == piece)
      {
        output->GetPointData()->AddArray(part.Medial);
        output->GetPointData()->AddArray(part.Angle);
        output->GetPointData()->AddArray(part.Radius);
      }
      else
      {
        output->GetPointData()->AddArray(vtkdf::CropArray(part.Medial.Get(), part.Box, piece));
        output->GetPointData()->AddArray(vtkdf::CropArray(part.Angle.Get(), part.Box, piece));
        output->GetPointData()->AddArray(vtkdf::CropArray(part.Radius.Get(), part.Box, piece));
      }
      output->GetPointData()->SetActiveScalars("Medial");
    }
  }
  // Port 1: a vertex per medial voxel, in voxel order; in a distributed run rank 0 gathers
  // every rank's voxels (each voxel from the one rank that owns it) and outputs them all.
  std::vector<double> owned;
  if (part.Ok && !part.Aborted && !nothing)
  {
    this->OwnedMedialVoxels(part, piece, whole.Whole, owned);
    this->LastMedialCount = static_cast<vtkIdType>(owned.size() / 3);
  }
  const bool gathered = this->GatherMedialVoxels(part.Ok && !part.Aborted, owned);
  if (!part.Ok)
  {
    return vtkdf::RunStatus::Failed;
  }
  if (empty || part.Aborted)
  {
    return vtkdf::RunStatus::Empty;
  }
  if (gathered) // rank 0 (the only one in one process): every rank's medial points
  {
    this->WriteMedialPoints(whole, owned, points);
  }
  return vtkdf::RunStatus::Done;
}

bool vtkMedialAxisFilter::ComputePart(vtkPolyData* mesh,
  vtkImageData* image,
  const vtkdf::SampleGrid& whole,
  const vtkdf::IndexBox& needed,
  vtkdf::FilterRun& run,
  MedialPart& part)
{
  vtkdf::MedialInput field;
  field.SeparationAngle = this->SeparationAngle;
  field.Region = static_cast<vtkdf::MedialRegion>(this->Region);
  vtkSmartPointer<vtkFloatArray> distance, closest;
  vtkdf::MeshInput input;
  std::string error;
  if (mesh)
  {
    field.Grid = whole;
    part.Box = needed;
    // The field (distances, closest points, nearest sites), the cosines, the outputs.
    if (!this->CheckMemory(double(needed.Count()) * (8 + 8 + 1 + 4 + 4 + 16), needed) ||
      !this->ReadMesh(mesh, field.Grid, input))
    {
      return false;
    }
  }
  else if (!GetImageGrid(image, field.Grid))
  {
    return false; // not reached: RequestData checked the image
  }
  else if (!this->ReadField(image, field, distance, closest))
  {
    return false;
  }
  else
  {
    part.Box = field.Grid.Whole; // what the input gives: at least `needed`
  }
  // Where the field and a mesh's winding sign run (Common/BackendPolicy.h), as for the
  // linear factorization.
  vtkdf::WorkDescription work;
  work.Backend = static_cast<vtkdf::BackendChoice>(this->Backend);
  work.Samples = needed.Count();
  work.WindingSign = mesh && this->SignMode == WINDING_NUMBER;
  work.CrossingsDecide = [&] { return vtkdf::CrossingsDecide(input.Points, input.Triangles); };
  if (!run.Resolve(work))
  {
    return false;
  }
  part.GL = run.Context();
  part.Grid = field.Grid;
  const vtkIdType n = static_cast<vtkIdType>(part.Box.Count());
  part.Medial = vtkdf::NewArray<vtkUnsignedCharArray>("Medial", n);
  part.Angle = vtkdf::NewArray<vtkFloatArray>("SeparationAngle", n);
  part.Radius = vtkdf::NewArray<vtkFloatArray>("Radius", n);
  vtkdf::MedialArrays arrays;
  arrays.Medial = part.Medial->GetPointer(0);
  arrays.SeparationAngle = part.Angle->GetPointer(0);
  arrays.Radius = part.Radius->GetPointer(0);
  const vtkdf::Execution execution = run.MakeExecution();
  vtkdf::HeadlessGL* signContext = vtkdf::SignContext(run.Plan());
  const bool ok = mesh ? vtkdf::ComputeMedialAxis(std::move(input),
                           this->SignMode == WINDING_NUMBER ? vtkdf::SignMode::WindingNumber
                                                            : vtkdf::SignMode::PseudoNormal,
                           field,
                           needed,
                           part.GL,
                           arrays,
                           execution,
                           error,
                           signContext)
                       : vtkdf::ComputeMedialAxis(field, part.GL, arrays, execution, error);
  if (!ok)
  {
    vtkErrorMacro(<< error);
    return false;
  }
  part.Aborted = arrays.Aborted;
  return true;
}

void vtkMedialAxisFilter::OwnedMedialVoxels(const MedialPart& part,
  const vtkdf::IndexBox& piece,
  const vtkdf::IndexBox& whole,
  std::vector<double>& owned) const
{
  // Pieces of a grid share their boundary planes: a voxel on one belongs to the piece
  // below it, but on the grid's own last plane.
  vtkdf::IndexBox mine = piece;
  for (int a = 0; a < 3; ++a)
  {
    if (mine.Hi[a] < whole.Hi[a])
    {
      mine.Hi[a] -= 1;
    }
  }
  const vtkIdType nx = part.Box.Size(0), ny = part.Box.Size(1);
  const double wx = whole.Size(0), wy = whole.Size(1);
  for (int k = mine.Lo[2]; k <= mine.Hi[2]; ++k)
  {
    for (int j = mine.Lo[1]; j <= mine.Hi[1]; ++j)
    {
      for (int i = mine.Lo[0]; i <= mine.Hi[0]; ++i)
      {
        const vtkIdType v =
          (vtkIdType(k - part.Box.Lo[2]) * ny + (j - part.Box.Lo[1])) * nx + (i - part.Box.Lo[0]);
        if (part.Medial->GetValue(v))
        {
          // The voxel's index in the whole grid (below 2^53: exact as a double).
          owned.push_back(((k - whole.Lo[2]) * wy + (j - whole.Lo[1])) * wx + (i - whole.Lo[0]));
          owned.push_back(part.Angle->GetValue(v));
          owned.push_back(part.Radius->GetValue(v));
        }
      }
    }
  }
}

bool vtkMedialAxisFilter::GatherMedialVoxels(bool ok, std::vector<double>& owned) const
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() < 2)
  {
    return ok;
  }
  // Every rank takes part, a failed one too (it sends -1), or the others would wait.
  std::vector<double> send = ok ? owned : std::vector<double>{ -1 };
  vtkNew<vtkDoubleArray> mine, all;
  mine->SetArray(send.data(), static_cast<vtkIdType>(send.size()), 1);
  controller->GatherV(mine, all, 0);
  if (controller->GetLocalProcessId() != 0)
  {
    return false;
  }
  const double* values = all->GetPointer(0);
  const vtkIdType n = all->GetNumberOfValues();
  std::vector<std::array<double, 3>> voxels;
  for (vtkIdType at = 0; at < n; at += 3)
  {
    if (values[at] < 0 || at + 3 > n)
    {
      return false; // a rank failed and said why
    }
    voxels.push_back({ values[at], values[at + 1], values[at + 2] });
  }
  std::sort(voxels.begin(),
    voxels.end(),
    [](const std::array<double, 3>& a, const std::array<double, 3>& b) { return a[0] < b[0]; });
  owned.clear();
  for (const auto& voxel : voxels)
  {
    owned.insert(owned.end(), voxel.begin(), voxel.end());
  }
  return true;
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
  // A piece of the field may lie wholly outside the shape: only the whole field tells.
  int extent[6], whole[6];
  image->GetExtent(extent);
  std::copy(extent, extent + 6, whole);
  vtkInformation* inInfo = this->GetInputInformation(0, 0);
  if (inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  }
  if (this->Region == INSIDE && distance->GetRange()[0] >= 0 &&
    std::equal(extent, extent + 6, whole))
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
  const std::vector<double>& voxels,
  vtkPolyData* points)
{
  const vtkIdType count = static_cast<vtkIdType>(voxels.size() / 3);
  vtkNew<vtkPoints> positions;
  positions->SetDataTypeToDouble();
  positions->SetNumberOfPoints(count);
  vtkNew<vtkCellArray> vertices;
  auto pointMedial = vtkdf::NewArray<vtkUnsignedCharArray>("Medial", count);
  auto pointAngle = vtkdf::NewArray<vtkFloatArray>("SeparationAngle", count);
  auto pointRadius = vtkdf::NewArray<vtkFloatArray>("Radius", count);
  const vtkdf::IndexBox& whole = grid.Whole;
  const vtkIdType nx = whole.Size(0), ny = whole.Size(1);
  for (vtkIdType p = 0; p < count; ++p)
  {
    const vtkIdType v = static_cast<vtkIdType>(voxels[3 * p]);
    const int ijk[3] = { whole.Lo[0] + static_cast<int>(v % nx),
      whole.Lo[1] + static_cast<int>((v / nx) % ny),
      whole.Lo[2] + static_cast<int>(v / (nx * ny)) };
    positions->SetPoint(
      p, grid.Coordinate(0, ijk[0]), grid.Coordinate(1, ijk[1]), grid.Coordinate(2, ijk[2]));
    pointMedial->SetValue(p, 1);
    pointAngle->SetValue(p, static_cast<float>(voxels[3 * p + 1]));
    pointRadius->SetValue(p, static_cast<float>(voxels[3 * p + 2]));
    vertices->InsertNextCell(1, &p);
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
    !this->CheckEnum(this->Region, vtkdf::enums::MedialRegion) ||
    !this->CheckEnum(this->SignMode, vtkdf::enums::MedialSign))
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
  os << indent << "Region: " << vtkdf::enums::MedialRegion.Name(this->Region) << "\n";
  os << indent << "SignMode: " << vtkdf::enums::MedialSign.Name(this->SignMode) << "\n";
  os << indent << "LastMedialCount: " << this->LastMedialCount << "\n";
}
