// CGAL's checks stay on in release builds: a mesh it cannot refine then throws (and is
// reported) instead of running on unchecked.
#define CGAL_DEBUG 1

#include "Segment/CrossingRefinement.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <map>
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

} // namespace

void RefineCrossingGroup(const std::vector<Point3>& points,
  const std::vector<TriangleCorners>& polygons,
  const std::vector<int64_t>& triangle,
  std::vector<uint8_t>& wasCut,
  SelfIntersectionCut& out)
{
  const QuietCGAL quiet;
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
        soupPoints.emplace_back(points[q[k]][0], points[q[k]][1], points[q[k]][2]);
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
} // namespace vtkdf
