#include "LinearFactor/LinearFactorScan.h"

#include "Common/Rounding.h"
#include "LinearFactor/SliceDomain.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vtkdf
{

int SiteIndexPlanes(const MeshSites& sites,
  int64_t index,
  const Site& site,
  const SampleGrid& grid,
  IndexPlane* out,
  int capacity)
{
  HalfSpace planes[MaxDomainPlanes];
  const int count = sites.Planes(index, site, planes, std::min(capacity, MaxDomainPlanes));
  for (int p = 0; p < count; ++p)
  {
    const HalfSpace& h = planes[p];
    // n . (origin + spacing * index - anchor) + d >= 0
    out[p].A = h.N[0] * grid.Spacing[0];
    out[p].B = h.N[1] * grid.Spacing[1];
    out[p].C = h.N[2] * grid.Spacing[2];
    out[p].D = h.N[0] * (grid.Origin[0] - site.Anchor[0]) +
      h.N[1] * (grid.Origin[1] - site.Anchor[1]) + h.N[2] * (grid.Origin[2] - site.Anchor[2]) + h.D;
  }
  return count;
}

namespace
{

/// The distance vector of a site is P (anchor - x) with P a projector: identity for a
/// vertex, I - t t^T for an edge, n n^T for a face. Along a row it changes by a constant.
void SiteProjector(const Site& s, double P[3][3])
{
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (s.Type == VertexSite)
      {
        P[r][c] = r == c ? 1.0 : 0.0;
      }
      else if (s.Type == EdgeSite)
      {
        P[r][c] = (r == c ? 1.0 : 0.0) - s.Axis[r] * s.Axis[c];
      }
      else
      {
        P[r][c] = s.Axis[r] * s.Axis[c];
      }
    }
  }
}

/// The sample axes in the order the scan walks them: Slice (outer), Row, Inner
/// (innermost, along which the distance vector changes by a constant step). A domain
/// of a smooth surface is a thin column along the surface normal, so the scan runs the
/// inner loop along the normal's largest component and slices across its smallest:
/// few slices with long rows, instead of many slices holding a sample or two each.
struct ScanAxes
{
  int Inner = 0, Row = 1, Slice = 2;
};

ScanAxes ChooseScanAxes(const Site& site)
{
  double n[3];
  for (int a = 0; a < 3; ++a)
  {
    n[a] = site.Type == FaceSite ? site.Axis[a] : site.Normal[a];
  }
  const double m[3] = { std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2]) };
  ScanAxes axes;
  if (!(m[0] + m[1] + m[2] > 0))
  {
    return axes;
  }
  axes.Inner = m[0] >= m[1] ? (m[0] >= m[2] ? 0 : 2) : (m[1] >= m[2] ? 1 : 2);
  const int o1 = (axes.Inner + 1) % 3, o2 = (axes.Inner + 2) % 3;
  axes.Slice = m[o1] <= m[o2] ? o1 : o2;
  axes.Row = 3 - axes.Inner - axes.Slice;
  return axes;
}

