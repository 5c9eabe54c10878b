#include "Segment/SelfIntersections.h"

#include "Predicates/ExactPredicates.h"
#include "Segment/TriangleCrossings.h"
#ifdef DF_HAVE_CGAL
#include "Segment/CrossingRefinement.h"

#include <exception>
#endif

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>

namespace vtkdf
{
namespace
{
Point3 At(const LargeVector<double>& points, int64_t id)
{
  return { { points[3 * id], points[3 * id + 1], points[3 * id + 2] } };
}

size_t Root(std::vector<size_t>& parent, size_t i)
{
  while (parent[i] != i)
  {
    i = parent[i] = parent[parent[i]];
  }
  return i;
}

/// The triangles as the crossing search and the refinement take them: one point per position (the
/// used points sorted by position), the triangles with area, each once (their sorted id triples
/// sorted, the first of each kept; a repeat is passed through uncut).
struct Soup
{
  std::vector<Point3> Points;
  std::vector<TriangleCorners> Polygons;
  std::vector<int64_t> PolygonTriangle; // each polygon's input triangle

  Soup(const LargeVector<double>& points, const LargeVector<int64_t>& triangles)
  {
    const int64_t triangleCount = static_cast<int64_t>(triangles.size() / 3);
    const int64_t pointCount = static_cast<int64_t>(points.size() / 3);
    std::vector<int64_t> used;
    std::vector<uint8_t> isUsed(pointCount, 0);
    for (const int64_t id : triangles)
    {
      isUsed[id] = 1;
    }
    for (int64_t p = 0; p < pointCount; ++p)
    {
      if (isUsed[p])
      {
        used.push_back(p);
      }
    }
    std::sort(used.begin(),
      used.end(),
      [&](int64_t a, int64_t b)
      {
        const Point3 pa = At(points, a), pb = At(points, b);
        return pa != pb ? pa < pb : a < b;
      });
    std::vector<size_t> soupId(pointCount, 0);
    for (size_t i = 0; i < used.size(); ++i)
    {
      const Point3 p = At(points, used[i]);
      if (i == 0 || p != At(points, used[i - 1]))
      {
        this->Points.push_back(p);
      }
      soupId[used[i]] = this->Points.size() - 1;
    }
    std::vector<std::pair<TriangleCorners, int64_t>> candidates;
    for (int64_t t = 0; t < triangleCount; ++t)
    {
      TriangleCorners sorted = {
        soupId[triangles[3 * t]], soupId[triangles[3 * t + 1]], soupId[triangles[3 * t + 2]]
      };
      std::sort(sorted.begin(), sorted.end());
      if (sorted[0] != sorted[1] && sorted[1] != sorted[2] &&
        !Collinear(this->Points[sorted[0]].data(),
          this->Points[sorted[1]].data(),
          this->Points[sorted[2]].data()))
      {
        candidates.emplace_back(sorted, t);
      }
    }
    std::sort(candidates.begin(), candidates.end());
    std::vector<uint8_t> isPolygon(triangleCount, 0);
    for (size_t i = 0; i < candidates.size(); ++i)
    {
      if (i == 0 || candidates[i].first != candidates[i - 1].first)
      {
        isPolygon[candidates[i].second] = 1;
      }
    }
    for (int64_t t = 0; t < triangleCount; ++t)
    {
      if (isPolygon[t])
      {
        this->Polygons.push_back(
          { soupId[triangles[3 * t]], soupId[triangles[3 * t + 1]], soupId[triangles[3 * t + 2]] });
        this->PolygonTriangle.push_back(t);
      }
    }
  }
};

/// The groups of crossing polygons: the crossing pairs are polygons whose boxes meet,
/// that share no point and that intersect (exact predicates); a group holds the polygons
/// joined by crossings and shared points, keyed by its least polygon. Each group is
/// refined on its own, so that non-manifold edges elsewhere, which CGAL's halfedge mesh
/// would have to duplicate and its refinement then trips over, do not matter, and a
/// group CGAL refuses leaves the others cut.
std::map<size_t, std::vector<size_t>> FindCrossingGroups(const Soup& soup)
{
  const std::vector<TriangleCorners>& polygons = soup.Polygons;
  const std::vector<Point3>& points = soup.Points;
  std::vector<uint8_t> crossing(polygons.size(), 0);
  std::vector<size_t> group(polygons.size());
  std::iota(group.begin(), group.end(), size_t(0));
  ForEachOverlappingPair(points,
    polygons,
    [&](size_t a, size_t b)
    {
      const TriangleCorners& p = polygons[a];
      const TriangleCorners& q = polygons[b];
      for (const size_t u : p)
      {
        if (u == q[0] || u == q[1] || u == q[2])
        {
          return; // neighbours: they meet where they share
        }
      }
      const Point3 pc[3] = { points[p[0]], points[p[1]], points[p[2]] };
      const Point3 qc[3] = { points[q[0]], points[q[1]], points[q[2]] };
      if (TrianglesIntersect(pc, qc))
      {
        crossing[a] = crossing[b] = 1;
        group[Root(group, a)] = Root(group, b);
      }
    });
  std::map<size_t, size_t> firstAt; // point -> a crossing triangle that uses it
  for (size_t i = 0; i < polygons.size(); ++i)
  {
    for (const size_t u : polygons[i])
    {
      if (crossing[i])
      {
        const auto found = firstAt.emplace(u, i);
        group[Root(group, i)] = Root(group, found.first->second);
      }
    }
  }
  std::map<size_t, std::vector<size_t>> byRoot;
  for (size_t i = 0; i < polygons.size(); ++i)
  {
    if (crossing[i])
    {
      byRoot[Root(group, i)].push_back(i);
    }
  }
  std::map<size_t, std::vector<size_t>> groups;
  for (auto& g : byRoot)
  {
    groups[g.second.front()] = std::move(g.second);
  }
  return groups;
}

#ifdef DF_HAVE_CGAL
/// Refines every group into `out` (in the groups' order); a group CGAL refuses is
/// counted and left uncut. `refined` marks the input triangles of the groups that were
/// refined, `wasCut` those the refinement cut.
void RefineGroups(const Soup& soup,
  const std::map<size_t, std::vector<size_t>>& groups,
  std::vector<uint8_t>& wasCut,
  std::vector<uint8_t>& refined,
  SelfIntersectionCut& out)
{
  out.CrossingGroups = static_cast<int64_t>(groups.size());
  for (const auto& g : groups)
  {
    std::vector<TriangleCorners> members;
    std::vector<int64_t> memberTriangle;
    for (const size_t i : g.second)
    {
      members.push_back(soup.Polygons[i]);
      memberTriangle.push_back(soup.PolygonTriangle[i]);
    }
    const size_t pointsBefore = out.Points.size(), trianglesBefore = out.Triangles.size();
    try
    {
      RefineCrossingGroup(soup.Points, members, memberTriangle, wasCut, out);
    }
    catch (const std::exception& e)
    {
      for (const int64_t t : memberTriangle)
      {
        wasCut[t] = 0; // the visitor may have marked some before CGAL gave up
      }
      out.Points.resize(pointsBefore);
      out.Triangles.resize(trianglesBefore);
      out.Parent.resize(trianglesBefore / 3);
      ++out.FailedGroups;
      out.FailedTriangles += static_cast<int64_t>(members.size());
      if (out.FailedMessage.empty())
      {
        // CGAL's messages run over several lines: one line here.
        out.FailedMessage = std::string("CGAL: ") + e.what();
        std::replace(out.FailedMessage.begin(), out.FailedMessage.end(), '\n', ' ');
      }
      continue;
    }
    for (const int64_t t : memberTriangle)
    {
      refined[t] = 1;
    }
  }
}
#endif

#ifndef DF_HAVE_CGAL
/// Without CGAL every group is counted and left uncut, with the build as the reason.
void LeaveGroupsUncut(const std::map<size_t, std::vector<size_t>>& groups, SelfIntersectionCut& out)
{
  out.CrossingGroups = static_cast<int64_t>(groups.size());
  for (const auto& g : groups)
  {
    ++out.FailedGroups;
    out.FailedTriangles += static_cast<int64_t>(g.second.size());
  }
  if (out.FailedGroups > 0)
  {
    out.FailedMessage = "this build has no refinement: it was configured with "
                        "-DDF_USE_CGAL=OFF, without CGAL's GPL-licensed Polygon Mesh Processing";
  }
}
#endif

#ifdef DF_HAVE_CGAL
/// The output in a canonical order, so that it depends on the geometry alone (CGAL's
/// refinement orders its faces by what it met first, which varies from run to run, and
/// the patches' and regions' numbers follow the triangles' order): every triangle in its
/// input triangle's place; the pieces of a cut one sorted by their corners (each rotated
/// to start at its least corner, orientation kept), with three new points each after the
/// input's points, which the others keep.
void CanonicalOrder(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  const std::vector<uint8_t>& refined,
  SelfIntersectionCut& out)
{
  struct Piece
  {
    int64_t Parent;
    std::array<Point3, 3> Corners;
    bool operator<(const Piece& other) const
    {
      return this->Parent != other.Parent ? this->Parent < other.Parent
                                          : this->Corners < other.Corners;
    }
  };
  std::vector<Piece> pieces(out.Parent.size());
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    Piece& piece = pieces[i];
    piece.Parent = out.Parent[i];
    for (int k = 0; k < 3; ++k)
    {
      piece.Corners[k] = At(out.Points, out.Triangles[3 * i + k]);
    }
    const auto least = std::min_element(piece.Corners.begin(), piece.Corners.end());
    std::rotate(piece.Corners.begin(), least, piece.Corners.end());
  }
  std::sort(pieces.begin(), pieces.end());
  out.Points = points;
  out.Triangles.clear();
  out.Parent.clear();
  auto next = pieces.begin();
  const int64_t triangleCount = static_cast<int64_t>(triangles.size() / 3);
  for (int64_t t = 0; t < triangleCount; ++t)
  {
    if (!refined[t])
    {
      out.Triangles.insert(out.Triangles.end(), &triangles[3 * t], &triangles[3 * t] + 3);
      out.Parent.push_back(t);
      continue;
    }
    for (; next != pieces.end() && next->Parent == t; ++next)
    {
      for (const Point3& corner : next->Corners)
      {
        out.Triangles.push_back(static_cast<int64_t>(out.Points.size() / 3));
        out.Points.insert(out.Points.end(), corner.begin(), corner.end());
      }
      out.Parent.push_back(t);
    }
  }
}
#endif
} // namespace

void CutSelfIntersections(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  SelfIntersectionCut& out)
{
  out = SelfIntersectionCut();
  const Soup soup(points, triangles);
  const std::map<size_t, std::vector<size_t>> groups = FindCrossingGroups(soup);
#ifdef DF_HAVE_CGAL
  const size_t triangleCount = triangles.size() / 3;
  std::vector<uint8_t> wasCut(triangleCount, 0), refined(triangleCount, 0);
  RefineGroups(soup, groups, wasCut, refined, out);
  for (const uint8_t c : wasCut)
  {
    out.CutTriangles += c;
  }
  if (!out.Cut())
  {
    out.Points.clear();
    out.Triangles.clear();
    out.Parent.clear();
    return;
  }
  CanonicalOrder(points, triangles, refined, out);
#else
  LeaveGroupsUncut(groups, out);
#endif
}

} // namespace vtkdf
