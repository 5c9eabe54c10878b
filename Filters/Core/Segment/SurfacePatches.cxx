#include "Segment/SurfacePatches.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace vtkdf
{

void SurfacePatches::Build(const LargeVector<double>& points, const LargeVector<int64_t>& triangles)
{
  this->Points = &points;
  this->Ids = triangles;
  this->MergePositions();
  const std::vector<uint8_t> valid = this->TrianglesWithArea();
  this->IndexCorners(valid);
  this->Orient(valid, this->Links(valid));
}

/// Merged ids: the used points sorted by position, each group keyed by its lowest id.
void SurfacePatches::MergePositions()
{
  const LargeVector<double>& points = *this->Points;
  const int64_t pointCount = static_cast<int64_t>(points.size() / 3);
  this->Keys.resize(pointCount);
  std::vector<uint8_t> used(pointCount, 0);
  for (const int64_t id : this->Ids)
  {
    used[id] = 1;
  }
  std::vector<int64_t> order;
  for (int64_t p = 0; p < pointCount; ++p)
  {
    this->Keys[p] = p;
    if (used[p])
    {
      order.push_back(p);
    }
  }
  auto position = [&](int64_t p) {
    return std::array<double, 3>{ { points[3 * p], points[3 * p + 1], points[3 * p + 2] } };
  };
  std::sort(order.begin(),
    order.end(),
    [&](int64_t a, int64_t b)
    {
      const auto pa = position(a), pb = position(b);
      return pa != pb ? pa < pb : a < b;
    });
  for (size_t i = 1; i < order.size(); ++i)
  {
    if (position(order[i]) == position(order[i - 1]))
    {
      this->Keys[order[i]] = this->Keys[order[i - 1]]; // the group's first, its lowest id
    }
  }
}

/// Per triangle: whether it has three distinct points and an area.
std::vector<uint8_t> SurfacePatches::TrianglesWithArea() const
{
  const int64_t triangleCount = static_cast<int64_t>(this->Ids.size() / 3);
  std::vector<uint8_t> valid(triangleCount, 0);
  for (int64_t t = 0; t < triangleCount; ++t)
  {
    const int64_t a = this->Key(t, 0), b = this->Key(t, 1), c = this->Key(t, 2);
    if (a == b || b == c || a == c)
    {
      continue;
    }
    const double* p = this->Corner(t, 0);
    const double* q = this->Corner(t, 1);
    const double* r = this->Corner(t, 2);
    const double e[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
    const double f[3] = { r[0] - p[0], r[1] - p[1], r[2] - p[2] };
    const double n[3] = {
      e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]
    };
    valid[t] = n[0] != 0 || n[1] != 0 || n[2] != 0;
  }
  return valid;
}

/// The valid triangles' corners per merged point, in triangle order.
void SurfacePatches::IndexCorners(const std::vector<uint8_t>& valid)
{
  const int64_t pointCount = static_cast<int64_t>(this->Keys.size());
  const int64_t triangleCount = static_cast<int64_t>(valid.size());
  this->CornerStart.assign(pointCount + 1, 0);
  for (int64_t t = 0; t < triangleCount; ++t)
  {
    for (int k = 0; k < 3 && valid[t]; ++k)
    {
      ++this->CornerStart[this->Key(t, k) + 1];
    }
  }
  for (int64_t p = 0; p < pointCount; ++p)
  {
    this->CornerStart[p + 1] += this->CornerStart[p];
  }
  this->CornerTriangles.resize(this->CornerStart.back());
  std::vector<int64_t> fill(this->CornerStart.begin(), this->CornerStart.end() - 1);
  for (int64_t t = 0; t < triangleCount; ++t)
  {
    for (int k = 0; k < 3 && valid[t]; ++k)
    {
      this->CornerTriangles[fill[this->Key(t, k)]++] = t;
    }
  }
}

/// Manifold edges (exactly two uses) link two triangles; `Same` when both run the same
/// way, so that one of them must be flipped for the patch to be oriented.
std::vector<SurfacePatches::Link> SurfacePatches::Links(const std::vector<uint8_t>& valid) const
{
  // Edges: (lower key, higher key, triangle, whether the triangle runs low -> high).
  struct EdgeUse
  {
    int64_t Low, High, Triangle;
    bool Forward;
  };
  const int64_t triangleCount = static_cast<int64_t>(valid.size());
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangleCount);
  for (int64_t t = 0; t < triangleCount; ++t)
  {
    for (int k = 0; k < 3 && valid[t]; ++k)
    {
      const int64_t a = this->Key(t, k), b = this->Key(t, (k + 1) % 3);
      uses.push_back(EdgeUse{ std::min(a, b), std::max(a, b), t, a < b });
    }
  }
  std::sort(uses.begin(),
    uses.end(),
    [](const EdgeUse& x, const EdgeUse& y)
    {
      return x.Low != y.Low ? x.Low < y.Low
                            : (x.High != y.High ? x.High < y.High : x.Triangle < y.Triangle);
    });
  std::vector<Link> links;
  for (size_t i = 0; i < uses.size();)
  {
    size_t j = i;
    while (j < uses.size() && uses[j].Low == uses[i].Low && uses[j].High == uses[i].High)
    {
      ++j;
    }
    if (j - i == 2 && uses[i].Triangle != uses[i + 1].Triangle)
    {
      links.push_back(
        Link{ uses[i].Triangle, uses[i + 1].Triangle, uses[i].Forward == uses[i + 1].Forward });
    }
    i = j;
  }
  return links;
}