/// The scan conversion of one site's domain inside its region.
class SiteScan
{
public:
  SiteScan(const MeshSites& sites,
    const Site& site,
    uint32_t siteIndex,
    const IndexBox& region,
    const RangeCulling& culling,
    const LocalFieldRequest& request)
    : TheSite(site)
    , SiteIndex(siteIndex)
    , Culling(culling)
    , Region(region)
    , Grid(request.Grid)
  {
    const ScanAxes axes = ChooseScanAxes(site);
    this->U = axes.Inner, this->V = axes.Row, this->W = axes.Slice;
    const int u = this->U, v = this->V, w = this->W;
    // Planes with their coefficients in (inner, row, slice) order.
    IndexPlane planes[MaxDomainPlanes];
    const int numPlanes =
      SiteIndexPlanes(sites, siteIndex, site, this->Grid, planes, MaxDomainPlanes);
    for (int p = 0; p < numPlanes; ++p)
    {
      const double c[3] = { planes[p].A, planes[p].B, planes[p].C };
      planes[p].A = c[u], planes[p].B = c[v], planes[p].C = c[w];
    }
    this->Domain.Setup(
      planes, numPlanes, site.Required, region.Lo[u], region.Hi[u], region.Lo[v], region.Hi[v]);
    double P[3][3];
    SiteProjector(site, P);
    // The distance vector is affine in the sample index: d(i, j, k) = d0 + i du + j dv +
    // k dw (u, v, w the scan axes), evaluated in double at each sample and compared in
    // float (the GPU interpolates in float).
    const SampleGrid& grid = this->Grid;
    const double r[3] = { site.Anchor[0] - grid.Origin[0],
      site.Anchor[1] - grid.Origin[1],
      site.Anchor[2] - grid.Origin[2] };
    for (int a = 0; a < 3; ++a)
    {
      this->D0[a] = P[a][0] * r[0] + P[a][1] * r[1] + P[a][2] * r[2];
      this->Du[a] = -P[a][u] * grid.Spacing[u];
      this->Dv[a] = -P[a][v] * grid.Spacing[v];
      this->Dw[a] = -P[a][w] * grid.Spacing[w];
    }
    const IndexBox& ext = request.Extent;
    int64_t stride[3];
    stride[0] = 1;
    stride[1] = ext.Size(0);
    stride[2] = stride[1] * ext.Size(1);
    this->Base = -(ext.Lo[0] * stride[0] + ext.Lo[1] * stride[1] + ext.Lo[2] * stride[2]);
    this->StrideU = stride[u], this->StrideV = stride[v], this->StrideW = stride[w];
  }

  /// Scans the domain's slices, calling visit(*this, dk, j, k, i0, i1, at) for every
  /// row of samples i0..i1 (the first at `at`) of row j of slice k (dk: the distance
  /// vector's part up to the slice); returns the distance evaluations. The domain
  /// contains the anchor, so (when the anchor is in the region's rectangle) the slices it
  /// covers are one run of slices around the anchor's: the scan runs outward from there
  /// and stops at the first empty slice on each side.
  template<class RowVisitor>
  int64_t Run(RowVisitor& visit)
  {
    const int u = this->U, v = this->V, w = this->W;
    const IndexBox& region = this->Region;
    double anchor[3];
    for (int a = 0; a < 3; ++a)
    {
      anchor[a] = (this->TheSite.Anchor[a] - this->Grid.Origin[a]) / this->Grid.Spacing[a];
    }
    const bool inRect = anchor[u] >= region.Lo[u] && anchor[u] <= region.Hi[u] &&
      anchor[v] >= region.Lo[v] && anchor[v] <= region.Hi[v];
    if (!inRect)
    {
      for (int k = region.Lo[w]; k <= region.Hi[w]; ++k)
      {
        this->Slice(k, visit);
      }
      return this->Evaluations;
    }
    auto clampSlice = [&](double z)
    { return static_cast<int>(std::min<double>(std::max<double>(z, region.Lo[w]), region.Hi[w])); };
    int start = clampSlice(std::round(anchor[w]));
    bool found = this->Slice(start, visit);
    if (!found)
    {
      for (int k : { clampSlice(std::floor(anchor[w])), clampSlice(std::ceil(anchor[w])) })
      {
        if (k != start && this->Slice(k, visit))
        {
          start = k;
          found = true;
          break;
        }
      }
    }
    if (found)
    {
      for (int k = start + 1; k <= region.Hi[w] && this->Slice(k, visit); ++k)
      {
      }
      for (int k = start - 1; k >= region.Lo[w] && this->Slice(k, visit); --k)
      {
      }
    }
    return this->Evaluations;
  }

