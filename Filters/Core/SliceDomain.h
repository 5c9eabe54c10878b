// SliceDomain: scan conversion of a site's domain (an intersection of half-spaces) inside
// a rectangle of sample indices, slice by slice and row by row.
//
// Clipping a polygon on every slice costs about a hundred operations, and most domains
// of a fine mesh hold a sample or two per slice. So the half-spaces are turned once per
// site, by Fourier-Motzkin elimination, into bounds of each scan variable in terms of
// the outer ones: the box of the slice's polygon (x and y ranges as affine functions of
// the slice k) and the span of a row (x range as an affine function of y and k). The
// projection that elimination computes is exact, so the rows and spans are those of
// the clipped polygon; each costs a few multiply-adds. The GPU path clips the same
// half-spaces into polygons for its rasterizer (Shaders/LinearFactorDomain.geom.glsl).
#ifndef vtkdf_SliceDomain_h
#define vtkdf_SliceDomain_h

#include <algorithm>
#include <cmath>

namespace vtkdf
{

/// A*x + B*y + C*k + D >= 0 in sample-index coordinates, x the inner (row) axis, y the
/// row axis and k the slice axis of the scan.
struct IndexPlane
{
  double A, B, C, D;
};

/// The most planes a site's domain keeps on the CPU (optional ones beyond are dropped,
/// which only enlarges the domain).
constexpr int MaxDomainPlanes = 60;

class DomainSpans
{
public:
  /// Sets up the domain of `count` planes inside [x0,x1]x[y0,y1]. The first `required`
  /// planes are always kept; optional ones are dropped from the end when the
  /// elimination would exceed its capacity (that only enlarges the domain).
  void Setup(const IndexPlane* planes,
    int count,
    int required,
    double x0,
    double x1,
    double y0,
    double y1)
  {
    this->X0 = x0, this->X1 = x1, this->Y0 = y0, this->Y1 = y1;
    this->Empty = false;
    this->ConditionCount = 0; // both eliminations add to them
    count = std::min(count, MaxDomainPlanes);
    IndexPlane normalized[MaxDomainPlanes + 2];
    int kept = 0;
    for (int p = 0; p < count; ++p)
    {
      const IndexPlane& h = planes[p];
      const double scale = std::max(std::fabs(h.A), std::max(std::fabs(h.B), std::fabs(h.C)));
      if (!(scale > 0))
      {
        // A plane without direction keeps all or nothing.
        this->Empty = this->Empty || !(h.D >= 0);
        continue;
      }
      normalized[kept++] = { h.A / scale, h.B / scale, h.C / scale, h.D / scale };
    }
    // Optional planes come after the required ones: drop them from the end until the
    // elimination fits (the required ones, at most 3, always fit).
    while (kept > required && !Fits(normalized, kept))
    {
      --kept;
    }
    this->SetupRows(normalized, kept);
    // Y range: eliminate x from the planes and the rectangle's x sides.
    normalized[kept] = { 1, 0, 0, -x0 };
    normalized[kept + 1] = { -1, 0, 0, x1 };
    this->Eliminate(normalized, kept + 2, 0, this->YLo, this->YLoCount, this->YHi, this->YHiCount);
    // X range: eliminate y from the planes and the rectangle's y sides.
    normalized[kept] = { 0, 1, 0, -y0 };
    normalized[kept + 1] = { 0, -1, 0, y1 };
    this->Eliminate(normalized, kept + 2, 1, this->XLo, this->XLoCount, this->XHi, this->XHiCount);
  }

  /// The box of the domain's polygon on slice k, as {xmin, xmax, ymin, ymax};
  /// false when the polygon is empty.
  bool SliceBox(double k, double box[4]) const
  {
    if (this->Empty)
    {
      return false;
    }
    for (int c = 0; c < this->ConditionCount; ++c)
    {
      if (this->Conditions[c].K * k + this->Conditions[c].C < 0)
      {
        return false;
      }
    }
    box[2] = Lower(this->YLo, this->YLoCount, k, this->Y0);
    box[3] = Upper(this->YHi, this->YHiCount, k, this->Y1);
    if (!(box[2] <= box[3]))
    {
      return false;
    }
    box[0] = Lower(this->XLo, this->XLoCount, k, this->X0);
    box[1] = Upper(this->XHi, this->XHiCount, k, this->X1);
    return box[0] <= box[1];
  }

  /// Prepares RowSpan for slice k.
  void BeginSlice(double k)
  {
    for (int r = 0; r < this->RowCount; ++r)
    {
      this->RowOffset[r] = this->Rows[r].K * k + this->Rows[r].C;
    }
  }

  /// The x range of row y on the slice of the last BeginSlice; false when it is empty.
  bool RowSpan(double y, double& xl, double& xr) const
  {
    xl = this->X0;
    xr = this->X1;
    for (int r = 0; r < this->RowCount; ++r)
    {
      const double value = this->Rows[r].Y * y + this->RowOffset[r];
      switch (this->RowKind[r])
      {
        case Lo:
          xl = std::max(xl, value);
          break;
        case Hi:
          xr = std::min(xr, value);
          break;
        default:
          if (value < 0)
          {
            return false;
          }
      }
    }
    return xl <= xr;
  }

private:
  static constexpr double Tiny = 1e-9; // coefficients below it (of unit-scaled planes) are 0
  static constexpr int MaxPairs = 256;
  static constexpr int MaxBounds = MaxPairs + MaxDomainPlanes + 2;

