// SampleGrid: the regular grid of sample points a distance field lives on.
// Plain C++ (no VTK types) so the algorithm cores and stand-alone benchmarks share it.
#ifndef vtkdf_SampleGrid_h
#define vtkdf_SampleGrid_h

#include <array>
#include <cmath>
#include <cstdint>

namespace vtkdf
{

/// Inclusive index range [Lo, Hi] per axis, as in a VTK extent.
struct IndexBox
{
  std::array<int, 3> Lo{ { 0, 0, 0 } };
  std::array<int, 3> Hi{ { -1, -1, -1 } };

  bool Empty() const { return Hi[0] < Lo[0] || Hi[1] < Lo[1] || Hi[2] < Lo[2]; }
  int Size(int a) const { return Hi[a] - Lo[a] + 1; }
  int64_t Count() const
  {
    return this->Empty() ? 0 : int64_t(Size(0)) * int64_t(Size(1)) * int64_t(Size(2));
  }
  IndexBox Intersect(const IndexBox& o) const
  {
    IndexBox r;
    for (int a = 0; a < 3; ++a)
    {
      r.Lo[a] = Lo[a] > o.Lo[a] ? Lo[a] : o.Lo[a];
      r.Hi[a] = Hi[a] < o.Hi[a] ? Hi[a] : o.Hi[a];
    }
    return r;
  }
};

/// Sample points origin + (i,j,k) * spacing for (i,j,k) in Whole.
struct SampleGrid
{
  std::array<double, 3> Origin{ { 0, 0, 0 } };
  std::array<double, 3> Spacing{ { 1, 1, 1 } };
  IndexBox Whole;

  double Coordinate(int a, int index) const { return Origin[a] + index * Spacing[a]; }
  double MinSpacing() const { return std::fmin(Spacing[0], std::fmin(Spacing[1], Spacing[2])); }

  /// The default grid of shared/docs/GRID.md: bounds padded by padding * longest side,
  /// isotropic spacing, `resolution` samples along the longest padded side.
  static SampleGrid FromBounds(const double bounds[6], int resolution, double padding)
  {
    SampleGrid g;
    double len[3];
    double longest = 0;
    for (int a = 0; a < 3; ++a)
    {
      len[a] = bounds[2 * a + 1] - bounds[2 * a];
      longest = std::fmax(longest, len[a]);
    }
    if (longest <= 0)
    {
      // A single point (or coincident points): use a unit box so the grid is well defined.
      longest = 1.0;
    }
    const double pad = padding * longest;
    const double h = (longest + 2 * pad) / (resolution - 1);
    for (int a = 0; a < 3; ++a)
    {
      g.Origin[a] = bounds[2 * a] - pad;
      g.Spacing[a] = h;
      g.Whole.Lo[a] = 0;
      const int dims = static_cast<int>(std::ceil((len[a] + 2 * pad) / h - 1e-9)) + 1;
      g.Whole.Hi[a] = (dims < 1 ? 1 : dims) - 1;
    }
    return g;
  }
};

} // namespace vtkdf

#endif
