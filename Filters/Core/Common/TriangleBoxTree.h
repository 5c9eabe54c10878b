// TriangleBoxTree: a bounding-volume hierarchy over the axis-aligned boxes of triangles,
// without VTK types, for the searches that pair triangles: with itself (the triangles
// whose boxes meet: Segment/TriangleCrossings) or with another tree (Proximity/).
#ifndef vtkdf_TriangleBoxTree_h
#define vtkdf_TriangleBoxTree_h

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <vector>

namespace vtkdf
{
using Point3 = std::array<double, 3>;
using TriangleCorners = std::array<size_t, 3>;

/// A closed axis-aligned box.
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
  /// The squared distance between the two boxes (0 when they meet), rounded down: a
  /// lower bound on the squared distance of any point of one to any point of the other.
  double SquaredDistance(const Box& other) const
  {
    double d2 = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double gap =
        std::max(0.0, std::max(other.Min[k] - this->Max[k], this->Min[k] - other.Max[k]));
      d2 += gap * gap;
    }
    // Three products and two sums, each within half an ulp: 4 ulps cover them.
    return d2 * (1 - 8 * std::numeric_limits<double>::epsilon());
  }
};

/// A bounding-volume hierarchy over the triangles' boxes: each node's triangles are a
/// range of Order(), split at the median of the boxes' centres along the range's longest
/// side until at most LeafSize remain. Node 0 is the root.
class TriangleBoxTree
{
public:
  static constexpr size_t LeafSize = 4;
  struct Node
  {
    Box Bounds;
    size_t Begin, End; // the node's range of Order()
    int64_t Left = -1; // children's indices in Nodes(), -1 for a leaf
    int64_t Right = -1;
    bool IsLeaf() const { return this->Left < 0; }
    size_t Size() const { return this->End - this->Begin; }
  };

  TriangleBoxTree(const std::vector<Point3>& points, const std::vector<TriangleCorners>& triangles)
  {
    this->TriangleBoxes.resize(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      this->TriangleBoxes[t] = TriangleBox(points, triangles[t]);
    }
    this->TriangleOrder.resize(triangles.size());
    std::iota(this->TriangleOrder.begin(), this->TriangleOrder.end(), size_t(0));
    if (!triangles.empty())
    {
      this->Build(0, triangles.size());
    }
  }

  /// The same triangles at new coordinates (a deforming mesh: same topology): the
  /// triangles' and nodes' boxes recomputed, the hierarchy's order kept. Every search
  /// stays exact; only the pruning may loosen as the mesh moves away from the pose the
  /// order was built for.
  void Refit(const std::vector<Point3>& points, const std::vector<TriangleCorners>& triangles)
  {
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      this->TriangleBoxes[t] = TriangleBox(points, triangles[t]);
    }
    // Children come after their parent in Nodes(): the last node first.
    for (size_t n = this->TreeNodes.size(); n-- > 0;)
    {
      Node& node = this->TreeNodes[n];
      if (node.IsLeaf())
      {
        node.Bounds = this->TriangleBoxes[this->TriangleOrder[node.Begin]];
        for (size_t i = node.Begin + 1; i < node.End; ++i)
        {
          node.Bounds.Add(this->TriangleBoxes[this->TriangleOrder[i]]);
        }
      }
      else
      {
        node.Bounds = this->TreeNodes[node.Left].Bounds;
        node.Bounds.Add(this->TreeNodes[node.Right].Bounds);
      }
    }
  }

  const std::vector<Node>& Nodes() const { return this->TreeNodes; }
  /// The triangles' indices, each node's in one range.
  const std::vector<size_t>& Order() const { return this->TriangleOrder; }
  /// Each triangle's box.
  const std::vector<Box>& Boxes() const { return this->TriangleBoxes; }

  /// Calls `report(i, k)` (i < k) once for every pair of this tree's triangles whose boxes
  /// meet, in an order that depends only on the input.
  void ForEachOverlappingPair(const std::function<void(size_t, size_t)>& report) const
  {
    if (!this->TreeNodes.empty())
    {
      this->SelfJoin(0, report);
    }
  }

  /// Calls `report(i, k)` once for every triangle i of this tree and k of `other` whose
  /// boxes meet, in an order that depends only on the inputs; stops when `report`
  /// returns false. Returns false when it stopped.
  bool ForEachOverlappingPair(const TriangleBoxTree& other,
    const std::function<bool(size_t, size_t)>& report) const
  {
    if (this->TreeNodes.empty() || other.TreeNodes.empty())
    {
      return true;
    }
    return this->CrossJoin(0, other, 0, report);
  }

