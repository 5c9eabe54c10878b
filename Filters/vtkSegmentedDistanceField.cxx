#include "vtkSegmentedDistanceField.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
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
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkSegmentedDistanceField);

namespace
{
/// Every rank's piece, in rank order. Collective.
std::vector<vtkdf::IndexBox> AllPieces(vtkMultiProcessController* controller,
  const vtkdf::IndexBox& piece)
{
  const int ranks = controller->GetNumberOfProcesses();
  const int mine[6] = {
    piece.Lo[0], piece.Hi[0], piece.Lo[1], piece.Hi[1], piece.Lo[2], piece.Hi[2]
  };
  std::vector<int> all(6 * static_cast<size_t>(ranks));
  controller->AllGather(mine, all.data(), 6);
  std::vector<vtkdf::IndexBox> pieces(ranks);
  for (int r = 0; r < ranks; ++r)
  {
    for (int a = 0; a < 3; ++a)
    {
      pieces[r].Lo[a] = all[6 * r + 2 * a];
      pieces[r].Hi[a] = all[6 * r + 2 * a + 1];
    }
  }
  return pieces;
}

/// Replaces `evidence` (this rank's; null when this rank failed before it had any) by
/// the sum of every rank's, the same on every rank. Collective: a rank that failed still
/// takes part (the others would wait), and then every rank fails.
bool ShareEvidence(vtkMultiProcessController* controller,
  vtkdf::RegionEvidence* evidence,
  std::string& error)
{
  const int ranks = controller->GetNumberOfProcesses();
  // A packed evidence has at least 3 words: one word -1 says "failed".
  const std::vector<int64_t> words = evidence ? evidence->Pack() : std::vector<int64_t>{ -1 };
  const long length = static_cast<long>(words.size());
  std::vector<long> lengths(ranks);
  controller->AllGather(&length, lengths.data(), 1);
  std::vector<vtkIdType> counts(ranks), offsets(ranks);
  vtkIdType total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    counts[r] = lengths[r];
    offsets[r] = total;
    total += lengths[r];
  }
  std::vector<long> all(total);
  std::vector<long> send(words.begin(), words.end());
  controller->AllGatherV(send.data(), all.data(), length, counts.data(), offsets.data());
  if (!evidence)
  {
    return false;
  }
  vtkdf::RegionEvidence sum;
  for (int r = 0; r < ranks; ++r)
  {
    const long* part = all.data() + offsets[r];
    if (counts[r] == 1 && part[0] == -1)
    {
      error = "rank " + std::to_string(r) + " failed before it could share its evidence";
      return false;
    }
    std::vector<int64_t> copy(part, part + counts[r]);
    if (!sum.Add(copy.data(), counts[r]))
    {
      error = "rank " + std::to_string(r) + " sent an evidence that is not one";
      return false;
    }
  }
  *evidence = std::move(sum);
  return true;
}
} // namespace

vtkSegmentedDistanceField::vtkSegmentedDistanceField() = default;

vtkdf::RunStatus vtkSegmentedDistanceField::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkPolyData* mesh = vtkPolyData::GetData(inputVector[0], 0);
  // The whole mesh, gathered when a distributed run partitioned it (vtkDistanceFieldPartitions.h).
  if (!this->InputMesh(mesh))
  {
    return vtkdf::RunStatus::Failed;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  this->LastRegionCount = 0;
  this->LastPatchCount = this->LastCutEdges = this->LastRefusedMerges = 0;
  this->LastCrossedTriangles = 0;
  std::fill(this->LastComputedExtent, this->LastComputedExtent + 6, 0);
  this->LastComputedExtent[1] = this->LastComputedExtent[3] = this->LastComputedExtent[5] = -1;
  // The same on every rank (the mesh and the grid are): no rank goes on alone.
  if (!mesh || mesh->GetNumberOfCells() == 0 || mesh->GetNumberOfPoints() == 0)
  {
    return run.Empty("The input mesh is empty: the output is empty.");
  }
  vtkdf::SegmentedFieldRequest request;
  vtkdf::IndexBox piece;
  const bool hasPiece = GetOutputGrid(outInfo, request.Grid, piece);
  const vtkdf::IndexBox& whole = request.Grid.Whole;
  if (whole.Empty())
  {
    return run.Empty("The grid is empty: the output is empty.");
  }
  // The regions are global. In a distributed run whose pieces tile the grid, each rank
  // computes its piece and one sample around it, counts the region evidence of the
  // samples it owns, and the ranks add their evidence up: every rank then merges the
  // same sums into the whole grid's regions. Otherwise (one process, or pieces that
  // leave samples out) the whole grid is computed and the piece cut from it.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  bool split = false;
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    const std::vector<vtkdf::IndexBox> pieces =
      AllPieces(controller, hasPiece ? piece : vtkdf::IndexBox());
    split = vtkdf::CoveredSamples(pieces, whole) == whole.Count();
    const int rank = controller->GetLocalProcessId();
    request.Pieces.Piece = hasPiece ? piece : vtkdf::IndexBox();
    request.Pieces.Before.assign(pieces.begin(), pieces.begin() + rank);
  }
  if (!hasPiece && !split)
  {
    return run.Empty("The requested extent is empty: the output is empty.");
  }
  bool shared = false;
  if (split)
  {
    request.Combine = [controller, &shared](vtkdf::RegionEvidence& evidence, std::string& error)
    {
      shared = true;
      return ShareEvidence(controller, &evidence, error);
    };
  }
  vtkdf::RunStatus status = vtkdf::RunStatus::Done;
  if (split && !hasPiece)
  {
    // A rank with no samples (more ranks than the grid has slabs) adds no evidence.
    vtkdf::RegionEvidence none;
    std::string error;
    if (!request.Combine(none, error))
    {
      status = run.Fail("The regions could not be merged across the pieces: " + error + ".");
    }
  }
  else
  {
    request.Extent = split ? piece.Grown(1, whole) : whole;
    status = this->ComputePiece(mesh, request, piece, output, run);
  }
  if (split && !shared)
  {
    std::string ignored; // this rank failed before its evidence: the others fail with it
    ShareEvidence(controller, nullptr, ignored);
  }
  return status;
}

