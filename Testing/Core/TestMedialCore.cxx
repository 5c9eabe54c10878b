// The medial-axis cell estimator (Filters/Core/Medial/MedialAxis.h), VTK-free:
// - SmallestCapCosine on random sets of 8 directions spread from a few degrees to all
//   around: its cap holds every direction, and a numerical search finds no smaller one
//   (the smallest cap's cosine is the largest, over centres c, of the smallest c . u_k);
// - the worst cases MedialAxis.h states: a sheet through a cell gives its separation
//   angle, a line or a point through it 180 degrees (any theta finds them);
// - the fan bound: a cell whose corners all have one point, or one line, as closest
//   feature never reaches beyond it (Reach <= 1), on cubic and stretched cells, and the
//   bound is tight (the largest reach seen is near 1: the margin is what keeps exact
//   fans out).
#include "CoreTest.h"
#include "Medial/MedialAxis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{
std::mt19937_64 Random(20261123);

double Uniform(double lo, double hi)
{
  return std::uniform_real_distribution<double>(lo, hi)(Random);
}

void RandomDirection(double u[3])
{
  std::normal_distribution<double> normal;
  double n = 0;
  do
  {
    for (int a = 0; a < 3; ++a)
    {
      u[a] = normal(Random);
    }
    n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  } while (n < 1e-6);
  for (int a = 0; a < 3; ++a)
  {
    u[a] /= n;
  }
}

void Normalize(double u[3])
{
  const double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int a = 0; a < 3; ++a)
  {
    u[a] /= n;
  }
}

double Dot(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The smallest of c . u_k.
double Worst(const double c[3], const double u[8][3])
{
  double w = 1;
  for (int k = 0; k < 8; ++k)
  {
    w = std::min(w, Dot(c, u[k]));
  }
  return w;
}

/// max over unit c of min_k c . u_k: many starting centres, each refined by a shrinking
/// random search. A lower bound of the true value, close to it.
double SearchedCapCosine(const double u[8][3])
{
  double best = -1, centre[3] = { 0, 0, 1 };
  for (int s = 0; s < 1000; ++s)
  {
    double c[3];
    RandomDirection(c);
    const double w = Worst(c, u);
    if (w > best)
    {
      best = w;
      std::copy(c, c + 3, centre);
    }
  }
  for (double step = 0.5; step > 1e-12; step *= 0.8)
  {
    for (int t = 0; t < 100; ++t)
    {
      double c[3], r[3];
      RandomDirection(r);
      for (int a = 0; a < 3; ++a)
      {
        c[a] = centre[a] + step * r[a];
      }
      Normalize(c);
      const double w = Worst(c, u);
      if (w > best)
      {
        best = w;
        std::copy(c, c + 3, centre);
      }
    }
  }
  return std::max(0.0, best);
}

/// The 8 corners of the cell [0, h] with spacings h.
void Corners(const double h[3], double x[8][3])
{
  for (int k = 0; k < 8; ++k)
  {
    x[k][0] = (k & 1) * h[0];
    x[k][1] = ((k >> 1) & 1) * h[1];
    x[k][2] = (k >> 2) * h[2];
  }
}

/// The cell's measure when every corner's closest point is closest[k] (distances from
/// the corners, negative: inside).
MedialCellMeasure Measure(const double h[3], const double x[8][3], const double closest[8][3])
{
  float d[8];
  float c[8][3];
  const float* cp[8];
  for (int k = 0; k < 8; ++k)
  {
    double r2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      c[k][a] = static_cast<float>(closest[k][a]);
      r2 += (closest[k][a] - x[k][a]) * (closest[k][a] - x[k][a]);
    }
    d[k] = -static_cast<float>(std::sqrt(r2));
    cp[k] = c[k];
  }
  return MeasureMedialCell(d, cp, x, 0.5 * std::sqrt(Dot(h, h)));
}
} // namespace

