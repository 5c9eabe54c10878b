#include "LinearFactor/QueryTree.h"

#include "Common/PointTriangleDistance.h"
#include "Common/Vector3.h"
#include "Winding/WindingCrossings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// The searches of the tree that QueryTree.cxx builds: the nearest primitive to a point
// and to a set of points, the primitives in a box, a vertex's or edge's cell and
// pseudonormal, a ray's crossings.
namespace vtkdf
{
namespace nearest
{
namespace
{
/// Lower bounds on the squared distances from p to a wide node's four boxes, rounded
/// down. Two children a vector where SSE2 is (every x86-64 CPU): the same operations per
/// lane as the scalar loop, so the same bounds. (GCC leaves the scalar loop's max as
/// branches.)
void BoxDistances2(const WideNode& node, const double p[3], double bound[4])
{
#if defined(__SSE2__)
  const __m128d zero = _mm_setzero_pd();
  __m128d sum01 = zero, sum23 = zero;
  for (int a = 0; a < 3; ++a)
  {
    const __m128d at = _mm_set1_pd(p[a]);
    const __m128 lo = _mm_loadu_ps(node.Lo[a]), hi = _mm_loadu_ps(node.Hi[a]);
    const __m128d lo01 = _mm_cvtps_pd(lo), lo23 = _mm_cvtps_pd(_mm_movehl_ps(lo, lo));
    const __m128d hi01 = _mm_cvtps_pd(hi), hi23 = _mm_cvtps_pd(_mm_movehl_ps(hi, hi));
    // std::max(0.0, std::max(below, above)): _mm_max_pd(x, y) is x > y ? x : y.
    const __m128d gap01 = _mm_max_pd(_mm_max_pd(_mm_sub_pd(at, hi01), _mm_sub_pd(lo01, at)), zero);
    const __m128d gap23 = _mm_max_pd(_mm_max_pd(_mm_sub_pd(at, hi23), _mm_sub_pd(lo23, at)), zero);
    sum01 = _mm_add_pd(sum01, _mm_mul_pd(gap01, gap01));
    sum23 = _mm_add_pd(sum23, _mm_mul_pd(gap23, gap23));
  }
  const __m128d down = _mm_set1_pd(1 - 8 * std::numeric_limits<double>::epsilon());
  _mm_storeu_pd(bound, _mm_mul_pd(sum01, down));
  _mm_storeu_pd(bound + 2, _mm_mul_pd(sum23, down));
#else
  double sum[4] = { 0, 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    for (int k = 0; k < 4; ++k)
    {
      const double below = double(node.Lo[a][k]) - p[a], above = p[a] - double(node.Hi[a][k]);
      const double gap = std::max(0.0, std::max(below, above));
      sum[k] += gap * gap;
    }
  }
  for (int k = 0; k < 4; ++k)
  {
    bound[k] = sum[k] * (1 - 8 * std::numeric_limits<double>::epsilon());
  }
#endif
}

/// Pushes the node's children whose bound `keep` accepts, nearest on top of the stack
/// (popped first).
template<typename Entry, typename Keep>
void PushChildren(const WideNode& node,
  const double bound[4],
  const Keep& keep,
  Entry* stack,
  int& depth)
{
  int order[4], hits = 0;
  for (int k = 0; k < 4; ++k)
  {
    if (node.Count[k] >= 0 && keep(bound[k]))
    {
      int at = hits++;
      for (; at > 0 && bound[order[at - 1]] < bound[k]; --at)
      {
        order[at] = order[at - 1];
      }
      order[at] = k;
    }
  }
  for (int h = 0; h < hits; ++h)
  {
    const int k = order[h];
    stack[depth++] = Entry{ node.First[k], node.Count[k], bound[k] };
  }
}
} // namespace

int64_t QueryTree::Nearest(const double p[3],
  double bound2,
  int64_t& index,
  double& best2,
  double closest[3],
  int& feature) const
{
  index = -1;
  best2 = bound2;
  int64_t evaluations = 0;
  if (this->WideNodes.empty())
  {
    return 0;
  }
  // A box is skipped when even its nearest point is farther than the best so far by more
  // than rounding could explain, so that exact ties are always seen.
  auto reach = [this](double d2) { return d2 * (1 + 1e-9) + this->Tolerance2; };
  struct Entry
  {
    int32_t First, Count;
    double Bound; // a lower bound on the squared distance to the entry's box
  };
  // Each step pops one entry and pushes at most four: the stack grows by at most 3 a
  // level of the wide tree, which has at most 31 (the binary tree's 30 levels that split
  // a code bit and 31 that halve equal codes, two at a time).
  Entry stack[StackSize];
  int depth = 0;
  stack[depth++] = Entry{ 0, 0, 0.0 };
  while (depth > 0)
  {
    const Entry entry = stack[--depth];
    if (entry.Bound > reach(best2))
    {
      continue;
    }
    if (entry.Count > 0)
    {
      const Leaf& leaf = this->Leaves[entry.First];
      if (this->LeafDistance2(leaf, p) > reach(best2))
      {
        continue;
      }
      for (int32_t i = leaf.First; i < leaf.First + leaf.Count; ++i)
      {
        // The closest point and feature only for the winner, afterwards.
        const double d2 = this->Distance2(i, p);
        ++evaluations;
        const bool better = index < 0
          ? d2 <= best2
          : (d2 < best2 ||
              (d2 == best2 &&
                (this->Cells[i] < this->Cells[index] ||
                  (this->Cells[i] == this->Cells[index] && i < index))));
        if (better)
        {
          index = i;
          best2 = d2;
        }
      }
      continue;
    }
    const WideNode& node = this->WideNodes[entry.First];
    double bound[4];
    BoxDistances2(node, p, bound);
    const double limit = reach(best2);
    PushChildren(
      node, bound, [limit](double b) { return b <= limit; }, stack, depth);
  }
  if (index >= 0)
  {
    const Primitive t = this->Get(index);
    if (this->Faces[index])
    {
      SquaredDistanceToTriangle(p, t.X, t.X + 3, t.X + 6, closest, &feature);
    }
    else
    {
      SquaredDistanceToTriangleEdges(p, t.X, t.X + 3, t.X + 6, closest, &feature);
    }
  }
  return evaluations;
}

int64_t QueryTree::NearestToAll(const double* points,
  int count,
  double bound2,
  double enough2,
  int64_t& index,
  double& worst2) const
{
  index = -1;
  worst2 = bound2;
  int64_t evaluations = 0;
  if (this->WideNodes.empty() || count < 1)
  {
    return 0;
  }
  // The largest squared distance from the points to primitive i, abandoned once it
  // reaches `limit` (the primitive cannot win then).
  auto farthest2 = [&](int32_t i, double limit)
  {
    double worst = 0;
    for (int j = 0; j < count && worst < limit; ++j)
    {
      const double d2 = this->Distance2(i, points + 3 * j);
      ++evaluations;
      worst = std::max(worst, d2);
    }
    return worst;
  };
  struct Entry
  {
    int32_t First, Count;
    double Bound; // a lower bound on every point's squared distance to the entry's box
  };
  Entry stack[StackSize]; // as in Nearest
  int depth = 0;
  stack[depth++] = Entry{ 0, 0, 0.0 };
  while (depth > 0 && !(index >= 0 && worst2 <= enough2))
  {
    const Entry entry = stack[--depth];
    if (entry.Bound >= worst2)
    {
      continue;
    }
    if (entry.Count > 0)
    {
      const Leaf& leaf = this->Leaves[entry.First];
      double reach = 0;
      for (int j = 0; j < count; ++j)
      {
        reach = std::max(reach, this->LeafDistance2(leaf, points + 3 * j));
      }
      for (int32_t i = leaf.First; reach < worst2 && i < leaf.First + leaf.Count; ++i)
      {
        const double d2 = farthest2(i, worst2);
        if (d2 < worst2)
        {
          index = i;
          worst2 = d2;
          if (worst2 <= enough2)
          {
            break;
          }
        }
      }
      continue;
    }
    const WideNode& node = this->WideNodes[entry.First];
    // Each child's bound is the largest of the points' distances to its box.
    double bound[4] = { 0, 0, 0, 0 }, own[4];
    for (int j = 0; j < count; ++j)
    {
      BoxDistances2(node, points + 3 * j, own);
      for (int k = 0; k < 4; ++k)
      {
        bound[k] = std::max(bound[k], own[k]);
      }
    }
    PushChildren(
      node, bound, [worst2](double b) { return b < worst2; }, stack, depth);
  }
  return evaluations;
}

/// Every primitive of the leaves under the children that `inBox(wide, k)` accepts, from
/// the root down, to `visit(i)`; false as soon as a visit returns false.
template<typename InBox, typename Visit>
bool QueryTree::VisitPrimitives(const InBox& inBox, const Visit& visit) const
{
  if (this->WideNodes.empty())
  {
    return true;
  }
  struct Range
  {
    int32_t First, Count;
  };
  Range stack[StackSize]; // as in Nearest
  int depth = 0;
  stack[depth++] = Range{ 0, 0 };
  while (depth > 0)
  {
    const Range node = stack[--depth];
    if (node.Count == 0)
    {
      const WideNode& wide = this->WideNodes[node.First];
      for (int k = 0; k < 4; ++k)
      {
        if (wide.Count[k] >= 0 && inBox(wide, k))
        {
          stack[depth++] = wide.Count[k] > 0
            ? Range{ this->Leaves[wide.First[k]].First, wide.Count[k] }
            : Range{ wide.First[k], 0 };
        }
      }
      continue;
    }
    for (int32_t i = node.First; i < node.First + node.Count; ++i)
    {
      if (!visit(i))
      {
        return false;
      }
    }
  }
  return true;
}

bool QueryTree::GatherFaces(const double lo[3],
  const double hi[3],
  size_t limit,
  std::vector<int32_t>& found) const
{
  found.clear();
  auto inBox = [&](const WideNode& wide, int k)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (double(wide.Lo[a][k]) > hi[a] || double(wide.Hi[a][k]) < lo[a])
      {
        return false;
      }
    }
    return true;
  };
  auto visit = [&](int32_t i)
  {
    if (!this->Faces[i])
    {
      return true;
    }
    const double *x = this->Corner(i, 0), *y = this->Corner(i, 1), *z = this->Corner(i, 2);
    for (int a = 0; a < 3; ++a)
    {
      if (std::min(std::min(x[a], y[a]), z[a]) > hi[a] ||
        std::max(std::max(x[a], y[a]), z[a]) < lo[a])
      {
        return true;
      }
    }
    found.push_back(i);
    return found.size() <= limit;
  };
  return this->VisitPrimitives(inBox, visit);
}

