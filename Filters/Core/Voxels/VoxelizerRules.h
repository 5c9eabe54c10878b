// VoxelizerRules: the per-triangle setup and the per-lane rules of the voxelizer, shared
// by the CPU pass (Voxelizer.cxx) and the GPU pass (VoxelGPU.cxx, whose shaders in
// Shaders/Voxelize*.glsl repeat the set-ups and the per-lane arithmetic operation for
// operation, in integers and IEEE doubles, so that both backends set the same bits).
//
// A view looks along axis A; its lanes are indexed by the other two axes B = A+1 and
// C = A+2 (mod 3), so (B, C, A) is a cyclic permutation of (x, y, z).
#ifndef vtkdf_VoxelizerRules_h
#define vtkdf_VoxelizerRules_h

#include "Common/MeshInput.h"
#include "Common/PointTriangleDistance.h"
#include "Common/Rounding.h"
#include "Common/SampleGrid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>

namespace vtkdf
{
namespace voxelizer
{
constexpr int64_t Subpixel = 256;       // vertices snapped to 1/256 of a spacing
constexpr double SnapRange = 4194304.0; // 2^22 cells: keeps the edge functions exact
constexpr int SolidGuard = 2;           // half-voxel bins -2 and -1 before the grid

inline int64_t FloorDiv(int64_t a, int64_t b)
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/// A triangle as one view sees it: lane-plane coordinates snapped to Subpixel
/// (counter-clockwise), depths in voxel units along A, world-space corners.
struct ProjectedTriangle
{
  int64_t X[3], Y[3];
  double Z[3];
  double P[3][3];
  int64_t Area;  // twice the snapped area, > 0
  bool Entering; // faces the viewer looking along +A: a lane enters the solid here
  bool Owns[3];  // top-left rule: edge k (vertex k to k+1) owns the lanes on it
};

/// A triangle's corners in voxel units along each axis, and snapped to Subpixel along the
/// axes where every corner lies within SnapRange: what all three views' projections
/// share.
struct TriangleCorners
{
  const double* P[3];    // the corners in world coordinates
  double V[3][3];        // V[k][d]: corner k along axis d, in voxel units
  int64_t Snapped[3][3]; // round(V[k][d] * Subpixel) where InRange[d]
  bool InRange[3];
};

inline void ComputeCorners(const MeshInput& mesh,
  int64_t t,
  const SampleGrid& grid,
  TriangleCorners& out)
{
  const IndexBox& whole = grid.Whole;
  for (int k = 0; k < 3; ++k)
  {
    out.P[k] = &mesh.Points[3 * mesh.Triangles[3 * t + k]];
  }
  for (int d = 0; d < 3; ++d)
  {
    bool inRange = true;
    for (int k = 0; k < 3; ++k)
    {
      out.V[k][d] = (out.P[k][d] - grid.Origin[d]) / grid.Spacing[d] - whole.Lo[d];
      inRange = inRange && std::fabs(out.V[k][d]) < SnapRange;
    }
    out.InRange[d] = inRange;
    for (int k = 0; k < 3; ++k)
    {
      out.Snapped[k][d] = inRange ? RoundHalfAway(out.V[k][d] * Subpixel) : 0;
    }
  }
}

/// Projects a triangle for view `a`. False when it covers no lane (seen edge-on) or lies
/// too far from the grid (`far` is then set).
inline bool ProjectTriangle(const TriangleCorners& corners,
  int a,
  double orientation,
  ProjectedTriangle& out,
  bool& far)
{
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  far = !corners.InRange[b] || !corners.InRange[c];
  if (far)
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    std::copy(corners.P[k], corners.P[k] + 3, out.P[k]);
    out.X[k] = corners.Snapped[k][b];
    out.Y[k] = corners.Snapped[k][c];
    out.Z[k] = corners.V[k][a];
  }
  int64_t area =
    (out.X[1] - out.X[0]) * (out.Y[2] - out.Y[0]) - (out.Y[1] - out.Y[0]) * (out.X[2] - out.X[0]);
  if (area == 0)
  {
    return false; // seen edge-on: the other views cover it
  }
  // The projected area has the sign of the normal's A component.
  out.Entering = area * orientation < 0;
  if (area < 0)
  {
    std::swap(out.X[1], out.X[2]);
    std::swap(out.Y[1], out.Y[2]);
    std::swap(out.Z[1], out.Z[2]);
    area = -area;
  }
  out.Area = area;
  for (int k = 0; k < 3; ++k)
  {
    const int64_t dx = out.X[(k + 1) % 3] - out.X[k], dy = out.Y[(k + 1) % 3] - out.Y[k];
    out.Owns[k] = dy < 0 || (dy == 0 && dx < 0);
  }
  return true;
}

/// Projects triangle `t` for view `a` (ComputeCorners, then the view's projection).
inline bool ProjectTriangle(const MeshInput& mesh,
  int64_t t,
  const SampleGrid& grid,
  int a,
  double orientation,
  ProjectedTriangle& out,
  bool& far)
{
  TriangleCorners corners;
  ComputeCorners(mesh, t, grid, corners);
  return ProjectTriangle(corners, a, orientation, out, far);
}

/// Edge function k at lane (p, q): > 0 inside.
inline int64_t Edge(const ProjectedTriangle& t, int k, int64_t p, int64_t q)
{
  const int k1 = (k + 1) % 3;
  return (t.X[k1] - t.X[k]) * (q * Subpixel - t.Y[k]) -
    (t.Y[k1] - t.Y[k]) * (p * Subpixel - t.X[k]);
}

/// Whether the lane's centre is in the triangle (top-left rule); fills the edge values.
inline bool CoversCentre(const ProjectedTriangle& t, int64_t p, int64_t q, int64_t e[3])
{
  for (int k = 0; k < 3; ++k)
  {
    e[k] = Edge(t, k, p, q);
    if (!(e[k] > 0 || (e[k] == 0 && t.Owns[k])))
    {
      return false;
    }
  }
  return true;
}

/// Depth of the triangle's plane on the lane (barycentric: the weight of vertex k is the
/// edge function opposite it).
inline double DepthAt(const ProjectedTriangle& t, const int64_t e[3])
{
  return (double(e[1]) * t.Z[0] + double(e[2]) * t.Z[1] + double(e[0]) * t.Z[2]) / double(t.Area);
}

/// The lane bit (half-voxel bin + guard) of a crossing at `depth`.
inline int SolidBit(double depth, int na)
{
  const double u = 2 * depth + 1;
  return FloorToInt(std::min(std::max(u, -1.0), 2.0 * na)) + SolidGuard;
}

/// Half the cell diagonal, squared: the boundary's distance limit.
inline double BoundaryLimit2(const SampleGrid& grid)
{
  return 0.25 *
    (grid.Spacing[0] * grid.Spacing[0] + grid.Spacing[1] * grid.Spacing[1] +
      grid.Spacing[2] * grid.Spacing[2]);
}

/// A triangle set up for the boundary rule. The rule must find every voxel whose centre
/// c lies within r (half the cell diagonal) of the triangle. With q the triangle point
/// nearest to c, |c - q| <= r bounds each coordinate difference by r, so along any
/// view c's lane lies within r / h_B and r / h_C (lane units) of q's projection, and c's
/// depth within r / h_A of q's. Each triangle is therefore rasterized in one view only:
/// the one its plane faces most (largest |n_A| h_A, so depth changes by at most one
/// voxel per lane), over the projected triangle grown by those reaches (the Minkowski
/// sum with a rectangle: three edge tests with slack, and the grown bounding box), with
/// the voxels of each lane between the depths of the plane over the grown lane cell,
/// clamped to the triangle's depth range and grown by r / h_A. Degenerate triangles
/// (segments, points: no usable plane) and triangles too far from the grid for double
/// edge functions use the grown bounding box and the whole depth range. No vertex is
/// snapped: the candidates only have to include every such voxel, and the exact distance
/// decides, so the CPU and GPU passes set the same bits. The reaches carry a relative
/// slack of 1e-6 for rounding.
struct BoundaryTriangle
{
  int View;                // A
  double X[3], Y[3], Z[3]; // lane-plane coordinates (lane units) and depths (voxels)
  double P[3][3];          // corners in the grid's coordinates
  double Orientation;      // +1 or -1: edge functions >= 0 inside; 0: bounding box only
  double Slack[3];         // the growth of edge function k by the reaches
  double GradP, GradQ;     // depth change per lane along B and C
  double Spread;           // half the depth change across a grown lane cell
  int P0, P1, Q0, Q1;      // the lanes of the grown bounding box, within the grid
  int K0, K1;              // the voxels of the depth range grown by the reach, within the grid
};

/// The reach along axis a, in voxels, with the rounding slack.
inline double BoundaryReach(const SampleGrid& grid, int a)
{
  return std::sqrt(BoundaryLimit2(grid)) / grid.Spacing[a] * (1 + 1e-6) + 1e-6;
}

/// The reaches along the three axes (BoundaryReach), computed once per grid.
struct BoundaryReaches
{
  double R[3];
  explicit BoundaryReaches(const SampleGrid& grid)
    : R{ BoundaryReach(grid, 0), BoundaryReach(grid, 1), BoundaryReach(grid, 2) }
  {
  }
};

/// Sets up triangle `t` for the boundary rule; false when no voxel of the grid can be
/// within reach of it.
inline bool SetupBoundaryTriangle(const MeshInput& mesh,
  int64_t t,
  const SampleGrid& grid,
  const BoundaryReaches& reaches,
  BoundaryTriangle& out)
{
  const double* corner[3];
  for (int k = 0; k < 3; ++k)
  {
    corner[k] = &mesh.Points[3 * mesh.Triangles[3 * t + k]];
    std::copy(corner[k], corner[k] + 3, out.P[k]);
  }
  // In voxel units (sample index coordinates).
  double v[3][3];
  for (int k = 0; k < 3; ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      v[k][d] = (corner[k][d] - grid.Origin[d]) / grid.Spacing[d] - grid.Whole.Lo[d];
    }
  }
  double u[3], w[3], n[3];
  for (int d = 0; d < 3; ++d)
  {
    u[d] = v[1][d] - v[0][d];
    w[d] = v[2][d] - v[0][d];
  }
  n[0] = u[1] * w[2] - u[2] * w[1];
  n[1] = u[2] * w[0] - u[0] * w[2];
  n[2] = u[0] * w[1] - u[1] * w[0];
  const double longest2 = std::max(u[0] * u[0] + u[1] * u[1] + u[2] * u[2],
    std::max(w[0] * w[0] + w[1] * w[1] + w[2] * w[2],
      (w[0] - u[0]) * (w[0] - u[0]) + (w[1] - u[1]) * (w[1] - u[1]) +
        (w[2] - u[2]) * (w[2] - u[2])));
  const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  // A usable plane: the sine of the triangle's largest angle above 1e-9 or so.
  bool planar = n2 > 1e-18 * longest2 * longest2;
  int a = 0;
  for (int d = 1; d < 3; ++d)
  {
    if (planar ? std::fabs(n[d]) > std::fabs(n[a])
               : std::fabs(std::max(v[0][d], std::max(v[1][d], v[2][d])) -
                   std::min(v[0][d], std::min(v[1][d], v[2][d]))) >
          std::fabs(std::max(v[0][a], std::max(v[1][a], v[2][a])) -
            std::min(v[0][a], std::min(v[1][a], v[2][a]))))
    {
      a = d;
    }
  }
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  out.View = a;
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (int k = 0; k < 3; ++k)
  {
    out.X[k] = v[k][b];
    out.Y[k] = v[k][c];
    out.Z[k] = v[k][a];
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], v[k][d]);
      hi[d] = std::max(hi[d], v[k][d]);
    }
  }
  // Edge functions in double stay exact enough within 2^22 lanes of the grid.
  for (int d = 0; d < 3; ++d)
  {
    planar = planar && std::fabs(lo[d]) < SnapRange && std::fabs(hi[d]) < SnapRange;
  }
  const double rb = reaches.R[b], rc = reaches.R[c], ra = reaches.R[a];
  const double nb = grid.Whole.Size(b), nc = grid.Whole.Size(c), na = grid.Whole.Size(a);
  // The grown box, clamped in double before the conversion to int.
  auto first = [](double x, double size) { return CeilToInt(std::min(std::max(x, -1.0), size)); };
  auto last = [](double x, double size) { return FloorToInt(std::min(std::max(x, -1.0), size)); };
  out.P0 = std::max(0, first(lo[b] - rb, nb));
  out.P1 = std::min(grid.Whole.Size(b) - 1, last(hi[b] + rb, nb));
  out.Q0 = std::max(0, first(lo[c] - rc, nc));
  out.Q1 = std::min(grid.Whole.Size(c) - 1, last(hi[c] + rc, nc));
  out.K0 = std::max(0, first(lo[a] - ra, na));
  out.K1 = std::min(grid.Whole.Size(a) - 1, last(hi[a] + ra, na));
  if (out.P0 > out.P1 || out.Q0 > out.Q1 || out.K0 > out.K1)
  {
    return false;
  }
  out.Orientation = 0;
  out.GradP = out.GradQ = out.Spread = 0;
  for (int k = 0; k < 3; ++k)
  {
    out.Slack[k] = 0;
  }
  if (planar)
  {
    // n[a] is twice the projected area: not zero for the view the plane faces most.
    out.Orientation = n[a] > 0 ? 1.0 : -1.0;
    for (int k = 0; k < 3; ++k)
    {
      const int k1 = (k + 1) % 3;
      out.Slack[k] = std::fabs(out.X[k1] - out.X[k]) * rc + std::fabs(out.Y[k1] - out.Y[k]) * rb;
    }
    out.GradP = -n[b] / n[a];
    out.GradQ = -n[c] / n[a];
    out.Spread = std::fabs(out.GradP) * rb + std::fabs(out.GradQ) * rc;
  }
  return true;
}

