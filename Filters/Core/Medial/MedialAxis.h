// MedialAxis: the theta-simplified medial axis of a distance field (Sud et al., I3D 2006, §6.3, the
// separation-angle criterion of Foskey, Lin and Manocha's theta-SMA), without VTK types.
//
// The estimator works on the 2x2x2 cells of the grid. Each corner x_k of a cell has a
// closest-point direction u_k = (c(x_k) - x_k) / |c(x_k) - x_k|. The cell's aperture A
// is that of the smallest cone (spherical cap) holding the 8 directions, at most 180
// degrees (directions that no open half-space holds). Worst cases, for a medial set
// through the cell:
// - a sheet between two surface parts meeting at separation angle S: the corners on
//   each side see their own part, so A = S (exact for planar parts);
// - a line (a tube's axis) through the cell's interior: the corners surround it, their
//   directions (normal to the line, for a tube) no open half-space holds: A = 180;
// - a point (a sphere's centre) in the cell: the directions surround it in 3D: A = 180.
// So theta up to 180 finds axes and centres wherever the grid falls.
//
// Near the surface, a cell sees a fan of directions without any medial set: around a
// vertex or an edge (a reflex edge inside, any feature outside). If every corner's
// closest point is one point f, the corners (all at distance l/2 from the cell centre
// m, l the cell diagonal) lie in the ball B(m, l/2), so their directions lie in the cone
// from f around that ball: A <= 2 asin(l / 2D), D = |f - m|. And since |f - x_k| = d_k,
// D^2 = mean(d_k^2) - l^2/4 exactly (the corners' centroid is m). An edge gives the same
// bound (projected along it), a curved concave part less. So a cell counts only when
// sin(A/2) D > l/2 (with a small margin): no fan can explain its aperture. The test is
// the cell's own, not theta's, so a larger theta always keeps a subset.
//
// A cell whose 8 corners lie in the region and whose aperture counts and reaches theta
// marks one corner: the one of largest |distance| (ties: the lower voxel index), the
// corner nearest the medial set, which keeps the axis thin. Each voxel looks at its 8
// cells and writes only itself, so the pass is parallel and independent of the order.
#ifndef vtkdf_MedialAxis_h
#define vtkdf_MedialAxis_h