private:
  static Box TriangleBox(const std::vector<Point3>& points, const TriangleCorners& triangle)
  {
    Box box{ points[triangle[0]], points[triangle[0]] };
    for (int c = 1; c < 3; ++c)
    {
      const Point3& p = points[triangle[c]];
      for (int k = 0; k < 3; ++k)
      {
        box.Min[k] = std::min(box.Min[k], p[k]);
        box.Max[k] = std::max(box.Max[k], p[k]);
      }
    }
    return box;
  }

  std::vector<Box> TriangleBoxes;
  std::vector<size_t> TriangleOrder;
  std::vector<Node> TreeNodes;

  int64_t Build(size_t begin, size_t end)
  {
    const int64_t index = static_cast<int64_t>(this->TreeNodes.size());
    this->TreeNodes.push_back(Node{ this->TriangleBoxes[this->TriangleOrder[begin]], begin, end });
    Box centres{ { 0, 0, 0 }, { 0, 0, 0 } };
    for (size_t i = begin; i < end; ++i)
    {
      const Box& box = this->TriangleBoxes[this->TriangleOrder[i]];
      this->TreeNodes[index].Bounds.Add(box);
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
    std::nth_element(this->TriangleOrder.begin() + begin,
      this->TriangleOrder.begin() + middle,
      this->TriangleOrder.begin() + end,
      [&](size_t a, size_t b)
      {
        const double ca = this->TriangleBoxes[a].Min[axis] + this->TriangleBoxes[a].Max[axis];
        const double cb = this->TriangleBoxes[b].Min[axis] + this->TriangleBoxes[b].Max[axis];
        return ca != cb ? ca < cb : a < b;
      });
    const int64_t left = this->Build(begin, middle);
    const int64_t right = this->Build(middle, end);
    this->TreeNodes[index].Left = left;
    this->TreeNodes[index].Right = right;
    return index;
  }

  void Report(size_t a, size_t b, const std::function<void(size_t, size_t)>& report) const
  {
    if (this->TriangleBoxes[a].Meets(this->TriangleBoxes[b]))
    {
      report(std::min(a, b), std::max(a, b));
    }
  }

  void SelfJoin(int64_t n, const std::function<void(size_t, size_t)>& report) const
  {
    const Node& node = this->TreeNodes[n];
    if (node.IsLeaf())
    {
      for (size_t i = node.Begin; i < node.End; ++i)
      {
        for (size_t k = i + 1; k < node.End; ++k)
        {
          this->Report(this->TriangleOrder[i], this->TriangleOrder[k], report);
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
    const Node& a = this->TreeNodes[m];
    const Node& b = this->TreeNodes[n];
    if (!a.Bounds.Meets(b.Bounds))
    {
      return;
    }
    if (a.IsLeaf() && b.IsLeaf())
    {
      for (size_t i = a.Begin; i < a.End; ++i)
      {
        for (size_t k = b.Begin; k < b.End; ++k)
        {
          this->Report(this->TriangleOrder[i], this->TriangleOrder[k], report);
        }
      }
      return;
    }
    // Descend the larger node (or the one that is not a leaf).
    if (b.IsLeaf() || (!a.IsLeaf() && a.Size() >= b.Size()))
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

  bool CrossJoin(int64_t m,
    const TriangleBoxTree& other,
    int64_t n,
    const std::function<bool(size_t, size_t)>& report) const
  {
    const Node& a = this->TreeNodes[m];
    const Node& b = other.TreeNodes[n];
    if (!a.Bounds.Meets(b.Bounds))
    {
      return true;
    }
    if (a.IsLeaf() && b.IsLeaf())
    {
      for (size_t i = a.Begin; i < a.End; ++i)
      {
        const size_t s = this->TriangleOrder[i];
        for (size_t k = b.Begin; k < b.End; ++k)
        {
          const size_t t = other.TriangleOrder[k];
          if (this->TriangleBoxes[s].Meets(other.TriangleBoxes[t]) && !report(s, t))
          {
            return false;
          }
        }
      }
      return true;
    }
    if (b.IsLeaf() || (!a.IsLeaf() && a.Size() >= b.Size()))
    {
      return this->CrossJoin(a.Left, other, n, report) &&
        this->CrossJoin(a.Right, other, n, report);
    }
    return this->CrossJoin(m, other, b.Left, report) && this->CrossJoin(m, other, b.Right, report);
  }
};
} // namespace vtkdf

#endif
