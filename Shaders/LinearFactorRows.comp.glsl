// The scan's rows on the GPU: each invocation offers one site to one row of samples, with
// the CPU's arithmetic (LinearFactorScan.cxx, SiteScan::Offer): the distance vector in
// double from the row's start (the CPU's) and the site's step, the product and the sum
// rounded apart (`precise`), rounded to float, its squared length in float. The nearest site of a sample is the least
// (squared distance, site) pair, whatever the order of the offers:
// - ONE_PASS: one 64-bit atomic minimum of the packed pair (NearestSiteBuffer::Pack);
// - otherwise two passes over the same rows: DISTANCE_PASS keeps the least squared
//   distance (its float bits order as the floats do) and, where an offer lowers it,
//   forgets the sample's site; then, where an offer equals the least distance, the
//   other pass keeps the least site. A site kept by an earlier batch stays exactly when
//   its distance is still the least.
// Prepended by LinearFactorGPU.cxx: #version, the extensions and the pass's #define.
layout(local_size_x = 64) in;
struct Row
{
  double StartX, StartY, StartZ; // the distance vector at i = 0
  uint Frame;
  int At, I0, I1, Stride;
};
layout(std430, binding = 0) readonly buffer Frames
{
  dvec4 frames[]; // xyz: the distance vector's step along the row; w: the site's index
};
layout(std430, binding = 1) readonly buffer Rows
{
  Row rows[];
};
#ifdef ONE_PASS
layout(std430, binding = 2) buffer Nearest
{
  uint64_t nearest[];
};
#else
layout(std430, binding = 2) buffer Distances
{
  uint distance2[];
};
layout(std430, binding = 3) buffer Sites
{
  uint site[];
};
#endif
uniform int First, Count; // the rows of this dispatch
uniform int SampleBase;    // the first sample of the bound ranges

void main()
{
  int r = First + int(gl_GlobalInvocationID.x);
  if (r >= Count)
  {
    return;
  }
  Row row = rows[r];
  dvec4 step = frames[row.Frame];
  dvec3 start = dvec3(row.StartX, row.StartY, row.StartZ);
  uint id = uint(step.w);
  int at = row.At - SampleBase;
  for (int i = row.I0; i <= row.I1; ++i, at += row.Stride)
  {
    precise dvec3 d = start + double(i) * step.xyz;
    precise float dx = float(d.x), dy = float(d.y), dz = float(d.z);
    precise float d2 = dx * dx + dy * dy + dz * dz;
    uint bits = floatBitsToUint(d2);
#if defined(ONE_PASS)
    atomicMin(nearest[at], (uint64_t(bits) << 32) | uint64_t(id));
#elif defined(DISTANCE_PASS)
    if (bits < atomicMin(distance2[at], bits))
    {
      site[at] = 0xffffffffu;
    }
#else
    if (bits == distance2[at])
    {
      atomicMin(site[at], id);
    }
#endif
  }
}
