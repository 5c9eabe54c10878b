// SliceDomain: scan conversion of a site's domain (an intersection of half-spaces) inside
// a rectangle of sample indices, slice by slice and row by row.
//
// Clipping a polygon on every slice costs about a hundred operations, and most domains
// of a fine mesh hold a sample or two per slice. So the half-spaces are turned once per
// site, by Fourier-Motzkin elimination, into bounds of each scan variable in terms of
// the outer ones: the box of the slice's polygon (x and y ranges as affine functions of
// the slice k) and the span of a row (x range as an affine function of y and k). The
// projection that elimination computes is exact, so the rows and spans are those of
// the clipped polygon; each costs a few multiply-adds. The GPU path evaluates the rows
// this walk gives (CollectScanRows).
#ifndef vtkdf_SliceDomain_h
#define vtkdf_SliceDomain_h

#include "Common/MinMax.h"

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
      const double inv = 1.0 / scale;
      normalized[kept++] = { h.A * inv, h.B * inv, h.C * inv, h.D * inv };
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
    // Rows holds the lower bounds, then the upper bounds, then the conditions.
    double lo = this->X0, hi = this->X1;
    int r = 0;
    for (; r < this->RowLoEnd; ++r)
    {
      lo = Max(lo, this->Rows[r].Y * y + this->RowOffset[r]);
    }
    for (; r < this->RowHiEnd; ++r)
    {
      hi = Min(hi, this->Rows[r].Y * y + this->RowOffset[r]);
    }
    for (; r < this->RowCount; ++r)
    {
      if (this->Rows[r].Y * y + this->RowOffset[r] < 0)
      {
        return false;
      }
    }
    xl = lo;
    xr = hi;
    return lo <= hi;
  }

private:
  static constexpr double Tiny = 1e-9; // coefficients below it (of unit-scaled planes) are 0
  static constexpr int MaxPairs = 256;
  static constexpr int MaxBounds = MaxPairs + MaxDomainPlanes + 2;

  /// Y*y + K*k + C: a lower bound of x, an upper bound, or a condition (>= 0) when the
  /// plane does not involve x.
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

  // The setup runs once per site, and a fine mesh has millions of sites whose domains
  // hold no sample at all: its loops store every candidate and advance the counts by
  // the tests' outcomes instead of branching on coefficient signs the CPU cannot predict.

  void SetupRows(const IndexPlane* planes, int count)
  {
    // Lower bounds of x first, then upper bounds, then the conditions, so that RowSpan's
    // loops do not branch on the kind.
    int lower = 0, upper = 0;
    for (int p = 0; p < count; ++p)
    {
      lower += planes[p].A > Tiny;
      upper += planes[p].A < -Tiny;
    }
    int at[3] = { 0, lower, lower + upper };
    for (int p = 0; p < count; ++p)
    {
      const IndexPlane& h = planes[p];
      const bool bound = std::fabs(h.A) > Tiny;
      const double inv = -1.0 / (bound ? h.A : 1.0);
      const int kind = bound ? (h.A > 0 ? 0 : 1) : 2;
      this->Rows[at[kind]++] =
        bound ? RowBound{ h.B * inv, h.C * inv, h.D * inv } : RowBound{ h.B, h.C, h.D };
    }
    this->RowLoEnd = lower;
    this->RowHiEnd = lower + upper;
    this->RowCount = count;
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
    // Split the planes by the sign of the eliminated variable's coefficient; a plane
    // without it is already a constraint on (kept variable, k).
    double gc[MaxDomainPlanes + 2], kc[MaxDomainPlanes + 2];
    int positive[MaxDomainPlanes + 2], negative[MaxDomainPlanes + 2];
    int np = 0, nn = 0;
    lowerCount = upperCount = 0;
    for (int p = 0; p < count; ++p)
    {
      gc[p] = gone == 0 ? planes[p].A : planes[p].B;
      kc[p] = gone == 0 ? planes[p].B : planes[p].A;
      positive[np] = p;
      negative[nn] = p;
      np += gc[p] > Tiny;
      nn += gc[p] < -Tiny;
      if (!(std::fabs(gc[p]) > Tiny))
      {
        this->AddBound(kc[p], planes[p].C, planes[p].D, lower, lowerCount, upper, upperCount);
      }
    }
    for (int i = 0; i < np; ++i)
    {
      const int l = positive[i];
      for (int j = 0; j < nn; ++j)
      {
        const int q = negative[j];
        // (-g_q) * l + g_l * q has no `gone` term, and both weights are positive.
        const double wl = -gc[q], wq = gc[l];
        this->AddBound(wl * kc[l] + wq * kc[q],
          wl * planes[l].C + wq * planes[q].C,
          wl * planes[l].D + wq * planes[q].D,
          lower,
          lowerCount,
          upper,
          upperCount);
      }
    }
  }

  /// Files the constraint v*kept + c*k + d >= 0 as a lower or upper bound of the kept
  /// variable, or (v counts as zero below Tiny relative to the constraint's scale) as a
  /// condition on k alone.
  void AddBound(double v,
    double c,
    double d,
    SliceBound* lower,
    int& lowerCount,
    SliceBound* upper,
    int& upperCount)
  {
    const double scale = std::max(std::fabs(v), std::fabs(c));
    const bool bound = std::fabs(v) > Tiny * scale;
    const bool condition = !bound && scale > 0;
    // With neither, the constraint is 0 <= d: all or nothing.
    this->Empty = this->Empty || (!(scale > 0) && !(d >= 0));
    const double inv = -1.0 / (bound ? v : 1.0);
    lower[lowerCount] = upper[upperCount] = { c * inv, d * inv };
    lowerCount += bound && v > 0;
    upperCount += bound && v < 0;
    // A condition is rare (a pair of planes whose combination loses the kept variable):
    // a branch the CPU predicts, and no second division on every bound.
    if (condition && this->ConditionCount < 2 * MaxBounds)
    {
      const double cInv = 1.0 / scale;
      this->Conditions[this->ConditionCount++] = { c * cInv, d * cInv };
    }
  }

  static double Lower(const SliceBound* b, int count, double k, double start)
  {
    for (int i = 0; i < count; ++i)
    {
      start = Max(start, b[i].K * k + b[i].C);
    }
    return start;
  }
  static double Upper(const SliceBound* b, int count, double k, double start)
  {
    for (int i = 0; i < count; ++i)
    {
      start = Min(start, b[i].K * k + b[i].C);
    }
    return start;
  }

  double X0 = 0, X1 = 0, Y0 = 0, Y1 = 0;
  bool Empty = false;
  int RowCount = 0, RowLoEnd = 0, RowHiEnd = 0;
  RowBound Rows[MaxDomainPlanes];
  double RowOffset[MaxDomainPlanes];
  int YLoCount = 0, YHiCount = 0, XLoCount = 0, XHiCount = 0, ConditionCount = 0;
  SliceBound YLo[MaxBounds], YHi[MaxBounds], XLo[MaxBounds], XHi[MaxBounds];
  SliceBound Conditions[2 * MaxBounds];
};

} // namespace vtkdf

#endif
