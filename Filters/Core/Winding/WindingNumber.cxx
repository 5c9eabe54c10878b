#include "Winding/WindingNumber.h"

#include "Common/ArcTangent.h"
#include "Common/Vector3.h"

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
} // namespace

void AngleProduct::Add(const double a[3], const double b[3], const double c[3], const double q[3])
{
  const double u[3] = { a[0] - q[0], a[1] - q[1], a[2] - q[2] };
  const double v[3] = { b[0] - q[0], b[1] - q[1], b[2] - q[2] };
  const double w[3] = { c[0] - q[0], c[1] - q[1], c[2] - q[2] };
  const double lu = std::sqrt(Dot(u, u)), lv = std::sqrt(Dot(v, v)), lw = std::sqrt(Dot(w, w));
  const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
  const double den = lu * lv * lw + Dot(u, v) * lw + Dot(u, w) * lv + Dot(v, w) * lu;
  this->Multiply(den, det);
}

void AngleProduct::Multiply(double re, double im)
{
  if (re == 0 && im == 0)
  {
    return; // q at a corner: atan2(0, 0) = 0
  }
  const double pr = this->Re * re - this->Im * im, pi = this->Re * im + this->Im * re;
  // Arguments in (-pi, pi] (an imaginary part of 0, either sign, counts as the upper
  // side): the sum wrapped when both lie on one side and the product on the other.
  if (this->Im >= 0 && im >= 0)
  {
    this->Turns += pi < 0 || (pi == 0 && pr > 0 && this->Re < 0 && re < 0);
  }
  else if (this->Im < 0 && im < 0 && pi >= 0)
  {
    --this->Turns;
  }
  this->Re = pr;
  this->Im = pi;
  // Kept near 1 by powers of two, which change no bit of the argument.
  const double m = std::max(std::fabs(pr), std::fabs(pi));
  if (m > 0x1p+100 || m < 0x1p-100)
  {
    int e = 0;
    std::frexp(m, &e);
    this->Re = std::ldexp(this->Re, -e);
    this->Im = std::ldexp(this->Im, -e);
  }
}

double AngleProduct::Argument() const
{
  // ArcTangent2 takes an imaginary part of 0, either sign, as +0, as the turns count it.
  return ArcTangent2(this->Im, this->Re);
}

double AngleProduct::Winding() const
{
  return static_cast<double>(this->Turns) + this->Argument() / (2 * M_PI);
}

bool AngleProduct::Inside() const
{
  // Winding() is Turns + a fraction in (-1/2, 1/2]: |w| > 1/2 exactly when Turns is not
  // 0, but for w = -1/2.
  return this->Turns != 0 && !(this->Turns == -1 && this->Im == 0 && this->Re < 0);
}

void TriangleSolidAngleGradient(const double a[3],
  const double b[3],
  const double c[3],
  const double q[3],
  double gradient[3])
{
  // The field of a unit current around the triangle's edges (Biot-Savart), edge by edge:
  // (u x v) (|u| + |v|) / (|u| |v| (|u| |v| + u . v)), u and v the edge's ends from q.
  const double* corner[3] = { a, b, c };
  gradient[0] = gradient[1] = gradient[2] = 0;
  for (int e = 0; e < 3; ++e)
  {
    const double* p0 = corner[e];
    const double* p1 = corner[(e + 1) % 3];
    const double u[3] = { p0[0] - q[0], p0[1] - q[1], p0[2] - q[2] };
    const double v[3] = { p1[0] - q[0], p1[1] - q[1], p1[2] - q[2] };
    const double lu = std::sqrt(Dot(u, u)), lv = std::sqrt(Dot(v, v));
    const double den = lu * lv * (lu * lv + Dot(u, v));
    if (!(den > 0))
    {
      continue; // q on the edge's line outside it: no field from it
    }
    const double f = (lu + lv) / den;
    gradient[0] += f * (u[1] * v[2] - u[2] * v[1]);
    gradient[1] += f * (u[2] * v[0] - u[0] * v[2]);
    gradient[2] += f * (u[0] * v[1] - u[1] * v[0]);
  }
}

void WindingNumber::Build(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
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
  // First-order tensor T_ij = sum of m_i (g - c)_j (m the vector area, g the centroid:
  // exact for flat triangles) and the second moment of area about the centre, the sum of
  // a (|g - c|^2 + sum_k |p_k - g|^2 / 12) (a triangle's moment about its centroid is a/12
  // times its corners' squared distances from it).
  std::fill(node.Tensor, node.Tensor + 9, 0.0);
  double second = 0;
  for (int64_t i = first; i < first + count; ++i)
  {
    const double* p = corners.data() + 9 * order[i];
    const double* g = centroids.data() + 3 * order[i];
    const double e[3] = { p[3] - p[0], p[4] - p[1], p[5] - p[2] };
    const double f[3] = { p[6] - p[0], p[7] - p[1], p[8] - p[2] };
    const double m[3] = { 0.5 * (e[1] * f[2] - e[2] * f[1]),
      0.5 * (e[2] * f[0] - e[0] * f[2]),
      0.5 * (e[0] * f[1] - e[1] * f[0]) };
    const double s[3] = { g[0] - node.Centre[0], g[1] - node.Centre[1], g[2] - node.Centre[2] };
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        node.Tensor[3 * a + b] += m[a] * s[b];
      }
    }
    double spread = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double v[3] = { p[3 * k] - g[0], p[3 * k + 1] - g[1], p[3 * k + 2] - g[2] };
      spread += Dot(v, v);
    }
    second += std::sqrt(Dot(m, m)) * (Dot(s, s) + spread / 12);
  }
  // Rounding can only make the bound a little small; the factor covers it.
  node.Second = second * (1 + 1e-12);
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

