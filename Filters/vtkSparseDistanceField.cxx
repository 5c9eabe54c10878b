#include "vtkSparseDistanceField.h"

#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
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
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <cmath>
#include <utility>

vtkStandardNewMacro(vtkSparseDistanceField);

namespace
{
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

/// The coarse grid of sides, a cell per brick, over `extent` (the whole grid's, or the
/// piece a distributed run asks of this process).
void SidesImage(const vtkdf::SparseBandField& field,
  const vtkdf::SampleGrid& grid,
  const int extent[6],
  vtkImageData* sides)
{
  const std::array<int, 3>& nb = field.BrickCounts;
  int e[6];
  for (int a = 0; a < 3; ++a)
  {
    e[2 * a] = std::max(0, std::min(extent[2 * a], nb[a]));
    e[2 * a + 1] = std::max(e[2 * a], std::min(extent[2 * a + 1], nb[a]));
  }
  sides->SetExtent(e);
  double origin[3], spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = grid.Coordinate(a, grid.Whole.Lo[a]);
    spacing[a] = grid.Spacing[a] * field.BrickSize;
  }
  sides->SetOrigin(origin);
  sides->SetSpacing(spacing);
  const vtkIdType cells = vtkIdType(e[1] - e[0]) * (e[3] - e[2]) * (e[5] - e[4]);
  vtkNew<vtkSignedCharArray> side;
  side->SetName("Side");
  side->SetNumberOfTuples(cells);
  vtkNew<vtkIntArray> piece;
  piece->SetName("Piece");
  piece->SetNumberOfTuples(cells);
  vtkIdType cell = 0;
  for (int k = e[4]; k < e[5]; ++k)
  {
    for (int j = e[2]; j < e[3]; ++j)
    {
      for (int i = e[0]; i < e[1]; ++i, ++cell)
      {
        const size_t b = i + size_t(nb[0]) * (j + size_t(nb[1]) * k);
        side->SetValue(cell, field.Sides[b]);
        piece->SetValue(cell, field.BrickOf[b]);
      }
    }
  }
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
    const std::array<int, 3> counts = vtkdf::BrickGrid::Over(grid.Whole, this->BrickSize).Counts;
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
  // A distributed run asks each rank for a piece of the sides (every rank has them all).
  sidesInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  return 1;
}

vtkdf::RunStatus vtkSparseDistanceField::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  this->LastBandSamples = this->LastPieces = this->LastCandidateBricks = 0;
  this->LastWindingBricksDecided = 0;
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
  request.Sign = static_cast<vtkdf::SignMode>(this->SignMode);
  request.ClosestCellId = this->ComputeClosestCellId;
  request.ClosestPoint = this->ComputeClosestPoint;
  request.MemoryLimit = this->EffectiveMemoryLimit();
  // A distributed run: each rank computes its share of the bricks.
  vtkdf::MeshPiece(request.Piece, request.Pieces);
  request.SumOverPieces = [](std::vector<int8_t>& values)
  {
    std::vector<int8_t> sum(values.size());
    vtkMultiProcessController::GetGlobalController()->AllReduce(
      reinterpret_cast<const signed char*>(values.data()),
      reinterpret_cast<signed char*>(sum.data()),
      static_cast<vtkIdType>(values.size()),
      vtkCommunicator::SUM_OP);
    values.swap(sum);
  };
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
  this->LastWindingBricksDecided = field.WindingBricksDecided;
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
  vtkInformation* sidesInfo = outputVector->GetInformationObject(1);
  int sidesExtent[6] = {
    0, field.BrickCounts[0], 0, field.BrickCounts[1], 0, field.BrickCounts[2]
  };
  if (sidesInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    sidesInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), sidesExtent);
  }
  SidesImage(field, request.Grid, sidesExtent, vtkImageData::GetData(outputVector, 1));
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
    !this->CheckEnum(this->SignMode, vtkdf::enums::LinearFactorSign) ||
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
  os << indent << "SignMode: " << vtkdf::enums::LinearFactorSign.Name(this->SignMode) << "\n";
  os << indent << "DomainShape: " << vtkdf::enums::DomainShape.Name(this->DomainShape) << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "BrickSize: " << this->BrickSize << "\n";
  os << indent << "ComputeClosestCellId: " << this->ComputeClosestCellId << "\n";
  os << indent << "ComputeClosestFeature: " << this->ComputeClosestFeature << "\n";
  os << indent << "ComputeClosestPoint: " << this->ComputeClosestPoint << "\n";
  os << indent << "LastBandSamples: " << this->LastBandSamples << "\n";
  os << indent << "LastPieces: " << this->LastPieces << "\n";
  os << indent << "LastCandidateBricks: " << this->LastCandidateBricks << "\n";
  os << indent << "LastWindingBricksDecided: " << this->LastWindingBricksDecided << "\n";
  os << indent << "LastPieceMemory: " << this->LastPieceMemory << " MiB\n";
}