/// Patches: breadth-first from the lowest unvisited triangle. A link whose two triangles'
/// orientations disagree once both are set is cut, and the search runs again until no
/// link disagrees (each run cuts at least one more, so it ends).
void SurfacePatches::Orient(const std::vector<uint8_t>& valid, const std::vector<Link>& links)
{
  const int64_t triangleCount = static_cast<int64_t>(valid.size());
  std::vector<int64_t> linkStart(triangleCount + 1, 0), linkOf;
  for (const Link& l : links)
  {
    ++linkStart[l.A + 1];
    ++linkStart[l.B + 1];
  }
  for (int64_t t = 0; t < triangleCount; ++t)
  {
    linkStart[t + 1] += linkStart[t];
  }
  linkOf.resize(linkStart.back());
  std::vector<int64_t> fill(linkStart.begin(), linkStart.end() - 1);
  for (size_t l = 0; l < links.size(); ++l)
  {
    linkOf[fill[links[l].A]++] = static_cast<int64_t>(l);
    linkOf[fill[links[l].B]++] = static_cast<int64_t>(l);
  }
  this->Patch.assign(triangleCount, -1);
  this->Flipped.assign(triangleCount, 0);
  std::vector<uint8_t> cut(links.size(), 0);
  for (;;)
  {
    std::fill(this->Patch.begin(), this->Patch.end(), -1);
    std::fill(this->Flipped.begin(), this->Flipped.end(), 0);
    this->PatchCount = 0;
    bool disagreed = false;
    std::vector<int64_t> queue;
    for (int64_t seed = 0; seed < triangleCount; ++seed)
    {
      if (!valid[seed] || this->Patch[seed] >= 0)
      {
        continue;
      }
      this->Patch[seed] = this->PatchCount;
      queue.assign(1, seed);
      for (size_t head = 0; head < queue.size(); ++head)
      {
        const int64_t t = queue[head];
        for (int64_t e = linkStart[t]; e < linkStart[t + 1]; ++e)
        {
          const int64_t l = linkOf[e];
          if (cut[l])
          {
            continue;
          }
          const int64_t other = links[l].A == t ? links[l].B : links[l].A;
          const uint8_t wanted = this->Flipped[t] ^ (links[l].Same ? 1 : 0);
          if (this->Patch[other] < 0)
          {
            this->Patch[other] = this->PatchCount;
            this->Flipped[other] = wanted;
            queue.push_back(other);
          }
          else if (this->Flipped[other] != wanted)
          {
            cut[l] = 1;
            disagreed = true;
          }
        }
      }
      ++this->PatchCount;
    }
    if (!disagreed)
    {
      break;
    }
  }
  this->CutEdges = std::count(cut.begin(), cut.end(), 1);
}

void SurfacePatches::Normal(int64_t t, double n[3]) const
{
  const double* p = this->Corner(t, 0);
  const double* q = this->Corner(t, 1);
  const double* r = this->Corner(t, 2);
  const double e[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
  const double f[3] = { r[0] - p[0], r[1] - p[1], r[2] - p[2] };
  n[0] = e[1] * f[2] - e[2] * f[1];
  n[1] = e[2] * f[0] - e[0] * f[2];
  n[2] = e[0] * f[1] - e[1] * f[0];
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double scale = (this->Flipped[t] ? -1 : 1) / (length > 0 ? length : 1);
  for (int a = 0; a < 3; ++a)
  {
    n[a] *= scale;
  }
}

bool SurfacePatches::Flatten(std::vector<int32_t>& triangles, std::vector<int32_t>& corners) const
{
  const int64_t count = static_cast<int64_t>(this->Patch.size());
  const int64_t keys = static_cast<int64_t>(this->CornerStart.size());
  if (count > INT32_MAX / 5 ||
    keys + static_cast<int64_t>(this->CornerTriangles.size()) > INT32_MAX)
  {
    return false;
  }
  triangles.resize(5 * count);
  for (int64_t t = 0; t < count; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      triangles[5 * t + k] = static_cast<int32_t>(this->Key(t, k));
    }
    triangles[5 * t + 3] = static_cast<int32_t>(this->Patch[t]);
    triangles[5 * t + 4] = this->Flipped[t];
  }
  corners.assign(this->CornerStart.begin(), this->CornerStart.end());
  corners.insert(corners.end(), this->CornerTriangles.begin(), this->CornerTriangles.end());
  return true;
}

void SurfacePatches::TrianglesAtPoint(int64_t p, std::vector<int64_t>& out) const
{
  const int64_t key = this->Keys[p];
  out.assign(this->CornerTriangles.begin() + this->CornerStart[key],
    this->CornerTriangles.begin() + this->CornerStart[key + 1]);
}

void SurfacePatches::TrianglesAtEdge(int64_t a, int64_t b, std::vector<int64_t>& out) const
{
  const int64_t ka = this->Keys[a], kb = this->Keys[b];
  out.clear();
  std::set_intersection(this->CornerTriangles.begin() + this->CornerStart[ka],
    this->CornerTriangles.begin() + this->CornerStart[ka + 1],
    this->CornerTriangles.begin() + this->CornerStart[kb],
    this->CornerTriangles.begin() + this->CornerStart[kb + 1],
    std::back_inserter(out));
}

} // namespace vtkdf
