#include "Winding/BrickWindingSigns.h"

#include <algorithm>
#include <cmath>

namespace vtkdf
{

namespace
{
/// The index of the grid's line nearest below (`down`) or above a coordinate along axis
/// a, one more line out: a bound that holds whatever the rounding (spacing > 0).
int64_t LineBound(const SampleGrid& grid, int a, double x, bool down)
{
  const double t = (x - grid.Origin[a]) / grid.Spacing[a];
  const double line = down ? std::floor(t) - 1 : std::ceil(t) + 1;
  return static_cast<int64_t>(std::min(std::max(line, -1e12), 1e12));
}

/// Each triangle's range of bricks along `axis`: those that hold a line its box may
/// reach.
void TriangleBrickRange(const LargeVector<double>& points,
  const int64_t* ids,
  const SampleGrid& grid,
  const BrickGrid& bricks,
  int axis,
  int& first,
  int& last)
{
  const double a = points[3 * ids[0] + axis], b = points[3 * ids[1] + axis],
               c = points[3 * ids[2] + axis];
  bricks.Range(axis,
    LineBound(grid, axis, std::min({ a, b, c }), true),
    LineBound(grid, axis, std::max({ a, b, c }), false),
    first,
    last);
}
} // namespace

void BrickWindingSigns::Prepare(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  const SampleGrid& grid,
  const BrickGrid& bricks,
  const ParallelFor& parallelFor)
{
  this->Grid = grid;
  this->Bricks = bricks;
  this->MeshPoints = &points;
  this->MeshTriangles = &triangles;
  // WindingSigns' choice of route (CrossingsApply, ComputeWindingSigns).
  const bool crossings = grid.Spacing[0] > 0 && grid.Spacing[1] > 0 && grid.Spacing[2] > 0;
  if (crossings && IsClosedChain(points, triangles))
  {
    this->Chosen = Route::Crossings;
    this->ChainPoints = &points;
    this->ChainTriangles = &triangles;
  }
  else
  {
    const WindingNumber& surface = this->MeshHierarchy();
    if (crossings && CloseWithCones(surface.TriangleCorners(), this->Closure))
    {
      this->Chosen = Route::Cones;
      this->Cones.Build(this->Closure.Points, this->Closure.Cone);
      this->ChainPoints = &this->Closure.Points;
      this->ChainTriangles = &this->Closure.Triangles;
    }
    else
    {
      this->Chosen = Route::Blocks;
    }
  }
  if (this->Chosen != Route::Blocks)
  {
    this->BinColumns(parallelFor);
  }
  this->ProveBricks(parallelFor);
}

const WindingNumber& BrickWindingSigns::MeshHierarchy() const
{
  std::call_once(
    this->SurfaceBuilt, [this]() { this->Surface.Build(*this->MeshPoints, *this->MeshTriangles); });
  return this->Surface;
}

void BrickWindingSigns::BinColumns(const ParallelFor& parallelFor)
{
  const LargeVector<int64_t>& chain = *this->ChainTriangles;
  const int64_t triangles = static_cast<int64_t>(chain.size() / 3);
  const int64_t columns = int64_t(this->Bricks.Counts[1]) * this->Bricks.Counts[2];
  std::vector<std::array<int, 4>> range(static_cast<size_t>(triangles));
  parallelFor(triangles,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t t = begin; t < end; ++t)
      {
        std::array<int, 4>& r = range[static_cast<size_t>(t)];
        TriangleBrickRange(
          *this->ChainPoints, &chain[3 * t], this->Grid, this->Bricks, 1, r[0], r[1]);
        TriangleBrickRange(
          *this->ChainPoints, &chain[3 * t], this->Grid, this->Bricks, 2, r[2], r[3]);
      }
    });
  auto forColumns = [&](const std::array<int, 4>& r, const auto& visit)
  {
    for (int k = r[2]; k <= r[3]; ++k)
    {
      for (int j = r[0]; j <= r[1]; ++j)
      {
        visit(j + int64_t(this->Bricks.Counts[1]) * k);
      }
    }
  };
  this->ColumnStart.assign(static_cast<size_t>(columns + 1), 0);
  for (const std::array<int, 4>& r : range)
  {
    forColumns(r, [&](int64_t c) { ++this->ColumnStart[static_cast<size_t>(c + 1)]; });
  }
  for (int64_t c = 0; c < columns; ++c)
  {
    this->ColumnStart[static_cast<size_t>(c + 1)] += this->ColumnStart[static_cast<size_t>(c)];
  }
  this->ColumnMembers.resize(static_cast<size_t>(this->ColumnStart.back()));
  std::vector<int64_t> next(this->ColumnStart.begin(), this->ColumnStart.end() - 1);
  for (int64_t t = 0; t < triangles; ++t)
  {
    forColumns(range[static_cast<size_t>(t)],
      [&](int64_t c)
      { this->ColumnMembers[static_cast<size_t>(next[static_cast<size_t>(c)]++)] = t; });
  }
}

