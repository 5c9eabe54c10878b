#include "Winding/WindingCrossings.h"

#include "Predicates/ExactPredicates.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <numeric>

namespace vtkdf
{

namespace
{
/// Sorts `items` by key(item), a 64-bit unsigned integer, stably: 16 bits a pass from the
/// least significant, passes where every key has the same digit skipped.
template<typename T, typename Key>
void RadixSort(std::vector<T>& items, Key key)
{
  std::vector<T> sorted(items.size());
  std::vector<size_t> start(65537);
  for (int shift = 0; shift < 64; shift += 16)
  {
    std::fill(start.begin(), start.end(), 0);
    for (const T& x : items)
    {
      ++start[((key(x) >> shift) & 0xffff) + 1];
    }
    if (std::find(start.begin() + 1, start.end(), items.size()) != start.end())
    {
      continue; // one digit for all
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    for (const T& x : items)
    {
      sorted[start[(key(x) >> shift) & 0xffff]++] = x;
    }
    items.swap(sorted);
  }
}

/// Each point's id with points at equal coordinates merged: the least id among them.
/// Empty when there are 2^32 points or more.
std::vector<uint32_t> MergedIds(const LargeVector<double>& points)
{
  const size_t count = points.size() / 3;
  if (count >= (size_t(1) << 32) - 1)
  {
    return {};
  }
  // An open-addressing table of the first point at each position (+0.0 for -0.0: equal
  // coordinates, equal bits).
  size_t size = 16;
  while (size < 2 * count)
  {
    size *= 2;
  }
  constexpr uint32_t Empty = UINT32_MAX;
  std::vector<uint32_t> slot(size, Empty);
  std::vector<uint32_t> id(count);
  for (size_t i = 0; i < count; ++i)
  {
    const double* x = &points[3 * i];
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int k = 0; k < 3; ++k)
    {
      uint64_t bits;
      const double c = x[k] + 0.0;
      std::memcpy(&bits, &c, sizeof(bits));
      h = (h ^ bits) * 0xff51afd7ed558ccdull;
      h ^= h >> 32;
    }
    for (size_t at = h & (size - 1);; at = (at + 1) & (size - 1))
    {
      if (slot[at] == Empty)
      {
        slot[at] = static_cast<uint32_t>(i);
        id[i] = static_cast<uint32_t>(i);
        break;
      }
      const double* y = &points[3 * size_t(slot[at])];
      if (y[0] == x[0] && y[1] == x[1] && y[2] == x[2])
      {
        id[i] = slot[at];
        break;
      }
    }
  }
  return id;
}
} // namespace

namespace
{
/// Boundary edges whose surplus exceeds this are refused (a soup of so many layers).
constexpr int MaximumSurplus = 64;

/// The edges that triangles use more often in one direction than in the other (points
/// merged: `id`; `corner(t, c)` the point of corner c of triangle t), as (from, to) in
/// the direction of the surplus, once per surplus use; false when a surplus exceeds
/// MaximumSurplus.
template<typename Corner>
bool BoundaryEdges(const std::vector<uint32_t>& id,
  Corner corner,
  size_t triangles,
  std::vector<std::array<uint32_t, 2>>& boundary)
{
  // Each edge between distinct points once, from its lesser id, with +1 or -1 a use.
  std::vector<std::pair<uint64_t, int>> edges;
  edges.reserve(3 * triangles);
  for (size_t t = 0; t < triangles; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      const uint64_t u = id[corner(t, c)], v = id[corner(t, (c + 1) % 3)];
      if (u != v)
      {
        edges.emplace_back(u < v ? u << 32 | v : v << 32 | u, u < v ? 1 : -1);
      }
    }
  }
  RadixSort(edges, [](const std::pair<uint64_t, int>& e) { return e.first; });
  boundary.clear();
  for (size_t e = 0; e < edges.size();)
  {
    int net = 0;
    size_t f = e;
    for (; f < edges.size() && edges[f].first == edges[e].first; ++f)
    {
      net += edges[f].second;
    }
    const uint32_t lo = static_cast<uint32_t>(edges[e].first >> 32);
    const uint32_t hi = static_cast<uint32_t>(edges[e].first & 0xffffffffu);
    if (net > MaximumSurplus || net < -MaximumSurplus)
    {
      return false;
    }
    for (int copy = 0; copy < std::abs(net); ++copy)
    {
      boundary.push_back(
        net > 0 ? std::array<uint32_t, 2>{ { lo, hi } } : std::array<uint32_t, 2>{ { hi, lo } });
    }
    e = f;
  }
  return true;
}
} // namespace

