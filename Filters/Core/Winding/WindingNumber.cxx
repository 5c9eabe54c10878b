#include "WindingNumber.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace vtkdf
{

namespace
{
constexpr double FourPi = 4 * M_PI;
constexpr int64_t LeafSize = 8;

double Dot(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
} // namespace

double TriangleSolidAngle(const double a[3],
  const double b[3],
  const double c[3],
  const double q[3])
{
  const double u[3] = { a[0] - q[0], a[1] - q[1], a[2] - q[2] };
  const double v[3] = { b[0] - q[0], b[1] - q[1], b[2] - q[2] };
  const double w[3] = { c[0] - q[0], c[1] - q[1], c[2] - q[2] };
  const double lu = std::sqrt(Dot(u, u)), lv = std::sqrt(Dot(v, v)), lw = std::sqrt(Dot(w, w));
  const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
  const double den = lu * lv * lw + Dot(u, v) * lw + Dot(u, w) * lv + Dot(v, w) * lu;
  return 2 * std::atan2(det, den);
}

void WindingNumber::Build(const std::vector<double>& points,
  const std::vector<int64_t>& triangles,
  double accuracy)
{
  if (!(accuracy > 1))
  {
    throw std::invalid_argument("the winding number's accuracy must exceed 1");
  }
  this->Accuracy = accuracy;
  // Each triangle's corners, rotated to start at its lexicographically smallest one (the
  // cyclic order, hence the orientation, kept), so that repeats sort next to each other.
  const int64_t n = static_cast<int64_t>(triangles.size() / 3);
  std::vector<std::array<double, 9>> keyed(n);
  for (int64_t t = 0; t < n; ++t)
  {
    const double* p[3];
    for (int k = 0; k < 3; ++k)
    {
      p[k] = points.data() + 3 * triangles[3 * t + k];
    }
    int first = 0;
    for (int k = 1; k < 3; ++k)
    {
      if (std::lexicographical_compare(p[k], p[k] + 3, p[first], p[first] + 3))
      {
        first = k;
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      std::copy(p[(first + k) % 3], p[(first + k) % 3] + 3, keyed[t].data() + 3 * k);
    }
  }
  std::sort(keyed.begin(), keyed.end());
  keyed.erase(std::unique(keyed.begin(), keyed.end()), keyed.end());

  const int64_t kept = static_cast<int64_t>(keyed.size());
  std::vector<double> corners(9 * kept), centroids(3 * kept);
  for (int64_t t = 0; t < kept; ++t)
  {
    std::copy(keyed[t].begin(), keyed[t].end(), corners.begin() + 9 * t);
    for (int a = 0; a < 3; ++a)
    {
      centroids[3 * t + a] = (keyed[t][a] + keyed[t][3 + a] + keyed[t][6 + a]) / 3;
    }
  }
  std::vector<int64_t> order(kept);
  for (int64_t t = 0; t < kept; ++t)
  {
    order[t] = t;
  }
  this->Nodes.clear();
  if (kept > 0)
  {
    this->BuildNode(order, 0, kept, corners, centroids);
  }
  this->Corners.resize(9 * kept);
  this->Balls.resize(4 * kept);
  this->Areas.resize(kept);
  for (int64_t t = 0; t < kept; ++t)
  {
    double* p = this->Corners.data() + 9 * t;
    std::copy(corners.begin() + 9 * order[t], corners.begin() + 9 * order[t] + 9, p);
    double* ball = this->Balls.data() + 4 * t;
    double reach2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      ball[a] = centroids[3 * order[t] + a];
    }
    for (int k = 0; k < 3; ++k)
    {
      const double e[3] = { p[3 * k] - ball[0], p[3 * k + 1] - ball[1], p[3 * k + 2] - ball[2] };
      reach2 = std::max(reach2, Dot(e, e));
    }
    ball[3] = std::sqrt(reach2);
    const double e[3] = { p[3] - p[0], p[4] - p[1], p[5] - p[2] };
    const double f[3] = { p[6] - p[0], p[7] - p[1], p[8] - p[2] };
    const double m[3] = {
      e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]
    };
    this->Areas[t] = 0.5 * std::sqrt(Dot(m, m));
  }
}

int32_t WindingNumber::BuildNode(std::vector<int64_t>& order,
  int64_t first,
  int64_t count,
  const std::vector<double>& corners,
  const std::vector<double>& centroids)
{
  const int32_t index = static_cast<int32_t>(this->Nodes.size());
  this->Nodes.push_back(Node());
  Node node;
  node.First = first;
  node.Count = count;
  node.Children[0] = node.Children[1] = -1;
  // Moment, area and the area-weighted centre.
  double weighted[3] = { 0, 0, 0 }, area = 0, moment[3] = { 0, 0, 0 };
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (int64_t i = first; i < first + count; ++i)
  {
    const double* p = corners.data() + 9 * order[i];
    const double e[3] = { p[3] - p[0], p[4] - p[1], p[5] - p[2] };
    const double f[3] = { p[6] - p[0], p[7] - p[1], p[8] - p[2] };
    const double m[3] = { 0.5 * (e[1] * f[2] - e[2] * f[1]),
      0.5 * (e[2] * f[0] - e[0] * f[2]),
      0.5 * (e[0] * f[1] - e[1] * f[0]) };
    const double a = std::sqrt(Dot(m, m));
    for (int c = 0; c < 3; ++c)
    {
      moment[c] += m[c];
      weighted[c] += a * centroids[3 * order[i] + c];
      lo[c] = std::min(lo[c], centroids[3 * order[i] + c]);
      hi[c] = std::max(hi[c], centroids[3 * order[i] + c]);
    }
    area += a;
  }
  for (int c = 0; c < 3; ++c)
  {
    node.Moment[c] = moment[c];
    // Degenerate (zero-area) triangles only: the centroids' box centre.
    node.Centre[c] = area > 0 ? weighted[c] / area : 0.5 * (lo[c] + hi[c]);
  }
  node.Area = area;
  double radius2 = 0;
  for (int64_t i = first; i < first + count; ++i)
  {
    const double* p = corners.data() + 9 * order[i];
    for (int k = 0; k < 3; ++k)
    {
      const double d[3] = {
        p[3 * k] - node.Centre[0], p[3 * k + 1] - node.Centre[1], p[3 * k + 2] - node.Centre[2]
      };
      radius2 = std::max(radius2, Dot(d, d));
    }
  }
  node.Radius = std::sqrt(radius2);
  if (count > LeafSize)
  {
    // Split at the median centroid along the box's longest side.
    int axis = 0;
    for (int c = 1; c < 3; ++c)
    {
      if (hi[c] - lo[c] > hi[axis] - lo[axis])
      {
        axis = c;
      }
    }
    const int64_t half = count / 2;
    std::nth_element(order.begin() + first,
      order.begin() + first + half,
      order.begin() + first + count,
      [&](int64_t s, int64_t t) { return centroids[3 * s + axis] < centroids[3 * t + axis]; });
    node.Children[0] = this->BuildNode(order, first, half, corners, centroids);
    node.Children[1] = this->BuildNode(order, first + half, count - half, corners, centroids);
  }
  this->Nodes[index] = node;
  return index;
}

WindingValue WindingNumber::Evaluate(const double q[3]) const
{
  WindingValue result;
  if (this->Nodes.empty())
  {
    return result;
  }
  double angle = 0; // the exact part, as a solid angle
  int32_t stack[128];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    const Node& node = this->Nodes[stack[--depth]];
    const double d[3] = { node.Centre[0] - q[0], node.Centre[1] - q[1], node.Centre[2] - q[2] };
    const double r = std::sqrt(Dot(d, d));
    if (r > this->Accuracy * node.Radius)
    {
      // Far: the dipole term, and its error bound (WindingNumber.h).
      result.Value += Dot(node.Moment, d) / (FourPi * r * r * r);
      const double gap = r - node.Radius;
      result.Bound += node.Area * node.Radius / (2 * M_PI * gap * gap * gap);
    }
    else if (node.Children[0] < 0)
    {
      for (int64_t t = node.First; t < node.First + node.Count; ++t)
      {
        const double* p = this->Corners.data() + 9 * t;
        angle += TriangleSolidAngle(p, p + 3, p + 6, q);
      }
    }
    else
    {
      stack[depth++] = node.Children[0];
      stack[depth++] = node.Children[1];
    }
  }
  result.Value += angle / FourPi;
  return result;
}

