#include "Voxels/Voxelizer.h"

#include "Voxels/VoxelizerRules.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace vtkdf
{
using namespace voxelizer;
namespace
{
void AtomicOr(uint64_t* word, uint64_t bits)
{
  // Rasterization threads OR bits into shared lane words.
  __atomic_fetch_or(word, bits, __ATOMIC_RELAXED);
}

/// One view: lanes along axis A over the plane of axes B = A+1, C = A+2 (mod 3).
/// Boundary lanes have a bit per voxel. Solid lanes (Front, Back) have a bit per half
/// voxel: bin m covers lane positions u in [m, m+1) with u = 2 * index + 1, so voxel k
/// holds bins 2k and 2k+1 and its centre is where bin 2k+1 starts; bins -2 and -1
/// (before the grid) and 2n (after it) keep crossings outside the grid.
struct View
{
  int A, B, C;
  BitVolume Boundary, Front, Back;
};

/// Rasterizes a triangle projected for a view into its solid lanes (vertices snapped
/// to 1/256 of a spacing, exact integer edge functions): each lane whose centre the
/// projected triangle covers (top-left rule) meets it at depth z; the half-voxel bin of z
/// goes to Front (triangle facing the view) or Back.
void RasterizeSolidTriangle(const ProjectedTriangle& t, const SampleGrid& grid, View& view)
{
  const IndexBox& whole = grid.Whole;
  const int nb = whole.Size(view.B), nc = whole.Size(view.C), na = whole.Size(view.A);
  const int64_t xmin = std::min(t.X[0], std::min(t.X[1], t.X[2]));
  const int64_t xmax = std::max(t.X[0], std::max(t.X[1], t.X[2]));
  const int64_t ymin = std::min(t.Y[0], std::min(t.Y[1], t.Y[2]));
  const int64_t ymax = std::max(t.Y[0], std::max(t.Y[1], t.Y[2]));
  int64_t e[3];
  BitVolume& half = t.Entering ? view.Front : view.Back;
  const int64_t p0 = std::max<int64_t>(0, -FloorDiv(-xmin, Subpixel));
  const int64_t p1 = std::min<int64_t>(nb - 1, FloorDiv(xmax, Subpixel));
  const int64_t q0 = std::max<int64_t>(0, -FloorDiv(-ymin, Subpixel));
  const int64_t q1 = std::min<int64_t>(nc - 1, FloorDiv(ymax, Subpixel));
  for (int64_t q = q0; q <= q1; ++q)
  {
    for (int64_t p = p0; p <= p1; ++p)
    {
      if (CoversCentre(t, p, q, e))
      {
        const int at = SolidBit(DepthAt(t, e), na);
        uint64_t* lane = half.Lane(static_cast<int>(p), static_cast<int>(q));
        AtomicOr(&lane[at >> 6], uint64_t(1) << (at & 63));
      }
    }
  }
}

/// Every triangle into the three views' solid lanes, in one pass over the triangles:
/// the views share each corner's grid coordinates and snapped values (ComputeCorners).
/// `far` counts the triangles too far from the grid, once per view.
void RasterizeSolid(const MeshInput& mesh,
  const SampleGrid& grid,
  double orientation,
  View views[3],
  const ParallelFor& parallelFor,
  std::atomic<int64_t>& far)
{
  parallelFor(static_cast<int64_t>(mesh.Triangles.size() / 3),
    256,
    [&](int64_t begin, int64_t end)
    {
      int64_t farHere = 0;
      TriangleCorners corners;
      ProjectedTriangle t;
      for (int64_t index = begin; index < end; ++index)
      {
        ComputeCorners(mesh, index, grid, corners);
        for (int a = 0; a < 3; ++a)
        {
          bool isFar = false;
          if (ProjectTriangle(corners, a, orientation, t, isFar))
          {
            RasterizeSolidTriangle(t, grid, views[a]);
          }
          farHere += isFar;
        }
      }
      far += farHere;
    });
}

/// The boundary voxels of one triangle set up for the boundary rule: the candidates of
/// each lane of its grown footprint in its view, decided by the exact distance.
void RasterizeBoundaryTriangle(const BoundaryTriangle& t,
  const SampleGrid& grid,
  double limit2,
  double reach,
  View& view)
{
  const IndexBox& whole = grid.Whole;
  const int a = view.A, b = view.B, c = view.C;
  for (int q = t.Q0; q <= t.Q1; ++q)
  {
    for (int p = t.P0; p <= t.P1; ++p)
    {
      int k0, k1;
      if (!BoundaryLaneCandidates(t, p, q, reach, k0, k1))
      {
        continue;
      }
      uint64_t* lane = view.Boundary.Lane(p, q);
      for (int k = k0; k <= k1; ++k)
      {
        if ((__atomic_load_n(&lane[k >> 6], __ATOMIC_RELAXED) >> (k & 63)) & 1u)
        {
          continue;
        }
        int ijk[3];
        ijk[a] = k, ijk[b] = p, ijk[c] = q;
        double centre[3];
        for (int d = 0; d < 3; ++d)
        {
          centre[d] = grid.Coordinate(d, whole.Lo[d] + ijk[d]);
        }
        if (SquaredDistanceToTriangle(centre, t.P[0], t.P[1], t.P[2]) <= limit2)
        {
          AtomicOr(&lane[k >> 6], uint64_t(1) << (k & 63));
        }
      }
    }
  }
}

/// The boundary voxels of every triangle, each in the view its setup chooses
/// (BoundaryTriangle). One pass: each triangle is set up on the stack and rasterized at
/// once, so that no per-triangle setup is stored (on a fine mesh the stored setups were
/// 200 MB written and read back).
void RasterizeBoundary(const MeshInput& mesh,
  const SampleGrid& grid,
  View views[3],
  const ParallelFor& parallelFor)
{
  const double limit2 = BoundaryLimit2(grid);
  const BoundaryReaches reaches(grid);
  parallelFor(static_cast<int64_t>(mesh.Triangles.size() / 3),
    256,
    [&](int64_t begin, int64_t end)
    {
      BoundaryTriangle t;
      for (int64_t index = begin; index < end; ++index)
      {
        if (SetupBoundaryTriangle(mesh, index, grid, reaches, t))
        {
          RasterizeBoundaryTriangle(t, grid, limit2, reaches.R[t.View], views[t.View]);
        }
      }
    });
}

/// Sets bits [from, to] of a lane.
void FillBits(uint64_t* lane, int from, int to)
{
  for (int w = from >> 6; w <= (to >> 6); ++w)
  {
    const int lo = std::max(from, w * 64) - w * 64, hi = std::min(to, w * 64 + 63) - w * 64;
    const uint64_t upper = hi == 63 ? ~uint64_t(0) : ((uint64_t(1) << (hi + 1)) - 1);
    lane[w] |= upper & ~((uint64_t(1) << lo) - 1);
  }
}

/// Per lane, the solid intervals, into Front. Martinek et al. (VMV 2011) §4.2 fill from a
/// front bit to the next back bit with no other bit between. Here a run of front bits followed by a
/// run of back bits fills from the run's first front to its last back: the same on
/// disjoint closed parts, the union of overlapping parts, and an open sheet crossing a
/// closed part (F F B or F B B along the lane) changes nothing. A bin holding a front
/// and a back is read front first (a part thinner than half a voxel). The bins filled
/// are those after the front's bin up to the back's bin, so a voxel is solid exactly
/// when its centre lies between the two crossings.
void FillIntervals(View& view, const ParallelFor& parallelFor)
{
  const int nb = view.Front.Size(0), nc = view.Front.Size(1);
  const int words = view.Front.WordsPerLane();
  parallelFor(int64_t(nb) * nc,
    256,
    [&](int64_t begin, int64_t end)
    {
      std::vector<uint64_t> solid(words);
      for (int64_t id = begin; id < end; ++id)
      {
        const int p = static_cast<int>(id % nb), q = static_cast<int>(id / nb);
        uint64_t* front = view.Front.Lane(p, q);
        const uint64_t* back = view.Back.Lane(p, q);
        std::fill(solid.begin(), solid.end(), 0);
        enum
        {
          Outside,
          InFronts,
          InBacks
        } phase = Outside;
        int first = 0, last = 0;
        auto close = [&]()
        {
          if (last > first)
          {
            FillBits(solid.data(), first + 1, last);
          }
        };
        for (int w = 0; w < words; ++w)
        {
          uint64_t events = front[w] | back[w];
          while (events)
          {
            const int bit = __builtin_ctzll(events);
            events &= events - 1;
            const int z = 64 * w + bit;
            if ((front[w] >> bit) & 1u)
            {
              if (phase == InBacks)
              {
                close();
              }
              if (phase != InFronts)
              {
                first = z;
                phase = InFronts;
              }
            }
            if (((back[w] >> bit) & 1u) && phase != Outside)
            {
              last = z;
              phase = InBacks;
            }
          }
        }
        if (phase == InBacks)
        {
          close();
        }
        std::copy(solid.begin(), solid.end(), front);
      }
    });
}
/// ORs (or ANDs, with `intersect`) the voxels of view `a` (0: lanes (y, z) along x; 1:
/// lanes (z, x) along y) into z-lanes (x, y), 64 x 64 bits at a time.
void TransposeInto(const BitVolume& view,
  int a,
  BitVolume& out,
  bool intersect,
  const ParallelFor& parallelFor)
{
  const int nx = out.Size(0), ny = out.Size(1), nz = out.Size(2);
  // View 0: for each y, rows z hold bits x; view 1: for each x, rows z hold bits y.
  const int planes = a == 0 ? ny : nx, columns = a == 0 ? nx : ny;
  parallelFor(planes,
    1,
    [&](int64_t begin, int64_t end)
    {
      uint64_t tile[64];
      for (int64_t plane = begin; plane < end; ++plane)
      {
        const int fixed = static_cast<int>(plane);
        for (int z0 = 0; z0 < nz; z0 += 64)
        {
          for (int c0 = 0; c0 < columns; c0 += 64)
          {
            // The lane pointer is chosen before it is indexed: GCC 12 miscompiles
            // (a ? p() : q())[i >> 6] under -fsanitize=shift (the front end puts the
            // index into both arms with one SAVE_EXPR, evaluated in the first arm only,
            // so the other arm reads an uninitialized temporary: a wild address).
            for (int r = 0; r < 64; ++r)
            {
              const int z = z0 + r;
              tile[r] = 0;
              if (z < nz)
              {
                const uint64_t* lane = a == 0 ? view.Lane(fixed, z) : view.Lane(z, fixed);
                tile[r] = lane[c0 >> 6];
              }
            }
            // Empty tiles (most of a boundary's) and, for an intersection, full ones
            // need no transpose: an OR with zeros and an AND with ones change nothing,
            // and an AND with zeros clears.
            uint64_t any = 0, all = ~uint64_t(0);
            for (int r = 0; r < 64; ++r)
            {
              any |= tile[r];
              all &= tile[r];
            }
            if (any == 0 && !intersect)
            {
              continue;
            }
            if (all == ~uint64_t(0) && intersect)
            {
              continue;
            }
            if (any != 0)
            {
              TransposeBits64(tile);
            }
            for (int c = 0; c < 64 && c0 + c < columns; ++c)
            {
              uint64_t* lane = a == 0 ? out.Lane(c0 + c, fixed) : out.Lane(fixed, c0 + c);
              uint64_t& word = lane[z0 >> 6];
              word = intersect ? (word & tile[c]) : (word | tile[c]);
            }
          }
        }
      }
    });
}

/// The even bits of x, packed into its low 32 bits.
inline uint64_t EvenBits(uint64_t x)
{
  x &= 0x5555555555555555ull;
  x = (x | (x >> 1)) & 0x3333333333333333ull;
  x = (x | (x >> 2)) & 0x0F0F0F0F0F0F0F0Full;
  x = (x | (x >> 4)) & 0x00FF00FF00FF00FFull;
  x = (x | (x >> 8)) & 0x0000FFFF0000FFFFull;
  x = (x | (x >> 16)) & 0x00000000FFFFFFFFull;
  return x;
}

/// From half-voxel bin lanes, one bit per voxel: voxel k is bin 2k + 1 + SolidGuard.
BitVolume VoxelBins(const BitVolume& bins, int voxels, const ParallelFor& parallelFor)
{
  BitVolume out(bins.Size(0), bins.Size(1), voxels);
  const int inWords = bins.WordsPerLane(), outWords = out.WordsPerLane();
  parallelFor(out.NumberOfLanes(),
    256,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t id = begin; id < end; ++id)
      {
        const int p = static_cast<int>(id % bins.Size(0)), q = static_cast<int>(id / bins.Size(0));
        const uint64_t* in = bins.Lane(p, q);
        uint64_t* lane = out.Lane(p, q);
        // 64 bits starting at bit `from` of the bin lane.
        auto take = [&](int from)
        {
          const int w = from >> 6, shift = from & 63;
          const uint64_t lo = w < inWords ? in[w] : 0, hi = w + 1 < inWords ? in[w + 1] : 0;
          return shift ? (lo >> shift) | (hi << (64 - shift)) : lo;
        };
        for (int w = 0; w < outWords; ++w)
        {
          const int from = 128 * w + 1 + SolidGuard;
          lane[w] = EvenBits(take(from)) | (EvenBits(take(from + 64)) << 32);
        }
        lane[outWords - 1] &= out.LastWordMask();
      }
    });
  return out;
}
} // namespace

