// WindingNumber: the generalized winding number of a triangle mesh (Jacobson, Kavan and
// Sorkine-Hornung 2013), w(q) = the sum of the triangles' signed solid angles at q over
// 4 pi, evaluated fast (Barill et al. 2018) with a bound on the error, without VTK types.
//
// w is 1 inside and 0 outside a closed outward-oriented mesh (-1 inside an inward one),
// and degrades gracefully on open meshes and soups; "inside" is |w| > 1/2.
//
// Evaluation: a bounding-volume hierarchy over the triangles; a node far enough from q
// (distance r > Accuracy x its radius R) contributes its order-1 expansion about its
// centre c, with d = c - q:
//   (M . d + tr T - 3 d.T.d / r^2) / (4 pi r^3),
// M the sum of its triangles' vector areas, T_ij the sum of their vector areas' i-th
// component times their centroids' offset from c along j; the rest is exact (Van
// Oosterom and Strackee's formula per triangle). The expansion of a triangle's term errs
// by at most half |D^3 (1/|x|)| <= 6 / g^4 times the integral of |y - c|^2 over the
// triangle, over 4 pi, g the distance from q to the node's ball; so each far node adds
// 3 S / (4 pi (r - R)^4) to the bound, S the second moment of its triangles' area about
// c (from the absolute areas: folded sheets and opposite duplicates cancel in M and T,
// not in the error). Inside() evaluates exactly wherever |w| lies within the bound of
// 1/2, so the approximation never decides a sign.
//
// Triangles repeated with the same orientation (same three positions in the same cyclic
// order) count once. Two copies with opposite orientations cancel: their solid angles
// sum to zero, so a closed mesh glued to its flipped copy has w = 0 everywhere (outside).
#ifndef vtkdf_WindingNumber_h
#define vtkdf_WindingNumber_h

#include "Common/LargeVector.h"

#include <cstdint>
#include <vector>

namespace vtkdf
{

/// The gradient in q of the signed solid angle of triangle (a, b, c) seen from q (positive
/// when q sees the triangle's back: its normal, by the right-hand rule, points away).
void TriangleSolidAngleGradient(const double a[3],
  const double b[3],
  const double c[3],
  const double q[3],
  double gradient[3]);

/// A sum of triangles' solid angles kept as the argument of a product of complex
/// numbers, den + i det per triangle (Van Oosterom and Strackee: the angle is twice its
/// argument), with a count of the full turns the product makes: no atan2 per triangle,
/// and the sign of the sum (|w| > 1/2) from the count alone. The argument is
/// ArcTangent2's, whose bits a shader can give: the GPU does the same, operation for
/// operation (Shaders/WindingNumber.comp.glsl).
class AngleProduct
{
public:
  /// Adds triangle (a, b, c) seen from q.
  void Add(const double a[3], const double b[3], const double c[3], const double q[3]);
  /// The sum over 4 pi: the winding number of the triangles added.
  double Winding() const;
  /// Whether |Winding()| > 1/2, from the turns (no rounding of the argument).
  bool Inside() const;

private:
  void Multiply(double re, double im);
  double Argument() const; // in (-pi, pi]
  double Re = 1, Im = 0;
  int64_t Turns = 0;
};

struct WindingValue
{
  double Value = 0; // w(q)
  double Bound = 0; // |w(q) - exact w(q)| <= Bound (0: exact)
};

struct WindingGradient
{
  double Value = 0, Bound = 0;      // as WindingValue
  double Gradient[3] = { 0, 0, 0 }; // grad w(q)
  double GradientBound = 0;         // |Gradient - exact grad w(q)| <= GradientBound
};

class WindingNumber
{
public:
  /// Default Accuracy: a node is far when r > 4 R. Inside() tries CoarseAccuracy first
  /// (most samples are far from |w| = 1/2 and need little), then Accuracy, then the exact
  /// sum. With 4 the bound decides all but the samples within a small fraction of a
  /// spacing of |w| = 1/2; higher values move work from the exact sums to every sample
  /// (aneurysm at 128^3: 411 exact samples at 4, 27 at 8, at 1.8 times the time).
  static constexpr double DefaultAccuracy = 4;
  static constexpr double CoarseAccuracy = 3;
  /// Inside() with a value evaluates at this accuracy at least: the values users read
  /// are then within about 1e-3 of the exact ones (order 1, Testing/Cxx/TestWindingSign).
  static constexpr double ValueAccuracy = 8;
  /// An approximation decides a sample when its margin exceeds its bound plus what
  /// rounding may have added to w (sums of a few thousand terms of at most a few units).
  static constexpr double RoundingSlack = 1e-12;

