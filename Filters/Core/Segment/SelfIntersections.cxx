// CGAL's checks stay on in release builds: a mesh it cannot refine then throws (and is
// reported) instead of running on unchecked.
#define CGAL_DEBUG 1

#include "Segment/SelfIntersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <map>
#include <numeric>
#include <stdexcept>

namespace vtkdf
{
namespace
{
namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Face = Mesh::Face_index;
using ParentMap = Mesh::Property_map<Face, int64_t>;
using Triple = std::array<size_t, 3>;

// Gives each face the refinement creates the input triangle of the face it splits, and
// marks that triangle as cut.
struct ParentVisitor : PMP::Corefinement::Default_visitor<Mesh>
{
  ParentMap Parent;
  std::vector<uint8_t>* WasCut = nullptr;
  int64_t Current = -1;

  void before_subface_creations(Face split, Mesh&)
  {
    this->Current = this->Parent[split];
    (*this->WasCut)[this->Current] = 1;
  }
  void after_subface_created(Face created, Mesh&) { this->Parent[created] = this->Current; }
};

using Position = std::array<double, 3>;

Position At(const std::vector<double>& points, int64_t id)
{
  return { { points[3 * id], points[3 * id + 1], points[3 * id + 2] } };
}

// While it lives, CGAL's failed checks only throw (the message is the exception's, which
// the caller reports once) instead of also printing to stderr.
class QuietCGAL
{
public:
  QuietCGAL()
    : Error(CGAL::set_error_handler(&QuietCGAL::Ignore))
    , Warning(CGAL::set_warning_handler(&QuietCGAL::Ignore))
  {
  }
  ~QuietCGAL()
  {
    CGAL::set_error_handler(this->Error);
    CGAL::set_warning_handler(this->Warning);
  }
  QuietCGAL(const QuietCGAL&) = delete;
  QuietCGAL& operator=(const QuietCGAL&) = delete;

private:
  static void Ignore(const char*, const char*, const char*, int, const char*) {}
  CGAL::Failure_function Error, Warning;
};

size_t Root(std::vector<size_t>& parent, size_t i)
{
  while (parent[i] != i)
  {
    i = parent[i] = parent[parent[i]];
  }
  return i;
}

// Refines one group of crossing triangles (`polygons`, ids into `points`; `triangle`:
// each one's input triangle) and appends the result to `out`. Throws what CGAL throws.
void RefineGroup(const std::vector<Point>& points,
  const std::vector<Triple>& polygons,
  const std::vector<int64_t>& triangle,
  std::vector<uint8_t>& wasCut,
  SelfIntersectionCut& out)
{
  // Only the group's points, so that the mesh has no isolated vertex.
  std::vector<Point> soupPoints;
  std::map<size_t, size_t> newId;
  std::vector<Triple> oriented;
  for (const Triple& q : polygons)
  {
    Triple ids;
    for (int k = 0; k < 3; ++k)
    {
      const auto found = newId.emplace(q[k], soupPoints.size());
      if (found.second)
      {
        soupPoints.push_back(points[q[k]]);
      }
      ids[k] = found.first->second;
    }
    oriented.push_back(ids);
  }
  const std::vector<Triple> given = oriented;
  // orient_polygon_soup may reverse polygons and duplicate (non-manifold) points; a
  // reversed polygon's faces are reversed back on the way out.
  PMP::orient_polygon_soup(soupPoints, oriented);
  std::vector<uint8_t> reversed(polygons.size(), 0);
  for (size_t i = 0; i < given.size(); ++i)
  {
    // The same cyclic order of positions (a triangle's three are distinct), or reversed.
    int k = 0;
    while (k < 3 && soupPoints[oriented[i][k]] != soupPoints[given[i][0]])
    {
      ++k;
    }
    if (k == 3)
    {
      throw std::runtime_error("orienting the triangles changed a triangle's corners");
    }
    reversed[i] = soupPoints[oriented[i][(k + 1) % 3]] != soupPoints[given[i][1]];
  }
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(soupPoints, oriented, mesh);
  if (mesh.number_of_faces() != oriented.size())
  {
    throw std::runtime_error("the triangles do not make a mesh");
  }
  ParentMap parent = mesh.add_property_map<Face, int64_t>("f:vtkdf_parent", -1).first;
  auto flip = mesh.add_property_map<Face, uint8_t>("f:vtkdf_flip", 0).first;
  size_t i = 0;
  for (const Face f : mesh.faces()) // added in the polygons' order
  {
    parent[f] = triangle[i];
    flip[f] = reversed[i++];
  }
  std::map<int64_t, uint8_t> flipOf;
  for (const Face f : mesh.faces())
  {
    flipOf[parent[f]] = flip[f];
  }

  ParentVisitor visitor;
  visitor.Parent = parent;
  visitor.WasCut = &wasCut;
  PMP::experimental::autorefine(mesh, PMP::parameters::visitor(visitor));

  // Read back the refined mesh's points and faces.
  std::map<Mesh::Vertex_index, int64_t> vertexId;
  for (const auto v : mesh.vertices())
  {
    vertexId[v] = static_cast<int64_t>(out.Points.size() / 3);
    const Point& p = mesh.point(v);
    out.Points.insert(out.Points.end(), { p.x(), p.y(), p.z() });
  }
  for (const Face f : mesh.faces())
  {
    std::array<int64_t, 3> ids;
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
    {
      if (k == 3)
      {
        throw std::runtime_error("the refinement made a face that is not a triangle");
      }
      ids[k++] = vertexId[v];
    }
    const int64_t t = parent[f];
    if (k != 3 || t < 0)
    {
      throw std::runtime_error("the refinement made a face without a parent triangle");
    }
    if (flipOf[t])
    {
      std::swap(ids[1], ids[2]);
    }
    out.Triangles.insert(out.Triangles.end(), ids.begin(), ids.end());
    out.Parent.push_back(t);
  }
}

/// The triangles as CGAL takes them: one point per position (the used points sorted by
/// position), the triangles with area, each once (their sorted id triples sorted, the
/// first of each kept; a repeat is passed through uncut).
struct Soup
{
  std::vector<Point> Points;
  std::vector<Triple> Polygons;
  std::vector<int64_t> PolygonTriangle; // each polygon's input triangle