vtkdf::RunStatus vtkSegmentedDistanceField::ComputePiece(vtkPolyData* mesh,
  const vtkdf::SegmentedFieldRequest& grid,
  const vtkdf::IndexBox& piece,
  vtkImageData* output,
  vtkdf::FilterRun& run)
{
  if (!run.ResolveBackend(this->Backend))
  {
    return vtkdf::RunStatus::Failed;
  }
  vtkdf::SegmentedFieldRequest request = grid;
  request.Delta = this->Delta;
  request.RegionOffset = this->RegionOffset;
  request.CutSelfIntersections = this->CutSelfIntersections;
  const vtkdf::IndexBox box = request.Extent;
  const vtkIdType n = static_cast<vtkIdType>(box.Count());
  vtkdf::MeshInput input;
  if (!this->CheckMemory(double(n) * (4 + 8 + 1 + 12 + 24 + 8 + 4 + 4 + 4 + 4 + 8), box) ||
    !this->ReadMesh(mesh, request.Grid, input))
  {
    return vtkdf::RunStatus::Failed;
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
    std::move(input), request, run.Context(), arrays, run.MakeExecution(), report, error);
  for (const std::string& warning : report.Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  this->LastCrossedTriangles = report.CrossedTriangles;
  this->LastPatchCount = report.PatchCount;
  this->LastCutEdges = report.CutEdges;
  if (!ok)
  {
    return run.Fail(error);
  }
  if (report.Aborted)
  {
    return vtkdf::RunStatus::Empty;
  }
  this->LastRegionCount = report.RegionCount;
  this->LastRefusedMerges = report.RefusedMerges;
  for (int a = 0; a < 3; ++a)
  {
    this->LastComputedExtent[2 * a] = box.Lo[a];
    this->LastComputedExtent[2 * a + 1] = box.Hi[a];
  }

  SetOutputExtent(output, request.Grid, piece);
  vtkPointData* pd = output->GetPointData();
  if (box == piece)
  {
    pd->SetScalars(segmented);
    pd->AddArray(region);
    pd->AddArray(distance);
    pd->AddArray(patch);
    if (points)
    {
      pd->AddArray(points);
    }
  }
  else
  {
    pd->SetScalars(vtkdf::CropArray(segmented.Get(), box, piece));
    pd->AddArray(vtkdf::CropArray(region.Get(), box, piece));
    pd->AddArray(vtkdf::CropArray(distance.Get(), box, piece));
    pd->AddArray(vtkdf::CropArray(patch.Get(), box, piece));
    if (points)
    {
      pd->AddArray(vtkdf::CropArray(points.Get(), box, piece));
    }
  }
  this->WriteFieldData(report, output->GetFieldData());
  return vtkdf::RunStatus::Done;
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
  os << indent << "LastComputedExtent: " << this->LastComputedExtent[0] << " "
     << this->LastComputedExtent[1] << " " << this->LastComputedExtent[2] << " "
     << this->LastComputedExtent[3] << " " << this->LastComputedExtent[4] << " "
     << this->LastComputedExtent[5] << "\n";
}
