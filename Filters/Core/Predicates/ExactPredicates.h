// ExactPredicates: the signs of the 2D and 3D orientation determinants of points given
// as doubles, exact for every finite input, without VTK types.
//
// A determinant evaluated in floating point whose magnitude exceeds a bound on its
// rounding error has the right sign (the bound is Shewchuk's first-stage bound for these
// determinants, rounded up: J. R. Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", Discrete & Computational Geometry
// 18(3):305-363, 1997). The rest, near zero or exactly zero (coplanar points), are
// evaluated again in integers (Boost.Multiprecision's cpp_int): every double is an
// integer times a power of two, so the inputs scaled to their least power of two are
// integers and the determinant is exact.
#ifndef vtkdf_ExactPredicates_h
#define vtkdf_ExactPredicates_h

namespace vtkdf
{
/// Sign (-1, 0 or 1) of det[b - a, c - a, d - a] = ((b - a) x (c - a)) . (d - a):
/// positive when d lies on the side of the plane through a, b, c that the normal
/// (b - a) x (c - a) points to, zero exactly when the four points are coplanar.
int Orient3D(const double a[3], const double b[3], const double c[3], const double d[3]);

/// Sign of det[b - a, c - a] in the plane of coordinates i and j (the other one
/// ignored): positive when a, b, c turn counter-clockwise there, zero exactly when their
/// projections are collinear.
int Orient2D(const double a[3], const double b[3], const double c[3], int i, int j);

/// Whether three points lie on one line (or coincide), exactly.
bool Collinear(const double a[3], const double b[3], const double c[3]);
} // namespace vtkdf

#endif
