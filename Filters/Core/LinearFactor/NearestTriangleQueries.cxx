#include "LinearFactor/NearestTriangleQueries.h"

#include "Common/FloatBounds.h"
#include "Common/LargeVector.h"
#include "Common/PointTriangleDistance.h"
#include "Common/Vector3.h"
#include "LinearFactor/QueryTree.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

namespace vtkdf
{
namespace
{
using nearest::Primitive;
using nearest::QueryTree;
} // namespace

double QueriedSamples(const MeshInput& mesh, const SampleGrid& wholeGrid, double maximumDistance)
{
  const double samples = double(wholeGrid.Whole.Count());
  if (!(maximumDistance > 0))
  {
    return samples;
  }
  // Within the band: about its volume (twice the cap times the surface's area) over a
  // sample's cell. Beyond it a query stops at the tree's first levels: a 64th of one.
  double area = 0;
  const double* P = mesh.Points.data();
  for (size_t t = 0; t + 2 < mesh.Triangles.size(); t += 3)
  {
    const double* a = P + 3 * mesh.Triangles[t];
    const double* b = P + 3 * mesh.Triangles[t + 1];
    const double* c = P + 3 * mesh.Triangles[t + 2];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    double n[3];
    Cross(u, v, n);
    area += 0.5 * std::sqrt(Dot(n, n));
  }
  const double cell = wholeGrid.Spacing[0] * wholeGrid.Spacing[1] * wholeGrid.Spacing[2];
  const double band = 2 * maximumDistance * area / cell;
  return std::min(samples, std::max(band, samples / 64));
}

bool PreferSampleQueries(const MeshInput& mesh, const SampleGrid& wholeGrid, double maximumDistance)
{
  const double primitives = double(mesh.Triangles.size() / 3) + double(mesh.Segments.size() / 2) +
    double(mesh.Vertices.size());
  return primitives >=
    SampleQueriesCellsPerSample * QueriedSamples(mesh, wholeGrid, maximumDistance);
}

namespace
{
/// What a sample's query writes into the arrays (local frame in, world units out).
struct SampleWriter
{
  const QueryTree& Tree;
  const LocalFieldArrays& Arrays;
  bool WantFeature;          // the closest cell or the sign needs the feature's cell
  std::vector<int8_t>& Side; // a narrow band's sides (empty: none kept)
  float WorldCap;            // the band's distance in world units

  /// A sample beyond the band: the cap, no closest feature.
  void Beyond(int64_t at) const
  {
    const LocalFieldArrays& arrays = this->Arrays;
    if (arrays.Distance)
    {
      arrays.Distance[at] = this->WorldCap;
    }
    if (arrays.ClosestCellId)
    {
      arrays.ClosestCellId[at] = -1;
    }
    if (arrays.ClosestFeature)
    {
      arrays.ClosestFeature[at] = 255;
    }
    if (arrays.ClosestPoint)
    {
      std::fill(arrays.ClosestPoint + 3 * at, arrays.ClosestPoint + 3 * at + 3, NAN);
    }
  }