bool WindingNumber::FarTerm(const Node& node, const double q[3], double& term, double& bound) const
{
  const double d[3] = { node.Centre[0] - q[0], node.Centre[1] - q[1], node.Centre[2] - q[2] };
  const double r2 = Dot(d, d);
  const double r = std::sqrt(r2);
  const double gap = r - node.Radius;
  if (!(gap > 0))
  {
    return false;
  }
  // Order 1 (WindingNumber.h): M . d / r^3 + (tr T - 3 d.T.d / r^2) / r^3.
  const double* t = node.Tensor;
  const double td[3] = { t[0] * d[0] + t[1] * d[1] + t[2] * d[2],
    t[3] * d[0] + t[4] * d[1] + t[5] * d[2],
    t[6] * d[0] + t[7] * d[1] + t[8] * d[2] };
  const double r3 = r2 * r;
  term = (Dot(node.Moment, d) + t[0] + t[4] + t[8] - 3 * Dot(d, td) / r2) / (FourPi * r3);
  const double gap2 = gap * gap;
  bound = 3 * node.Second / (FourPi * gap2 * gap2);
  return true;
}

WindingValue WindingNumber::Evaluate(const double q[3]) const
{
  return this->Evaluate(q, this->Accuracy);
}

WindingValue WindingNumber::Evaluate(const double q[3], double accuracy) const
{
  WindingValue result;
  AngleProduct angles; // the exact part
  this->Walk(
    [&](const Node& node)
    {
      const double d[3] = { node.Centre[0] - q[0], node.Centre[1] - q[1], node.Centre[2] - q[2] };
      double term, bound;
      if (Dot(d, d) > accuracy * accuracy * node.Radius * node.Radius &&
        this->FarTerm(node, q, term, bound))
      {
        result.Value += term;
        result.Bound += bound;
        return false;
      }
      if (node.Children[0] < 0)
      {
        this->AddLeaf(node, q, angles);
      }
      return true;
    });
  result.Value += angles.Winding();
  return result;
}

void WindingNumber::AddLeaf(const Node& node, const double q[3], AngleProduct& angles) const
{
  for (int64_t t = node.First; t < node.First + node.Count; ++t)
  {
    const double* p = this->Corners.data() + 9 * t;
    angles.Add(p, p + 3, p + 6, q);
  }
}

WindingGradient WindingNumber::EvaluateWithGradient(const double q[3]) const
{
  WindingGradient result;
  AngleProduct angles;
  double angleGradient[3] = { 0, 0, 0 };
  this->Walk(
    [&](const Node& node)
    {
      const double d[3] = { node.Centre[0] - q[0], node.Centre[1] - q[1], node.Centre[2] - q[2] };
      const double r2 = Dot(d, d);
      double term, bound;
      if (r2 > this->Accuracy * this->Accuracy * node.Radius * node.Radius &&
        this->FarTerm(node, q, term, bound))
      {
        result.Value += term;
        result.Bound += bound;
        // The order-1 term's gradient in q (= minus its gradient in d):
        // f(d) = M.d / r^3 + tr T / r^3 - 3 d.T.d / r^5.
        const double* t = node.Tensor;
        const double td[3] = { t[0] * d[0] + t[1] * d[1] + t[2] * d[2],
          t[3] * d[0] + t[4] * d[1] + t[5] * d[2],
          t[6] * d[0] + t[7] * d[1] + t[8] * d[2] };
        const double dt[3] = { t[0] * d[0] + t[3] * d[1] + t[6] * d[2],
          t[1] * d[0] + t[4] * d[1] + t[7] * d[2],
          t[2] * d[0] + t[5] * d[1] + t[8] * d[2] };
        const double r = std::sqrt(r2);
        const double r3 = r2 * r, r5 = r3 * r2;
        const double md = Dot(node.Moment, d), trace = t[0] + t[4] + t[8], dtd = Dot(d, td);
        for (int a = 0; a < 3; ++a)
        {
          const double df = node.Moment[a] / r3 - 3 * (md + trace) * d[a] / r5 -
            3 * (td[a] + dt[a]) / r5 + 15 * dtd * d[a] / (r5 * r2);
          result.Gradient[a] -= df / FourPi;
        }
        // Its error: half the third derivative of G (norm <= 4!/g^5) times the second
        // moment, over 4 pi.
        const double gap = r - node.Radius, gap2 = gap * gap;
        result.GradientBound += 3 * node.Second / (M_PI * gap2 * gap2 * gap);
        return false;
      }
      if (node.Children[0] < 0)
      {
        for (int64_t t = node.First; t < node.First + node.Count; ++t)
        {
          const double* p = this->Corners.data() + 9 * t;
          angles.Add(p, p + 3, p + 6, q);
          double g[3];
          TriangleSolidAngleGradient(p, p + 3, p + 6, q, g);
          for (int a = 0; a < 3; ++a)
          {
            angleGradient[a] += g[a];
          }
        }
      }
      return true;
    });
  result.Value += angles.Winding();
  for (int a = 0; a < 3; ++a)
  {
    result.Gradient[a] += angleGradient[a] / FourPi;
  }
  return result;
}