void QueryTree::FeatureCellAndNormal(const double* a,
  const double* b,
  int64_t& cell,
  double normal[3],
  int64_t* primitive) const
{
  cell = std::numeric_limits<int64_t>::max();
  int64_t source = -1;
  normal[0] = normal[1] = normal[2] = 0;
  // The leaves whose boxes hold a.
  auto holdsA = [a](const WideNode& wide, int k)
  {
    return wide.Lo[0][k] <= a[0] && a[0] <= wide.Hi[0][k] && wide.Lo[1][k] <= a[1] &&
      a[1] <= wide.Hi[1][k] && wide.Lo[2][k] <= a[2] && a[2] <= wide.Hi[2][k];
  };
  this->VisitPrimitives(holdsA,
    [&](int32_t i)
    {
      const Primitive t = this->Get(i);
      int atA = -1;
      bool hasB = !b;
      for (int k = 0; k < 3; ++k)
      {
        atA = atA < 0 && SamePoint(t.X + 3 * k, a) ? k : atA;
        hasB = hasB || SamePoint(t.X + 3 * k, b);
      }
      if (atA < 0 || !hasB)
      {
        return true;
      }
      if (this->Cells[i] < cell || (this->Cells[i] == cell && this->Sources[i] < source))
      {
        cell = this->Cells[i];
        source = this->Sources[i];
        if (primitive)
        {
          *primitive = i;
        }
      }
      if (!this->Faces[i])
      {
        return true;
      }
      double n[3];
      FaceNormal(t.X, this->Degenerate, n);
      double weight = 1;
      if (!b)
      {
        // The face's angle at the vertex, as MeshSites computes it.
        const double* x = t.X + 3 * atA;
        const double* next = t.X + 3 * ((atA + 1) % 3);
        const double* prev = t.X + 3 * ((atA + 2) % 3);
        double u[3], w[3], uw[3];
        for (int k = 0; k < 3; ++k)
        {
          u[k] = next[k] - x[k], w[k] = prev[k] - x[k];
        }
        Cross(u, w, uw);
        weight = std::atan2(std::sqrt(Dot(uw, uw)), Dot(u, w));
      }
      for (int k = 0; k < 3; ++k)
      {
        normal[k] += n[k] * weight * this->Orientation;
      }
      return true;
    });
}

bool QueryTree::CrossingCount(const double p[3], int64_t& count) const
{
  count = 0;
  // The leaves whose boxes the ray meets: p's (y, z) within them, their x from p's on down.
  auto onRay = [p](const WideNode& wide, int k)
  {
    return wide.Lo[0][k] <= p[0] && wide.Lo[1][k] <= p[1] && p[1] <= wide.Hi[1][k] &&
      wide.Lo[2][k] <= p[2] && p[2] <= wide.Hi[2][k];
  };
  return this->VisitPrimitives(onRay,
    [&](int32_t i)
    {
      if (static_cast<int64_t>(this->Sources[i]) >= this->Triangles)
      {
        return true; // a segment or a point: not part of w
      }
      const Primitive t = this->Get(i);
      int delta = 0;
      const bool decided = RayCrossing(t.X, t.X + 3, t.X + 6, p, delta);
      count += delta;
      return decided;
    });
}
} // namespace nearest
} // namespace vtkdf