  /// Offers the site to samples i0..i1 of row j (the first at `at`). Each sample's
  /// vector to the site is evaluated from the row's start in double and rounded to float
  /// once: its bits do not depend on where the row's run begins (a piece of the grid or
  /// a culling region clips it), so a piece and the whole grid break ties alike.
  /// Shaders/LinearFactorRows.comp.glsl evaluates the same expressions.
  void Offer(NearestSiteBuffer& nearest, const double dk[3], int j, int i0, int i1, int64_t at)
    const
  {
    const double* du = this->Du;
    double row[3];
    this->RowStart(dk, j, row);
    for (int i = i0; i <= i1; ++i, at += this->StrideU)
    {
      const float dx = static_cast<float>(row[0] + i * du[0]);
      const float dy = static_cast<float>(row[1] + i * du[1]);
      const float dz = static_cast<float>(row[2] + i * du[2]);
      nearest.Offer(at, NearestSiteBuffer::Pack(dx * dx + dy * dy + dz * dz, this->SiteIndex));
    }
  }

  /// The distance vector at i = 0 of row j (dk: its part up to the slice).
  void RowStart(const double dk[3], int j, double row[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      row[a] = dk[a] + j * this->Dv[a];
    }
  }

  /// The site's step along its rows, for the GPU's rows.
  ScanFrame Frame() const
  {
    return { { this->Du[0], this->Du[1], this->Du[2], static_cast<double>(this->SiteIndex) } };
  }

  int64_t RowStride() const { return this->StrideU; }

private:
  /// Whether the site may be the nearest one in a block's cell (RangeCulling's bound),
  /// remembered in a small direct-mapped cache: the slices of a block layer ask about
  /// the same blocks, and a region is too large to hold an entry per block.
  bool MayWin(const int block[3])
  {
    const int64_t key = block[0] + (int64_t(block[1]) << 21) + (int64_t(block[2]) << 42);
    const int slot = (block[0] + 3 * block[1] + 5 * block[2]) & (CacheSize - 1);
    const uint64_t bit = uint64_t(1) << slot;
    if (!(this->CacheFilled & bit) || this->CacheKey[slot] != key)
    {
      this->CacheFilled |= bit;
      this->CacheKey[slot] = key;
      this->CacheValue[slot] =
        this->Culling.MayWin(block, this->TheSite.BoundsMin, this->TheSite.BoundsMax);
    }
    return this->CacheValue[slot];
  }

