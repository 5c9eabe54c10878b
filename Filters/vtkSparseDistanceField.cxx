#include "vtkSparseDistanceField.h"

#include "vtkCellData.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSignedCharArray.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include "Common/Parallel.h"
#include "LinearFactor/SparseBand.h"

#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <cmath>
#include <utility>

vtkStandardNewMacro(vtkSparseDistanceField);

namespace
{
/// The grid of bricks over a whole grid (SparseBand.h's: at least one brick per axis).
std::array<int, 3> BrickCounts(const vtkdf::IndexBox& whole, int brickSize)
{
  std::array<int, 3> counts;
  for (int a = 0; a < 3; ++a)
  {
    const int64_t intervals = int64_t(whole.Hi[a]) - whole.Lo[a];
    counts[a] = static_cast<int>(std::max<int64_t>(1, (intervals + brickSize - 1) / brickSize));
  }
  return counts;
}

/// A VTK array that adopts a brick's block (released by ReleaseBlock: Common/BlockArena.h).
template<typename ArrayT, typename T>
vtkNew<ArrayT> AdoptArray(const char* name,
  vtkdf::BrickArray<T>& block,
  vtkIdType tuples,
  int components = 1)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetArray(reinterpret_cast<typename ArrayT::ValueType*>(block.release()),
    tuples * components,
    0,
    vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(vtkdf::ReleaseBlock);
  return array;
}

/// One brick as a vtkImageData of the global grid, its arrays adopted.
vtkSmartPointer<vtkImageData> BrickImage(vtkdf::SparseBrick& brick,
  const vtkdf::SampleGrid& grid,
  bool keepFeature)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  const vtkdf::IndexBox& e = brick.Extent;
  image->SetExtent(e.Lo[0], e.Hi[0], e.Lo[1], e.Hi[1], e.Lo[2], e.Hi[2]);
  image->SetOrigin(grid.Origin.data());
  image->SetSpacing(grid.Spacing.data());
  const vtkIdType n = static_cast<vtkIdType>(e.Count());
  vtkPointData* pd = image->GetPointData();
  // The ghost array: HIDDENPOINT beyond the band (ClosestFeature 255), written over the
  // features' own block when they are not kept.
  vtkdf::BrickArray<uint8_t> hidden =
    keepFeature ? vtkdf::NewBlockArray<uint8_t>(n) : std::move(brick.ClosestFeature);
  const uint8_t* feature = keepFeature ? brick.ClosestFeature.get() : hidden.get();
  std::transform(feature,
    feature + n,
    hidden.get(),
    [](uint8_t f) { return f == 255 ? uint8_t(vtkDataSetAttributes::HIDDENPOINT) : uint8_t(0); });
  pd->AddArray(AdoptArray<vtkUnsignedCharArray>(vtkDataSetAttributes::GhostArrayName(), hidden, n));
  pd->SetScalars(AdoptArray<vtkFloatArray>("Distance", brick.Distance, n));
  if (brick.ClosestCellId)
  {
    static_assert(sizeof(vtkIdType) == sizeof(int64_t), "vtkIdType is 64 bits");
    pd->AddArray(AdoptArray<vtkIdTypeArray>("ClosestCellId", brick.ClosestCellId, n));
  }
  if (keepFeature)
  {
    pd->AddArray(AdoptArray<vtkUnsignedCharArray>("ClosestFeature", brick.ClosestFeature, n));
  }
  if (brick.ClosestPoint)
  {
    pd->AddArray(AdoptArray<vtkFloatArray>("ClosestPoint", brick.ClosestPoint, n, 3));
  }
  return image;
}

/// The coarse grid of sides: a cell per brick.
void SidesImage(const vtkdf::SparseBandField& field,
  const vtkdf::SampleGrid& grid,
  vtkImageData* sides)
{
  const std::array<int, 3>& nb = field.BrickCounts;
  sides->SetExtent(0, nb[0], 0, nb[1], 0, nb[2]);
  double origin[3], spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = grid.Coordinate(a, grid.Whole.Lo[a]);
    spacing[a] = grid.Spacing[a] * field.BrickSize;
  }
  sides->SetOrigin(origin);
  sides->SetSpacing(spacing);
  const vtkIdType cells = static_cast<vtkIdType>(field.Sides.size());
  vtkNew<vtkSignedCharArray> side;
  side->SetName("Side");
  side->SetNumberOfTuples(cells);
  std::copy(field.Sides.begin(), field.Sides.end(), side->GetPointer(0));
  vtkNew<vtkIntArray> piece;
  piece->SetName("Piece");
  piece->SetNumberOfTuples(cells);
  std::copy(field.BrickOf.begin(), field.BrickOf.end(), piece->GetPointer(0));
  sides->GetCellData()->AddArray(side);
  sides->GetCellData()->AddArray(piece);
}
} // namespace

vtkSparseDistanceField::vtkSparseDistanceField()
{
  this->SetNumberOfOutputPorts(2);
  this->ProducesSubExtents = false;
}

int vtkSparseDistanceField::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPartitionedDataSet" : "vtkImageData");
  return 1;
}