int PerturbedSide(const double u[3], const double v[3])
{
  if (u[2] != v[2])
  {
    return u[2] > v[2] ? 1 : -1;
  }
  return v[1] > u[1] ? 1 : (v[1] < u[1] ? -1 : 0);
}

bool RayCrossing(const double* a, const double* b, const double* c, const double p[3], int& delta)
{
  delta = 0;
  // Cheap rejections first: p's (y, z) outside the triangle's box, or p before all of it
  // along x (its crossing, if any, lies ahead of p), leave no crossing behind p and p
  // off the triangle.
  if (p[1] < std::min({ a[1], b[1], c[1] }) || p[1] > std::max({ a[1], b[1], c[1] }) ||
    p[2] < std::min({ a[2], b[2], c[2] }) || p[2] > std::max({ a[2], b[2], c[2] }) ||
    p[0] < std::min({ a[0], b[0], c[0] }))
  {
    return true;
  }
  const int orientation = Orient2D(a, b, c, 1, 2);
  const int side[3] = { Orient2D(p, a, b, 1, 2), Orient2D(p, b, c, 1, 2), Orient2D(p, c, a, 1, 2) };
  if (orientation == 0)
  {
    // Seen edge-on along x: no crossing, but p on the line of its projection, within its
    // x range, may lie on it.
    return !(side[0] == 0 && side[1] == 0 && side[2] == 0 &&
      std::min({ a[0], b[0], c[0] }) <= p[0] && p[0] <= std::max({ a[0], b[0], c[0] }));
  }
  bool closed = true, moved = true;
  const double* from[3] = { a, b, c };
  const double* to[3] = { b, c, a };
  for (int e = 0; e < 3; ++e)
  {
    closed = closed && (side[e] == orientation || side[e] == 0);
    moved = moved && (side[e] != 0 ? side[e] : PerturbedSide(from[e], to[e])) == orientation;
  }
  if (!closed)
  {
    return true;
  }
  const int beyond = orientation * Orient3D(a, b, c, p);
  if (beyond == 0)
  {
    return false; // p on the triangle (or on its boundary)
  }
  // w counts crossings entering the side the normal points away from.
  delta = moved && beyond > 0 ? -orientation : 0;
  return true;
}

bool CrossingsDecide(const LargeVector<double>& points, const LargeVector<int64_t>& triangles)
{
  const std::vector<uint32_t> id = MergedIds(points);
  std::vector<std::array<uint32_t, 2>> boundary;
  return id.size() == points.size() / 3 &&
    BoundaryEdges(
      id,
      [&](size_t t, int c) { return static_cast<size_t>(triangles[3 * t + c]); },
      triangles.size() / 3,
      boundary);
}