bool VoxelizeCPU(const MeshInput& mesh,
  const SampleGrid& grid,
  BitVolume* boundary,
  BitVolume* solid,
  const ParallelFor& parallelFor,
  VoxelizeStatistics& statistics,
  std::string& error)
{
  statistics = VoxelizeStatistics();
  const IndexBox& whole = grid.Whole;
  const int n[3] = { whole.Size(0), whole.Size(1), whole.Size(2) };
  if (!ValidateMesh(mesh, grid, error, parallelFor))
  {
    return false;
  }
  statistics.Triangles = static_cast<int64_t>(mesh.Triangles.size() / 3);
  const double orientation = MeshOrientation(mesh);
  statistics.FlippedOrientation = orientation < 0;

  View views[3];
  std::atomic<int64_t> far{ 0 };
  for (int a = 0; a < 3; ++a)
  {
    View& v = views[a];
    v.A = a;
    v.B = (a + 1) % 3;
    v.C = (a + 2) % 3;
    if (boundary)
    {
      v.Boundary.Resize(n[v.B], n[v.C], n[a]);
    }
    if (solid)
    {
      v.Front.Resize(n[v.B], n[v.C], 2 * n[a] + 1 + SolidGuard);
      v.Back.Resize(n[v.B], n[v.C], 2 * n[a] + 1 + SolidGuard);
    }
  }
  if (solid)
  {
    RasterizeSolid(mesh, grid, orientation, views, parallelFor, far);
  }
  if (boundary)
  {
    RasterizeBoundary(mesh, grid, views, parallelFor);
  }
  statistics.FarTriangles = far.load() / 3;

  // The views rotated into z-lanes (Martinek et al. (VMV 2011) §4.1: the voxel (i, j, k) is bit
  // i[A] of lane (i[B], i[C]) of view A): OR for the boundary, AND for the solid.
  if (boundary)
  {
    boundary->Resize(n[0], n[1], n[2]);
  }
  if (solid)
  {
    for (View& v : views)
    {
      FillIntervals(v, parallelFor);
    }
    solid->Resize(n[0], n[1], n[2]);
  }
  if (boundary)
  {
    // View z already has z-lanes; the x and y views are transposed in 64 x 64 tiles.
    boundary->Data() = views[2].Boundary.Data();
    TransposeInto(views[0].Boundary, 0, *boundary, false, parallelFor);
    TransposeInto(views[1].Boundary, 1, *boundary, false, parallelFor);
  }
  if (solid)
  {
    // The solid lanes hold half-voxel bins: keep the voxel centres' bins, then AND.
    BitVolume centres[3];
    for (int a = 0; a < 3; ++a)
    {
      centres[a] = VoxelBins(views[a].Front, n[a], parallelFor);
    }
    solid->Data() = centres[2].Data();
    TransposeInto(centres[0], 0, *solid, true, parallelFor);
    TransposeInto(centres[1], 1, *solid, true, parallelFor);
  }
  return true;
}

} // namespace vtkdf
