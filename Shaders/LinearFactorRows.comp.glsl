// The scan's rows on the GPU: each invocation offers one site to one row of samples, with
// the CPU's arithmetic (LinearFactorScan.cxx, SiteScan::Offer): the distance vector in
// double from the site's frame, each product and sum rounded apart (`precise`), rounded
// to float, its squared length in float. The nearest site of a sample is the least
// (squared distance, site) pair, whatever the order of the offers:
// - ONE_PASS: one 64-bit atomic minimum of the packed pair (NearestSiteBuffer::Pack);
// - otherwise two passes over the same rows: DISTANCE_PASS keeps the least squared
//   distance (its float bits order as the floats do) and, where an offer lowers it,
//   forgets the sample's site; then, where an offer equals the least distance, the
//   other pass keeps the least site. A site kept by an earlier batch stays exactly when
//   its distance is still the least.
// Prepended by LinearFactorGPU.cxx: #version, the extensions and the pass's #define.
layout(local_size_x = 64) in;
struct Frame
{
  dvec4 D0; // w: the site's index
  dvec4 Du; // w: the extent's stride along the row
  dvec4 Dv;
  dvec4 Dw;
};
struct Row
{
  uint Frame;
  int At, J, K, I0, I1;
};
layout(std430, binding = 0) readonly buffer Frames
{
  Frame frames[];
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
  Frame f = frames[row.Frame];
  precise dvec3 slice = f.D0.xyz + double(row.K) * f.Dw.xyz;
  precise dvec3 start = slice + double(row.J) * f.Dv.xyz;
  uint id = uint(f.D0.w);
  int stride = int(f.Du.w);
  int at = row.At - SampleBase;
  for (int i = row.I0; i <= row.I1; ++i, at += stride)
  {
    precise dvec3 d = start + double(i) * f.Du.xyz;
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
