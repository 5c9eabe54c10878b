#include "Segment/TriangleCrossings.h"

#include "Segment/ExactPredicates.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace vtkdf
{
namespace
{
// Whether a and b have opposite strict signs.
bool Opposite(int a, int b)
{
  return a * b < 0;
}

// The coordinate axes (i, j) of a projection that keeps the triangle t from collapsing:
// one whose normal component, the orientation of t's projection, is nonzero. Every
// figure in t's plane is projected one to one there.
void ProjectionAxes(const Point3 t[3], int& i, int& j)
{
  for (const int k : { 2, 1, 0 })
  {
    i = (k + 1) % 3;
    j = (k + 2) % 3;
    if (Orient2D(t[0].data(), t[1].data(), t[2].data(), i, j) != 0)
    {
      return;
    }
  }
}

// In the projection (i, j): whether x lies in the closed triangle t.
bool InTriangle2D(const Point3& x, const Point3 t[3], int i, int j)
{
  const int s0 = Orient2D(t[0].data(), t[1].data(), x.data(), i, j);
  const int s1 = Orient2D(t[1].data(), t[2].data(), x.data(), i, j);
  const int s2 = Orient2D(t[2].data(), t[0].data(), x.data(), i, j);
  return !(Opposite(s0, s1) || Opposite(s1, s2) || Opposite(s2, s0));
}

// In the projection (i, j), for x collinear with a and b: whether x lies between them.
bool Between2D(const Point3& a, const Point3& b, const Point3& x, int i, int j)
{
  return std::min(a[i], b[i]) <= x[i] && x[i] <= std::max(a[i], b[i]) &&
    std::min(a[j], b[j]) <= x[j] && x[j] <= std::max(a[j], b[j]);
}

// In the projection (i, j): whether the closed segments ab and cd meet.
bool SegmentsMeet2D(const Point3& a,
  const Point3& b,
  const Point3& c,
  const Point3& d,
  int i,
  int j)
{
  const int s1 = Orient2D(a.data(), b.data(), c.data(), i, j);
  const int s2 = Orient2D(a.data(), b.data(), d.data(), i, j);
  const int s3 = Orient2D(c.data(), d.data(), a.data(), i, j);
  const int s4 = Orient2D(c.data(), d.data(), b.data(), i, j);
  if (Opposite(s1, s2) && Opposite(s3, s4))
  {
    return true;
  }
  return (s1 == 0 && Between2D(a, b, c, i, j)) || (s2 == 0 && Between2D(a, b, d, i, j)) ||
    (s3 == 0 && Between2D(c, d, a, i, j)) || (s4 == 0 && Between2D(c, d, b, i, j));
}

// Whether coplanar triangles p and q meet: a corner of one inside the other, or two
// edges that meet.
bool CoplanarTrianglesMeet(const Point3 p[3], const Point3 q[3])
{
  int i = 0, j = 1;
  ProjectionAxes(q, i, j);
  for (int k = 0; k < 3; ++k)
  {
    if (InTriangle2D(p[k], q, i, j) || InTriangle2D(q[k], p, i, j))
    {
      return true;
    }
  }
  for (int e = 0; e < 3; ++e)
  {
    for (int f = 0; f < 3; ++f)
    {
      if (SegmentsMeet2D(p[e], p[(e + 1) % 3], q[f], q[(f + 1) % 3], i, j))
      {
        return true;
      }
    }
  }
  return false;
}

// Whether the segment ab meets triangle t, given the sides sa, sb of a and b with respect
// to t's plane (Orient3D), for triangles that are not coplanar. Off the plane, the line
// ab crosses it at one point, inside the closed triangle when the line passes all three
// edges on one side (the orientations of ab with each edge do not have opposite signs).
// A segment lying in t's plane needs no test of its own: where it meets t, either one
// of its ends does, found by the triangle's other edges through that end, which leave
// the plane, or one of t's edges meets the segment's triangle, found from t's side.
bool SegmentMeetsTriangle(const Point3& a, const Point3& b, int sa, int sb, const Point3 t[3])
{
  if (sa == sb)
  {
    return false; // both strictly on one side, or both in the plane
  }
  const int e0 = Orient3D(a.data(), b.data(), t[0].data(), t[1].data());
  const int e1 = Orient3D(a.data(), b.data(), t[1].data(), t[2].data());
  const int e2 = Orient3D(a.data(), b.data(), t[2].data(), t[0].data());
  return !(Opposite(e0, e1) || Opposite(e1, e2) || Opposite(e2, e0));
}

struct Box
{
  std::array<double, 3> Min, Max;

  bool Meets(const Box& other) const
  {
    for (int k = 0; k < 3; ++k)
    {
      if (this->Max[k] < other.Min[k] || other.Max[k] < this->Min[k])
      {
        return false;
      }
    }
    return true;
  }
  void Add(const Box& other)
  {
    for (int k = 0; k < 3; ++k)
    {
      this->Min[k] = std::min(this->Min[k], other.Min[k]);
      this->Max[k] = std::max(this->Max[k], other.Max[k]);
    }
  }
};

/// A bounding-volume hierarchy over the triangles' boxes: each node's triangles are a
/// range of Order, split at the median of the boxes' centres along the range's longest
/// side until at most LeafSize remain.
class BoxTree
{
public:
  BoxTree(const std::vector<Point3>& points, const std::vector<TriangleCorners>& triangles)
  {
    this->Boxes.resize(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      Box& box = this->Boxes[t];
      box.Min = box.Max = points[triangles[t][0]];
      for (int c = 1; c < 3; ++c)
      {
        const Point3& p = points[triangles[t][c]];
        for (int k = 0; k < 3; ++k)
        {
          box.Min[k] = std::min(box.Min[k], p[k]);
          box.Max[k] = std::max(box.Max[k], p[k]);
        }
      }
    }
    this->Order.resize(triangles.size());
    std::iota(this->Order.begin(), this->Order.end(), size_t(0));
    if (!triangles.empty())
    {
      this->Build(0, triangles.size());
    }
  }

  void ForEachOverlappingPair(const std::function<void(size_t, size_t)>& report) const
  {
    if (!this->Nodes.empty())
    {
      this->SelfJoin(0, report);
    }
  }

private:
  static constexpr size_t LeafSize = 4;
  struct Node
  {
    Box Bounds;
    size_t Begin, End; // the node's range of Order
    int64_t Left = -1; // children's indices in Nodes, -1 for a leaf
    int64_t Right = -1;
  };
  std::vector<Box> Boxes;
  std::vector<size_t> Order;
  std::vector<Node> Nodes;

  int64_t Build(size_t begin, size_t end)
  {
    const int64_t index = static_cast<int64_t>(this->Nodes.size());
    this->Nodes.push_back(Node{ this->Boxes[this->Order[begin]], begin, end });
    Box centres{ { 0, 0, 0 }, { 0, 0, 0 } };
    for (size_t i = begin; i < end; ++i)
    {
      const Box& box = this->Boxes[this->Order[i]];
      this->Nodes[index].Bounds.Add(box);
      for (int k = 0; k < 3; ++k)
      {
        const double centre = 0.5 * (box.Min[k] + box.Max[k]);
        centres.Min[k] = i == begin ? centre : std::min(centres.Min[k], centre);
        centres.Max[k] = i == begin ? centre : std::max(centres.Max[k], centre);
      }
    }
    if (end - begin <= LeafSize)
    {
      return index;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
    {
      if (centres.Max[k] - centres.Min[k] > centres.Max[axis] - centres.Min[axis])
      {
        axis = k;
      }
    }
    const size_t middle = begin + (end - begin) / 2;
    // Ties broken by the triangle's index, so that the tree depends on the input alone.
    std::nth_element(this->Order.begin() + begin,
      this->Order.begin() + middle,
      this->Order.begin() + end,
      [&](size_t a, size_t b)
      {
        const double ca = this->Boxes[a].Min[axis] + this->Boxes[a].Max[axis];
        const double cb = this->Boxes[b].Min[axis] + this->Boxes[b].Max[axis];
        return ca != cb ? ca < cb : a < b;
      });
    const int64_t left = this->Build(begin, middle);
    const int64_t right = this->Build(middle, end);
    this->Nodes[index].Left = left;
    this->Nodes[index].Right = right;
    return index;
  }

  void Report(size_t a, size_t b, const std::function<void(size_t, size_t)>& report) const
  {
    if (this->Boxes[a].Meets(this->Boxes[b]))
    {
      report(std::min(a, b), std::max(a, b));
    }
  }

  void SelfJoin(int64_t n, const std::function<void(size_t, size_t)>& report) const
  {
    const Node& node = this->Nodes[n];
    if (node.Left < 0)
    {
      for (size_t i = node.Begin; i < node.End; ++i)
      {
        for (size_t k = i + 1; k < node.End; ++k)
        {
          this->Report(this->Order[i], this->Order[k], report);
        }
      }
      return;
    }
    this->SelfJoin(node.Left, report);
    this->SelfJoin(node.Right, report);
    this->Join(node.Left, node.Right, report);
  }

  void Join(int64_t m, int64_t n, const std::function<void(size_t, size_t)>& report) const
  {
    const Node& a = this->Nodes[m];
    const Node& b = this->Nodes[n];
    if (!a.Bounds.Meets(b.Bounds))
    {
      return;
    }
    if (a.Left < 0 && b.Left < 0)
    {
      for (size_t i = a.Begin; i < a.End; ++i)
      {
        for (size_t k = b.Begin; k < b.End; ++k)
        {
          this->Report(this->Order[i], this->Order[k], report);
        }
      }
      return;
    }
    // Descend the larger node (or the one that is not a leaf).
    if (b.Left < 0 || (a.Left >= 0 && a.End - a.Begin >= b.End - b.Begin))
    {
      this->Join(a.Left, n, report);
      this->Join(a.Right, n, report);
    }
    else
    {
      this->Join(m, b.Left, report);
      this->Join(m, b.Right, report);
    }
  }
};
} // namespace

bool TrianglesIntersect(const Point3 p[3], const Point3 q[3])
{
  // The sides of p's corners with respect to q's plane: all strictly on one side, no
  // point in common; all on it, a question in that plane.
  int sp[3], sq[3];
  for (int k = 0; k < 3; ++k)
  {
    sp[k] = Orient3D(q[0].data(), q[1].data(), q[2].data(), p[k].data());
  }
  if ((sp[0] > 0 && sp[1] > 0 && sp[2] > 0) || (sp[0] < 0 && sp[1] < 0 && sp[2] < 0))
  {
    return false;
  }
  if (sp[0] == 0 && sp[1] == 0 && sp[2] == 0)
  {
    return CoplanarTrianglesMeet(p, q);
  }
  for (int k = 0; k < 3; ++k)
  {
    sq[k] = Orient3D(p[0].data(), p[1].data(), p[2].data(), q[k].data());
  }
  if ((sq[0] > 0 && sq[1] > 0 && sq[2] > 0) || (sq[0] < 0 && sq[1] < 0 && sq[2] < 0))
  {
    return false;
  }
  // Not coplanar: the triangles' common part is a segment of the planes' common line
  // whose ends lie on edges, so they meet exactly when an edge of one meets the other.
  for (int e = 0; e < 3; ++e)
  {
    const int f = (e + 1) % 3;
    if (SegmentMeetsTriangle(p[e], p[f], sp[e], sp[f], q) ||
      SegmentMeetsTriangle(q[e], q[f], sq[e], sq[f], p))
    {
      return true;
    }
  }
  return false;
}

void ForEachOverlappingPair(const std::vector<Point3>& points,
  const std::vector<TriangleCorners>& triangles,
  const std::function<void(size_t, size_t)>& report)
{
  BoxTree(points, triangles).ForEachOverlappingPair(report);
}
} // namespace vtkdf
