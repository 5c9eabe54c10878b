#version 450 core
// The medial axis pass (Filters/Core/Medial/MedialAxis.cxx MedialAxisCPU and SmallestCapCosine
// in MedialAxis.h: the same arithmetic in double precision, `precise`, with IEEE's
// square roots and quotients (SqrtRN, DivRN: a GL's own may be less exact), so that both
// backends mark the same voxels): per voxel, over the 2x2x2 cells whose marked corner it
// is (largest |distance|, ties to the lower index), the smallest cosine of the cells'
// apertures that count (not a fan's) and reach the threshold; 2 when none.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Distances
{
  float distance[];
};
layout(std430, binding = 1) readonly buffer ClosestPoints
{
  float closest[];
};
layout(std430, binding = 2) writeonly buffer Cosines
{
  double cosine[];
};
//DF::SampleGrid
uniform double Threshold;    // cos(theta)
uniform double HalfDiagonal; // half the cell diagonal, l/2
uniform double CapTolerance; // MedialCapTolerance
uniform double FanMargin;    // MedialFanMargin
uniform int Region;          // 0 inside, 1 outside, 2 both
uniform int First;           // voxel index of invocation 0 (dispatches are split)
uniform int Last;            // one past the last voxel of this dispatch
// The buffers are bound by ranges (slabs of z): element offsets of their first element.
uniform int DistanceBase, ClosestBase, CosineBase;
//DF::CorrectlyRounded

// The cell's 8 closest-point directions, as the bits of their doubles: NVIDIA's GL
// (driver 580, H100) kept a dvec3 array here in single precision (the dot products of
// unit vectors came 1e-8 from the CPU's), and the caps' tolerance is 1e-9.
uvec2 directionBits[24];

dvec3 U(int k)
{
  return dvec3(packDouble2x32(directionBits[3 * k]), packDouble2x32(directionBits[3 * k + 1]),
    packDouble2x32(directionBits[3 * k + 2]));
}

void SetU(int k, dvec3 v)
{
  directionBits[3 * k] = unpackDouble2x32(v.x);
  directionBits[3 * k + 1] = unpackDouble2x32(v.y);
  directionBits[3 * k + 2] = unpackDouble2x32(v.z);
}

bool HoldsAll(dvec3 centre, double cosRadius)
{
  for (int k = 0; k < 8; ++k)
  {
    dvec3 uk = U(k);
    precise double c = centre.x * uk.x + centre.y * uk.y + centre.z * uk.z;
    if (c < cosRadius - CapTolerance)
    {
      return false;
    }
  }
  return true;
}

double Dot(dvec3 a, dvec3 b)
{
  precise double c = a.x * b.x + a.y * b.y + a.z * b.z;
  return c;
}

double SmallestCapCosine()
{
  int wi = 0, wj = 1;
  double widest = Dot(U(0), U(1));
  for (int i = 0; i < 8; ++i)
  {
    for (int j = i + 1; j < 8; ++j)
    {
      double c = Dot(U(i), U(j));
      if (c < widest)
      {
        widest = c;
        wi = i;
        wj = j;
      }
    }
  }
  precise dvec3 s = U(wi) + U(wj);
  precise double sn = SqrtRN(Dot(s, s));
  if (!(sn > 1e-12lf))
  {
    return 0.0lf;
  }
  s = dvec3(DivRN(s.x, sn), DivRN(s.y, sn), DivRN(s.z, sn));
  double pairCos = Dot(s, U(wi));
  if (HoldsAll(s, pairCos))
  {
    return pairCos;
  }
  double best = 0.0lf;
  for (int i = 0; i < 8; ++i)
  {
    for (int j = i + 1; j < 8; ++j)
    {
      for (int k = j + 1; k < 8; ++k)
      {
        precise dvec3 e = U(j) - U(i);
        precise dvec3 f = U(k) - U(i);
        precise dvec3 n =
          dvec3(e.y * f.z - e.z * f.y, e.z * f.x - e.x * f.z, e.x * f.y - e.y * f.x);
        precise double nn = SqrtRN(Dot(n, n));
        if (!(nn > 1e-12lf))
        {
          continue;
        }
        n = dvec3(DivRN(n.x, nn), DivRN(n.y, nn), DivRN(n.z, nn));
        double c = Dot(n, U(i));
        if (c < 0.0lf)
        {
          c = -c;
          n = -n;
        }
        if (c > best && HoldsAll(n, c))
        {
          best = c;
        }
      }
    }
  }
  return best;
}

