#include "Medial/MedialAxis.h"

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
  const auto& h = input.Grid.Spacing;
  const double halfDiagonal = 0.5 * std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  const double fanLeast = halfDiagonal * halfDiagonal * (MedialFanMargin * MedialFanMargin);
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
        double best = 2;
        // A voxel marks only cells whose corners are in the region and no deeper than it,
        // so its own |distance| bounds their D: D^2 <= d^2 - l^2/4 (most voxels stop here;
        // the 1e-6 keeps this test looser than the cell's, whatever the rounding).
        const double own = input.Distance[at];
        const bool candidate = InRegion(input.Distance[at], input.Region) &&
          own * own * (1 + 1e-6) - halfDiagonal * halfDiagonal > fanLeast;
        // The 8 cells this voxel is a corner of: as corner o, of the cell from ijk - o.
        for (int o = 0; o < 8 && candidate; ++o)
        {
          const int lo[3] = { ijk[0] - (o & 1), ijk[1] - ((o >> 1) & 1), ijk[2] - (o >> 2) };
          if (lo[0] < 0 || lo[1] < 0 || lo[2] < 0 || lo[0] + 1 >= n[0] || lo[1] + 1 >= n[1] ||
            lo[2] + 1 >= n[2])
          {
            continue;
          }
          const int64_t base = lo[0] + lo[1] * stride[1] + lo[2] * stride[2];
          float d[8];
          for (int k = 0; k < 8; ++k)
          {
            d[k] =
              input.Distance[base + (k & 1) + ((k >> 1) & 1) * stride[1] + (k >> 2) * stride[2]];
          }
          if (MarkedCorner(d, input.Region) != o)
          {
            continue;
          }
          const float* closest[8];
          double x[8][3];
          for (int k = 0; k < 8; ++k)
          {
            const int c[3] = { lo[0] + (k & 1), lo[1] + ((k >> 1) & 1), lo[2] + (k >> 2) };
            closest[k] = input.ClosestPoint + 3 * (c[0] + c[1] * stride[1] + c[2] * stride[2]);
            for (int a = 0; a < 3; ++a)
            {
              x[k][a] = input.Grid.Coordinate(a, whole.Lo[a] + c[a]);
            }
          }
          const MedialCellMeasure cell = MeasureMedialCell(d, closest, x, halfDiagonal, threshold);
          if (cell.Reach > MedialFanMargin && cell.Cosine <= threshold && cell.Cosine < best)
          {
            best = cell.Cosine;
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
