// References for the voxel tests, computed independently of the code under test:
// - exact distances from voxel centres to a triangle mesh, near the surface (every
//   triangle visits the voxels of its bounding box grown by a radius);
// - an inside test by ray parity along z (the lane's position nudged off the grid so
//   that it meets no edge or vertex);
// - the chamfer layers by breadth-first search.
#ifndef vtkdf_VoxelReference_h
#define vtkdf_VoxelReference_h

#include "ExactDistance.h"

#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <vector>

namespace voxelref
{

struct Grid
{
  double Origin[3], Spacing[3];
  int Dims[3];
  explicit Grid(vtkImageData* image)
  {
    image->GetOrigin(this->Origin);
    image->GetSpacing(this->Spacing);
    image->GetDimensions(this->Dims);
  }
  int64_t Count() const { return int64_t(Dims[0]) * Dims[1] * Dims[2]; }
  int64_t Index(int i, int j, int k) const
  {
    return i + int64_t(Dims[0]) * (j + int64_t(Dims[1]) * k);
  }
  double X(int a, int i) const { return Origin[a] + i * Spacing[a]; }
};

/// The mesh as a flat list of triangles (polygons and strips triangulated).
inline std::vector<std::array<std::array<double, 3>, 3>> Triangles(vtkPolyData* mesh)
{
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(mesh);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  vtkPolyData* t = triangulate->GetOutput();
  std::vector<std::array<std::array<double, 3>, 3>> out;
  vtkIdType n;
  const vtkIdType* ids;
  for (t->GetPolys()->InitTraversal(); t->GetPolys()->GetNextCell(n, ids);)
  {
    if (n == 3)
    {
      std::array<std::array<double, 3>, 3> tri;
      for (int k = 0; k < 3; ++k)
      {
        t->GetPoint(ids[k], tri[k].data());
      }
      out.push_back(tri);
    }
  }
  return out;
}

/// Distance from every voxel centre to the triangles, exact where it is <= radius and
/// +infinity (meaning "more than radius") elsewhere.
inline std::vector<double> NearDistance(const Grid& g,
  const std::vector<std::array<std::array<double, 3>, 3>>& triangles,
  double radius)
{
  std::vector<double> d(g.Count(), HUGE_VAL);
  for (const auto& t : triangles)
  {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      const double mn = std::min(t[0][a], std::min(t[1][a], t[2][a])) - radius;
      const double mx = std::max(t[0][a], std::max(t[1][a], t[2][a])) + radius;
      lo[a] = std::max(0, static_cast<int>(std::ceil((mn - g.Origin[a]) / g.Spacing[a])));
      hi[a] =
        std::min(g.Dims[a] - 1, static_cast<int>(std::floor((mx - g.Origin[a]) / g.Spacing[a])));
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
    {
      for (int j = lo[1]; j <= hi[1]; ++j)
      {
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          const double x[3] = { g.X(0, i), g.X(1, j), g.X(2, k) };
          double c[3];
          vtkdf::reference::ClosestOnTriangle(x, t[0].data(), t[1].data(), t[2].data(), c);
          const double dist = std::sqrt((c[0] - x[0]) * (c[0] - x[0]) +
            (c[1] - x[1]) * (c[1] - x[1]) + (c[2] - x[2]) * (c[2] - x[2]));
          if (dist <= radius)
          {
            double& slot = d[g.Index(i, j, k)];
            slot = std::min(slot, dist);
          }
        }
      }
    }
  }
  return d;
}

