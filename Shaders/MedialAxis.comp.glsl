#version 450 core
// The medial axis pass (Filters/Core/MedialAxis.cxx MedialAxisCPU, the same arithmetic
// in double precision, `precise`): per voxel, the smallest cosine of the separation
// angles of the 6 pairs it is the medial voxel of (larger |distance|, ties to the lower
// index), 2 when none reaches the threshold.
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
uniform ivec3 Dims;
uniform ivec3 Lo;
uniform dvec3 Origin, Spacing;
uniform double Threshold; // cos(theta)
uniform double Depth;     // the depth a pair needs, in spacings (MedialMinimumDepth)
uniform int Region;       // 0 inside, 1 outside, 2 both
uniform int First;        // voxel index of invocation 0 (dispatches are split)
uniform int Last;         // one past the last voxel of this dispatch
// The buffers are bound by ranges (slabs of z): element offsets of their first element.
uniform int DistanceBase, ClosestBase, CosineBase;

double PairCosine(dvec3 m, int i, int j)
{
  int a = 3 * i - ClosestBase, b = 3 * j - ClosestBase;
  precise dvec3 u = dvec3(double(closest[a]), double(closest[a + 1]), double(closest[a + 2])) - m;
  precise dvec3 v = dvec3(double(closest[b]), double(closest[b + 1]), double(closest[b + 2])) - m;
  precise double uu = u.x * u.x + u.y * u.y + u.z * u.z;
  precise double vv = v.x * v.x + v.y * v.y + v.z * v.z;
  precise double uv = u.x * v.x + u.y * v.y + u.z * v.z;
  precise double norms = sqrt(uu * vv);
  if (!(norms > 0.0lf))
  {
    return 2.0lf;
  }
  precise double c = uv / norms;
  return c;
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
  float d = distance[at - DistanceBase];
  bool inRegion = Region == 2 || (Region == 0 ? d < 0.0 : d > 0.0);
  double best = 2.0lf;
  if (inRegion)
  {
    for (int a = 0; a < 3; ++a)
    {
      for (int side = -1; side <= 1; side += 2)
      {
        int other = ijk[a] + side;
        if (other < 0 || other >= Dims[a])
        {
          continue;
        }
        int nb = at + side * stride[a];
        float dn = distance[nb - DistanceBase];
        bool mine = abs(d) > abs(dn) || (abs(d) == abs(dn) && at < nb);
        if (!mine || double(min(abs(d), abs(dn))) <= Depth * Spacing[a])
        {
          continue;
        }
        precise dvec3 m = Origin + dvec3(Lo + ijk) * Spacing;
        m[a] += 0.5lf * double(side) * Spacing[a];
        double cs = PairCosine(m, at, nb);
        if (cs <= Threshold && cs < best)
        {
          best = cs;
        }
      }
    }
  }
  cosine[at - CosineBase] = best;
}
