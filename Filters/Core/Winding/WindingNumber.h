// WindingNumber: the generalized winding number of a triangle mesh (Jacobson, Kavan and
// Sorkine-Hornung 2013), w(q) = the sum of the triangles' signed solid angles at q over
// 4 pi, evaluated fast (Barill et al. 2018) with a bound on the error, without VTK types.
//
// w is 1 inside and 0 outside a closed outward-oriented mesh (-1 inside an inward one),
// and degrades gracefully on open meshes and soups; "inside" is |w| > 1/2.
//
// Evaluation: a bounding-volume hierarchy over the triangles; a node far enough from q
// (distance r > Accuracy x its radius R) contributes its dipole term, M . (c - q) /
// (4 pi r^3) with M the sum of its triangles' vector areas and c its centre; the rest is
// exact (Van Oosterom and Strackee's formula per triangle). The dipole term of a
// triangle of area a within R of c errs by at most a R |Hessian(1/4 pi |x|)| <=
// a R / (2 pi (r - R)^3), so each far node adds A R / (2 pi (r - R)^3) to the bound, A
// the sum of its triangles' areas (not |M|: folded sheets and opposite duplicates cancel
// in M, not in the error). Inside() evaluates exactly wherever |w| lies within the bound
// of 1/2, so the approximation never decides a sign.
//
// Triangles repeated with the same orientation (same three positions in the same cyclic
// order) count once. Two copies with opposite orientations cancel: their solid angles
// sum to zero, so a closed mesh glued to its flipped copy has w = 0 everywhere (outside).
#ifndef vtkdf_WindingNumber_h
#define vtkdf_WindingNumber_h

#include <cstdint>
#include <vector>

namespace vtkdf
{

/// The signed solid angle of triangle (a, b, c) seen from q, in [-2 pi, 2 pi]: positive
/// when q sees the triangle's back (its normal, by the right-hand rule, points away).
double TriangleSolidAngle(const double a[3],
  const double b[3],
  const double c[3],
  const double q[3]);

struct WindingValue
{
  double Value = 0; // w(q)
  double Bound = 0; // |w(q) - exact w(q)| <= Bound (0: exact)
};

class WindingNumber
{
public:
  /// Default Accuracy: a node is far when r > 8 R. With 2 (the usual choice without a
  /// bound) the bound decides almost no sample and nearly all go exact; with 8 it decides
  /// all but those within a fraction of a spacing of |w| = 1/2 (Testing/Core).
  static constexpr double DefaultAccuracy = 8;

  /// Builds the hierarchy over the triangles (3 point ids each into xyz `points`).
  /// Accuracy must exceed 1.
  void Build(const std::vector<double>& points,
    const std::vector<int64_t>& triangles,
    double accuracy = DefaultAccuracy);

  /// w(q) from the hierarchy, with its error bound.
  WindingValue Evaluate(const double q[3]) const;
  /// w(q) from every triangle's solid angle.
  double Exact(const double q[3]) const;
  /// Whether |w(q)| > 1/2, never decided by the approximation; `value` receives the w
  /// used (exact when it was needed) and `exact` whether it was exact.
  bool Inside(const double q[3], double* value = nullptr, bool* exact = nullptr) const;

  /// An upper bound of |grad w| over the ball B(c, radius), HUGE_VAL when a triangle may
  /// reach into it. The gradient of a triangle's term at z is bounded by its area times
  /// the Hessian bound 2 / (4 pi g^3), g the triangle's distance from z, so a node whose
  /// ball is g from B(c, radius) adds at most A / (2 pi g^3).
  double GradientBound(const double c[3], double radius) const;

  /// The triangles kept (repeated ones once).
  int64_t TriangleCount() const { return static_cast<int64_t>(this->Corners.size() / 9); }

private:
  struct Node
  {
    double Centre[3];
    double Moment[3];     // sum of the vector areas (half cross products)
    double Radius;        // of the ball around Centre holding the node's triangles
    double Area;          // sum of the triangles' areas
    int64_t First, Count; // the node's triangles, in Corners order
    int32_t Children[2];  // -1: a leaf
  };
  int32_t BuildNode(std::vector<int64_t>& order,
    int64_t first,
    int64_t count,
    const std::vector<double>& corners,
    const std::vector<double>& centroids);

  std::vector<Node> Nodes;
  std::vector<double> Corners; // 9 per triangle, in the hierarchy's order
  // Per triangle, in the same order, for GradientBound: the ball around its centroid
  // through its farthest corner (centre, radius) and its area.
  std::vector<double> Balls; // 4 per triangle
  std::vector<double> Areas;
  double Accuracy = DefaultAccuracy;
};

} // namespace vtkdf

#endif