double WindingNumber::GradientBound(const double c[3], double radius) const
{
  double bound = 0;
  if (this->Nodes.empty())
  {
    return bound;
  }
  int32_t stack[128];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    const Node& node = this->Nodes[stack[--depth]];
    const double d[3] = { node.Centre[0] - c[0], node.Centre[1] - c[1], node.Centre[2] - c[2] };
    const double gap = std::sqrt(Dot(d, d)) - node.Radius - radius;
    if (gap > node.Radius + radius)
    {
      bound += node.Area / (2 * M_PI * gap * gap * gap);
    }
    else if (node.Children[0] < 0)
    {
      // Each triangle from the ball around its centroid through its farthest corner.
      for (int64_t t = node.First; t < node.First + node.Count; ++t)
      {
        const double* ball = this->Balls.data() + 4 * t;
        const double to[3] = { ball[0] - c[0], ball[1] - c[1], ball[2] - c[2] };
        const double g = std::sqrt(Dot(to, to)) - ball[3] - radius;
        if (!(g > 0))
        {
          return HUGE_VAL;
        }
        bound += this->Areas[t] / (2 * M_PI * g * g * g);
      }
    }
    else
    {
      stack[depth++] = node.Children[0];
      stack[depth++] = node.Children[1];
    }
  }
  return bound;
}

double WindingNumber::Exact(const double q[3]) const
{
  double angle = 0;
  for (size_t t = 0; t < this->Corners.size(); t += 9)
  {
    const double* p = this->Corners.data() + t;
    angle += TriangleSolidAngle(p, p + 3, p + 6, q);
  }
  return angle / FourPi;
}

bool WindingNumber::Inside(const double q[3], double* value, bool* exact) const
{
  const WindingValue w = this->Evaluate(q);
  const bool decided = std::fabs(std::fabs(w.Value) - 0.5) > w.Bound;
  const double used = decided ? w.Value : this->Exact(q);
  if (value)
  {
    *value = used;
  }
  if (exact)
  {
    *exact = !decided;
  }
  return std::fabs(used) > 0.5;
}

} // namespace vtkdf
