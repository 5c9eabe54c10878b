// LinearFactorScan: the scan of the linear factorization on the CPU, and Finalize.
//
// Pipeline: MeshSites (sites + domains) -> RangeCulling (regions) -> a scan pass that
// writes, per sample, the nearest site found so far (CPU here, GPU in
// LinearFactorGPU) -> Finalize, which turns the winning site of every sample into the
// requested arrays, recomputing distance and closest point in double precision.
#ifndef vtkdf_LinearFactorScan_h
#define vtkdf_LinearFactorScan_h

#include "Common/LargeVector.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "LinearFactor/MeshSites.h"
#include "LinearFactor/RangeCulling.h"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

namespace vtkdf
{

/// Per sample: (float bits of the squared distance << 32) | site index. Unsigned order
/// of the packed value = order of distances, ties to the lower site index, so an atomic
/// minimum gives the same answer whatever the thread schedule.
class NearestSiteBuffer
{
public:
  static constexpr uint64_t Empty = ~uint64_t(0);
  /// `count` empty entries; `parallelFor` (optional) fills them in parallel. The block
  /// is kept when it is large enough (a buffer reused for many small pieces).
  void Reset(int64_t count, const ParallelFor& parallelFor = ParallelFor())
  {
    if (count > this->Capacity || !this->Values)
    {
      this->Values.reset(); // the old block first: never both at once
      this->Values.reset(DefaultInitAllocator<std::atomic<uint64_t>>().allocate(count));
      this->Capacity = count;
    }
    this->Count = count;
    auto fill = [this](int64_t begin, int64_t end)
    {
      for (int64_t i = begin; i < end; ++i)
      {
        new (&this->Values[i]) std::atomic<uint64_t>(Empty);
      }
    };
    if (parallelFor)
    {
      parallelFor(count, 1 << 16, fill);
    }
    else
    {
      fill(0, count);
    }
  }
  static uint64_t Pack(float distance2, uint32_t site)
  {
    uint32_t bits;
    static_assert(sizeof(bits) == sizeof(distance2), "float is 32 bits");
    std::memcpy(&bits, &distance2, sizeof(bits));
    return (uint64_t(bits) << 32) | site;
  }
  void Offer(int64_t at, uint64_t packed)
  {
    uint64_t old = this->Values[at].load(std::memory_order_relaxed);
    while (packed < old &&
      !this->Values[at].compare_exchange_weak(old, packed, std::memory_order_relaxed))
    {
    }
  }
  /// Frees the block.
  void Release()
  {
    this->Values.reset();
    this->Count = this->Capacity = 0;
  }
  /// The block's bytes.
  int64_t Bytes() const { return this->Capacity * int64_t(sizeof(uint64_t)); }
  uint64_t Get(int64_t at) const { return this->Values[at].load(std::memory_order_relaxed); }
  void Set(int64_t at, uint64_t v) { this->Values[at].store(v, std::memory_order_relaxed); }
  int64_t Size() const { return this->Count; }

private:
  struct Free
  {
    void operator()(std::atomic<uint64_t>* p) const
    {
      DefaultInitAllocator<std::atomic<uint64_t>>().deallocate(p, 0);
    }
  };
  std::unique_ptr<std::atomic<uint64_t>[], Free> Values;
  int64_t Count = 0, Capacity = 0;
};

/// The request of the scan and the queries, in the grid's local frame (GridFrame: the
/// world's LinearFactorRequest moved there by ComputeLinearFactorField).
struct LocalFieldRequest
{
  SampleGrid Grid;
  IndexBox Extent; // the samples to compute (a sub-extent of Grid.Whole when streaming)
  double MaximumDistance = HUGE_VAL;
};

/// Where Finalize writes (the world's LinearFactorArrays, with the local frame to map
/// back from); any pointer may be null. Arrays cover Extent, x fastest.
/// The sites and the request are in the local frame `Frame`; distances and closest
/// points are written in world coordinates (mapped in double, then rounded to float).
struct LocalFieldArrays
{
  GridFrame Frame;
  float* Distance = nullptr;
  bool Signed = false;
  int64_t* ClosestCellId = nullptr;
  uint8_t* ClosestFeature = nullptr;
  float* ClosestPoint = nullptr; // 3 per sample
};

struct ScanStatistics
{
  int64_t Evaluations = 0; // distance evaluations (culling factor = Evaluations / samples)
  int64_t Samples = 0;
  bool Aborted = false;
};

/// Sample-index planes of the domain of site `index` (described by `site`), at most
/// `capacity` (optional planes beyond that are dropped, which only enlarges the domain).
int SiteIndexPlanes(const MeshSites& sites,
  int64_t index,
  const Site& site,
  const SampleGrid& grid,
  struct IndexPlane* out,
  int capacity);

/// The CPU scan conversion: every site's domain polygon, slice by slice, row by row.
ScanStatistics ScanSitesCPU(const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  NearestSiteBuffer& nearest,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress);

/// A site's step along its rows for the GPU (Shaders/LinearFactorRows.comp.glsl): the
/// distance vector of sample i of a row is Start + i Du (SiteScan, LinearFactorScan.cxx),
/// in double, rounded to float. The fourth component: the site's index.
struct ScanFrame
{
  double Du[4];
};

/// Samples I0..I1 of a row of a frame's site: the first at index At of the extent, the
/// next ones Stride apart; Start is the distance vector at i = 0, computed as the CPU
/// scan computes it.
struct ScanRow
{
  double Start[3];
  uint32_t Frame;
  int32_t At, I0, I1, Stride;
};
static_assert(sizeof(ScanRow) == 48, "the layout of Shaders/LinearFactorRows.comp.glsl's Row");

struct ScanRows
{
  std::vector<ScanFrame> Frames;
  std::vector<ScanRow> Rows;
  int64_t Evaluations = 0; // the samples of the rows
};

/// The rows ScanSitesCPU offers the sites at culling.Order[first .. last) to, for a GPU
/// to evaluate: the same walk, so the same offers. The extent must have fewer than
/// 2^31 samples.
void CollectScanRows(const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  int64_t first,
  int64_t last,
  const ParallelFor& parallelFor,
  ScanRows& out);

/// With a MaximumDistance and a sign: the sides (+1 outside, -1 inside, 0 unknown) of the
/// samples beyond the band, flooded from those within it (the surface lies in the band,
/// so a side cannot change beyond it); the distances of those found inside become
/// -worldCap. `side` covers `extent`, x fastest.
void FloodBandSides(const IndexBox& extent,
  std::vector<int8_t>& side,
  float* distance,
  float worldCap);

/// Writes the arrays from the nearest site of every sample.
void Finalize(const MeshSites& sites,
  const LocalFieldRequest& request,
  const NearestSiteBuffer& nearest,
  const LocalFieldArrays& arrays,
  const ParallelFor& parallelFor);

} // namespace vtkdf

#endif