  /// Builds the hierarchy over the triangles (3 point ids each into xyz `points`).
  /// Accuracy must exceed 1.
  void Build(const LargeVector<double>& points,
    const LargeVector<int64_t>& triangles,
    double accuracy = DefaultAccuracy);

  /// w(q) from the hierarchy, with its error bound.
  WindingValue Evaluate(const double q[3]) const;
  /// The same with another accuracy (> 1).
  WindingValue Evaluate(const double q[3], double accuracy) const;
  /// w(q) from every triangle's solid angle.
  double Exact(const double q[3]) const;
  /// Whether |w(q)| > 1/2, never decided by the approximation; `exact` receives whether
  /// the exact sum was needed. With `value`, the w used (Evaluate's at ValueAccuracy, or
  /// the exact one where its bound reaches 1/2); without, the evaluation stops as soon as its bound
  /// decides (CoarseAccuracy first), and the answer is the same.
  bool Inside(const double q[3], double* value = nullptr, bool* exact = nullptr) const;

  /// w(q) and its gradient from the hierarchy (at Accuracy), with error bounds of both.
  WindingGradient EvaluateWithGradient(const double q[3]) const;

  /// An upper bound of the norm of w's Hessian over the ball B(c, radius), HUGE_VAL when a
  /// triangle may reach into it. A triangle's term has a Hessian of norm at most its area
  /// times |D^3 (1/|x|)| / 4 pi <= 6 / (4 pi g^4), g its distance from the point, so a
  /// node whose ball is g from B(c, radius) adds at most 3 A / (2 pi g^4).
  double HessianBound(const double c[3], double radius) const;

  /// The hierarchy flattened for the GPU (Shaders/WindingNumber.comp.glsl): per node,
  /// NodeDoubles doubles (centre, radius, moment, tensor row by row, second moment) and
  /// 4 ints (first triangle, count, children or -1 for a leaf).
  static constexpr int NodeDoubles = 17;
  void Flatten(std::vector<double>& nodes, std::vector<int32_t>& links) const;
  /// The kept triangles' corners, 9 doubles each, in the hierarchy's order.
  const LargeVector<double>& TriangleCorners() const { return this->Corners; }
  double GetAccuracy() const { return this->Accuracy; }

  /// The triangles kept (repeated ones once).
  int64_t TriangleCount() const { return static_cast<int64_t>(this->Corners.size() / 9); }

private:
  struct Node
  {
    double Centre[3];
    double Moment[3];     // sum of the vector areas (half cross products)
    double Radius;        // of the ball around Centre holding the node's triangles
    double Area;          // sum of the triangles' areas
    double Tensor[9];     // first-order tensor T_ij (row i: the vector area's component)
    double Second;        // second moment of area about Centre, at least its exact value
    int64_t First, Count; // the node's triangles, in Corners order
    int32_t Children[2];  // -1: a leaf
  };
  int32_t BuildNode(std::vector<int64_t>& order,
    int64_t first,
    int64_t count,
    const std::vector<double>& corners,
    const std::vector<double>& centroids);

  /// Visits the hierarchy depth first from the root: `visit(node)` returns true to go on
  /// into the node's children (for a leaf, true or false alike), false when it took the
  /// node whole.
  template<typename Visit>
  void Walk(Visit&& visit) const
  {
    if (this->Nodes.empty())
    {
      return;
    }
    int32_t stack[128]; // the median split keeps the depth near log2(triangles / 8)
    int depth = 0;
    stack[depth++] = 0;
    while (depth > 0)
    {
      const Node& node = this->Nodes[stack[--depth]];
      if (visit(node) && node.Children[0] >= 0)
      {
        stack[depth++] = node.Children[0];
        stack[depth++] = node.Children[1];
      }
    }
  }
  /// A far node's order-1 term at q and its error bound; false when q is in its ball.
  bool FarTerm(const Node& node, const double q[3], double& term, double& bound) const;
  /// Adds a leaf's triangles seen from q.
  void AddLeaf(const Node& node, const double q[3], AngleProduct& angles) const;
  /// Every triangle seen from q.
  AngleProduct ExactAngles(const double q[3]) const;

  std::vector<Node> Nodes;
  LargeVector<double> Corners; // 9 per triangle, in the hierarchy's order
  // Per triangle, in the same order, for HessianBound: the ball around its centroid
  // through its farthest corner (centre, radius) and its area.
  std::vector<double> Balls; // 4 per triangle
  std::vector<double> Areas;
  double Accuracy = DefaultAccuracy;
};

} // namespace vtkdf

#endif