void main()
{
  int at = First + int(gl_GlobalInvocationID.x);
  if (at >= Last)
  {
    return;
  }
  ivec3 ijk = ivec3(at % Dims.x, (at / Dims.x) % Dims.y, at / (Dims.x * Dims.y));
  ivec3 stride = ivec3(1, Dims.x, Dims.x * Dims.y);
  double best = 2.0lf;
  // The voxel's own |distance| bounds its cells' D (MedialAxis.cxx): most stop here.
  float own = distance[at - DistanceBase];
  bool inRegion = Region == 2 ? !isnan(own) : (Region == 0 ? own < 0.0 : own > 0.0);
  double own2 = double(own) * double(own) * (1.0lf + 1e-6lf);
  bool candidate = inRegion &&
    own2 - HalfDiagonal * HalfDiagonal > HalfDiagonal * HalfDiagonal * (FanMargin * FanMargin);
  for (int o = 0; o < 8 && candidate; ++o)
  {
    ivec3 lo = ijk - ivec3(o & 1, (o >> 1) & 1, o >> 2);
    if (any(lessThan(lo, ivec3(0))) || any(greaterThanEqual(lo + 1, Dims)))
    {
      continue;
    }
    int base = lo.x + lo.y * stride.y + lo.z * stride.z;
    // This voxel is the cell's marked corner (MedialAxis.h MarkedCorner): every corner
    // in the region, the earlier ones less deep, the later ones no deeper. Most cells
    // fail at their first deeper corner.
    int corner[8];
    float d[8];
    bool mine = true;
    for (int k = 0; k < 8 && mine; ++k)
    {
      corner[k] = base + (k & 1) + ((k >> 1) & 1) * stride.y + (k >> 2) * stride.z;
      d[k] = distance[corner[k] - DistanceBase];
      bool inside = Region == 2 ? !isnan(d[k]) : (Region == 0 ? d[k] < 0.0 : d[k] > 0.0);
      mine = inside && (k == o || (k < o ? abs(d[k]) < abs(own) : abs(d[k]) <= abs(own)));
    }
    if (!mine)
    {
      continue;
    }
    // MedialAxis.h MeasureMedialCell.
    precise double squares = 0.0lf;
    for (int k = 0; k < 8; ++k)
    {
      squares += double(d[k]) * double(d[k]);
    }
    precise double fan2 = DivRN(squares, 8.0lf) - HalfDiagonal * HalfDiagonal;
    precise double depth = fan2 > 0.0lf ? DivRN(SqrtRN(fan2), HalfDiagonal) : 0.0lf;
    if (!(depth > FanMargin))
    {
      continue;
    }
    bool usable = true;
    for (int k = 0; k < 8 && usable; ++k)
    {
      int c = 3 * corner[k] - ClosestBase;
      ivec3 kijk = lo + ivec3(k & 1, (k >> 1) & 1, k >> 2);
      precise dvec3 x = Origin + dvec3(Lo + kijk) * Spacing;
      precise dvec3 v =
        dvec3(double(closest[c]), double(closest[c + 1]), double(closest[c + 2])) - x;
      precise double norm = SqrtRN(v.x * v.x + v.y * v.y + v.z * v.z);
      usable = norm > 0.0lf && !isinf(norm);
      SetU(k, dvec3(DivRN(v.x, norm), DivRN(v.y, norm), DivRN(v.z, norm)));
    }
    if (!usable)
    {
      continue;
    }
    // A cell that surely does not count (MedialAxis.h MeasureMedialCell).
    double farthest = 1.0lf;
    for (int k = 1; k < 8; ++k)
    {
      farthest = min(farthest, Dot(U(0), U(k)));
    }
    precise double doubled = 2.0lf * farthest * farthest - 1.0lf;
    precise double farReach = SqrtRN(1.0lf - farthest * farthest) * depth;
    if (farthest >= 0.0lf && (doubled > Threshold + 1e-6lf || farReach < FanMargin - 1e-6lf))
    {
      continue;
    }
    precise double capCos = SmallestCapCosine();
    precise double reach = SqrtRN(1.0lf - capCos * capCos) * depth;
    precise double cs = 2.0lf * capCos * capCos - 1.0lf;
    if (reach > FanMargin && cs <= Threshold && cs < best)
    {
      best = cs;
    }
  }
  cosine[at - CosineBase] = best;
}