int vtkSparseDistanceField::RequestInformation(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The grid, on port 0's information (the base's), and the grid of bricks on port 1's.
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkdf::SampleGrid grid;
  vtkdf::IndexBox extent;
  int whole[6] = { 0, -1, 0, -1, 0, -1 };
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  if (GetOutputGrid(outputVector->GetInformationObject(0), grid, extent))
  {
    const std::array<int, 3> counts = BrickCounts(grid.Whole, this->BrickSize);
    for (int a = 0; a < 3; ++a)
    {
      whole[2 * a] = 0;
      whole[2 * a + 1] = counts[a];
      origin[a] = grid.Coordinate(a, grid.Whole.Lo[a]);
      spacing[a] = grid.Spacing[a] * this->BrickSize;
    }
  }
  vtkInformation* sidesInfo = outputVector->GetInformationObject(1);
  sidesInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  sidesInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  sidesInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  return 1;
}

vtkdf::RunStatus vtkSparseDistanceField::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  this->LastBandSamples = this->LastPieces = this->LastCandidateBricks = 0;
  this->LastPieceMemory = 0;
  if (this->Backend == BACKEND_GPU)
  {
    return run.Fail("The sparse band runs on the CPU only: set Backend to Auto or CPU.");
  }
  vtkPolyData* input = nullptr;
  vtkdf::SparseBandRequest request;
  vtkdf::IndexBox extent;
  const vtkdf::RunStatus opened =
    this->OpenMeshRun(inputVector, outputVector, run, input, request.Grid, extent);
  if (opened != vtkdf::RunStatus::Done)
  {
    return opened;
  }
  vtkdf::MeshInput mesh;
  if (!this->ReadMesh(input, request.Grid, mesh) || !run.ResolveBackend(BACKEND_CPU))
  {
    return vtkdf::RunStatus::Failed;
  }
  run.Timer.End("input");
  request.BandWidth = this->BandWidth * request.Grid.MinSpacing();
  request.BrickSize = this->BrickSize;
  request.Domains = static_cast<vtkdf::DomainShape>(this->DomainShape);
  request.Sign =
    this->SignMode == PSEUDO_NORMAL ? vtkdf::SignMode::PseudoNormal : vtkdf::SignMode::Unsigned;
  request.ClosestCellId = this->ComputeClosestCellId;
  request.ClosestPoint = this->ComputeClosestPoint;
  request.MemoryLimit = this->EffectiveMemoryLimit();
  vtkdf::SparseBandField field;
  std::string error;
  if (!vtkdf::ComputeSparseBand(std::move(mesh), request, run.MakeExecution(), field, error))
  {
    return run.Fail(error);
  }
  if (field.NoUsableCell)
  {
    return run.Empty("The input has no usable cell: the outputs are empty.");
  }
  if (field.Aborted)
  {
    return run.Empty();
  }
  this->LastBandSamples = field.BandSamples;
  this->LastPieces = static_cast<vtkTypeInt64>(field.Bricks.size());
  this->LastCandidateBricks = field.CandidateBricks;
  this->LastPieceMemory = double(field.Bytes()) / 1048576.0;
  vtkPartitionedDataSet* pieces = vtkPartitionedDataSet::GetData(outputVector, 0);
  pieces->SetNumberOfPartitions(static_cast<unsigned int>(field.Bricks.size()));
  for (size_t b = 0; b < field.Bricks.size(); ++b)
  {
    pieces->SetPartition(static_cast<unsigned int>(b),
      BrickImage(field.Bricks[b], request.Grid, this->ComputeClosestFeature));
  }
  // The band's half-width in world units: what a reader of the pieces (the .vdb writer,
  // vtkOpenVDBLevelSetWriter) takes as the level set's background.
  vtkNew<vtkDoubleArray> bandWidth;
  bandWidth->SetName("BandWidth");
  bandWidth->InsertNextValue(request.BandWidth);
  pieces->GetFieldData()->AddArray(bandWidth);
  SidesImage(field, request.Grid, vtkImageData::GetData(outputVector, 1));
  run.Timer.End("pieces");
  return vtkdf::RunStatus::Done;
}

std::string vtkSparseDistanceField::PointCloudRefusal()
{
  if (this->SignMode != UNSIGNED)
  {
    return "a sign (SignMode) needs a surface; with SignMode Unsigned the field is the "
           "distance to the points";
  }
  return std::string();
}

bool vtkSparseDistanceField::CheckProperties()
{
  if (!this->Superclass::CheckProperties() ||
    !this->CheckEnum(this->SignMode, vtkdf::enums::SparseSign) ||
    !this->CheckEnum(this->DomainShape, vtkdf::enums::DomainShape))
  {
    return false;
  }
  if (!(std::isfinite(this->BandWidth) && this->BandWidth >= 1e-3))
  {
    vtkErrorMacro(
      "BandWidth must be finite and at least 1e-3 (spacings); it is " << this->BandWidth << ".");
    return false;
  }
  if (this->BrickSize < 2 || this->BrickSize > 1024)
  {
    vtkErrorMacro("BrickSize must be between 2 and 1024; it is " << this->BrickSize << ".");
    return false;
  }
  return true;
}

void vtkSparseDistanceField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SignMode: " << vtkdf::enums::SparseSign.Name(this->SignMode) << "\n";
  os << indent << "DomainShape: " << vtkdf::enums::DomainShape.Name(this->DomainShape) << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "BrickSize: " << this->BrickSize << "\n";
  os << indent << "ComputeClosestCellId: " << this->ComputeClosestCellId << "\n";
  os << indent << "ComputeClosestFeature: " << this->ComputeClosestFeature << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "LastBandSamples: " << this->LastBandSamples << "\n";
  os << indent << "LastPieces: " << this->LastPieces << "\n";
  os << indent << "LastCandidateBricks: " << this->LastCandidateBricks << "\n";
  os << indent << "LastPieceMemory: " << this->LastPieceMemory << " MiB\n";
}