  Soup(const std::vector<double>& points, const std::vector<int64_t>& triangles)
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
        const Position pa = At(points, a), pb = At(points, b);
        return pa != pb ? pa < pb : a < b;
      });
    std::vector<size_t> soupId(pointCount, 0);
    for (size_t i = 0; i < used.size(); ++i)
    {
      const Position p = At(points, used[i]);
      if (i == 0 || p != At(points, used[i - 1]))
      {
        this->Points.emplace_back(p[0], p[1], p[2]);
      }
      soupId[used[i]] = this->Points.size() - 1;
    }
    std::vector<std::pair<Triple, int64_t>> candidates;
    for (int64_t t = 0; t < triangleCount; ++t)
    {
      Triple sorted = {
        soupId[triangles[3 * t]], soupId[triangles[3 * t + 1]], soupId[triangles[3 * t + 2]]
      };
      std::sort(sorted.begin(), sorted.end());
      if (sorted[0] != sorted[1] && sorted[1] != sorted[2] &&
        !CGAL::collinear(this->Points[sorted[0]], this->Points[sorted[1]], this->Points[sorted[2]]))
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
/// that share no point and that intersect (an exact predicate); a group holds the
/// polygons joined by crossings and shared points. Each group is refined on its own, so
/// that non-manifold edges elsewhere, which CGAL's halfedge mesh would have to duplicate
/// and its refinement then trips over, do not matter, and a group CGAL refuses leaves the
/// others cut. False and `error` when the search fails.
bool FindCrossingGroups(const Soup& soup,
  std::map<size_t, std::vector<size_t>>& groups,
  std::string& error)
{
  const std::vector<Triple>& polygons = soup.Polygons;
  const std::vector<Point>& points = soup.Points;
  using Box = CGAL::Box_intersection_d::
    Box_with_info_d<double, 3, size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<Box> boxes;
  boxes.reserve(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i)
  {
    const Triple& q = polygons[i];
    boxes.emplace_back(points[q[0]].bbox() + points[q[1]].bbox() + points[q[2]].bbox(), i);
  }
  std::vector<uint8_t> crossing(polygons.size(), 0);
  std::vector<size_t> group(polygons.size());
  std::iota(group.begin(), group.end(), size_t(0));
  auto test = [&](const Box& a, const Box& b)
  {
    const Triple& p = polygons[a.info()];
    const Triple& q = polygons[b.info()];
    for (const size_t u : p)
    {
      if (u == q[0] || u == q[1] || u == q[2])
      {
        return; // neighbours: they meet where they share
      }
    }
    if (CGAL::do_intersect(Kernel::Triangle_3(points[p[0]], points[p[1]], points[p[2]]),
          Kernel::Triangle_3(points[q[0]], points[q[1]], points[q[2]])))
    {
      crossing[a.info()] = crossing[b.info()] = 1;
      group[Root(group, a.info())] = Root(group, b.info());
    }
  };
  try
  {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), test);
  }
  catch (const std::exception& e)
  {
    error = std::string("finding the crossings failed: ") + e.what();
    return false;
  }
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
  for (size_t i = 0; i < polygons.size(); ++i)
  {
    if (crossing[i])
    {
      groups[Root(group, i)].push_back(i);
    }
  }
  return true;
}