  /// Scans slice k when it is alive: when its domain polygon meets a cell where the site
  /// may win. The site's Voronoi region is star-shaped about the site, so the slices that
  /// hold a part of it form one run around the anchor's. Where the slice's box spans
  /// more than RowTestBlocks blocks, each row is also narrowed to its blocks where the
  /// site may win (TrimToLiveBlocks). A sliver, a polygon without a sample inside the
  /// region (its box has no whole row or column, or a thin polygon across its box misses
  /// the box's samples), is passed without the block tests: a fine mesh on a coarse grid
  /// has mostly such slices (8 % less scan time for the dragon of 871k triangles at 64
  /// samples; finding the first row with a sample before the block tests, another 1.5-2 %
  /// for the bunny and the armadillo at 128). Going on where a dead sliver would have
  /// stopped the walk only adds slices where the site may win, so the nearest sites are
  /// the same.
  template<class RowVisitor>
  bool Slice(int k, RowVisitor& visit)
  {
    const int u = this->U, v = this->V, w = this->W;
    double box[4];
    if (!this->Domain.SliceBox(k, box))
    {
      return false;
    }
    const IndexBox& region = this->Region;
    // The box lies within the region's rectangle: its bounds fit an int.
    const int j0 = std::max(region.Lo[v], CeilToInt(box[2]));
    const int j1 = std::min(region.Hi[v], FloorToInt(box[3]));
    const int firstColumn = std::max(region.Lo[u], CeilToInt(box[0]));
    const int lastColumn = std::min(region.Hi[u], FloorToInt(box[1]));
    if (j1 < j0 || lastColumn < firstColumn)
    {
      return true;
    }
    // The first row with a sample: a thin polygon's box may hold samples that it does not.
    this->Domain.BeginSlice(k);
    int jStart = j0, i0 = 0, i1 = -1;
    while (jStart <= j1 && !this->RowSamples(jStart, i0, i1))
    {
      ++jStart;
    }
    if (jStart > j1)
    {
      return true;
    }
    const int bu0 = this->Culling.BlockOf(u, box[0]), bu1 = this->Culling.BlockOf(u, box[1]);
    const int bv0 = this->Culling.BlockOf(v, box[2]), bv1 = this->Culling.BlockOf(v, box[3]);
    int block[3];
    block[w] = this->Culling.BlockOfSample(w, k);
    bool alive = false;
    for (int bv = bv0; bv <= bv1 && !alive; ++bv)
    {
      for (int bu = bu0; bu <= bu1 && !alive; ++bu)
      {
        block[u] = bu, block[v] = bv;
        alive = this->MayWin(block);
      }
    }
    if (!alive)
    {
      return false;
    }
    const bool testRows = int64_t(bu1 - bu0 + 1) * (bv1 - bv0 + 1) > RowTestBlocks;
    const double dk[3] = {
      this->D0[0] + k * this->Dw[0], this->D0[1] + k * this->Dw[1], this->D0[2] + k * this->Dw[2]
    };
    const int64_t sliceStart = this->Base + k * this->StrideW;
    for (int j = jStart; j <= j1; ++j)
    {
      if ((j > jStart && !this->RowSamples(j, i0, i1)) ||
        (testRows && !this->TrimToLiveBlocks(block, j, i0, i1)))
      {
        continue;
      }
      visit(*this, dk, j, k, i0, i1, sliceStart + j * this->StrideV + i0 * this->StrideU);
      this->Evaluations += i1 - i0 + 1;
    }
    return true;
  }

  /// Samples i0..i1 of row j of the slice of the last BeginSlice, within the region;
  /// false when the row has none.
  bool RowSamples(int j, int& i0, int& i1) const
  {
    double xl, xr;
    if (!this->Domain.RowSpan(j, xl, xr))
    {
      return false;
    }
    i0 = std::max(this->Region.Lo[this->U], CeilToInt(xl));
    i1 = std::min(this->Region.Hi[this->U], FloorToInt(xr));
    return i0 <= i1;
  }

  /// Narrows samples i0..i1 of row j (block[w]: its slice's layer) to the blocks from
  /// the first to the last where the site may win; false when there is none. The rows
  /// skip only cells where the site cannot be nearest, so the nearest sites are the same.
  bool TrimToLiveBlocks(int block[3], int j, int& i0, int& i1)
  {
    const int u = this->U, v = this->V;
    block[v] = this->Culling.BlockOfSample(v, j);
    int first = this->Culling.BlockOfSample(u, i0), last = this->Culling.BlockOfSample(u, i1);
    for (block[u] = first; !this->MayWin(block); block[u] = first)
    {
      if (++first > last)
      {
        return false;
      }
    }
    for (block[u] = last; last > first && !this->MayWin(block); block[u] = last)
    {
      --last;
    }
    const int lo = this->Culling.BlockExtent.Lo[u], size = RangeCulling::BlockSize;
    i0 = std::max(i0, lo + first * size);
    if (last < this->Culling.BlockCounts[u] - 1) // the last block holds the extent's rest
    {
      i1 = std::min(i1, lo + last * size + size - 1);
    }
    return true;
  }