bool IsClosedChain(const LargeVector<double>& points, const LargeVector<int64_t>& triangles)
{
  const std::vector<uint32_t> id = MergedIds(points);
  if (id.size() != points.size() / 3)
  {
    return false;
  }
  // No triangle repeated with the same orientation (each as its cyclic order from its
  // least corner), and balanced edges: the sorted edges equal the sorted reversed ones.
  const size_t n = triangles.size() / 3;
  std::vector<std::array<uint32_t, 3>> oriented(n);
  std::vector<uint64_t> forward, backward;
  forward.reserve(3 * n);
  backward.reserve(3 * n);
  for (size_t t = 0; t < n; ++t)
  {
    std::array<uint32_t, 3>& c = oriented[t];
    for (int k = 0; k < 3; ++k)
    {
      c[k] = id[static_cast<size_t>(triangles[3 * t + k])];
    }
    for (int k = 0; k < 3; ++k)
    {
      const uint64_t u = c[k], v = c[(k + 1) % 3];
      if (u != v)
      {
        forward.push_back(u << 32 | v);
        backward.push_back(v << 32 | u);
      }
    }
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  }
  RadixSort(oriented, [](const std::array<uint32_t, 3>& c) { return uint64_t(c[2]); });
  RadixSort(oriented, [](const std::array<uint32_t, 3>& c) { return uint64_t(c[0]) << 32 | c[1]; });
  if (std::adjacent_find(oriented.begin(), oriented.end()) != oriented.end())
  {
    return false;
  }
  RadixSort(forward, [](uint64_t e) { return e; });
  RadixSort(backward, [](uint64_t e) { return e; });
  return forward == backward;
}

namespace
{
constexpr int TileLines = 8; // lines a side of the tiles the work is split in

/// The indices of `extent` along axis a whose coordinate lies in [lo, hi]: [first, last],
/// empty when first > last.
void IndexRange(const SampleGrid& grid,
  const IndexBox& extent,
  int a,
  double lo,
  double hi,
  int& first,
  int& last)
{
  const double s = grid.Spacing[a], o = grid.Origin[a];
  // An estimate, then exact comparisons with the coordinates the samples have.
  const double from = std::floor((lo - o) / s), to = std::ceil((hi - o) / s);
  first =
    static_cast<int>(std::max<double>(extent.Lo[a], std::min<double>(extent.Hi[a] + 1, from)));
  last = static_cast<int>(std::min<double>(extent.Hi[a], std::max<double>(extent.Lo[a] - 1, to)));
  while (first > extent.Lo[a] && grid.Coordinate(a, first - 1) >= lo)
  {
    --first;
  }
  while (first <= extent.Hi[a] && grid.Coordinate(a, first) < lo)
  {
    ++first;
  }
  while (last < extent.Hi[a] && grid.Coordinate(a, last + 1) <= hi)
  {
    ++last;
  }
  while (last >= extent.Lo[a] && grid.Coordinate(a, last) > hi)
  {
    --last;
  }
}

struct Footprint
{
  int J0, J1, K0, K1; // the lines its projection's box covers
  int Orientation;    // sign of its projection's area (of the normal's x component)
};

/// A crossing of one line: samples from First on have it behind them.
struct Event
{
  int Line;  // within the tile
  int First; // first sample index (extent.Lo[0] ... extent.Hi[0] + 1)
  int Delta; // its contribution to w
};
} // namespace

namespace
{
/// Each triangle's orientation in projection along x and the lines its box covers.
std::vector<Footprint> Footprints(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangleIds,
  const SampleGrid& grid,
  const IndexBox& extent,
  const ParallelFor& parallelFor)
{
  const int64_t triangles = static_cast<int64_t>(triangleIds.size() / 3);
  auto corner = [&](int64_t t, int c) { return &points[3 * triangleIds[3 * t + c]]; };
  std::vector<Footprint> footprints(static_cast<size_t>(triangles));
  parallelFor(triangles,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t t = begin; t < end; ++t)
      {
        const double* a = corner(t, 0);
        const double* b = corner(t, 1);
        const double* c = corner(t, 2);
        Footprint& f = footprints[static_cast<size_t>(t)];
        f.Orientation = Orient2D(a, b, c, 1, 2);
        IndexRange(grid,
          extent,
          1,
          std::min({ a[1], b[1], c[1] }),
          std::max({ a[1], b[1], c[1] }),
          f.J0,
          f.J1);
        IndexRange(grid,
          extent,
          2,
          std::min({ a[2], b[2], c[2] }),
          std::max({ a[2], b[2], c[2] }),
          f.K0,
          f.K1);
      }
    });
  return footprints;
}