/// The voxels [k0, k1] of lane (p, q) that may lie within reach of the triangle; false
/// when none.
inline bool BoundaryLaneCandidates(const BoundaryTriangle& t,
  int p,
  int q,
  double reach,
  int& k0,
  int& k1)
{
  const double zmin = std::min(t.Z[0], std::min(t.Z[1], t.Z[2]));
  const double zmax = std::max(t.Z[0], std::max(t.Z[1], t.Z[2]));
  double lo = zmin - reach, hi = zmax + reach;
  if (t.Orientation != 0)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int k1 = (k + 1) % 3;
      const double e =
        t.Orientation * ((t.X[k1] - t.X[k]) * (q - t.Y[k]) - (t.Y[k1] - t.Y[k]) * (p - t.X[k]));
      if (e + t.Slack[k] < 0)
      {
        return false;
      }
    }
    const double depth = t.Z[0] + t.GradP * (p - t.X[0]) + t.GradQ * (q - t.Y[0]);
    lo = std::max(depth - t.Spread, zmin) - reach;
    hi = std::min(depth + t.Spread, zmax) + reach;
  }
  k0 = std::max(t.K0, CeilToInt(std::max(lo, -1.0)));
  k1 = std::min(t.K1, FloorToInt(std::min(hi, double(t.K1) + 1)));
  return k0 <= k1;
}

