// ProximitySearch: the searches the proximity queries share, over a model's triangles
// and their box hierarchy (Common/TriangleBoxTree.h): loading a model, the nearest
// triangle to a point, the nearest pair of triangles of two models. Private to the
// Proximity family.
#ifndef vtkdf_ProximitySearch_h
#define vtkdf_ProximitySearch_h

#include "Common/MeshInput.h"
#include "Common/PointTriangleDistance.h"
#include "Common/TriangleBoxTree.h"
#include "Proximity/MeshProximity.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>
#include <vector>

namespace vtkdf
{
/// One model: its triangles as the box tree and the exact predicates take them.
struct TriangleModel
{
  std::vector<Point3> Points;
  std::vector<TriangleCorners> Triangles;

  bool Load(const MeshInput& mesh, const char* name, std::string& error)
  {
    if (mesh.Triangles.empty())
    {
      error = std::string("model ") + name + " has no triangle";
      return false;
    }
    const size_t points = mesh.Points.size() / 3;
    this->Points.resize(points);
    for (size_t i = 0; i < points; ++i)
    {
      this->Points[i] = { { mesh.Points[3 * i], mesh.Points[3 * i + 1], mesh.Points[3 * i + 2] } };
    }
    this->Triangles.resize(mesh.Triangles.size() / 3);
    for (size_t t = 0; t < this->Triangles.size(); ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        const int64_t id = mesh.Triangles[3 * t + c];
        if (id < 0 || static_cast<size_t>(id) >= points)
        {
          error = std::string("model ") + name + ": triangle " + std::to_string(t) +
            " uses point " + std::to_string(id) + ", not one of its " + std::to_string(points);
          return false;
        }
        const Point3& x = this->Points[id];
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
        {
          error = std::string("model ") + name + ": point " + std::to_string(id) +
            " has a coordinate that is not finite";
          return false;
        }
        this->Triangles[t][c] = static_cast<size_t>(id);
      }
    }
    return true;
  }

  void Corners(size_t t, Point3 out[3]) const
  {
    for (int c = 0; c < 3; ++c)
    {
      out[c] = this->Points[this->Triangles[t][c]];
    }
  }
  void Corners(size_t t, double out[9]) const
  {
    for (int c = 0; c < 3; ++c)
    {
      std::copy(this->Points[this->Triangles[t][c]].begin(),
        this->Points[this->Triangles[t][c]].end(),
        out + 3 * c);
    }
  }
};

/// The nearest pair of triangles of two models that do not intersect, searched from the
/// nearest pairs of nodes on; pairs whose boxes are farther than `bound` (squared) are
/// not searched. False when no pair is within the bound.
inline bool NearestPair(const TriangleModel& a,
  const TriangleBoxTree& treeA,
  const TriangleModel& b,
  const TriangleBoxTree& treeB,
  double bound,
  ProximityResult& result)
{
  struct NodePair
  {
    double Bound;
    int64_t A, B;
    bool operator>(const NodePair& other) const { return this->Bound > other.Bound; }
  };
  std::priority_queue<NodePair, std::vector<NodePair>, std::greater<NodePair>> queue;
  const auto& nodesA = treeA.Nodes();
  const auto& nodesB = treeB.Nodes();
  queue.push({ nodesA[0].Bounds.SquaredDistance(nodesB[0].Bounds), 0, 0 });
  double best = bound;
  bool found = false;
  while (!queue.empty())
  {
    const NodePair pair = queue.top();
    queue.pop();
    if (pair.Bound > best)
    {
      break;
    }
    const auto& na = nodesA[pair.A];
    const auto& nb = nodesB[pair.B];
    if (na.IsLeaf() && nb.IsLeaf())
    {
      for (size_t i = na.Begin; i < na.End; ++i)
      {
        const size_t s = treeA.Order()[i];
        double p[9];
        a.Corners(s, p);
        for (size_t k = nb.Begin; k < nb.End; ++k)
        {
          const size_t t = treeB.Order()[k];
          if (treeA.Boxes()[s].SquaredDistance(treeB.Boxes()[t]) > best)
          {
            continue;
          }
          double q[9], onP[3], onQ[3];
          b.Corners(t, q);
          ++result.DistanceTests;
          const double d2 = SquaredTriangleDistance(p, q, onP, onQ);
          if (d2 < best || (!found && d2 <= best))
          {
            best = d2;
            found = true;
            result.Separation = std::sqrt(d2);
            std::copy(onP, onP + 3, result.ClosestA.begin());
            std::copy(onQ, onQ + 3, result.ClosestB.begin());
            result.ClosestTriangleA = static_cast<int64_t>(s);
            result.ClosestTriangleB = static_cast<int64_t>(t);
          }
        }
      }
      continue;
    }
    // Split the larger node (or the one that is not a leaf).
    auto push = [&](int64_t m, int64_t n)
    {
      const double d2 = nodesA[m].Bounds.SquaredDistance(nodesB[n].Bounds);
      if (d2 <= best)
      {
        queue.push({ d2, m, n });
      }
    };
    if (nb.IsLeaf() || (!na.IsLeaf() && na.Size() >= nb.Size()))
    {
      push(na.Left, pair.B);
      push(na.Right, pair.B);
    }
    else
    {
      push(pair.A, nb.Left);
      push(pair.A, nb.Right);
    }
  }
  return found;
}
/// The nearest triangle of `model` to x: the squared distance, the closest point and the
/// triangle, the nearer child first and nodes farther than the best pruned. When
/// `triangle` comes in as a triangle's index (a neighbour's nearest, say), the search
/// starts from its distance: the answer is the same nearest distance, found sooner.
inline double NearestTriangle(const TriangleModel& model,
  const TriangleBoxTree& tree,
  const double x[3],
  double closest[3],
  int64_t& triangle)
{
  const Box point{ { { x[0], x[1], x[2] } }, { { x[0], x[1], x[2] } } };
  double best = HUGE_VAL;
  if (triangle >= 0)
  {
    double c[9];
    model.Corners(static_cast<size_t>(triangle), c);
    best = SquaredDistanceToTriangle(x, c, c + 3, c + 6, closest);
  }
  // A median split halves every node: the depth stays below 64 for any count.
  int64_t stack[130];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    const auto& node = tree.Nodes()[stack[--depth]];
    if (node.Bounds.SquaredDistance(point) > best)
    {
      continue;
    }
    if (node.IsLeaf())
    {
      for (size_t i = node.Begin; i < node.End; ++i)
      {
        const size_t t = tree.Order()[i];
        double c[9], on[3];
        model.Corners(t, c);
        const double d2 = SquaredDistanceToTriangle(x, c, c + 3, c + 6, on);
        if (d2 < best)
        {
          best = d2;
          std::copy(on, on + 3, closest);
          triangle = static_cast<int64_t>(t);
        }
      }
      continue;
    }
    const double left = tree.Nodes()[node.Left].Bounds.SquaredDistance(point);
    const double right = tree.Nodes()[node.Right].Bounds.SquaredDistance(point);
    // The nearer child on top of the stack.
    stack[depth++] = left <= right ? node.Right : node.Left;
    stack[depth++] = left <= right ? node.Left : node.Right;
  }
  return best;
}
} // namespace vtkdf

#endif