/// The triangles of each tile of TileLines x TileLines lines (tile = tz * tilesY + ty),
/// as compressed rows: the triangles of tile t are members[start[t] .. start[t + 1]).
void TileMembers(const std::vector<Footprint>& footprints,
  const IndexBox& extent,
  int tilesY,
  int64_t tiles,
  std::vector<int64_t>& start,
  std::vector<int64_t>& members)
{
  start.assign(static_cast<size_t>(tiles + 1), 0);
  auto forTiles = [&](const Footprint& f, auto&& visit)
  {
    if (f.J0 > f.J1 || f.K0 > f.K1)
    {
      return;
    }
    for (int tz = (f.K0 - extent.Lo[2]) / TileLines; tz <= (f.K1 - extent.Lo[2]) / TileLines; ++tz)
    {
      for (int ty = (f.J0 - extent.Lo[1]) / TileLines; ty <= (f.J1 - extent.Lo[1]) / TileLines;
           ++ty)
      {
        visit(int64_t(tz) * tilesY + ty);
      }
    }
  };
  for (const Footprint& f : footprints)
  {
    forTiles(f, [&](int64_t tile) { ++start[static_cast<size_t>(tile + 1)]; });
  }
  for (int64_t tile = 0; tile < tiles; ++tile)
  {
    start[static_cast<size_t>(tile + 1)] += start[static_cast<size_t>(tile)];
  }
  members.assign(static_cast<size_t>(start.back()), 0);
  std::vector<int64_t> next(start.begin(), start.end() - 1);
  for (int64_t t = 0; t < static_cast<int64_t>(footprints.size()); ++t)
  {
    forTiles(footprints[static_cast<size_t>(t)],
      [&](int64_t tile) { members[static_cast<size_t>(next[static_cast<size_t>(tile)]++)] = t; });
  }
}