/// +1 when the mesh's signed volume is positive (outward triangles), else -1.
inline double MeshOrientation(const MeshInput& mesh)
{
  double volume = 0;
  for (size_t t = 0; t + 2 < mesh.Triangles.size(); t += 3)
  {
    const double* p0 = &mesh.Points[3 * mesh.Triangles[t]];
    const double* p1 = &mesh.Points[3 * mesh.Triangles[t + 1]];
    const double* p2 = &mesh.Points[3 * mesh.Triangles[t + 2]];
    volume += p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0]) +
      p0[2] * (p1[0] * p2[1] - p1[1] * p2[0]);
  }
  return volume < 0 ? -1.0 : 1.0;
}

/// The most voxels along an axis: a solid lane holds two bins per voxel plus guards in
/// an int bit index.
constexpr int MaximumAxisVoxels = 1 << 29;

/// Point ids in range, finite coordinates and a grid whose lanes fit; false and `error`
/// otherwise (about the first bad id in order). `parallelFor` (optional) scans the ids
/// in parallel.
inline bool ValidateMesh(const MeshInput& mesh,
  const SampleGrid& grid,
  std::string& error,
  const ParallelFor& parallelFor = ParallelFor())
{
  for (int a = 0; a < 3; ++a)
  {
    if (grid.Whole.Size(a) > MaximumAxisVoxels)
    {
      error = "the grid has " + std::to_string(grid.Whole.Size(a)) +
        " voxels along an axis; the voxelizer takes at most 2^29";
      return false;
    }
  }
  const int64_t numPoints = static_cast<int64_t>(mesh.Points.size() / 3);
  const int64_t numIds = static_cast<int64_t>(mesh.Triangles.size());
  auto inRange = [&](int64_t id) { return id >= 0 && id < numPoints; };
  auto finite = [&](int64_t id)
  {
    const double* x = &mesh.Points[3 * id];
    return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
  };
  // The first bad position, as the least over the chunks.
  std::atomic<int64_t> firstBad{ numIds };
  auto scan = [&](int64_t begin, int64_t end)
  {
    for (int64_t i = begin; i < end && i < firstBad.load(std::memory_order_relaxed); ++i)
    {
      const int64_t id = mesh.Triangles[i];
      if (!inRange(id) || !finite(id))
      {
        int64_t seen = firstBad.load(std::memory_order_relaxed);
        while (i < seen && !firstBad.compare_exchange_weak(seen, i, std::memory_order_relaxed))
        {
        }
        return;
      }
    }
  };
  if (parallelFor)
  {
    parallelFor(numIds, 1 << 15, scan);
  }
  else
  {
    scan(0, numIds);
  }
  if (firstBad.load() == numIds)
  {
    return true;
  }
  const int64_t id = mesh.Triangles[firstBad.load()];
  error = !inRange(id)
    ? "a cell refers to point " + std::to_string(id) + " of " + std::to_string(numPoints)
    : "point " + std::to_string(id) + " has a NaN or infinite coordinate";
  return false;
}

} // namespace voxelizer
} // namespace vtkdf

#endif