  /// The slices whose box spans more blocks than this test their rows' blocks. A block
  /// test costs the CPU about what a few distance evaluations do, and a thin domain's
  /// slice of a few blocks rarely has a row in a dead one; a slice of many blocks (a
  /// vertex's cone far from a bumpy surface) has many. At 128 samples, rows tested in
  /// slices of more than 8 blocks: distances a sample armadillo 11.99 -> 4.60, dragon
  /// 12.51 -> 5.36, bunny 2.66 -> 2.10, the CPU scan within -7 % to +4 %, the GPU's
  /// (which evaluates every offer twice on llvmpipe) a third faster for the armadillo.
  static constexpr int64_t RowTestBlocks = 8;

  static constexpr int CacheSize = 64;
  const Site& TheSite;
  const uint32_t SiteIndex;
  const RangeCulling& Culling;
  const IndexBox Region;
  const SampleGrid& Grid;
  int U, V, W;
  DomainSpans Domain;
  double D0[3], Du[3], Dv[3], Dw[3];
  int64_t Base, StrideU, StrideV, StrideW;
  int64_t Evaluations = 0;
  uint64_t CacheFilled = 0; // a bit a slot: a new site's cache empties in one store
  int64_t CacheKey[CacheSize];
  bool CacheValue[CacheSize];
};

} // namespace

ScanStatistics ScanSitesCPU(const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  NearestSiteBuffer& nearest,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress)
{
  ScanStatistics stats;
  stats.Samples = request.Extent.Count();
  const int64_t numSites = static_cast<int64_t>(culling.Order.size());
  // Sites come grouped by block (RangeCulling::Order); batches of them report progress.
  const int64_t batches = std::max<int64_t>(1, std::min<int64_t>(20, numSites / 1024));
  std::atomic<int64_t> evaluations{ 0 };
  for (int64_t batch = 0; batch < batches; ++batch)
  {
    const int64_t first = numSites * batch / batches;
    const int64_t last = numSites * (batch + 1) / batches;
    parallelFor(last - first,
      64,
      [&](int64_t begin, int64_t end)
      {
        int64_t local = 0;
        Site site;
        culling.ForEachSite(first + begin,
          first + end,
          [&](int64_t id, const IndexBox& reach)
          {
            sites.Describe(id, site);
            const IndexBox region = culling.Region(reach, site);
            if (!region.Empty())
            {
              auto offer =
                [&nearest](
                  const SiteScan& scan, const double dk[3], int j, int, int i0, int i1, int64_t at)
              { scan.Offer(nearest, dk, j, i0, i1, at); };
              local += SiteScan(sites, site, static_cast<uint32_t>(id), region, culling, request)
                         .Run(offer);
            }
          });
        evaluations += local;
      });
    if (progress && !progress(double(batch + 1) / batches))
    {
      stats.Aborted = true;
      break;
    }
  }
  stats.Evaluations = evaluations.load();
  return stats;
}