/// The first sample index i of the line through q (q[1], q[2] set) whose point lies
/// beyond the plane of (a, b, c), o * Orient3D > 0 (x above the crossing's), within
/// [extent.Lo[0], extent.Hi[0] + 1]: from an estimate of the crossing, then by halving.
/// `beyond(i)` is that sign at sample i. The line runs through the triangle's closed
/// projection, so that the crossing lies on the triangle, within its x range.
template<typename Beyond>
int FirstBeyond(const double* a,
  const double* b,
  const double* c,
  const double* q,
  const SampleGrid& grid,
  const IndexBox& extent,
  const Beyond& beyond)
{
  if (grid.Spacing[0] > 0 && grid.Coordinate(0, extent.Lo[0]) > std::max({ a[0], b[0], c[0] }))
  {
    return extent.Lo[0]; // the whole extent lies beyond it
  }
  if (grid.Spacing[0] > 0 && grid.Coordinate(0, extent.Hi[0]) < std::min({ a[0], b[0], c[0] }))
  {
    return extent.Hi[0] + 1;
  }
  const double n[3] = { (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
    (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) };
  const double crossing = a[0] - (n[1] * (q[1] - a[1]) + n[2] * (q[2] - a[2])) / n[0];
  const double guess = std::ceil((crossing - grid.Origin[0]) / grid.Spacing[0]);
  int lo = extent.Lo[0], hi = extent.Hi[0] + 1; // the answer lies in [lo, hi]
  if (std::isfinite(guess) && guess > lo && guess <= hi)
  {
    const int g = static_cast<int>(guess);
    if (beyond(g - 1) <= 0)
    {
      lo = g;
      hi = g <= extent.Hi[0] && beyond(g) > 0 ? g : hi;
    }
    else
    {
      hi = g - 1;
    }
  }
  while (lo < hi)
  {
    const int middle = lo + (hi - lo) / 2;
    if (beyond(middle) > 0)
    {
      hi = middle;
    }
    else
    {
      lo = middle + 1;
    }
  }
  return lo;
}

/// What triangle (a, b, c), of footprint f, does to line `line` of the tile, through
/// (y_j, z_k): a crossing event, and the samples of the line that lie on the triangle
/// (as (line, i) in `onSurface`).
void CrossLine(const double* a,
  const double* b,
  const double* c,
  const Footprint& f,
  int j,
  int k,
  int line,
  const SampleGrid& grid,
  const IndexBox& extent,
  std::vector<Event>& events,
  std::vector<std::array<int, 2>>& onSurface)
{
  double q[3] = { 0, grid.Coordinate(1, j), grid.Coordinate(2, k) };
  const int side[3] = { Orient2D(q, a, b, 1, 2), Orient2D(q, b, c, 1, 2), Orient2D(q, c, a, 1, 2) };
  if (f.Orientation == 0)
  {
    // Seen edge-on from x: the line crosses it nowhere, but where it runs through its
    // projection (a segment: collinear with it, within its box) its samples may lie on
    // it, on the surface: they are decided alone.
    if (side[0] == 0 && side[1] == 0 && side[2] == 0)
    {
      int i0 = 0, i1 = -1;
      IndexRange(
        grid, extent, 0, std::min({ a[0], b[0], c[0] }), std::max({ a[0], b[0], c[0] }), i0, i1);
      for (int i = i0; i <= i1; ++i)
      {
        onSurface.push_back({ { line, i } });
      }
    }
    return;
  }
  // The line's point in the closed projection, and the moved point p' inside.
  bool closed = true, moved = true;
  const double* from[3] = { a, b, c };
  const double* to[3] = { b, c, a };
  for (int e = 0; e < 3; ++e)
  {
    closed = closed && (side[e] == f.Orientation || side[e] == 0);
    moved = moved && (side[e] != 0 ? side[e] : PerturbedSide(from[e], to[e])) == f.Orientation;
  }
  if (!closed)
  {
    return;
  }
  auto beyond = [&](int i)
  {
    q[0] = grid.Coordinate(0, i);
    return f.Orientation * Orient3D(a, b, c, q);
  };
  const int lo = FirstBeyond(a, b, c, q, grid, extent, beyond);
  // w counts crossings entering the side the normal points away from. A line through
  // the projection's boundary that the moved line misses only meets the triangle: a
  // sample there is on the surface.
  if (moved)
  {
    events.push_back({ line, lo, -f.Orientation });
  }
  if (lo > extent.Lo[0] && beyond(lo - 1) == 0)
  {
    onSurface.push_back({ { line, lo - 1 } });
  }
}

/// Each line of the tile (j0..j1, k0..k1) sample by sample: the crossings' contributions
/// summed into counts (N, or CountUnknown where |N| >= 127) or, without counts, inside
/// (N != 0). `events` is sorted by line here; `w` is scratch of nx + 1 values.
void WriteLines(std::vector<Event>& events,
  int j0,
  int j1,
  int k0,
  int k1,
  const IndexBox& extent,
  uint8_t* inside,
  int8_t* counts,
  std::vector<int>& w)
{
  std::sort(
    events.begin(), events.end(), [](const Event& x, const Event& y) { return x.Line < y.Line; });
  const int nx = extent.Size(0);
  const int64_t strideY = nx, strideZ = int64_t(nx) * extent.Size(1);
  size_t e = 0;
  for (int k = k0; k <= k1; ++k)
  {
    for (int j = j0; j <= j1; ++j)
    {
      const int line = (k - k0) * TileLines + (j - j0);
      std::fill(w.begin(), w.end(), 0);
      for (; e < events.size() && events[e].Line == line; ++e)
      {
        w[static_cast<size_t>(events[e].First - extent.Lo[0])] += events[e].Delta;
      }
      const int64_t rowStart = (j - extent.Lo[1]) * strideY + (k - extent.Lo[2]) * strideZ;
      int sum = 0;
      if (counts)
      {
        int8_t* row = counts + rowStart;
        for (int i = 0; i < nx; ++i)
        {
          sum += w[static_cast<size_t>(i)];
          row[i] = sum > -127 && sum < 127 ? static_cast<int8_t>(sum) : CountUnknown;
        }
      }
      else
      {
        uint8_t* row = inside + rowStart;
        for (int i = 0; i < nx; ++i)
        {
          sum += w[static_cast<size_t>(i)];
          row[i] = sum != 0 ? 1 : 0;
        }
      }
    }
  }
}

/// The crossings of every line of `extent`: for each sample, inside[v] = (N != 0), or
/// counts[v] = N (CountUnknown where |N| >= 127); the samples on the surface are left
/// (0, or CountUnknown) and returned as (i, j, k). The lines go by tiles of
/// TileLines x TileLines, each with the triangles whose boxes reach it.
std::vector<std::array<int, 3>> CrossingPass(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangleIds,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  int8_t* counts,
  const ParallelFor& parallelFor,
  int64_t& decidedSamples)
{
  std::vector<std::array<int, 3>> surface; // samples on the surface (i, j, k)
  decidedSamples = 0;
  if (extent.Empty())
  {
    return surface;
  }
  auto corner = [&](int64_t t, int c) { return &points[3 * triangleIds[3 * t + c]]; };
  const int nx = extent.Size(0), ny = extent.Size(1), nz = extent.Size(2);
  const int tilesY = (ny + TileLines - 1) / TileLines, tilesZ = (nz + TileLines - 1) / TileLines;
  const std::vector<Footprint> footprints =
    Footprints(points, triangleIds, grid, extent, parallelFor);
  const int64_t tiles = int64_t(tilesY) * tilesZ;
  std::vector<int64_t> start, members;
  TileMembers(footprints, extent, tilesY, tiles, start, members);

  std::atomic<int64_t> lineSamples{ 0 };
  std::mutex lock;
  parallelFor(tiles,
    1,
    [&](int64_t begin, int64_t end)
    {
      std::vector<Event> events;
      std::vector<std::array<int, 2>> onSurface; // (line within the tile, sample)
      std::vector<int> w(static_cast<size_t>(nx) + 1);
      std::vector<std::array<int, 3>> found;
      int64_t decided = 0;
      for (int64_t tile = begin; tile < end; ++tile)
      {
        const int j0 = extent.Lo[1] + static_cast<int>(tile % tilesY) * TileLines;
        const int k0 = extent.Lo[2] + static_cast<int>(tile / tilesY) * TileLines;
        const int j1 = std::min(extent.Hi[1], j0 + TileLines - 1);
        const int k1 = std::min(extent.Hi[2], k0 + TileLines - 1);
        events.clear();
        onSurface.clear();
        for (int64_t m = start[static_cast<size_t>(tile)]; m < start[static_cast<size_t>(tile + 1)];
             ++m)
        {
          const int64_t t = members[static_cast<size_t>(m)];
          const Footprint& f = footprints[static_cast<size_t>(t)];
          for (int k = std::max(k0, f.K0); k <= std::min(k1, f.K1); ++k)
          {
            for (int j = std::max(j0, f.J0); j <= std::min(j1, f.J1); ++j)
            {
              CrossLine(corner(t, 0),
                corner(t, 1),
                corner(t, 2),
                f,
                j,
                k,
                (k - k0) * TileLines + (j - j0),
                grid,
                extent,
                events,
                onSurface);
            }
          }
        }
        WriteLines(events, j0, j1, k0, k1, extent, inside, counts, w);
        decided += int64_t(nx) * (j1 - j0 + 1) * (k1 - k0 + 1);
        // Samples on the surface, once each (a sample on an edge is on two planes).
        std::sort(onSurface.begin(), onSurface.end());
        onSurface.erase(std::unique(onSurface.begin(), onSurface.end()), onSurface.end());
        for (const auto& s : onSurface)
        {
          found.push_back({ { s[1], j0 + s[0] % TileLines, k0 + s[0] / TileLines } });
        }
        decided -= static_cast<int64_t>(onSurface.size());
      }
      lineSamples += decided;
      std::lock_guard<std::mutex> hold(lock);
      surface.insert(surface.end(), found.begin(), found.end());
    });
  decidedSamples = lineSamples.load();
  const int64_t strideY = nx, strideZ = int64_t(nx) * ny;
  for (const auto& [i, j, k] : surface)
  {
    if (counts)
    {
      counts[(i - extent.Lo[0]) + (j - extent.Lo[1]) * strideY + (k - extent.Lo[2]) * strideZ] =
        CountUnknown;
    }
  }
  return surface;
}
} // namespace