/// Refines every group into `out` (in CGAL's order); a group CGAL refuses is counted
/// and left uncut. `refined` marks the input triangles of the groups that were refined,
/// `wasCut` those the refinement cut.
void RefineGroups(const Soup& soup,
  const std::map<size_t, std::vector<size_t>>& groups,
  std::vector<uint8_t>& wasCut,
  std::vector<uint8_t>& refined,
  SelfIntersectionCut& out)
{
  for (const auto& g : groups)
  {
    std::vector<Triple> members;
    std::vector<int64_t> memberTriangle;
    for (const size_t i : g.second)
    {
      members.push_back(soup.Polygons[i]);
      memberTriangle.push_back(soup.PolygonTriangle[i]);
    }
    const size_t pointsBefore = out.Points.size(), trianglesBefore = out.Triangles.size();
    try
    {
      RefineGroup(soup.Points, members, memberTriangle, wasCut, out);
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
        out.FailedMessage = e.what();
        std::replace(out.FailedMessage.begin(), out.FailedMessage.end(), '\n', ' ');
      }
      continue;
    }
    for (const int64_t t : memberTriangle)
    {
      refined[t] = 1;
    }
  }
  out.CrossingGroups = static_cast<int64_t>(groups.size());
}

/// The output in a canonical order, so that it depends on the geometry alone (CGAL's
/// refinement orders its faces by what it met first, which varies from run to run, and
/// the patches' and regions' numbers follow the triangles' order): every triangle in its
/// input triangle's place; the pieces of a cut one sorted by their corners (each rotated
/// to start at its least corner, orientation kept), with three new points each after the
/// input's points, which the others keep.
void CanonicalOrder(const std::vector<double>& points,
  const std::vector<int64_t>& triangles,
  const std::vector<uint8_t>& refined,
  SelfIntersectionCut& out)
{
  struct Piece
  {
    int64_t Parent;
    std::array<Position, 3> Corners;
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
      for (const Position& corner : next->Corners)
      {
        out.Triangles.push_back(static_cast<int64_t>(out.Points.size() / 3));
        out.Points.insert(out.Points.end(), corner.begin(), corner.end());
      }
      out.Parent.push_back(t);
    }
  }
}
} // namespace

bool CutSelfIntersections(const std::vector<double>& points,
  const std::vector<int64_t>& triangles,
  SelfIntersectionCut& out,
  std::string& error)
{
  out = SelfIntersectionCut();
  error.clear();
  const QuietCGAL quiet;
  const Soup soup(points, triangles);
  std::map<size_t, std::vector<size_t>> groups;
  if (!FindCrossingGroups(soup, groups, error))
  {
    return false;
  }
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
    return true;
  }
  CanonicalOrder(points, triangles, refined, out);
  return true;
}

} // namespace vtkdf
