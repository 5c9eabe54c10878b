#include "Union/UnionClosestPoint.h"

#include "Common/Vector3.h"
#include "Union/PlanarPolygon.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace vtkdf
{
namespace planar
{
Polygon Clip(const Polygon& in, const HalfPlane& h, int id)
{
  Polygon out;
  const size_t n = in.Corners.size();
  for (size_t k = 0; k < n; ++k)
  {
    const V2 a = in.Corners[k], b = in.Corners[(k + 1) % n];
    const double sa = h.A[0] * a.X + h.A[1] * a.Y - h.B;
    const double sb = h.A[0] * b.X + h.A[1] * b.Y - h.B;
    const V2 cut =
      sa == sb ? a : V2{ a.X + (b.X - a.X) * sa / (sa - sb), a.Y + (b.Y - a.Y) * sa / (sa - sb) };
    if (sa <= 0)
    {
      out.Corners.push_back(a);
      out.Source.push_back(in.Source[k]);
      if (sb > 0)
      {
        out.Corners.push_back(cut); // leaving: the next edge runs along the cut
        out.Source.push_back(id);
      }
    }
    else if (sb <= 0)
    {
      out.Corners.push_back(cut); // entering
      out.Source.push_back(in.Source[k]);
    }
  }
  if (out.Corners.size() < 3)
  {
    out.Corners.clear();
    out.Source.clear();
  }
  return out;
}

} // namespace planar

namespace
{
using planar::Clip;
using planar::HalfPlane;
using planar::Polygon;
using planar::V2;
} // namespace

int64_t MergeNearCorners(const std::vector<double>& points,
  std::vector<std::vector<int64_t>>& faces,
  double tolerance)
{
  std::vector<int64_t> used;
  for (const auto& face : faces)
  {
    used.insert(used.end(), face.begin(), face.end());
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  const double* x = points.data();
  std::sort(used.begin(),
    used.end(),
    [x](int64_t a, int64_t b) { return x[3 * a] != x[3 * b] ? x[3 * a] < x[3 * b] : a < b; });
  // Clusters of points within `tolerance` (a sweep along x), each led by its lowest id.
  std::map<int64_t, int64_t> parent;
  std::function<int64_t(int64_t)> find = [&](int64_t id) -> int64_t
  {
    auto it = parent.find(id);
    if (it == parent.end() || it->second == id)
    {
      return id;
    }
    return it->second = find(it->second);
  };
  int64_t merged = 0;
  for (size_t i = 0; i < used.size(); ++i)
  {
    const double* p = x + 3 * used[i];
    for (size_t j = i + 1; j < used.size() && x[3 * used[j]] - p[0] <= tolerance; ++j)
    {
      const double* q = x + 3 * used[j];
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
        (p[2] - q[2]) * (p[2] - q[2]);
      const int64_t a = find(used[i]), b = find(used[j]);
      if (d2 <= tolerance * tolerance && a != b)
      {
        parent[std::max(a, b)] = std::min(a, b);
        ++merged;
      }
    }
  }
  std::vector<std::vector<int64_t>> kept;
  for (const auto& face : faces)
  {
    std::vector<int64_t> corners;
    for (const int64_t id : face)
    {
      const int64_t leader = find(id);
      if (corners.empty() || corners.back() != leader)
      {
        corners.push_back(leader);
      }
    }
    while (corners.size() > 1 && corners.back() == corners.front())
    {
      corners.pop_back();
    }
    std::vector<int64_t> distinct = corners;
    std::sort(distinct.begin(), distinct.end());
    if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() >= 3)
    {
      kept.push_back(std::move(corners));
    }
  }
  faces = std::move(kept);
  return merged;
}

bool ConvexPiece::Build(const std::vector<double>& points,
  const std::vector<std::vector<int64_t>>& faces,
  double tolerance,
  std::string& error)
{
  this->Faces.clear();
  this->Planes.clear();
  double centre[3] = { 0, 0, 0 };
  int64_t count = 0;
  std::map<std::pair<int64_t, int64_t>, int> edges;
  for (const auto& face : faces)
  {
    for (size_t k = 0; k < face.size(); ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        centre[a] += points[3 * face[k] + a];
      }
      ++count;
      const int64_t x = face[k], y = face[(k + 1) % face.size()];
      ++edges[{ std::min(x, y), std::max(x, y) }];
    }
  }
  // Open first (the more telling answer when a piece is both), then too few faces.
  for (const auto& e : edges)
  {
    if (e.second != 2)
    {
      error = "open or non-manifold: edge " + std::to_string(e.first.first) + "-" +
        std::to_string(e.first.second) + " is used by " + std::to_string(e.second) + " faces";
      return false;
    }
  }
  if (faces.size() < 4 || count == 0)
  {
    error = "fewer than 4 faces";
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    centre[a] /= count;
    this->Lo[a] = HUGE_VAL;
    this->Hi[a] = -HUGE_VAL;
  }
  for (const auto& face : faces)
  {
    // Newell's normal, then outward (away from the corners' centre).
    double n[3] = { 0, 0, 0 }, mid[3] = { 0, 0, 0 };
    for (size_t k = 0; k < face.size(); ++k)
    {
      const double* p = &points[3 * face[k]];
      const double* q = &points[3 * face[(k + 1) % face.size()]];
      n[0] += (p[1] - q[1]) * (p[2] + q[2]);
      n[1] += (p[2] - q[2]) * (p[0] + q[0]);
      n[2] += (p[0] - q[0]) * (p[1] + q[1]);
      for (int a = 0; a < 3; ++a)
      {
        mid[a] += p[a] / face.size();
      }
    }
    const double length = std::sqrt(Dot(n, n));
    if (!(length > 0))
    {
      error = "a face has no area";
      return false;
    }
    const double out[3] = { mid[0] - centre[0], mid[1] - centre[1], mid[2] - centre[2] };
    const double sign = Dot(n, out) < 0 ? -1 : 1;
    std::vector<double> corners;
    for (size_t k = 0; k < face.size(); ++k)
    {
      const int64_t id = sign > 0 ? face[k] : face[face.size() - 1 - k];
      corners.insert(corners.end(), &points[3 * id], &points[3 * id] + 3);
      for (int a = 0; a < 3; ++a)
      {
        this->Lo[a] = std::min(this->Lo[a], points[3 * id + a]);
        this->Hi[a] = std::max(this->Hi[a], points[3 * id + a]);
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      n[a] *= sign / length;
    }
    this->Planes.insert(this->Planes.end(), { n[0], n[1], n[2], Dot(n, mid) });
    this->Faces.push_back(corners);
  }
  // Convex: every corner on the inner side of every face's plane; not flat.
  bool deep = false;
  for (size_t f = 0; f < this->Faces.size(); ++f)
  {
    const double* plane = &this->Planes[4 * f];
    for (const auto& face : this->Faces)
    {
      for (size_t k = 0; k < face.size(); k += 3)
      {
        const double s = Dot(plane, &face[k]) - plane[3];
        if (s > tolerance)
        {
          char text[160];
          std::snprintf(text,
            sizeof(text),
            "not convex: a corner lies %.3g outside a face's plane (tolerance %.3g)",
            s,
            tolerance);
          error = text;
          return false;
        }
        deep = deep || s < -tolerance;
      }
    }
  }
  if (!deep)
  {
    error = "flat: every corner lies in every face's plane";
    return false;
  }
  const std::vector<double> corners = this->Corners();
  for (int a = 0; a < 3; ++a)
  {
    this->Centre[a] = 0;
    for (size_t k = a; k < corners.size(); k += 3)
    {
      this->Centre[a] += corners[k] / (corners.size() / 3);
    }
  }
  this->InnerRadius = HUGE_VAL;
  for (size_t f = 0; f < this->Faces.size(); ++f)
  {
    this->InnerRadius = std::min(
      this->InnerRadius, this->Planes[4 * f + 3] - Dot(&this->Planes[4 * f], this->Centre));
  }
  this->InnerRadius = std::max(0.0, this->InnerRadius);
  return true;
}

std::vector<double> ConvexPiece::Corners() const
{
  std::vector<std::array<double, 3>> corners;
  for (const auto& face : this->Faces)
  {
    for (size_t k = 0; k < face.size(); k += 3)
    {
      corners.push_back({ face[k], face[k + 1], face[k + 2] });
    }
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  std::vector<double> xyz;
  for (const auto& c : corners)
  {
    xyz.insert(xyz.end(), c.begin(), c.end());
  }
  return xyz;
}

} // namespace vtkdf