int main()
{
  // SmallestCapCosine against the search.
  double worstGap = 0;
  for (int trial = 0; trial < 1000; ++trial)
  {
    double axis[3], u[8][3];
    RandomDirection(axis);
    const double spread = Uniform(0.01, 3.2); // radians, up to all around
    for (int k = 0; k < 8; ++k)
    {
      // A direction within `spread` of the axis.
      double r[3];
      RandomDirection(r);
      const double t = Uniform(0, spread);
      double w[3] = {
        r[0] - Dot(r, axis) * axis[0], r[1] - Dot(r, axis) * axis[1], r[2] - Dot(r, axis) * axis[2]
      };
      Normalize(w);
      for (int a = 0; a < 3; ++a)
      {
        u[k][a] = std::cos(t) * axis[a] + std::sin(t) * w[a];
      }
      Normalize(u[k]);
    }
    double centre[3] = { 0, 0, 0 };
    const double exact = SmallestCapCosine(u, centre);
    const double searched = SearchedCapCosine(u);
    worstGap = std::max(worstGap, exact - searched);
    Check(exact >= searched - 1e-9,
      "the search found a smaller cap (%.17g)",
      static_cast<double>(searched - exact));
    Check(exact == 0 || Worst(centre, u) >= exact - 2 * MedialCapTolerance,
      "the cap does not hold every direction (%.17g)",
      static_cast<double>(exact - Worst(centre, u)));
  }
  std::printf("SmallestCapCosine: 1000 random sets, none smaller found by a search (which "
              "stayed up to %.2g below), each holds its 8 directions\n",
    worstGap);

  // The worst cases, on cubic and stretched cells.
  const double spacings[3][3] = { { 1, 1, 1 }, { 1, 0.5, 2 }, { 0.3, 1, 0.7 } };
  for (const auto& h : spacings)
  {
    double x[8][3];
    Corners(h, x);
    double sheetError = 0, lineCos = 0, pointCos = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
      // A sheet through the cell between two planes: the corners on each side see their
      // own plane's normal; the angle between the normals is the separation angle.
      double n1[3], n2[3], m[3], p[3];
      RandomDirection(n1);
      RandomDirection(n2);
      RandomDirection(m);
      for (int a = 0; a < 3; ++a)
      {
        p[a] = Uniform(0.2, 0.8) * h[a];
      }
      double u[8][3];
      bool sides[2] = { false, false };
      for (int k = 0; k < 8; ++k)
      {
        const double s =
          (x[k][0] - p[0]) * m[0] + (x[k][1] - p[1]) * m[1] + (x[k][2] - p[2]) * m[2];
        sides[s > 0] = true;
        std::copy(s > 0 ? n1 : n2, (s > 0 ? n1 : n2) + 3, u[k]);
      }
      if (sides[0] && sides[1])
      {
        const double separation = std::acos(std::max(-1.0, std::min(1.0, Dot(n1, n2))));
        const double capCos = SmallestCapCosine(u);
        sheetError = std::max(
          sheetError, std::fabs(separation - 2 * std::acos(capCos)) * (separation < 3.1 ? 1 : 0));
      }
      // A line through the cell's interior: each corner's direction to its foot.
      double dir[3];
      RandomDirection(dir);
      for (int k = 0; k < 8; ++k)
      {
        double v[3] = { p[0] - x[k][0], p[1] - x[k][1], p[2] - x[k][2] };
        const double along = Dot(v, dir);
        for (int a = 0; a < 3; ++a)
        {
          u[k][a] = v[a] - along * dir[a];
        }
        Normalize(u[k]);
      }
      lineCos = std::max(lineCos, SmallestCapCosine(u));
      // A point in the cell.
      for (int k = 0; k < 8; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          u[k][a] = p[a] - x[k][a];
        }
        Normalize(u[k]);
      }
      pointCos = std::max(pointCos, SmallestCapCosine(u));
    }
    std::printf("cell %gx%gx%g: sheet aperture - separation angle at most %.2g rad; line and "
                "point: cap cosine at most %.2g and %.2g (0: 180 degrees)\n",
      h[0],
      h[1],
      h[2],
      sheetError,
      lineCos,
      pointCos);
    Check(sheetError <= 1e-6,
      "a sheet's aperture is not its separation angle (%.17g)",
      static_cast<double>(sheetError));
    Check(lineCos <= 1e-9,
      "a line through a cell below 180 degrees (%.17g)",
      static_cast<double>(lineCos));
    Check(pointCos <= 1e-9,
      "a point in a cell below 180 degrees (%.17g)",
      static_cast<double>(pointCos));

    // Fans: one closest point f (a vertex), or one closest line (an edge), for all 8
    // corners, at distances from under the cell's half diagonal to 20 diagonals.
    const double l = std::sqrt(Dot(h, h));
    double largest = 0;
    for (int trial = 0; trial < 20000; ++trial)
    {
      double f[3], e[3], closest[8][3];
      RandomDirection(f);
      const double r = l * std::exp(Uniform(std::log(0.5), std::log(20.0)));
      for (int a = 0; a < 3; ++a)
      {
        f[a] = 0.5 * h[a] + r * f[a];
      }
      const bool edge = trial % 2 == 1;
      RandomDirection(e);
      for (int k = 0; k < 8; ++k)
      {
        double along = 0;
        if (edge)
        {
          along = (x[k][0] - f[0]) * e[0] + (x[k][1] - f[1]) * e[1] + (x[k][2] - f[2]) * e[2];
        }
        for (int a = 0; a < 3; ++a)
        {
          closest[k][a] = f[a] + along * e[a];
        }
      }
      const MedialCellMeasure m = Measure(h, x, closest);
      if (m.Cosine <= 1)
      {
        largest = std::max(largest, m.Reach);
        Check(m.Reach <= 1 + 1e-6,
          "a fan reaches beyond its bound (%.17g)",
          static_cast<double>(m.Reach));
      }
    }
    std::printf("cell %gx%gx%g: fans of one point or one line reach at most %.6f (bound 1, "
                "counted above %.3f)\n",
      h[0],
      h[1],
      h[2],
      largest,
      MedialFanMargin);
    Check(largest > 0.9, "the fan bound is far from tight (%.17g)", static_cast<double>(largest));
  }
  return Verdict();
}
