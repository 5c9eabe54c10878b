#include "MedialAxis.h"

#include <atomic>

namespace vtkdf
{

int64_t MedialAxisCPU(const MedialInput& input,
  uint8_t* medial,
  double* cosine,
  const ParallelFor& parallelFor)
{
  const IndexBox& whole = input.Grid.Whole;
  const int n[3] = { whole.Size(0), whole.Size(1), whole.Size(2) };
  const int64_t stride[3] = { 1, n[0], int64_t(n[0]) * n[1] };
  const double threshold = std::cos(input.SeparationAngle * M_PI / 180.0);
  const double depth = MedialMinimumDepth;
  std::atomic<int64_t> total{ 0 };
  parallelFor(stride[2] * n[2],
    4096,
    [&](int64_t begin, int64_t end)
    {
      int64_t count = 0;
      for (int64_t at = begin; at < end; ++at)
      {
        const int ijk[3] = { static_cast<int>(at % n[0]),
          static_cast<int>((at / n[0]) % n[1]),
          static_cast<int>(at / stride[2]) };
        const float d = input.Distance[at];
        const bool inRegion = input.Region == MedialRegion::Both ||
          (input.Region == MedialRegion::Inside ? d < 0 : d > 0);
        double best = 2;
        if (inRegion)
        {
          for (int a = 0; a < 3; ++a)
          {
            for (int side = -1; side <= 1; side += 2)
            {
              const int other = ijk[a] + side;
              if (other < 0 || other >= n[a])
              {
                continue;
              }
              const int64_t nb = at + side * stride[a];
              // This voxel is the pair's medial one: larger |distance|, ties to the lower index.
              const float dn = input.Distance[nb];
              const bool mine =
                std::fabs(d) > std::fabs(dn) || (std::fabs(d) == std::fabs(dn) && at < nb);
              // Too close to the surface, the angle says nothing (MedialAxis.h).
              if (!mine ||
                double(std::fmin(std::fabs(d), std::fabs(dn))) <= depth * input.Grid.Spacing[a])
              {
                continue;
              }
              double m[3];
              for (int c = 0; c < 3; ++c)
              {
                m[c] = input.Grid.Coordinate(c, whole.Lo[c] + ijk[c]);
              }
              m[a] += 0.5 * side * input.Grid.Spacing[a];
              const double cs =
                PairCosine(m, input.ClosestPoint + 3 * at, input.ClosestPoint + 3 * nb);
              if (cs <= threshold && cs < best)
              {
                best = cs;
              }
            }
          }
        }
        medial[at] = best <= 1 ? 1 : 0;
        cosine[at] = best;
        count += medial[at];
      }
      total += count;
    });
  return total.load();
}

} // namespace vtkdf
