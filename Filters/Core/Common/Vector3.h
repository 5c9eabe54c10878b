// Vector3: dot and cross products and equality of 3-vectors held as plain double[3], for
// the cores that work on raw coordinate arrays.
#ifndef vtkdf_Vector3_h
#define vtkdf_Vector3_h

namespace vtkdf
{

inline double Dot(const double* u, const double* v)
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

/// w = u x v (w must not alias u or v).
inline void Cross(const double* u, const double* v, double* w)
{
  w[0] = u[1] * v[2] - u[2] * v[1];
  w[1] = u[2] * v[0] - u[0] * v[2];
  w[2] = u[0] * v[1] - u[1] * v[0];
}

/// Whether u and v are the same point (coordinate by coordinate; -0 equals 0).
inline bool SamePoint(const double* u, const double* v)
{
  return u[0] == v[0] && u[1] == v[1] && u[2] == v[2];
}

} // namespace vtkdf

#endif