LargeVector<int64_t> BrickWindingSigns::ColumnTriangles(int64_t column, double right) const
{
  const int64_t first = this->ColumnStart[static_cast<size_t>(column)];
  const int64_t last = this->ColumnStart[static_cast<size_t>(column + 1)];
  const LargeVector<double>& points = *this->ChainPoints;
  LargeVector<int64_t> ids;
  ids.reserve(static_cast<size_t>(3 * (last - first)));
  for (int64_t m = first; m < last; ++m)
  {
    const int64_t* t = &(*this->ChainTriangles)[static_cast<size_t>(3 * this->ColumnMembers[m])];
    if (std::min({ points[3 * t[0]], points[3 * t[1]], points[3 * t[2]] }) <= right)
    {
      ids.insert(ids.end(), t, t + 3);
    }
  }
  return ids;
}

void BrickWindingSigns::ProveBricks(const ParallelFor& parallelFor)
{
  const BrickGrid& bricks = this->Bricks;
  this->Proven.assign(static_cast<size_t>(bricks.Total()), -1);
  if (this->Chosen == Route::Blocks)
  {
    parallelFor(bricks.Total(),
      16,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t b = begin; b < end; ++b)
        {
          this->Proven[static_cast<size_t>(b)] = static_cast<int8_t>(
            WindingBoxSide(this->Surface, this->Grid, bricks.Extent(bricks.Indices(b))));
        }
      });
    return;
  }
  // Per column: the bricks that no triangle's box may meet, and N at each brick's first
  // sample from the crossings of the column's first line.
  const int64_t columns = int64_t(bricks.Counts[1]) * bricks.Counts[2];
  parallelFor(columns,
    1,
    [&](int64_t begin, int64_t end)
    {
      std::vector<uint8_t> touched;
      std::vector<int8_t> counts;
      for (int64_t c = begin; c < end; ++c)
      {
        const int bj = static_cast<int>(c % bricks.Counts[1]);
        const int bk = static_cast<int>(c / bricks.Counts[1]);
        const LargeVector<int64_t> ids = this->ColumnTriangles(c, HUGE_VAL);
        touched.assign(static_cast<size_t>(bricks.Counts[0]), 0);
        for (size_t t = 0; t < ids.size(); t += 3)
        {
          int first = 0, last = -1;
          TriangleBrickRange(*this->ChainPoints, &ids[t], this->Grid, bricks, 0, first, last);
          if (first <= last)
          {
            std::fill(touched.begin() + first, touched.begin() + last + 1, uint8_t(1));
          }
        }
        if (std::count(touched.begin(), touched.end(), uint8_t(0)) == 0)
        {
          continue;
        }
        IndexBox line = bricks.Extent({ { 0, bj, bk } });
        line.Lo[0] = bricks.Whole.Lo[0];
        line.Hi[0] = bricks.Whole.Hi[0];
        line.Hi[1] = line.Lo[1];
        line.Hi[2] = line.Lo[2];
        counts.resize(static_cast<size_t>(line.Count()));
        CrossingCounts(*this->ChainPoints, ids, this->Grid, line, counts.data(), SerialFor);
        for (int bi = 0; bi < bricks.Counts[0]; ++bi)
        {
          const IndexBox box = bricks.Extent({ { bi, bj, bk } });
          const int n = counts[static_cast<size_t>(box.Lo[0] - line.Lo[0])];
          if (touched[static_cast<size_t>(bi)] || n == CountUnknown)
          {
            continue;
          }
          const int side = this->Chosen == Route::Crossings
            ? (n != 0 ? 1 : 0)
            : WindingBoxSide(this->Cones, this->Grid, box, &n);
          this->Proven[static_cast<size_t>(bricks.Id(bi, bj, bk))] = static_cast<int8_t>(side);
        }
      }
    });
}

WindingSignStatistics BrickWindingSigns::Decide(const IndexBox& box,
  uint8_t* inside,
  const float* distance,
  double distanceScale) const
{
  WindingSignOptions options;
  if (this->Chosen == Route::Blocks)
  {
    options.Distance = distance;
    options.DistanceScale = distanceScale;
    return DecideWindingBlocks(this->Surface, this->Grid, box, inside, options, SerialFor);
  }
  int column[2];
  for (int a = 1; a < 3; ++a)
  {
    column[a - 1] = std::min(
      (box.Lo[a] - this->Bricks.Whole.Lo[a]) / this->Bricks.Size, this->Bricks.Counts[a] - 1);
  }
  // A triangle right of the box crosses none of its samples' rays.
  const LargeVector<int64_t> ids = this->ColumnTriangles(
    column[0] + int64_t(this->Bricks.Counts[1]) * column[1], this->Grid.Coordinate(0, box.Hi[0]));
  if (this->Chosen == Route::Crossings)
  {
    return CrossingSigns(*this->ChainPoints,
      ids,
      this->Grid,
      box,
      inside,
      SerialFor,
      [this]() -> const WindingNumber& { return this->MeshHierarchy(); });
  }
  // w = N - w_C, as WindingSigns' open meshes (the mesh's distance says nothing of w_C).
  std::vector<int8_t> counts(static_cast<size_t>(box.Count()));
  CrossingCounts(*this->ChainPoints, ids, this->Grid, box, counts.data(), SerialFor);
  return DecideWindingBlocks(
    this->Cones, this->Grid, box, inside, options, SerialFor, counts.data(), &this->Surface);
}

} // namespace vtkdf