int64_t CrossingCounts(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  const SampleGrid& grid,
  const IndexBox& extent,
  int8_t* counts,
  const ParallelFor& parallelFor)
{
  int64_t decided = 0;
  // The samples on the surface are marked CountUnknown in `counts`.
  CrossingPass(points, triangles, grid, extent, nullptr, counts, parallelFor, decided);
  return decided;
}

bool CloseWithCones(const LargeVector<double>& corners, ConeClosure& closure)
{
  const std::vector<uint32_t> id = MergedIds(corners);
  const size_t count = corners.size() / 3;
  if (id.size() != count)
  {
    return false;
  }
  std::vector<std::array<uint32_t, 2>> boundary; // from, to; an edge once per surplus use
  if (!BoundaryEdges(
        id, [](size_t t, int c) { return 3 * t + c; }, count / 3, boundary))
  {
    return false;
  }
  // The boundary is a cycle (every point has as many edges out as in), so a walk along
  // unused edges from an edge's end comes back to its start: closed walks, each the
  // rim of one cone.
  const size_t edges = boundary.size();
  std::vector<size_t> byStart(edges);
  std::iota(byStart.begin(), byStart.end(), size_t(0));
  RadixSort(byStart, [&](size_t e) { return uint64_t(boundary[e][0]); });
  std::vector<size_t> cursor(count + 1, 0); // first out-edge in byStart, per point
  for (const size_t e : byStart)
  {
    ++cursor[boundary[e][0] + 1];
  }
  std::partial_sum(cursor.begin(), cursor.end(), cursor.begin());
  std::vector<size_t> endOf(cursor.begin() + 1, cursor.end());
  std::vector<bool> used(edges, false);
  std::vector<std::vector<size_t>> walks;
  for (const size_t first : byStart)
  {
    if (used[first])
    {
      continue;
    }
    std::vector<size_t> walk{ first };
    used[first] = true;
    for (uint32_t at = boundary[first][1]; at != boundary[first][0];)
    {
      size_t& c = cursor[at];
      while (c < endOf[at] && used[byStart[c]])
      {
        ++c;
      }
      if (c == endOf[at])
      {
        return false; // not a cycle: cannot happen for a boundary
      }
      const size_t e = byStart[c];
      used[e] = true;
      walk.push_back(e);
      at = boundary[e][1];
    }
    walks.push_back(std::move(walk));
  }
  // Each walk's apex: the mean of its points, lifted along its area vector by half its
  // radius (a flat cap would lie on a flat sheet whose rim the walk is), further for each
  // earlier walk with the same mean; where sums overflow (coordinates near the largest
  // doubles), the mean or one of its points: any apex closes the chain.
  closure.Points = corners;
  closure.Cone.clear();
  std::map<std::array<double, 3>, int> means;
  for (const std::vector<size_t>& walk : walks)
  {
    std::array<double, 3> centre{ { 0, 0, 0 } }, area{ { 0, 0, 0 } };
    for (const size_t e : walk)
    {
      for (int k = 0; k < 3; ++k)
      {
        centre[k] += corners[3 * size_t(boundary[e][0]) + k];
      }
    }
    for (double& c : centre)
    {
      c /= static_cast<double>(walk.size());
    }
    double radius = 0;
    for (const size_t e : walk)
    {
      double u[3], v[3];
      for (int k = 0; k < 3; ++k)
      {
        u[k] = corners[3 * size_t(boundary[e][0]) + k] - centre[k];
        v[k] = corners[3 * size_t(boundary[e][1]) + k] - centre[k];
      }
      area[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
      area[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
      area[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
      radius = std::max(radius, std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
    }
    const double length = std::sqrt(area[0] * area[0] + area[1] * area[1] + area[2] * area[2]);
    const double lift = length > 0 ? 0.5 * (1 + means[centre]++) * radius / length : 0;
    double p[3] = {
      centre[0] + lift * area[0], centre[1] + lift * area[1], centre[2] + lift * area[2]
    };
    const double* candidates[3] = { p, centre.data(), &corners[3 * size_t(boundary[walk[0]][0])] };
    for (const double* candidate : candidates)
    {
      if (std::isfinite(candidate[0]) && std::isfinite(candidate[1]) && std::isfinite(candidate[2]))
      {
        std::copy(candidate, candidate + 3, p);
        break;
      }
    }
    const int64_t apex = static_cast<int64_t>(closure.Points.size() / 3);
    closure.Points.insert(closure.Points.end(), p, p + 3);
    for (const size_t e : walk)
    {
      // (P, to, from): its side from -> to runs against the boundary edge, cancelling it.
      closure.Cone.insert(
        closure.Cone.end(), { apex, int64_t(boundary[e][1]), int64_t(boundary[e][0]) });
    }
  }
  // The winding number counts a repeated triangle once, the crossings every time: no
  // cone triangle may repeat another (same apex position, same rim edge).
  std::map<std::array<double, 3>, uint32_t> apexIds;
  std::vector<std::array<uint32_t, 3>> keys(closure.Cone.size() / 3);
  for (size_t t = 0; t < keys.size(); ++t)
  {
    const double* a = &closure.Points[3 * size_t(closure.Cone[3 * t])];
    const auto found =
      apexIds.emplace(std::array<double, 3>{ { a[0], a[1], a[2] } }, uint32_t(apexIds.size()));
    keys[t] = { { found.first->second,
      static_cast<uint32_t>(closure.Cone[3 * t + 1]),
      static_cast<uint32_t>(closure.Cone[3 * t + 2]) } };
  }
  std::sort(keys.begin(), keys.end());
  if (std::adjacent_find(keys.begin(), keys.end()) != keys.end())
  {
    return false;
  }
  closure.Triangles.resize(count);
  std::iota(closure.Triangles.begin(), closure.Triangles.end(), int64_t(0));
  closure.Triangles.insert(closure.Triangles.end(), closure.Cone.begin(), closure.Cone.end());
  return true;
}

WindingSignStatistics CrossingSigns(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangleIds,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const ParallelFor& parallelFor,
  const std::function<const WindingNumber&()>& hierarchy)
{
  WindingSignStatistics stats;
  const std::vector<std::array<int, 3>> surface = CrossingPass(
    points, triangleIds, grid, extent, inside, nullptr, parallelFor, stats.LineSamples);
  const int64_t strideY = extent.Size(0), strideZ = int64_t(extent.Size(0)) * extent.Size(1);
  // The samples on the surface, as WindingSigns decides them: by the winding number's
  // hierarchy, built only when there is one.
  if (!surface.empty())
  {
    const WindingNumber& winding = hierarchy();
    std::atomic<int64_t> exact{ 0 };
    parallelFor(static_cast<int64_t>(surface.size()),
      64,
      [&](int64_t begin, int64_t end)
      {
        int64_t exactSums = 0;
        for (int64_t s = begin; s < end; ++s)
        {
          const auto& [i, j, k] = surface[static_cast<size_t>(s)];
          const double q[3] = {
            grid.Coordinate(0, i), grid.Coordinate(1, j), grid.Coordinate(2, k)
          };
          bool wasExact = false;
          inside[(i - extent.Lo[0]) + (j - extent.Lo[1]) * strideY + (k - extent.Lo[2]) * strideZ] =
            winding.Inside(q, nullptr, &wasExact) ? 1 : 0;
          exactSums += wasExact;
        }
        exact += exactSums;
      });
    stats.Evaluated = static_cast<int64_t>(surface.size());
    stats.Exact = exact.load();
  }
  return stats;
}

} // namespace vtkdf