#include "Common/Parallel.h"
#include "Common/SampleGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vtkdf
{

enum class MedialRegion
{
  Inside,  // only voxels with a negative distance
  Outside, // only voxels with a positive distance
  Both
};

struct MedialInput
{
  SampleGrid Grid;                     // Grid.Whole: the voxels (x fastest)
  const float* Distance = nullptr;     // one per voxel
  const float* ClosestPoint = nullptr; // three per voxel
  double SeparationAngle = 90;         // degrees, in (0, 180)
  MedialRegion Region = MedialRegion::Inside;
};

/// A direction inside a cap when its cosine to the cap's centre is at least the cap's
/// minus this (the directions come from float closest points).
constexpr double MedialCapTolerance = 1e-9;
/// A cell's aperture counts when sin(A/2) D exceeds l/2 by this factor (a fan from one
/// point reaches the bound exactly for some positions of the point).
constexpr double MedialFanMargin = 1.001;

/// The cosine of the angular radius (at most 90 degrees) of the smallest cap holding
/// the 8 unit vectors u; 0 when no cap smaller than a half-sphere holds them. The
/// smallest cap has 2 of them at the ends of a diameter (then they are the widest
/// pair) or 3 on its rim. The GPU pass (Shaders/MedialAxis.comp.glsl) repeats this
/// arithmetic operation for operation, in double precision. `centre`, when given,
/// receives the cap's centre (unchanged when the cosine is 0).
inline double SmallestCapCosine(const double u[8][3], double* centre = nullptr)
{
  auto dot = [](const double* a, const double* b)
  { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto holdsAll = [&](const double* centre, double cosRadius)
  {
    for (int k = 0; k < 8; ++k)
    {
      if (dot(centre, u[k]) < cosRadius - MedialCapTolerance)
      {
        return false;
      }
    }
    return true;
  };
  // The widest pair (the first of the smallest dot products).
  int wi = 0, wj = 1;
  double widest = dot(u[0], u[1]);
  for (int i = 0; i < 8; ++i)
  {
    for (int j = i + 1; j < 8; ++j)
    {
      const double c = dot(u[i], u[j]);
      if (c < widest)
      {
        widest = c;
        wi = i;
        wj = j;
      }
    }
  }
  double s[3] = { u[wi][0] + u[wj][0], u[wi][1] + u[wj][1], u[wi][2] + u[wj][2] };
  const double sn = std::sqrt(dot(s, s));
  if (!(sn > 1e-12))
  {
    return 0; // two opposite directions: a half-sphere at least
  }
  for (int a = 0; a < 3; ++a)
  {
    s[a] /= sn;
  }
  const double pairCos = dot(s, u[wi]);
  if (holdsAll(s, pairCos))
  {
    if (centre)
    {
      std::copy(s, s + 3, centre);
    }
    return pairCos;
  }
  // Three on the rim: the cap through them, the smallest that holds all.
  double best = 0;
  for (int i = 0; i < 8; ++i)
  {
    for (int j = i + 1; j < 8; ++j)
    {
      for (int k = j + 1; k < 8; ++k)
      {
        const double e[3] = { u[j][0] - u[i][0], u[j][1] - u[i][1], u[j][2] - u[i][2] };
        const double f[3] = { u[k][0] - u[i][0], u[k][1] - u[i][1], u[k][2] - u[i][2] };
        double n[3] = {
          e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]
        };
        const double nn = std::sqrt(dot(n, n));
        if (!(nn > 1e-12))
        {
          continue; // (nearly) collinear or repeated directions: the pair caps cover them
        }
        for (int a = 0; a < 3; ++a)
        {
          n[a] /= nn;
        }
        double c = dot(n, u[i]);
        if (c < 0)
        {
          c = -c;
          n[0] = -n[0];
          n[1] = -n[1];
          n[2] = -n[2];
        }
        if (c > best && holdsAll(n, c))
        {
          best = c;
          if (centre)
          {
            std::copy(n, n + 3, centre);
          }
        }
      }
    }
  }
  return best;
}

/// Whether a distance lies in the region (not a number: in none).
inline bool InRegion(float d, MedialRegion region)
{
  return region == MedialRegion::Both ? d == d : (region == MedialRegion::Inside ? d < 0 : d > 0);
}

/// The corner (0..7, x fastest) a cell marks: the one of largest |distance|, ties to the
/// lower index; -1 when a corner lies outside the region (or is not a number).
inline int MarkedCorner(const float d[8], MedialRegion region)
{
  int marked = 0;
  for (int k = 0; k < 8; ++k)
  {
    if (!InRegion(d[k], region))
    {
      return -1;
    }
    if (std::fabs(d[k]) > std::fabs(d[marked]))
    {
      marked = k;
    }
  }
  return marked;
}

/// What decides a cell: the cosine of its aperture (2 when it has none: a corner on the
/// surface, or too near it for any aperture to count), and its reach sin(A/2) D / (l/2),
/// which must exceed MedialFanMargin for the aperture to count (MedialAxis.h).
struct MedialCellMeasure
{
  double Cosine = 2;
  double Reach = 0;
};

/// Measures a cell from its corners' distances, closest points and positions. Given the
/// threshold cos(theta), a cell that surely does not count returns early (Cosine 2):
/// the cap around u_0 through the direction farthest from it, at angle g, holds all, so
/// A <= 2g; when cos(2g) exceeds the threshold, or sin(g) D falls short of l/2, by more
/// than rounding can explain, the smallest cap need not be searched (most cells away
/// from the medial set).
inline MedialCellMeasure MeasureMedialCell(const float d[8],
  const float* const closest[8],
  const double corner[8][3],
  double halfDiagonal,
  double threshold = -2)
{
  MedialCellMeasure measure;
  double squares = 0;
  for (int k = 0; k < 8; ++k)
  {
    squares += double(d[k]) * double(d[k]);
  }
  const double fan2 = squares / 8 - halfDiagonal * halfDiagonal; // D^2
  const double depth = fan2 > 0 ? std::sqrt(fan2) / halfDiagonal : 0;
  measure.Reach = depth; // an upper bound until the aperture is known
  if (!(depth > MedialFanMargin))
  {
    return measure; // even 180 degrees would be a fan's
  }
  double u[8][3];
  for (int k = 0; k < 8; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      u[k][a] = double(closest[k][a]) - corner[k][a];
    }
    const double norm = std::sqrt(u[k][0] * u[k][0] + u[k][1] * u[k][1] + u[k][2] * u[k][2]);
    if (!(norm > 0 && norm < HUGE_VAL))
    {
      return measure;
    }
    for (int a = 0; a < 3; ++a)
    {
      u[k][a] /= norm;
    }
  }
  if (threshold > -2)
  {
    double farthest = 1; // cos(g)
    for (int k = 1; k < 8; ++k)
    {
      farthest = std::min(farthest, u[0][0] * u[k][0] + u[0][1] * u[k][1] + u[0][2] * u[k][2]);
    }
    if (farthest >= 0 &&
      (2 * farthest * farthest - 1 > threshold + 1e-6 ||
        std::sqrt(1 - farthest * farthest) * depth < MedialFanMargin - 1e-6))
    {
      return MedialCellMeasure();
    }
  }
  const double capCos = SmallestCapCosine(u);
  measure.Reach = std::sqrt(1 - capCos * capCos) * depth;
  measure.Cosine = 2 * capCos * capCos - 1;
  return measure;
}

/// Writes, per voxel, 1 or 0 in `medial`, and in `cosine` the cosine of the largest
/// aperture among the cells that marked it (2 where none did). Returns the number of
/// medial voxels.
int64_t MedialAxisCPU(const MedialInput& input,
  uint8_t* medial,
  double* cosine,
  const ParallelFor& parallelFor);

} // namespace vtkdf

#endif
