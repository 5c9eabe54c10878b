#include "SegmentBlend.h"

#include <cmath>

namespace vtkdf
{

void BlendSegmented(const SegmentedSamples& first,
  const SegmentedSamples& second,
  double t,
  int64_t count,
  float* distance,
  int32_t* region,
  const ParallelFor& parallelFor)
{
  auto body = [&](int64_t begin, int64_t end)
  {
    for (int64_t v = begin; v < end; ++v)
    {
      const double a = first.Distance[v], b = second.Distance[v];
      const int32_t ra = first.Region[v], rb = second.Region[v];
      // The ends exactly (the formulas below round at t = 0 and 1 otherwise).
      if (t == 0 || t == 1)
      {
        distance[v] = t == 0 ? first.Distance[v] : second.Distance[v];
        region[v] = t == 0 ? ra : rb;
      }
      else if (ra == rb)
      {
        distance[v] = static_cast<float>((1 - t) * a + t * b);
        region[v] = ra;
      }
      else
      {
        const double s = (1 - t) * -a + t * b;
        distance[v] = static_cast<float>(std::fabs(s));
        region[v] = s < 0 ? ra : rb;
      }
    }
  };
  if (parallelFor)
  {
    parallelFor(count, 4096, body);
  }
  else
  {
    body(0, count);
  }
}

} // namespace vtkdf
