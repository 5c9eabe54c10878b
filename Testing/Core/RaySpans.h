// The ray brute force that the union and penetration-depth core tests share: a ray's
// interval through a convex set of half-spaces, and where the ray first leaves a union of
// such sets.
#ifndef vtkdf_RaySpans_h
#define vtkdf_RaySpans_h

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

/// The parameters t of a ray o + t d inside every half-space n . x <= c seen so far.
struct RaySpan
{
  double Lo = -HUGE_VAL, Hi = HUGE_VAL;

  /// One half-space, as a = n . d and b = c - n . o: a t <= b.
  void Constrain(double a, double b)
  {
    if (a > 0)
    {
      this->Hi = std::min(this->Hi, b / a);
    }
    else if (a < 0)
    {
      this->Lo = std::max(this->Lo, b / a);
    }
    else if (b < 0)
    {
      this->Lo = HUGE_VAL;
    }
  }
  bool Empty() const { return !(this->Lo <= this->Hi); }

  /// Its part at t >= 0 into `spans`, when there is one.
  void AddTo(std::vector<std::pair<double, double>>& spans) const
  {
    if (!this->Empty() && this->Hi >= 0)
    {
      spans.emplace_back(std::max(this->Lo, 0.0), this->Hi);
    }
  }
};

/// Where a ray from inside the union of `spans` first leaves it: the spans that chain from
/// t = 0, merged.
inline double FirstExit(std::vector<std::pair<double, double>> spans)
{
  std::sort(spans.begin(), spans.end());
  double reach = 0;
  for (const auto& span : spans)
  {
    if (span.first > reach + 1e-12)
    {
      break;
    }
    reach = std::max(reach, span.second);
  }
  return reach;
}

/// Where a ray from outside first enters the union of `spans` (HUGE_VAL: never).
inline double FirstEntry(const std::vector<std::pair<double, double>>& spans)
{
  double first = HUGE_VAL;
  for (const auto& span : spans)
  {
    first = std::min(first, span.first);
  }
  return first;
}

#endif