double WindingNumber::HessianBound(const double c[3], double radius) const
{
  // A triangle's term has a Hessian of norm at most its area times |D^3 (1/|x|)| / 4 pi
  // <= 6 / (4 pi g^4), g its distance from the point: 3 A / (2 pi g^4) per node.
  double bound = 0;
  bool touching = false;
  this->Walk(
    [&](const Node& node)
    {
      if (touching)
      {
        return false; // the answer is known: take no more nodes
      }
      const double d[3] = { node.Centre[0] - c[0], node.Centre[1] - c[1], node.Centre[2] - c[2] };
      const double gap = std::sqrt(Dot(d, d)) - node.Radius - radius;
      if (gap > node.Radius + radius)
      {
        const double gap2 = gap * gap;
        bound += 3 * node.Area / (2 * M_PI * gap2 * gap2);
        return false;
      }
      if (node.Children[0] < 0)
      {
        // Each triangle from the ball around its centroid through its farthest corner.
        for (int64_t t = node.First; t < node.First + node.Count; ++t)
        {
          const double* ball = this->Balls.data() + 4 * t;
          const double to[3] = { ball[0] - c[0], ball[1] - c[1], ball[2] - c[2] };
          const double g = std::sqrt(Dot(to, to)) - ball[3] - radius;
          if (!(g > 0))
          {
            touching = true;
            return false;
          }
          const double g2 = g * g;
          bound += 3 * this->Areas[t] / (2 * M_PI * g2 * g2);
        }
      }
      return true;
    });
  return touching ? HUGE_VAL : bound;
}

void WindingNumber::Flatten(std::vector<double>& nodes, std::vector<int32_t>& links) const
{
  nodes.clear();
  links.clear();
  nodes.reserve(NodeDoubles * this->Nodes.size());
  links.reserve(4 * this->Nodes.size());
  for (const Node& node : this->Nodes)
  {
    nodes.insert(nodes.end(), node.Centre, node.Centre + 3);
    nodes.push_back(node.Radius);
    nodes.insert(nodes.end(), node.Moment, node.Moment + 3);
    nodes.insert(nodes.end(), node.Tensor, node.Tensor + 9);
    nodes.push_back(node.Second);
    links.insert(links.end(),
      { static_cast<int32_t>(node.First),
        static_cast<int32_t>(node.Count),
        node.Children[0],
        node.Children[1] });
  }
}

AngleProduct WindingNumber::ExactAngles(const double q[3]) const
{
  AngleProduct angles;
  for (size_t t = 0; t < this->Corners.size(); t += 9)
  {
    const double* p = this->Corners.data() + t;
    angles.Add(p, p + 3, p + 6, q);
  }
  return angles;
}

double WindingNumber::Exact(const double q[3]) const
{
  return this->ExactAngles(q).Winding();
}

bool WindingNumber::Inside(const double q[3], double* value, bool* exact) const
{
  auto decides = [](const WindingValue& w)
  { return std::fabs(std::fabs(w.Value) - 0.5) > w.Bound + RoundingSlack; };
  if (exact)
  {
    *exact = false;
  }
  if (value)
  {
    // w wanted as well: to ValueAccuracy at least.
    const WindingValue w = this->Evaluate(q, std::max(this->Accuracy, ValueAccuracy));
    if (decides(w))
    {
      *value = w.Value;
      return std::fabs(w.Value) > 0.5;
    }
  }
  else
  {
    // Cheap first: a coarse accuracy decides most samples; then the fine one.
    for (const double accuracy : { std::min(CoarseAccuracy, this->Accuracy), this->Accuracy })
    {
      const WindingValue w = this->Evaluate(q, accuracy);
      if (decides(w))
      {
        return std::fabs(w.Value) > 0.5;
      }
    }
  }
  // The exact sum, whose sign comes from its count of turns (AngleProduct::Inside).
  const AngleProduct angles = this->ExactAngles(q);
  if (value)
  {
    *value = angles.Winding();
  }
  if (exact)
  {
    *exact = true;
  }
  return angles.Inside();
}

} // namespace vtkdf
