// SampleGrid: the regular grid of sample points a distance field lives on.
// Plain C++ (no VTK types) so the algorithm cores and stand-alone benchmarks share it.
#ifndef vtkdf_SampleGrid_h
#define vtkdf_SampleGrid_h

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace vtkdf
{

/// Inclusive index range [Lo, Hi] per axis, as in a VTK extent.
struct IndexBox
{
  std::array<int, 3> Lo{ { 0, 0, 0 } };
  std::array<int, 3> Hi{ { -1, -1, -1 } };

  bool Empty() const { return Hi[0] < Lo[0] || Hi[1] < Lo[1] || Hi[2] < Lo[2]; }
  int Size(int a) const { return Hi[a] - Lo[a] + 1; }
  /// The number of samples; INT64_MAX when that overflows (2^21 along every axis
  /// does): a caller checking memory rejects it.
  int64_t Count() const
  {
    if (this->Empty())
    {
      return 0;
    }
    int64_t count = 0;
    if (__builtin_mul_overflow(int64_t(Size(0)) * int64_t(Size(1)), int64_t(Size(2)), &count))
    {
      return INT64_MAX;
    }
    return count;
  }
  /// This box grown by `layers` samples on every side, within `within`.
  IndexBox Grown(int layers, const IndexBox& within) const
  {
    IndexBox r = *this;
    for (int a = 0; a < 3; ++a)
    {
      r.Lo[a] = Lo[a] - layers;
      r.Hi[a] = Hi[a] + layers;
    }
    return r.Intersect(within);
  }
  bool Contains(const IndexBox& o) const
  {
    for (int a = 0; a < 3; ++a)
    {
      if (o.Lo[a] < Lo[a] || o.Hi[a] > Hi[a])
      {
        return false;
      }
    }
    return true;
  }
  bool operator==(const IndexBox& o) const { return Lo == o.Lo && Hi == o.Hi; }
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

  /// The default grid (docs/grid.md): bounds padded by padding * longest side,
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
      // In double, clamped: a huge Resolution or an overflowing padding must not wrap
      // (CheckGrid then reports the non-finite spacing).
      const double dims = std::ceil((len[a] + 2 * pad) / h - 1e-9) + 1;
      g.Whole.Hi[a] = !(dims >= 1) ? 0 : (dims >= 2147483647.0 ? 2147483646 : int(dims) - 1);
    }
    return g;
  }
};

/// The normalized frame the cores work in: world = Origin + Scale * local. Origin is the
/// grid's origin and Scale the power of two at or below its smallest spacing, so local
/// spacings lie in [1, 2) and a mesh and grid scaled by 2^k give the cores the same
/// numbers bit for bit (a power of two scales every IEEE operation exactly). Float32
/// holds distances at any scale but not their squares (1e30^2 overflows, 1e-30^2
/// underflows): in the local frame both stay near 1.
struct GridFrame
{
  std::array<double, 3> Origin{ { 0, 0, 0 } };
  double Scale = 1;

  static GridFrame For(const SampleGrid& grid)
  {
    GridFrame f;
    f.Origin = grid.Origin;
    f.Scale = std::ldexp(1.0, std::ilogb(grid.MinSpacing()));
    return f;
  }
  double ToLocal(int a, double world) const { return (world - Origin[a]) / Scale; }
  double ToWorld(int a, double local) const { return Origin[a] + Scale * local; }
  /// The grid in the local frame (same extent).
  SampleGrid Local(const SampleGrid& grid) const
  {
    SampleGrid g = grid;
    for (int a = 0; a < 3; ++a)
    {
      g.Origin[a] = 0;
      g.Spacing[a] = grid.Spacing[a] / Scale;
    }
    return g;
  }
};

/// A number as %g prints it (std::to_string prints 1e-40 as 0.000000).
inline std::string FormatNumber(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

/// Smallest and largest spacing whose distances float32 holds to 1e-3 of a spacing as
/// normal numbers, and the most spacings a mesh and grid may span together (the squares
/// of local distances then stay far inside float32's range).
constexpr double MinimumSpacing = 1e-34;
constexpr double MaximumExtent = 1e38;
constexpr double MaximumSpacings = 1125899906842624.0; // 2^50

/// Whether `grid` (and, when `bounds` is given, the mesh bounds xmin, xmax, ...) can
/// carry float32 distances: finite origin, finite spacing in [MinimumSpacing, ...),
/// distinct sample coordinates, and a box holding mesh and grid with a diagonal below
/// MaximumExtent and at most MaximumSpacings smallest spacings. False and `error`
/// otherwise.
inline bool CheckGrid(const SampleGrid& grid, const double* bounds, std::string& error)
{
  static const char* axes = "xyz";
  double diagonal2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    const std::string axis(1, axes[a]);
    if (!std::isfinite(grid.Origin[a]))
    {
      error = "the grid origin is not finite along " + axis;
      return false;
    }
    if (!(std::isfinite(grid.Spacing[a]) && grid.Spacing[a] > 0))
    {
      error = "the grid spacing along " + axis + " is not a finite positive number";
      return false;
    }
    if (grid.Spacing[a] < MinimumSpacing)
    {
      error = "the grid spacing along " + axis + " (" + FormatNumber(grid.Spacing[a]) +
        ") is below 1e-34, where float32 distances lose their precision";
      return false;
    }
    // Even along an axis of one sample: a voxel's size enters the voxelizer's reach.
    if (!(grid.Spacing[a] < MaximumExtent &&
          grid.Spacing[a] <= MaximumSpacings * grid.MinSpacing()))
    {
      error = "the grid spacing along " + axis + " (" + FormatNumber(grid.Spacing[a]) +
        ") is above 1e38 or more than 2^50 times the smallest spacing";
      return false;
    }
    double lo = grid.Coordinate(a, grid.Whole.Lo[a]);
    double hi = grid.Coordinate(a, grid.Whole.Hi[a]);
    // Neighbouring samples must have distinct coordinates.
    const double magnitude = std::fmax(std::fabs(lo), std::fabs(hi));
    if (!std::isfinite(magnitude) || grid.Spacing[a] <= 1e-12 * magnitude)
    {
      error = "the grid along " + axis +
        " spans coordinates that double precision cannot tell apart or hold (spacing " +
        FormatNumber(grid.Spacing[a]) + " at coordinates up to " + FormatNumber(magnitude) + ")";
      return false;
    }
    if (bounds)
    {
      lo = std::fmin(lo, bounds[2 * a]);
      hi = std::fmax(hi, bounds[2 * a + 1]);
    }
    diagonal2 += (hi - lo) * (hi - lo);
  }
  const double diagonal = std::sqrt(diagonal2);
  if (!(diagonal < MaximumExtent))
  {
    error = std::string(bounds ? "the box holding the mesh and the grid" : "the grid") +
      " has a diagonal of " + FormatNumber(diagonal) +
      ", above 1e38, where float32 distances overflow";
    return false;
  }
  if (diagonal > MaximumSpacings * grid.MinSpacing())
  {
    error = std::string(bounds ? "the box holding the mesh and the grid" : "the grid") + " spans " +
      FormatNumber(diagonal / grid.MinSpacing()) +
      " spacings, more than 2^50, beyond what float32 distances can resolve";
    return false;
  }
  return true;
}

} // namespace vtkdf

#endif