void CollectScanRows(const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  int64_t first,
  int64_t last,
  const ParallelFor& parallelFor,
  ScanRows& out)
{
  // Chunks of sites collect their rows apart, then join in chunk order: the same list
  // whatever the thread schedule.
  const int64_t numChunks = std::max<int64_t>(1, std::min<int64_t>(256, (last - first) / 64));
  std::vector<ScanRows> chunks(static_cast<size_t>(numChunks));
  parallelFor(numChunks,
    1,
    [&](int64_t chunkBegin, int64_t chunkEnd)
    {
      Site site;
      for (int64_t c = chunkBegin; c < chunkEnd; ++c)
      {
        ScanRows& mine = chunks[c];
        culling.ForEachSite(first + (last - first) * c / numChunks,
          first + (last - first) * (c + 1) / numChunks,
          [&](int64_t id, const IndexBox& reach)
          {
            sites.Describe(id, site);
            const IndexBox region = culling.Region(reach, site);
            if (region.Empty())
            {
              return;
            }
            const uint32_t frame = static_cast<uint32_t>(mine.Frames.size());
            bool framed = false;
            auto record =
              [&](const SiteScan& scan, const double* dk, int j, int, int i0, int i1, int64_t at)
            {
              if (!framed)
              {
                mine.Frames.push_back(scan.Frame());
                framed = true;
              }
              ScanRow row;
              scan.RowStart(dk, j, row.Start);
              row.Frame = frame;
              row.At = static_cast<int32_t>(at);
              row.I0 = i0;
              row.I1 = i1;
              row.Stride = static_cast<int32_t>(scan.RowStride());
              mine.Rows.push_back(row);
            };
            mine.Evaluations +=
              SiteScan(sites, site, static_cast<uint32_t>(id), region, culling, request)
                .Run(record);
          });
      }
    });
  size_t frames = 0, rows = 0;
  for (const ScanRows& c : chunks)
  {
    frames += c.Frames.size();
    rows += c.Rows.size();
  }
  out.Frames.clear();
  out.Rows.clear();
  out.Frames.reserve(frames);
  out.Rows.reserve(rows);
  out.Evaluations = 0;
  for (ScanRows& c : chunks)
  {
    const uint32_t offset = static_cast<uint32_t>(out.Frames.size());
    out.Frames.insert(out.Frames.end(), c.Frames.begin(), c.Frames.end());
    for (ScanRow r : c.Rows)
    {
      r.Frame += offset;
      out.Rows.push_back(r);
    }
    out.Evaluations += c.Evaluations;
    c = ScanRows();
  }
}

void Finalize(const MeshSites& sites,
  const LocalFieldRequest& request,
  const NearestSiteBuffer& nearest,
  const LocalFieldArrays& arrays,
  const ParallelFor& parallelFor)
{
  const IndexBox& ext = request.Extent;
  const SampleGrid& grid = request.Grid;
  const int64_t nx = ext.Size(0), ny = ext.Size(1), n = ext.Count();
  const double cap = request.MaximumDistance;
  const bool banded = std::isfinite(cap);
  const GridFrame& frame = arrays.Frame;
  const float worldCap = static_cast<float>(cap * frame.Scale);
  const bool signedDistance = arrays.Signed && arrays.Distance;
  // Inside/outside of every sample (0: unknown, outside the band).
  std::vector<int8_t> side(arrays.Signed && arrays.Distance ? n : 0, 0);
  // One row of samples at a time: the row's j, k and coordinates are computed once.
  parallelFor(ny * ext.Size(2),
    std::max<int64_t>(1, 4096 / nx),
    [&](int64_t rowBegin, int64_t rowEnd)
    {
      Site last;
      int64_t described = -1;
      for (int64_t row = rowBegin; row < rowEnd; ++row)
      {
        const int j = ext.Lo[1] + static_cast<int>(row % ny);
        const int k = ext.Lo[2] + static_cast<int>(row / ny);
        const double y = grid.Coordinate(1, j), z = grid.Coordinate(2, k);
        for (int64_t at = row * nx, i = ext.Lo[0]; at < (row + 1) * nx; ++at, ++i)
        {
          const uint64_t packed = nearest.Get(at);
          const double x[3] = { grid.Coordinate(0, static_cast<int>(i)), y, z };
          double d[3] = { 0, 0, 0 }, distance = banded ? cap : HUGE_VAL;
          const Site* site = nullptr;
          if (packed != NearestSiteBuffer::Empty)
          {
            // Neighbouring samples mostly share their site: described once for them.
            const int64_t id = static_cast<int64_t>(packed & 0xffffffffu);
            if (id != described)
            {
              sites.Describe(id, last, false, signedDistance);
              described = id;
            }
            site = &last;
            MeshSites::DistanceVector(*site, x, d);
            distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (banded && distance > cap)
            {
              distance = cap;
              site = nullptr;
            }
          }
          if (arrays.Distance)
          {
            float value = static_cast<float>(distance * frame.Scale);
            if (site && arrays.Signed)
            {
              const double s =
                d[0] * site->Normal[0] + d[1] * site->Normal[1] + d[2] * site->Normal[2];
              side[at] = s > 0 ? -1 : 1;
              value = s > 0 ? -value : value;
            }
            arrays.Distance[at] = value;
          }
          if (arrays.ClosestCellId)
          {
            arrays.ClosestCellId[at] = site ? site->CellId : -1;
          }
          if (arrays.ClosestFeature)
          {
            arrays.ClosestFeature[at] = site ? site->Type : 255;
          }
          if (arrays.ClosestPoint)
          {
            for (int a = 0; a < 3; ++a)
            {
              arrays.ClosestPoint[3 * at + a] =
                site ? static_cast<float>(frame.ToWorld(a, x[a] + d[a])) : NAN;
            }
          }
        }
      }
    });
  if (side.empty() || !banded)
  {
    return;
  }
  FloodBandSides(ext, side, arrays.Distance, worldCap);
}