  /// Sample `at` (at x) whose nearest primitive is `index`, at squared distance best2,
  /// closest point `closest` on its `feature`.
  void Answer(int64_t at,
    const double x[3],
    int64_t index,
    double best2,
    const double closest[3],
    int feature) const
  {
    const LocalFieldArrays& arrays = this->Arrays;
    const Primitive& t = this->Tree.Get(index);
    // The feature: 0 vertex, 1 edge, 2 face (the site types).
    const uint8_t type = feature == InFace ? 2 : (feature >= OnEdgeAB ? 1 : 0);
    int64_t cell = this->Tree.Cell(index);
    double normal[3] = { 0, 0, 0 };
    if (this->WantFeature && type != 2)
    {
      const int first = feature >= OnEdgeAB ? feature - OnEdgeAB : feature;
      const double* a = t.X + 3 * first;
      const double* b = type == 1 ? t.X + 3 * ((first + 1) % 3) : nullptr;
      this->Tree.FeatureCellAndNormal(a, b, cell, normal);
    }
    if (arrays.Distance)
    {
      float value = static_cast<float>(std::sqrt(best2) * arrays.Frame.Scale);
      if (arrays.Signed)
      {
        if (type == 2)
        {
          this->Tree.FaceNormalOf(index, normal);
        }
        const double d[3] = { closest[0] - x[0], closest[1] - x[1], closest[2] - x[2] };
        const double s = d[0] * normal[0] + d[1] * normal[1] + d[2] * normal[2];
        value = s > 0 ? -value : value;
        if (!this->Side.empty())
        {
          this->Side[at] = s > 0 ? -1 : 1;
        }
      }
      arrays.Distance[at] = value;
    }
    if (arrays.ClosestCellId)
    {
      arrays.ClosestCellId[at] = cell;
    }
    if (arrays.ClosestFeature)
    {
      arrays.ClosestFeature[at] = type;
    }
    if (arrays.ClosestPoint)
    {
      for (int a = 0; a < 3; ++a)
      {
        arrays.ClosestPoint[3 * at + a] = static_cast<float>(arrays.Frame.ToWorld(a, closest[a]));
      }
    }
  }
};
} // namespace

bool QueryNearestTriangles(const MeshInput& mesh,
  const LocalFieldRequest& request,
  const LocalFieldArrays& arrays,
  const Execution& execution,
  ScanStatistics& stats,
  std::string& error)
{
  stats = ScanStatistics();
  QueryTree tree;
  if (!tree.Build(mesh, execution.For, error))
  {
    return false;
  }
  execution.EndStage("tree");
  const IndexBox& ext = request.Extent;
  const SampleGrid& grid = request.Grid;
  const int64_t nx = ext.Size(0), ny = ext.Size(1), rows = ny * ext.Size(2);
  stats.Samples = ext.Count();
  const GridFrame& frame = arrays.Frame;
  const bool wantFeature = arrays.ClosestCellId || arrays.Signed;
  // A narrow band: samples farther than the cap hold it, with no closest feature; their
  // sides are flooded from the band's afterwards (FloodBandSides), as the scan does.
  const double cap = request.MaximumDistance;
  const bool banded = std::isfinite(cap);
  const double capBound2 = banded ? cap * cap * (1 + 1e-9) + tree.Tolerance2 : HUGE_VAL;
  const float worldCap = banded ? static_cast<float>(cap * frame.Scale) : 0.0f;
  std::vector<int8_t> side(banded && arrays.Signed && arrays.Distance ? stats.Samples : 0, 0);
  const SampleWriter writer{ tree, arrays, wantFeature, side, worldCap };
  std::atomic<int64_t> evaluations{ 0 };
  // Rows are independent: each is walked in x, every sample seeded with the previous
  // sample's closest point (the distance to it bounds the next one's). Seeds change the
  // work, never the answer.
  auto queryRows = [&](int64_t rowBegin, int64_t rowEnd)
  {
    int64_t count = 0;
    for (int64_t row = rowBegin; row < rowEnd; ++row)
    {
      const double y = grid.Coordinate(1, ext.Lo[1] + static_cast<int>(row % ny));
      const double z = grid.Coordinate(2, ext.Lo[2] + static_cast<int>(row / ny));
      double previous[3] = { 0, 0, 0 };
      bool seeded = false;
      for (int64_t at = row * nx, i = ext.Lo[0]; at < (row + 1) * nx; ++at, ++i)
      {
        const double x[3] = { grid.Coordinate(0, static_cast<int>(i)), y, z };
        double bound2 = capBound2;
        if (seeded)
        {
          double r2 = 0;
          for (int a = 0; a < 3; ++a)
          {
            r2 += (x[a] - previous[a]) * (x[a] - previous[a]);
          }
          bound2 = std::min(bound2, r2 * (1 + 1e-9) + tree.Tolerance2);
        }
        int64_t index;
        double best2, closest[3];
        int feature = InFace;
        count += tree.Nearest(x, bound2, index, best2, closest, feature);
        if (index < 0 && bound2 < capBound2)
        {
          // The seed fell short by rounding: search without it.
          count += tree.Nearest(x, capBound2, index, best2, closest, feature);
        }
        if (index < 0 || (banded && std::sqrt(best2) > cap))
        {
          // Beyond the band (the previous seed, a point of the mesh, still bounds the next
          // sample's distance).
          writer.Beyond(at);
          continue;
        }
        std::copy(closest, closest + 3, previous);
        seeded = true;
        writer.Answer(at, x, index, best2, closest, feature);
      }
    }
    evaluations += count;
  };
  // Batches of rows report progress (and may abort) between them.
  const int64_t batches = std::min<int64_t>(rows, 64);
  for (int64_t batch = 0; batch < batches; ++batch)
  {
    const int64_t begin = rows * batch / batches, end = rows * (batch + 1) / batches;
    if (execution.For)
    {
      execution.For(end - begin, 1, [&](int64_t b, int64_t e) { queryRows(begin + b, begin + e); });
    }
    else
    {
      queryRows(begin, end);
    }
    if (!execution.Report(double(batch + 1) / batches))
    {
      stats.Aborted = true;
      break;
    }
  }
  stats.Evaluations = evaluations.load();
  if (!side.empty() && !stats.Aborted)
  {
    FloodBandSides(ext, side, arrays.Distance, worldCap);
  }
  return true;
}

} // namespace vtkdf
