// Barycentric: where a closest point lies on a triangle or a segment, as coordinates of
// its corners. The point filter and the grid field report their closest points so.
#ifndef vtkdf_Barycentric_h
#define vtkdf_Barycentric_h

#include "Common/PointTriangleDistance.h"
#include "Common/Vector3.h"

#include <algorithm>

namespace vtkdf
{

/// The barycentric coordinates of p (on the plane of a, b, c up to rounding) in that
/// triangle.
inline void FaceBarycentric(const double* a,
  const double* b,
  const double* c,
  const double p[3],
  double bary[3])
{
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = p[k] - a[k];
  }
  const double uu = Dot(u, u), uv = Dot(u, v), vv = Dot(v, v), wu = Dot(w, u), wv = Dot(w, v);
  const double denominator = uu * vv - uv * uv;
  bary[1] = (vv * wu - uv * wv) / denominator;
  bary[2] = (uu * wv - uv * wu) / denominator;
  bary[0] = 1 - bary[1] - bary[2];
}

/// How far along segment ab the projection of p lies, clamped to [0, 1] (0 when a = b).
inline double SegmentParameter(const double* a, const double* b, const double p[3])
{
  double ab[3], ap[3];
  for (int k = 0; k < 3; ++k)
  {
    ab[k] = b[k] - a[k], ap[k] = p[k] - a[k];
  }
  const double length2 = Dot(ab, ab);
  return length2 > 0 ? std::min(1.0, std::max(0.0, Dot(ap, ab) / length2)) : 0.0;
}

/// The coordinates on triangle abc of `closest`, which lies on its `feature`
/// (TriangleFeature, as SquaredDistanceToTriangle reports it): 1 at a corner, the two
/// ends' shares on an edge, FaceBarycentric in the face.
inline void FeatureBarycentric(const double* a,
  const double* b,
  const double* c,
  int feature,
  const double closest[3],
  double bary[3])
{
  std::fill(bary, bary + 3, 0.0);
  if (feature == InFace)
  {
    FaceBarycentric(a, b, c, closest, bary);
  }
  else if (feature >= OnEdgeAB)
  {
    const int from = feature - OnEdgeAB, to = (from + 1) % 3;
    const double* corners[3] = { a, b, c };
    const double t = SegmentParameter(corners[from], corners[to], closest);
    bary[from] = 1 - t;
    bary[to] = t;
  }
  else
  {
    bary[feature] = 1;
  }
}

} // namespace vtkdf

#endif