void FloodBandSides(const IndexBox& extent,
  std::vector<int8_t>& side,
  float* distance,
  float worldCap)
{
  // Beyond the band the closest site is unknown, but inside/outside cannot change
  // without crossing the surface, which lies in the band: flood the known sides,
  // breadth first from every known sample in index order. The queue is a vector read
  // from its head (every sample enters it once), of the samples' coordinates packed in
  // 21 bits each where they fit (no division to find a sample's neighbours), else of
  // their indices. Small extents (a sparse band's bricks, thousands of them) reuse their
  // thread's queue: fresh pages cost more than the flood.
  const int64_t nx = extent.Size(0), ny = extent.Size(1), nz = extent.Size(2);
  const int64_t n = static_cast<int64_t>(side.size()), nxy = nx * ny;
  const bool packed = nx < (1 << 21) && ny < (1 << 21) && nz < (1 << 21);
  constexpr uint64_t Mask = (uint64_t(1) << 21) - 1;
  auto key = [packed](int64_t i, int64_t j, int64_t k, int64_t at)
  { return packed ? uint64_t(i) | uint64_t(j) << 21 | uint64_t(k) << 42 : uint64_t(at); };
  thread_local std::vector<uint64_t> reused;
  std::vector<uint64_t> own;
  std::vector<uint64_t>& queue = n <= (int64_t(1) << 20) ? reused : own;
  queue.clear();
  queue.reserve(static_cast<size_t>(n));
  for (int64_t k = 0, at = 0; k < nz; ++k)
  {
    for (int64_t j = 0; j < ny; ++j)
    {
      for (int64_t i = 0; i < nx; ++i, ++at)
      {
        if (side[at] != 0)
        {
          queue.push_back(key(i, j, k, at));
        }
      }
    }
  }
  for (size_t head = 0; head < queue.size(); ++head)
  {
    const uint64_t q = queue[head];
    int64_t i, j, k, at;
    if (packed)
    {
      i = int64_t(q & Mask), j = int64_t((q >> 21) & Mask), k = int64_t(q >> 42);
      at = i + nx * (j + ny * k);
    }
    else
    {
      at = int64_t(q), k = at / nxy;
      const int64_t rest = at - k * nxy;
      j = rest / nx, i = rest - j * nx;
    }
    auto visit = [&](bool inside, int64_t b, int64_t bi, int64_t bj, int64_t bk)
    {
      if (inside && side[b] == 0)
      {
        side[b] = side[at];
        if (side[b] < 0)
        {
          distance[b] = -worldCap;
        }
        queue.push_back(key(bi, bj, bk, b));
      }
    };
    visit(i > 0, at - 1, i - 1, j, k);
    visit(i + 1 < nx, at + 1, i + 1, j, k);
    visit(j > 0, at - nx, i, j - 1, k);
    visit(j + 1 < ny, at + nx, i, j + 1, k);
    visit(k > 0, at - nxy, i, j, k - 1);
    visit(k + 1 < nz, at + nxy, i, j, k + 1);
  }
}

} // namespace vtkdf