  enum Kind : unsigned char
  {
    Lo,       // x >= value
    Hi,       // x <= value
    Condition // value >= 0 (the plane does not involve x)
  };
  /// Y*y + K*k + C.
  struct RowBound
  {
    double Y, K, C;
  };
  /// K*k + C.
  struct SliceBound
  {
    double K, C;
  };

  /// Whether eliminating x and y from the first `count` planes fits the capacity.
  static bool Fits(const IndexPlane* planes, int count)
  {
    int lx = 1, ux = 1, ly = 1, uy = 1; // the rectangle's sides
    for (int p = 0; p < count; ++p)
    {
      lx += planes[p].A > Tiny;
      ux += planes[p].A < -Tiny;
      ly += planes[p].B > Tiny;
      uy += planes[p].B < -Tiny;
    }
    return lx * ux <= MaxPairs && ly * uy <= MaxPairs;
  }

  void SetupRows(const IndexPlane* planes, int count)
  {
    this->RowCount = 0;
    for (int p = 0; p < count; ++p)
    {
      const IndexPlane& h = planes[p];
      const int r = this->RowCount++;
      if (std::fabs(h.A) > Tiny)
      {
        this->RowKind[r] = h.A > 0 ? Lo : Hi;
        this->Rows[r] = { -h.B / h.A, -h.C / h.A, -h.D / h.A };
      }
      else
      {
        this->RowKind[r] = Condition;
        this->Rows[r] = { h.B, h.C, h.D };
      }
    }
  }

  /// Fourier-Motzkin: eliminates the variable `gone` (0: x, 1: y) from the planes and
  /// sorts the resulting constraints on (kept variable, k) into lower and upper bounds
  /// of the kept variable, and conditions on k alone.
  void Eliminate(const IndexPlane* planes,
    int count,
    int gone,
    SliceBound* lower,
    int& lowerCount,
    SliceBound* upper,
    int& upperCount)
  {
    lowerCount = upperCount = 0;
    auto coefficient = [gone](const IndexPlane& h) { return gone == 0 ? h.A : h.B; };
    auto other = [gone](const IndexPlane& h) { return gone == 0 ? h.B : h.A; };
    // A constraint v*kept + c*k + d >= 0 on the kept variable and k.
    auto add = [&](double v, double c, double d)
    {
      const double scale = std::max(std::fabs(v), std::fabs(c));
      if (!(scale > 0))
      {
        this->Empty = this->Empty || !(d >= 0);
        return;
      }
      v /= scale, c /= scale, d /= scale;
      if (v > Tiny)
      {
        lower[lowerCount++] = { -c / v, -d / v };
      }
      else if (v < -Tiny)
      {
        upper[upperCount++] = { -c / v, -d / v };
      }
      else if (this->ConditionCount < 2 * MaxBounds)
      {
        this->Conditions[this->ConditionCount++] = { c, d };
      }
    };
    for (int p = 0; p < count; ++p)
    {
      const IndexPlane& l = planes[p];
      const double al = coefficient(l);
      if (std::fabs(al) <= Tiny)
      {
        add(other(l), l.C, l.D);
        continue;
      }
      if (al < 0)
      {
        continue;
      }
      for (int q = 0; q < count; ++q)
      {
        const IndexPlane& u = planes[q];
        const double au = coefficient(u);
        if (au < -Tiny)
        {
          // (-au) * l + al * u has no `gone` term, and both weights are positive.
          add(-au * other(l) + al * other(u), -au * l.C + al * u.C, -au * l.D + al * u.D);
        }
      }
    }
  }

  static double Lower(const SliceBound* b, int count, double k, double start)
  {
    for (int i = 0; i < count; ++i)
    {
      start = std::max(start, b[i].K * k + b[i].C);
    }
    return start;
  }
  static double Upper(const SliceBound* b, int count, double k, double start)
  {
    for (int i = 0; i < count; ++i)
    {
      start = std::min(start, b[i].K * k + b[i].C);
    }
    return start;
  }

  double X0 = 0, X1 = 0, Y0 = 0, Y1 = 0;
  bool Empty = false;
  int RowCount = 0;
  RowBound Rows[MaxDomainPlanes];
  Kind RowKind[MaxDomainPlanes];
  double RowOffset[MaxDomainPlanes];
  int YLoCount = 0, YHiCount = 0, XLoCount = 0, XHiCount = 0, ConditionCount = 0;
  SliceBound YLo[MaxBounds], YHi[MaxBounds], XLo[MaxBounds], XHi[MaxBounds];
  SliceBound Conditions[2 * MaxBounds];
};

} // namespace vtkdf

#endif
