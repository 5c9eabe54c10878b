#include "Voxelizer.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace vtkdf
{
namespace
{
constexpr int64_t Subpixel = 256;       // vertex snapping: 1/256 of a spacing
constexpr double SnapRange = 4194304.0; // 2^22 cells: keeps the edge functions exact
constexpr int SolidGuard = 2;           // half-voxel bins -2 and -1 before the grid

int64_t FloorDiv(int64_t a, int64_t b)
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

void AtomicOr(uint64_t* word, uint64_t bits)
{
  // Rasterization threads OR bits into shared lane words.
  __atomic_fetch_or(word, bits, __ATOMIC_RELAXED);
}

/// Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection,
/// 5.1.5), in the coordinates given.
double SquaredDistanceToTriangle(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3])
{
  double ab[3], ac[3], ap[3];
  for (int k = 0; k < 3; ++k)
  {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
  }
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto result = [&](double v, double w)
  {
    double d2 = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double e = a[k] + v * ab[k] + w * ac[k] - p[k];
      d2 += e * e;
    }
    return d2;
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
  {
    return result(0, 0);
  }
  double bp[3], cp[3];
  for (int k = 0; k < 3; ++k)
  {
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
  {
    return result(1, 0);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    return result(d1 / (d1 - d3), 0);
  }
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
  {
    return result(0, 1);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    return result(0, d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return result(1 - w, w);
  }
  const double denominator = 1 / (va + vb + vc);
  return result(vb * denominator, vc * denominator);
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

/// Rasterizes every triangle into a view (vertices snapped to 1/256 of a spacing, exact
/// integer edge functions):
/// - Solid: each lane whose centre the projected triangle covers (top-left rule) meets
///   it at depth z; the half-voxel bin of z goes to Front (triangle facing the view)
///   or Back.
/// - Boundary: each lane whose cell the projected triangle overlaps (conservative)
///   gets the voxels whose centre lies within half a cell diagonal of the triangle.
void Rasterize(const MeshInput& mesh,
  const SampleGrid& grid,
  double orientation,
  View& view,
  const ParallelFor& parallelFor,
  std::atomic<int64_t>& far)
{
  const IndexBox& whole = grid.Whole;
  const int a = view.A, b = view.B, c = view.C;
  const int nb = whole.Size(b), nc = whole.Size(c), na = whole.Size(a);
  const bool boundary = view.Boundary.Size(0) > 0, solid = view.Front.Size(0) > 0;
  const double limit2 = 0.25 *
    (grid.Spacing[0] * grid.Spacing[0] + grid.Spacing[1] * grid.Spacing[1] +
      grid.Spacing[2] * grid.Spacing[2]);
  const int64_t numTriangles = static_cast<int64_t>(mesh.Triangles.size() / 3);
  parallelFor(numTriangles,
    256,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t t = begin; t < end; ++t)
      {
        const double* P[3];
        double X[3], Y[3], Z[3];
        bool inRange = true;
        for (int k = 0; k < 3; ++k)
        {
          P[k] = &mesh.Points[3 * mesh.Triangles[3 * t + k]];
          X[k] = (P[k][b] - grid.Origin[b]) / grid.Spacing[b] - whole.Lo[b];
          Y[k] = (P[k][c] - grid.Origin[c]) / grid.Spacing[c] - whole.Lo[c];
          Z[k] = (P[k][a] - grid.Origin[a]) / grid.Spacing[a] - whole.Lo[a];
          inRange = inRange && std::fabs(X[k]) < SnapRange && std::fabs(Y[k]) < SnapRange;
        }
        if (!inRange)
        {
          ++far;
          continue;
        }
        int64_t x[3], y[3];
        for (int k = 0; k < 3; ++k)
        {
          x[k] = std::llround(X[k] * Subpixel);
          y[k] = std::llround(Y[k] * Subpixel);
        }
        int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        if (area == 0)
        {
          continue; // seen edge-on: the other views cover it
        }
        // (B, C, A) is a cyclic permutation of (x, y, z), so the projected area has the
        // sign of the normal's A component; a triangle facing the view (looking along +A)
        // is where a lane enters the solid.
        const bool entering = area * orientation < 0;
        if (area < 0)
        {
          std::swap(x[1], x[2]);
          std::swap(y[1], y[2]);
          std::swap(Z[1], Z[2]);
          area = -area;
        }
        // Edge k runs from vertex k to k+1; the top-left rule gives a lane through an
        // edge shared by two triangles to exactly one of them.
        bool owns[3];
        for (int k = 0; k < 3; ++k)
        {
          const int64_t dx = x[(k + 1) % 3] - x[k], dy = y[(k + 1) % 3] - y[k];
          owns[k] = dy < 0 || (dy == 0 && dx < 0);
        }
        const int64_t xmin = std::min(x[0], std::min(x[1], x[2]));
        const int64_t xmax = std::max(x[0], std::max(x[1], x[2]));
        const int64_t ymin = std::min(y[0], std::min(y[1], y[2]));
        const int64_t ymax = std::max(y[0], std::max(y[1], y[2]));
        auto edge = [&](int k, int64_t px, int64_t py)
        {
          const int k1 = (k + 1) % 3;
          return (x[k1] - x[k]) * (py - y[k]) - (y[k1] - y[k]) * (px - x[k]);
        };
        // Barycentric depth: the weight of vertex k is the edge function opposite it.
        auto depthAt = [&](const int64_t e[3]) {
          return (double(e[1]) * Z[0] + double(e[2]) * Z[1] + double(e[0]) * Z[2]) / double(area);
        };

        if (solid)
        {
          // Lanes whose centre the triangle covers.
          BitVolume& half = entering ? view.Front : view.Back;
          const int64_t p0 = std::max<int64_t>(0, -FloorDiv(-xmin, Subpixel));
          const int64_t p1 = std::min<int64_t>(nb - 1, FloorDiv(xmax, Subpixel));
          const int64_t q0 = std::max<int64_t>(0, -FloorDiv(-ymin, Subpixel));
          const int64_t q1 = std::min<int64_t>(nc - 1, FloorDiv(ymax, Subpixel));
          for (int64_t q = q0; q <= q1; ++q)
          {
            for (int64_t p = p0; p <= p1; ++p)
            {
              int64_t e[3];
              bool inside = true;
              for (int k = 0; k < 3 && inside; ++k)
              {
                e[k] = edge(k, p * Subpixel, q * Subpixel);
                inside = e[k] > 0 || (e[k] == 0 && owns[k]);
              }
              if (inside)
              {
                const double u = 2 * depthAt(e) + 1;
                const int at =
                  static_cast<int>(std::floor(std::min(std::max(u, -1.0), 2.0 * na))) + SolidGuard;
                uint64_t* lane = half.Lane(static_cast<int>(p), static_cast<int>(q));
                AtomicOr(&lane[at >> 6], uint64_t(1) << (at & 63));
              }
            }
          }
        }

        if (boundary)
        {
          // Conservative: lanes whose cell (the square of one spacing around the centre)
          // the projected triangle overlaps. Their candidate voxels span the triangle's
          // depths over the square, widened by the distance limit; the exact distance
          // decides.
          const int64_t halfCell = Subpixel / 2;
          const int64_t p0 = std::max<int64_t>(0, -FloorDiv(-(xmin - halfCell), Subpixel));
          const int64_t p1 = std::min<int64_t>(nb - 1, FloorDiv(xmax + halfCell, Subpixel));
          const int64_t q0 = std::max<int64_t>(0, -FloorDiv(-(ymin - halfCell), Subpixel));
          const int64_t q1 = std::min<int64_t>(nc - 1, FloorDiv(ymax + halfCell, Subpixel));
          const double slopeP = -(double(y[2] - y[1]) * Z[0] + double(y[0] - y[2]) * Z[1] +
                                  double(y[1] - y[0]) * Z[2]) /
            double(area) * Subpixel;
          const double slopeQ =
            (double(x[2] - x[1]) * Z[0] + double(x[0] - x[2]) * Z[1] + double(x[1] - x[0]) * Z[2]) /
            double(area) * Subpixel;
          const double spread = 0.5 * (std::fabs(slopeP) + std::fabs(slopeQ));
          const double zmin = std::min(Z[0], std::min(Z[1], Z[2]));
          const double zmax = std::max(Z[0], std::max(Z[1], Z[2]));
          const double reach = std::sqrt(limit2) / grid.Spacing[a];
          for (int64_t q = q0; q <= q1; ++q)
          {
            for (int64_t p = p0; p <= p1; ++p)
            {
              int64_t e[3];
              bool overlaps = true;
              for (int k = 0; k < 3 && overlaps; ++k)
              {
                const int k1 = (k + 1) % 3;
                e[k] = edge(k, p * Subpixel, q * Subpixel);
                overlaps =
                  e[k] + halfCell * (std::llabs(x[k1] - x[k]) + std::llabs(y[k1] - y[k])) >= 0;
              }
              if (!overlaps)
              {
                continue;
              }
              const double centre = depthAt(e);
              const double lo = std::max(centre - spread, zmin) - reach;
              const double hi = std::min(centre + spread, zmax) + reach;
              const int k0 = static_cast<int>(std::max(std::ceil(lo), 0.0));
              const int k1 = static_cast<int>(std::min(std::floor(hi), na - 1.0));
              uint64_t* lane = view.Boundary.Lane(static_cast<int>(p), static_cast<int>(q));
              for (int k = k0; k <= k1; ++k)
              {
                int ijk[3];
                ijk[a] = k, ijk[b] = static_cast<int>(p), ijk[c] = static_cast<int>(q);
                double point[3];
                for (int d = 0; d < 3; ++d)
                {
                  point[d] = grid.Coordinate(d, whole.Lo[d] + ijk[d]);
                }
                if (SquaredDistanceToTriangle(point, P[0], P[1], P[2]) <= limit2)
                {
                  AtomicOr(&lane[k >> 6], uint64_t(1) << (k & 63));
                }
              }
            }
          }
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

/// Per lane, the solid intervals, into Front. Paper 001 §4.2 fills from a front bit to
/// the next back bit with no other bit between. Here a run of front bits followed by a
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
  const int64_t numPoints = static_cast<int64_t>(mesh.Points.size() / 3);
  for (int64_t id : mesh.Triangles)
  {
    if (id < 0 || id >= numPoints)
    {
      error = "a cell refers to point " + std::to_string(id) + " of " + std::to_string(numPoints);
      return false;
    }
    for (int a = 0; a < 3; ++a)
    {
      if (!std::isfinite(mesh.Points[3 * id + a]))
      {
        error = "point " + std::to_string(id) + " has a NaN or infinite coordinate";
        return false;
      }
    }
  }
  statistics.Triangles = static_cast<int64_t>(mesh.Triangles.size() / 3);

  // Outward orientation for closed meshes (positive signed volume).
  double volume = 0;
  for (size_t t = 0; t + 2 < mesh.Triangles.size(); t += 3)
  {
    const double* p0 = &mesh.Points[3 * mesh.Triangles[t]];
    const double* p1 = &mesh.Points[3 * mesh.Triangles[t + 1]];
    const double* p2 = &mesh.Points[3 * mesh.Triangles[t + 2]];
    volume += p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0]) +
      p0[2] * (p1[0] * p2[1] - p1[1] * p2[0]);
  }
  const double orientation = volume < 0 ? -1.0 : 1.0;
  statistics.FlippedOrientation = volume < 0;

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
    Rasterize(mesh, grid, orientation, v, parallelFor, far);
  }
  statistics.FarTriangles = far.load() / 3;

  // The views rotated into z-lanes (paper 001 §4.1: the voxel (i, j, k) is bit i[A] of
  // lane (i[B], i[C]) of view A): OR for the boundary, AND for the solid.
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
  parallelFor(int64_t(n[0]) * n[1],
    256,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t id = begin; id < end; ++id)
      {
        const int i = static_cast<int>(id % n[0]), j = static_cast<int>(id / n[0]);
        for (int k = 0; k < n[2]; ++k)
        {
          const int ijk[3] = { i, j, k };
          const uint64_t bit = uint64_t(1) << (k & 63);
          if (boundary)
          {
            bool set = false;
            for (int a = 0; a < 3 && !set; ++a)
            {
              set = views[a].Boundary.Get(ijk[views[a].B], ijk[views[a].C], ijk[a]);
            }
            boundary->Lane(i, j)[k >> 6] |= set ? bit : 0;
          }
          if (solid)
          {
            bool set = true;
            for (int a = 0; a < 3 && set; ++a)
            {
              set =
                views[a].Front.Get(ijk[views[a].B], ijk[views[a].C], 2 * ijk[a] + 1 + SolidGuard);
            }
            solid->Lane(i, j)[k >> 6] |= set ? bit : 0;
          }
        }
      }
    });
  return true;
}

} // namespace vtkdf
