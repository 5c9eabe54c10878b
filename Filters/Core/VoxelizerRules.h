// VoxelizerRules: the per-triangle setup and the per-lane rules of the voxelizer, shared
// by the CPU pass (Voxelizer.cxx) and the GPU pass (VoxelGPU.cxx, whose shaders in
// Shaders/Voxelize*.glsl repeat the per-lane arithmetic operation for operation, in
// integers and IEEE doubles, so that both backends set the same bits).
//
// A view looks along axis A; its lanes are indexed by the other two axes B = A+1 and
// C = A+2 (mod 3), so (B, C, A) is a cyclic permutation of (x, y, z).
#ifndef vtkdf_VoxelizerRules_h
#define vtkdf_VoxelizerRules_h

#include "MeshSites.h"
#include "SampleGrid.h"

#include <algorithm>
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

/// Projects triangle `t` for view `a`. False when it covers no lane (seen edge-on) or
/// lies too far from the grid (`far` is then set).
inline bool ProjectTriangle(const MeshInput& mesh,
  int64_t t,
  const SampleGrid& grid,
  int a,
  double orientation,
  ProjectedTriangle& out,
  bool& far)
{
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const IndexBox& whole = grid.Whole;
  double X[3], Y[3];
  far = false;
  for (int k = 0; k < 3; ++k)
  {
    const double* p = &mesh.Points[3 * mesh.Triangles[3 * t + k]];
    std::copy(p, p + 3, out.P[k]);
    X[k] = (p[b] - grid.Origin[b]) / grid.Spacing[b] - whole.Lo[b];
    Y[k] = (p[c] - grid.Origin[c]) / grid.Spacing[c] - whole.Lo[c];
    out.Z[k] = (p[a] - grid.Origin[a]) / grid.Spacing[a] - whole.Lo[a];
    far = far || !(std::fabs(X[k]) < SnapRange && std::fabs(Y[k]) < SnapRange);
  }
  if (far)
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    out.X[k] = std::llround(X[k] * Subpixel);
    out.Y[k] = std::llround(Y[k] * Subpixel);
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

/// Whether the triangle overlaps the lane's cell (the square of one spacing around its
/// centre); fills the edge values.
inline bool OverlapsCell(const ProjectedTriangle& t, int64_t p, int64_t q, int64_t e[3])
{
  const int64_t half = Subpixel / 2;
  for (int k = 0; k < 3; ++k)
  {
    const int k1 = (k + 1) % 3;
    e[k] = Edge(t, k, p, q);
    if (e[k] + half * (std::llabs(t.X[k1] - t.X[k]) + std::llabs(t.Y[k1] - t.Y[k])) < 0)
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

/// Half the change of depth across a lane's cell.
inline double DepthSpread(const ProjectedTriangle& t)
{
  const double slopeP = -(double(t.Y[2] - t.Y[1]) * t.Z[0] + double(t.Y[0] - t.Y[2]) * t.Z[1] +
                          double(t.Y[1] - t.Y[0]) * t.Z[2]) /
    double(t.Area) * double(Subpixel);
  const double slopeQ = (double(t.X[2] - t.X[1]) * t.Z[0] + double(t.X[0] - t.X[2]) * t.Z[1] +
                          double(t.X[1] - t.X[0]) * t.Z[2]) /
    double(t.Area) * double(Subpixel);
  return 0.5 * (std::fabs(slopeP) + std::fabs(slopeQ));
}

/// The voxels of a lane that may lie within `reach` (voxel units along A) of the part of
/// the triangle over the lane's cell: [k0, k1], clamped to [0, na - 1].
inline void BoundaryCandidates(const ProjectedTriangle& t,
  double depth,
  double spread,
  double reach,
  int na,
  int& k0,
  int& k1)
{
  const double zmin = std::min(t.Z[0], std::min(t.Z[1], t.Z[2]));
  const double zmax = std::max(t.Z[0], std::max(t.Z[1], t.Z[2]));
  const double lo = std::max(depth - spread, zmin) - reach;
  const double hi = std::min(depth + spread, zmax) + reach;
  k0 = static_cast<int>(std::max(std::ceil(lo), 0.0));
  k1 = static_cast<int>(std::min(std::floor(hi), na - 1.0));
}

/// The lane bit (half-voxel bin + guard) of a crossing at `depth`.
inline int SolidBit(double depth, int na)
{
  const double u = 2 * depth + 1;
  return static_cast<int>(std::floor(std::min(std::max(u, -1.0), 2.0 * na))) + SolidGuard;
}

/// Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection,
/// 5.1.5).
inline double SquaredDistanceToTriangle(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3])
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; ++k)
  {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  double v = 0, w = 0;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (d1 <= 0 && d2 <= 0)
  {
    v = 0, w = 0;
  }
  else if (d3 >= 0 && d4 <= d3)
  {
    v = 1, w = 0;
  }
  else if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    v = d1 / (d1 - d3), w = 0;
  }
  else if (d6 >= 0 && d5 <= d6)
  {
    v = 0, w = 1;
  }
  else if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    v = 0, w = d2 / (d2 - d6);
  }
  else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    v = 1 - w;
  }
  else
  {
    const double denominator = 1 / (va + vb + vc);
    v = vb * denominator, w = vc * denominator;
  }
  double d2sum = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = a[k] + v * ab[k] + w * ac[k] - p[k];
    d2sum += e * e;
  }
  return d2sum;
}

/// Half the cell diagonal, squared: the boundary's distance limit.
inline double BoundaryLimit2(const SampleGrid& grid)
{
  return 0.25 *
    (grid.Spacing[0] * grid.Spacing[0] + grid.Spacing[1] * grid.Spacing[1] +
      grid.Spacing[2] * grid.Spacing[2]);
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
/// otherwise.
inline bool ValidateMesh(const MeshInput& mesh, const SampleGrid& grid, std::string& error)
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
  return true;
}

} // namespace voxelizer
} // namespace vtkdf

#endif
