#include "SegmentContour.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace vtkdf
{

namespace
{
// Cell corners (offsets along x, y, z) and edges, in marching cubes' numbering.
constexpr int CornerOffset[8][3] = { { 0, 0, 0 },
  { 1, 0, 0 },
  { 1, 1, 0 },
  { 0, 1, 0 },
  { 0, 0, 1 },
  { 1, 0, 1 },
  { 1, 1, 1 },
  { 0, 1, 1 } };
constexpr int EdgeCorners[12][2] = { { 0, 1 },
  { 1, 2 },
  { 3, 2 },
  { 0, 3 },
  { 4, 5 },
  { 5, 6 },
  { 7, 6 },
  { 4, 7 },
  { 0, 4 },
  { 1, 5 },
  { 3, 7 },
  { 2, 6 } };
// Faces: their four edges, the axis they are normal to, and the corner at their lowest
// sample (which, with the axis, names the face in the grid).
constexpr int FaceEdges[6][4] = { { 0, 1, 2, 3 },
  { 4, 5, 6, 7 },
  { 0, 9, 4, 8 },
  { 2, 11, 6, 10 },
  { 3, 10, 7, 8 },
  { 1, 11, 5, 9 } };
constexpr int FaceAxis[6] = { 2, 2, 1, 1, 0, 0 };
constexpr int FaceCorner[6] = { 0, 4, 0, 3, 0, 1 };

struct Builder
{
  const ContourInput& In;
  ContourResult& Out;
  int N[3];
  int64_t Stride[3];
  std::unordered_map<int64_t, int64_t> EdgePoints, FacePoints;

  Builder(const ContourInput& in, ContourResult& out)
    : In(in)
    , Out(out)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->N[a] = in.Grid.Whole.Size(a);
    }
    this->Stride[0] = 1;
    this->Stride[1] = this->N[0];
    this->Stride[2] = int64_t(this->N[0]) * this->N[1];
  }

  void Position(int64_t v, double p[3]) const
  {
    const int64_t ijk[3] = { v % this->N[0], (v / this->N[0]) % this->N[1], v / this->Stride[2] };
    for (int a = 0; a < 3; ++a)
    {
      p[a] = this->In.Grid.Coordinate(a, this->In.Grid.Whole.Lo[a] + static_cast<int>(ijk[a]));
    }
  }

  /// Whether the grid edge from sample v along `axis` holds an interface (eqs. 5, 7).
  bool IsInterface(int64_t v, int axis) const
  {
    const int64_t u = v + this->Stride[axis];
    const double sum = double(this->In.Distance[v]) + this->In.Distance[u];
    return this->In.Region[v] != this->In.Region[u] && sum > 0 &&
      sum <= this->In.Grid.Spacing[axis] * (1 + this->In.Tolerance);
  }

  int64_t AddPoint(const double p[3])
  {
    this->Out.Points.insert(this->Out.Points.end(), p, p + 3);
    return static_cast<int64_t>(this->Out.Points.size() / 3 - 1);
  }

  /// The interface point of grid edge (v, axis), at eq. 6's position, made once.
  int64_t EdgePoint(int64_t v, int axis)
  {
    const int64_t key = 3 * v + axis;
    auto it = this->EdgePoints.find(key);
    if (it != this->EdgePoints.end())
    {
      return it->second;
    }
    const int64_t u = v + this->Stride[axis];
    const double dv = this->In.Distance[v], du = this->In.Distance[u];
    const double t = dv / (dv + du);
    double p[3];
    this->Position(v, p);
    p[axis] += t * this->In.Grid.Spacing[axis];
    const int64_t id = this->AddPoint(p);
    this->EdgePoints.emplace(key, id);
    return id;
  }

  void AddTriangle(int64_t a, int64_t b, int64_t c, int32_t lo, int32_t hi)
  {
    this->Out.Triangles.insert(this->Out.Triangles.end(), { a, b, c });
    this->Out.Pairs.insert(this->Out.Pairs.end(), { lo, hi });
  }

  void Cell(int64_t v0)
  {
    int64_t corner[8];
    int32_t region[8];
    for (int c = 0; c < 8; ++c)
    {
      corner[c] = v0 + CornerOffset[c][0] * this->Stride[0] + CornerOffset[c][1] * this->Stride[1] +
        CornerOffset[c][2] * this->Stride[2];
      region[c] = this->In.Region[corner[c]];
    }
    int32_t lo = region[0], hi = region[0];
    bool twoRegions = true;
    for (int c = 1; c < 8; ++c)
    {
      if (region[c] != lo && region[c] != hi)
      {
        if (lo == hi)
        {
          lo = std::min(lo, region[c]);
          hi = std::max(hi, region[c]);
        }
        else
        {
          twoRegions = false;
        }
      }
    }
    if (lo == hi)
    {
      return; // one region: no interface
    }
    // Which edges hold an interface, and whether every edge between the two regions
    // does (then the case table applies).
    bool interface[12];
    int axis[12];
    int64_t start[12];
    bool complete = twoRegions;
    bool any = false;
    for (int e = 0; e < 12; ++e)
    {
      const int a = EdgeCorners[e][0], b = EdgeCorners[e][1];
      axis[e] = CornerOffset[a][0] != CornerOffset[b][0]
        ? 0
        : (CornerOffset[a][1] != CornerOffset[b][1] ? 1 : 2);
      start[e] = corner[a];
      interface[e] = this->IsInterface(corner[a], axis[e]);
      complete = complete && (region[a] == region[b] || interface[e]);
      any = any || interface[e];
    }
    if (!any)
    {
      return;
    }
    if (complete)
    {
      int index = 0;
      for (int c = 0; c < 8; ++c)
      {
        index |= region[c] == lo ? (1 << c) : 0;
      }
      const int* edges = this->In.Cases[index];
      for (int i = 0; edges[i] >= 0 && i < 15; i += 3)
      {
        const int64_t p = this->EdgePoint(start[edges[i]], axis[edges[i]]);
        const int64_t q = this->EdgePoint(start[edges[i + 1]], axis[edges[i + 1]]);
        const int64_t r = this->EdgePoint(start[edges[i + 2]], axis[edges[i + 2]]);
        if (p != q && q != r && p != r)
        {
          this->AddTriangle(p, q, r, lo, hi);
        }
      }
      ++this->Out.MarchingCells;
      return;
    }

    // Junction or boundary: a cell vertex, face segments, and their triangles.
    double centre[3] = { 0, 0, 0 };
    int count = 0;
    int64_t point[12];
    for (int e = 0; e < 12; ++e)
    {
      if (interface[e])
      {
        point[e] = this->EdgePoint(start[e], axis[e]);
        for (int a = 0; a < 3; ++a)
        {
          centre[a] += this->Out.Points[3 * point[e] + a];
        }
        ++count;
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      centre[a] /= count;
    }
    const int64_t cellVertex = this->AddPoint(centre);
    auto pairOf = [&](int e)
    {
      const int32_t x = region[EdgeCorners[e][0]], y = region[EdgeCorners[e][1]];
      return std::make_pair(std::min(x, y), std::max(x, y));
    };
    // A triangle (cell vertex, point of edge e, q), facing the higher region of e.
    auto triangle = [&](int e, int64_t q)
    {
      const int64_t p = point[e];
      const double* x = &this->Out.Points[3 * p];
      const double* y = &this->Out.Points[3 * q];
      const double u[3] = { x[0] - centre[0], x[1] - centre[1], x[2] - centre[2] };
      const double w[3] = { y[0] - centre[0], y[1] - centre[1], y[2] - centre[2] };
      const double n[3] = {
        u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]
      };
      const auto pair = pairOf(e);
      // From the lower region's corner towards the higher's: along the edge's axis.
      const bool upward = region[EdgeCorners[e][1]] == pair.second;
      const double facing = upward ? n[axis[e]] : -n[axis[e]];
      if (facing == 0)
      {
        return; // degenerate
      }
      if (facing > 0)
      {
        this->AddTriangle(cellVertex, p, q, pair.first, pair.second);
      }
      else
      {
        this->AddTriangle(cellVertex, q, p, pair.first, pair.second);
      }
    };
    for (int f = 0; f < 6; ++f)
    {
      int on[4], k = 0;
      for (int i = 0; i < 4; ++i)
      {
        if (interface[FaceEdges[f][i]])
        {
          on[k++] = FaceEdges[f][i];
        }
      }
      if (k == 2 && pairOf(on[0]) == pairOf(on[1]))
      {
        triangle(on[0], point[on[1]]);
      }
      else if (k >= 2)
      {
        const int64_t key = 3 * corner[FaceCorner[f]] + FaceAxis[f];
        auto it = this->FacePoints.find(key);
        if (it == this->FacePoints.end())
        {
          double m[3] = { 0, 0, 0 };
          for (int i = 0; i < k; ++i)
          {
            for (int a = 0; a < 3; ++a)
            {
              m[a] += this->Out.Points[3 * point[on[i]] + a] / k;
            }
          }
          it = this->FacePoints.emplace(key, this->AddPoint(m)).first;
        }
        for (int i = 0; i < k; ++i)
        {
          triangle(on[i], it->second);
        }
      }
    }
    ++this->Out.OtherCells;
  }
};
} // namespace

void ContourSegmented(const ContourInput& input, ContourResult& result)
{
  result = ContourResult();
  Builder builder(input, result);
  const int* n = builder.N;
  for (int k = 0; k + 1 < n[2]; ++k)
  {
    for (int j = 0; j + 1 < n[1]; ++j)
    {
      for (int i = 0; i + 1 < n[0]; ++i)
      {
        builder.Cell(i + j * builder.Stride[1] + k * builder.Stride[2]);
      }
    }
  }
}

} // namespace vtkdf