/// Inside (odd number of crossings below the centre along +z) for every voxel centre.
inline std::vector<char> Inside(const Grid& g,
  const std::vector<std::array<std::array<double, 3>, 3>>& triangles)
{
  std::vector<char> inside(g.Count(), 0);
  std::vector<std::vector<double>> hits(int64_t(g.Dims[0]) * g.Dims[1]);
  // Nudge the lanes by an irrational fraction of the spacing: no edge or vertex on them.
  const double ex = 1.3e-7 * std::sqrt(2.0) * g.Spacing[0], ey = 0.7e-7 * M_PI * g.Spacing[1];
  for (const auto& t : triangles)
  {
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    for (const auto& p : t)
    {
      xmin = std::min(xmin, p[0]), xmax = std::max(xmax, p[0]);
      ymin = std::min(ymin, p[1]), ymax = std::max(ymax, p[1]);
    }
    const int i0 = std::max(0, static_cast<int>(std::floor((xmin - g.Origin[0]) / g.Spacing[0])));
    const int i1 =
      std::min(g.Dims[0] - 1, static_cast<int>(std::ceil((xmax - g.Origin[0]) / g.Spacing[0])));
    const int j0 = std::max(0, static_cast<int>(std::floor((ymin - g.Origin[1]) / g.Spacing[1])));
    const int j1 =
      std::min(g.Dims[1] - 1, static_cast<int>(std::ceil((ymax - g.Origin[1]) / g.Spacing[1])));
    for (int j = j0; j <= j1; ++j)
    {
      for (int i = i0; i <= i1; ++i)
      {
        const double px = g.X(0, i) + ex, py = g.X(1, j) + ey;
        double w[3];
        for (int k = 0; k < 3; ++k)
        {
          const auto& a = t[(k + 1) % 3];
          const auto& b = t[(k + 2) % 3];
          w[k] = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
        }
        const bool in = (w[0] > 0 && w[1] > 0 && w[2] > 0) || (w[0] < 0 && w[1] < 0 && w[2] < 0);
        if (in)
        {
          const double s = w[0] + w[1] + w[2];
          hits[i + int64_t(g.Dims[0]) * j].push_back(
            (w[0] * t[0][2] + w[1] * t[1][2] + w[2] * t[2][2]) / s);
        }
      }
    }
  }
  for (int j = 0; j < g.Dims[1]; ++j)
  {
    for (int i = 0; i < g.Dims[0]; ++i)
    {
      auto& h = hits[i + int64_t(g.Dims[0]) * j];
      std::sort(h.begin(), h.end());
      size_t below = 0;
      for (int k = 0; k < g.Dims[2]; ++k)
      {
        const double z = g.X(2, k);
        while (below < h.size() && h[below] < z)
        {
          ++below;
        }
        inside[g.Index(i, j, k)] = below % 2;
      }
    }
  }
  return inside;
}

/// Chamfer layers by breadth-first search (metric 0: 6, 1: 18, 2: 26 neighbours).
inline std::vector<int> Layers(const Grid& g,
  const std::vector<char>& zero,
  int metric,
  int maxLayers,
  int unreached)
{
  std::vector<int> d(g.Count(), -1);
  std::deque<int64_t> queue;
  for (int64_t v = 0; v < g.Count(); ++v)
  {
    if (zero[v])
    {
      d[v] = 0;
      queue.push_back(v);
    }
  }
  while (!queue.empty())
  {
    const int64_t v = queue.front();
    queue.pop_front();
    if (maxLayers > 0 && d[v] >= maxLayers)
    {
      continue;
    }
    const int i = static_cast<int>(v % g.Dims[0]),
              j = static_cast<int>((v / g.Dims[0]) % g.Dims[1]);
    const int k = static_cast<int>(v / (int64_t(g.Dims[0]) * g.Dims[1]));
    for (int dz = -1; dz <= 1; ++dz)
    {
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int order = (dx != 0) + (dy != 0) + (dz != 0);
          if (order == 0 || order > metric + 1)
          {
            continue;
          }
          const int a = i + dx, b = j + dy, c = k + dz;
          if (a < 0 || b < 0 || c < 0 || a >= g.Dims[0] || b >= g.Dims[1] || c >= g.Dims[2])
          {
            continue;
          }
          const int64_t o = g.Index(a, b, c);
          if (d[o] < 0)
          {
            d[o] = d[v] + 1;
            queue.push_back(o);
          }
        }
      }
    }
  }
  for (int& v : d)
  {
    v = v < 0 ? unreached : v;
  }
  return d;
}

} // namespace voxelref

#endif
