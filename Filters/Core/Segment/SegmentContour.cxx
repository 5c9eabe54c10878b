#include "Segment/SegmentContour.h"

#include "Common/PointTriangleDistance.h"

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

double Length(const double* p, const double* q)
{
  return std::sqrt(
    (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

// The volume spanned by three unit normals above which a feature is a corner.
constexpr double CornerSpread = 0.1;

/// A cell's corners (sample indices), their regions, and its edges: axis, first corner
/// and whether an interface crosses it.
struct CellCorners
{
  int64_t Corner[8];
  int32_t Region[8];
  bool Interface[12];
  int Axis[12];
  int64_t Start[12];
};

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

  /// The tangent planes at the cell's corners: each corner's closest point and the unit
  /// direction from it to the corner. None for a corner on the surface (no direction)
  /// or farther than a cell diagonal from it (its plane touches the surface elsewhere).
  int TangentPlanes(const int64_t corner[8],
    double point[8][3],
    double normal[8][3],
    int which[8]) const
  {
    const double* h = this->In.Grid.Spacing.data();
    const double smallest = std::min({ h[0], h[1], h[2] });
    const double diagonal = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    int count = 0;
    for (int c = 0; c < 8; ++c)
    {
      double p[3];
      this->Position(corner[c], p);
      const double* q = this->In.ClosestPoint + 3 * corner[c];
      const double d = Length(p, q);
      if (!(d > 1e-6 * smallest && d <= diagonal))
      {
        continue;
      }
      for (int a = 0; a < 3; ++a)
      {
        point[count][a] = q[a];
        normal[count][a] = (p[a] - q[a]) / d;
      }
      which[count++] = c;
    }
    return count;
  }

  /// The point nearest the planes in the least-squares sense, pulled towards x0 with a
  /// weight of 2% of a plane's (so it stays at x0 along directions the planes leave
  /// free: along a crease, across a flat piece). False (x unset) when that point is
  /// outside the cell of lowest sample v0 grown by one spacing, or cannot be on the
  /// surface: inside a corner's empty ball (radius its distance) by more than a quarter
  /// spacing, as where the planes of two nearby sheets meet between them.
  bool FeaturePoint(int count,
    const double point[][3],
    const double normal[][3],
    const double x0[3],
    int64_t v0,
    const int64_t corner[8],
    double x[3]) const
  {
    double m[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } }, b[3] = { 0, 0, 0 };
    for (int i = 0; i < count; ++i)
    {
      const double* n = normal[i];
      const double offset = n[0] * point[i][0] + n[1] * point[i][1] + n[2] * point[i][2];
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          m[r][c] += n[r] * n[c];
        }
        b[r] += n[r] * offset;
      }
    }
    const double pull = 0.02 * std::max(count, 1);
    for (int r = 0; r < 3; ++r)
    {
      m[r][r] += pull;
      b[r] += pull * x0[r];
    }
    // Cramer's rule: m is symmetric positive definite.
    auto det = [](const double a[3][3])
    {
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
        a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
        a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double whole = det(m);
    double lo[3], solution[3];
    this->Position(v0, lo);
    for (int a = 0; a < 3; ++a)
    {
      double column[3][3];
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          column[r][c] = c == a ? b[r] : m[r][c];
        }
      }
      const double value = whole > 0 ? det(column) / whole : x0[a];
      const double h = this->In.Grid.Spacing[a];
      if (!(value >= lo[a] - 2 * h && value <= lo[a] + 3 * h))
      {
        return false; // farther: the planes meet away from this cell's piece of surface
      }
      solution[a] = value;
    }
    const double* h = this->In.Grid.Spacing.data();
    const double quarter = 0.25 * std::min({ h[0], h[1], h[2] });
    // A surface point within half a spacing: the closest point of a sample within two
    // spacings of the cell (an apex is the closest point of the samples past it). Where
    // the planes meet beyond the end of a thin part, or between two sheets, none is.
    if (!this->NearClosestPoint(v0, solution, 2 * quarter))
    {
      return false;
    }
    for (int c = 0; c < 8; ++c)
    {
      double p[3];
      this->Position(corner[c], p);
      if (Length(p, this->In.ClosestPoint + 3 * corner[c]) - Length(p, solution) > quarter)
      {
        return false;
      }
    }
    std::copy(solution, solution + 3, x);
    return true;
  }

  /// Whether a sample within two spacings of the cell of lowest sample v0 has its
  /// closest point within `radius` of x.
  bool NearClosestPoint(int64_t v0, const double x[3], double radius) const
  {
    const int64_t ijk[3] = {
      v0 % this->N[0], (v0 / this->N[0]) % this->N[1], v0 / this->Stride[2]
    };
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::max<int64_t>(ijk[a] - 2, 0);
      hi[a] = std::min<int64_t>(ijk[a] + 3, this->N[a] - 1);
    }
    for (int64_t k = lo[2]; k <= hi[2]; ++k)
    {
      for (int64_t j = lo[1]; j <= hi[1]; ++j)
      {
        for (int64_t i = lo[0]; i <= hi[0]; ++i)
        {
          const double* q =
            this->In.ClosestPoint + 3 * (i + j * this->Stride[1] + k * this->Stride[2]);
          if (Length(q, x) <= radius)
          {
            return true;
          }
        }
      }
    }
    return false;
  }

  /// Extended marching cubes: when the cell's surface is one piece whose tangent planes
  /// differ by more than FeatureAngle, that piece as a fan around the feature point with
  /// the same border (the border's points are shared with the neighbours). The case's
  /// triangles are `edges` (edge indices, -1 after the last).
  bool FeatureFan(const int64_t corner[8],
    const int32_t region[8],
    int32_t lo,
    int32_t hi,
    const int* edges,
    const int64_t start[12],
    const int axis[12],
    int64_t v0)
  {
    double point[8][3], normal[8][3];
    int which[8];
    const int count = this->TangentPlanes(corner, point, normal, which);
    if (count < 2)
    {
      return false;
    }
    // The planes' normals, each turned towards the higher region, against each other.
    const double limit = std::cos(this->In.FeatureAngle * M_PI / 180);
    double oriented[8][3];
    bool feature = false;
    for (int i = 0; i < count; ++i)
    {
      const double s = region[which[i]] == hi ? 1 : -1;
      for (int a = 0; a < 3; ++a)
      {
        oriented[i][a] = s * normal[i][a];
      }
      for (int j = 0; j < i && !feature; ++j)
      {
        feature = oriented[i][0] * oriented[j][0] + oriented[i][1] * oriented[j][1] +
            oriented[i][2] * oriented[j][2] <
          limit;
      }
    }
    // A corner (an apex, the tip of a thin part): the normals span space. Along a
    // crease they lie in one plane, and fans there would set a row of teeth along it
    // (extended marching cubes flips edges to join them); marching cubes' chamfer of a
    // crease stays within a cell.
    double spread = 0;
    for (int i = 0; i < count && feature; ++i)
    {
      for (int j = 0; j < i; ++j)
      {
        const double* u = oriented[i];
        const double* w = oriented[j];
        const double c[3] = {
          u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]
        };
        for (int k = 0; k < j; ++k)
        {
          spread = std::max(spread,
            std::fabs(c[0] * oriented[k][0] + c[1] * oriented[k][1] + c[2] * oriented[k][2]));
        }
      }
    }
    if (!feature || spread < CornerSpread)
    {
      return false;
    }
    // One piece only: its triangles joined through shared edges.
    int parent[12];
    for (int e = 0; e < 12; ++e)
    {
      parent[e] = e;
    }
    auto find = [&parent](int e)
    {
      while (parent[e] != e)
      {
        e = parent[e] = parent[parent[e]];
      }
      return e;
    };
    int triangles = 0;
    for (; triangles < 5 && edges[3 * triangles] >= 0; ++triangles)
    {
      const int* t = edges + 3 * triangles;
      parent[find(t[1])] = find(t[0]);
      parent[find(t[2])] = find(t[0]);
    }
    for (int i = 1; i < 3 * triangles; ++i)
    {
      if (find(edges[i]) != find(edges[0]))
      {
        return false;
      }
    }
    double x0[3] = { 0, 0, 0 };
    bool used[12] = { false };
    int points = 0;
    for (int i = 0; i < 3 * triangles; ++i)
    {
      if (!used[edges[i]])
      {
        used[edges[i]] = true;
        const double* p = &this->Out.Points[3 * this->EdgePoint(start[edges[i]], axis[edges[i]])];
        for (int a = 0; a < 3; ++a)
        {
          x0[a] += p[a];
        }
        ++points;
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      x0[a] /= points;
    }
    double x[3];
    if (!this->FeaturePoint(count, point, normal, x0, v0, corner, x))
    {
      return false;
    }
    // Only where marching cubes' piece misses the feature point by more than a quarter
    // of a spacing: elsewhere it already holds it, and a fan would only add a tooth.
    double nearest = HUGE_VAL;
    for (int t = 0; t < triangles; ++t)
    {
      const double* p[3];
      for (int k = 0; k < 3; ++k)
      {
        const int e = edges[3 * t + k];
        p[k] = &this->Out.Points[3 * this->EdgePoint(start[e], axis[e])];
      }
      nearest = std::min(nearest, SquaredDistanceToTriangle(x, p[0], p[1], p[2]));
    }
    const double* h = this->In.Grid.Spacing.data();
    const double quarter = 0.25 * std::min({ h[0], h[1], h[2] });
    if (nearest <= quarter * quarter)
    {
      return false;
    }
    const int64_t centre = this->AddPoint(x);
    // The border: the triangles' directed edges whose reverse is not among them.
    for (int i = 0; i < 3 * triangles; ++i)
    {
      const int a = edges[i], b = edges[i % 3 == 2 ? i - 2 : i + 1];
      bool inner = false;
      for (int j = 0; j < 3 * triangles && !inner; ++j)
      {
        inner = edges[j] == b && edges[j % 3 == 2 ? j - 2 : j + 1] == a;
      }
      if (!inner && a != b)
      {
        this->AddTriangle(
          this->EdgePoint(start[a], axis[a]), this->EdgePoint(start[b], axis[b]), centre, lo, hi);
      }
    }
    ++this->Out.FeatureCells;
    return true;
  }

  /// The surface in the cell whose first corner is sample v0: none within one region;
  /// the case table's triangles where the cell has two regions and every edge between
  /// them holds an interface (MarchingCell); else a cell vertex and its fan (JunctionCell).
  void Cell(int64_t v0)
  {
    CellCorners cell;
    for (int c = 0; c < 8; ++c)
    {
      cell.Corner[c] = v0 + CornerOffset[c][0] * this->Stride[0] +
        CornerOffset[c][1] * this->Stride[1] + CornerOffset[c][2] * this->Stride[2];
      cell.Region[c] = this->In.Region[cell.Corner[c]];
    }
    int32_t lo = cell.Region[0], hi = cell.Region[0];
    bool twoRegions = true;
    for (int c = 1; c < 8; ++c)
    {
      if (cell.Region[c] != lo && cell.Region[c] != hi)
      {
        if (lo == hi)
        {
          lo = std::min(lo, cell.Region[c]);
          hi = std::max(hi, cell.Region[c]);
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
    bool complete = twoRegions;
    bool any = false;
    for (int e = 0; e < 12; ++e)
    {
      const int a = EdgeCorners[e][0], b = EdgeCorners[e][1];
      cell.Axis[e] = CornerOffset[a][0] != CornerOffset[b][0]
        ? 0
        : (CornerOffset[a][1] != CornerOffset[b][1] ? 1 : 2);
      cell.Start[e] = cell.Corner[a];
      cell.Interface[e] = this->IsInterface(cell.Corner[a], cell.Axis[e]);
      complete = complete && (cell.Region[a] == cell.Region[b] || cell.Interface[e]);
      any = any || cell.Interface[e];
    }
    if (!any)
    {
      return;
    }
    if (complete)
    {
      this->MarchingCell(cell, lo, hi, v0);
    }
    else
    {
      this->JunctionCell(cell, v0);
    }
  }

  /// A cell of two regions whose interface crosses every edge between them: the case
  /// table's triangles, or a fan around a feature point (FeatureFan).
  void MarchingCell(const CellCorners& cell, int32_t lo, int32_t hi, int64_t v0)
  {
    int index = 0;
    for (int c = 0; c < 8; ++c)
    {
      index |= cell.Region[c] == lo ? (1 << c) : 0;
    }
    const int* edges = this->In.Cases[index];
    ++this->Out.MarchingCells;
    if (this->In.ClosestPoint &&
      this->FeatureFan(cell.Corner, cell.Region, lo, hi, edges, cell.Start, cell.Axis, v0))
    {
      return;
    }
    for (int i = 0; edges[i] >= 0 && i < 15; i += 3)
    {
      const int64_t p = this->EdgePoint(cell.Start[edges[i]], cell.Axis[edges[i]]);
      const int64_t q = this->EdgePoint(cell.Start[edges[i + 1]], cell.Axis[edges[i + 1]]);
      const int64_t r = this->EdgePoint(cell.Start[edges[i + 2]], cell.Axis[edges[i + 2]]);
      if (p != q && q != r && p != r)
      {
        this->AddTriangle(p, q, r, lo, hi);
      }
    }
  }

  /// A junction or boundary cell: a cell vertex (on the junction line or the open rim
  /// that the tangent planes meet at, with closest points), the interface's points on
  /// the faces, and the triangles joining them, each facing its pair's higher region.
  void JunctionCell(const CellCorners& cell, int64_t v0)
  {
    const int64_t* corner = cell.Corner;
    const int32_t* region = cell.Region;
    const bool* interface = cell.Interface;
    const int* axis = cell.Axis;
    const int64_t* start = cell.Start;
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
    if (this->In.ClosestPoint)
    {
      // On the junction line or the open rim that the tangent planes meet at.
      double point[8][3], normal[8][3];
      int which[8];
      const int planes = this->TangentPlanes(corner, point, normal, which);
      if (planes > 0)
      {
        const double mean[3] = { centre[0], centre[1], centre[2] };
        this->FeaturePoint(planes, point, normal, mean, v0, corner, centre);
      }
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

bool ContourSegmented(const ContourInput& input, ContourResult& result, const Execution& execution)
{
  result = ContourResult();
  Builder builder(input, result);
  const int* n = builder.N;
  for (int k = 0; k + 1 < n[2]; ++k)
  {
    if (!execution.Report(double(k) / (n[2] - 1)))
    {
      result = ContourResult();
      return false;
    }
    for (int j = 0; j + 1 < n[1]; ++j)
    {
      for (int i = 0; i + 1 < n[0]; ++i)
      {
        builder.Cell(i + j * builder.Stride[1] + k * builder.Stride[2]);
      }
    }
  }
  if (!execution.Report(1.0))
  {
    result = ContourResult();
    return false;
  }
  return true;
}

} // namespace vtkdf
