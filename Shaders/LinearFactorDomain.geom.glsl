// Builds a site's domain polygon on one slice (the same clipping as SliceDomain.h) and
// emits it into that slice's layer: its fragments are the samples where the site's
// distance is evaluated (linear factorization, Sud et al. (I3D 2006) section 3).
layout(points) in; // one point per site and slice
layout(triangle_strip, max_vertices = 32) out;

const int MaxPlanes = 28;

// Range culling (RangeCulling.h): a site's bounds, and an upper bound of the field per
// block of samples; a slice whose polygon meets no block where the site may still be
// the nearest is not emitted (a column ends at its reach, as on the CPU).
layout(std430, binding = 2) readonly buffer SiteBounds { vec4 siteBounds[]; }; // lo, hi per site
layout(std430, binding = 3) readonly buffer BlockBounds { float blockBound[]; };
uniform ivec3 blockCounts;
uniform int blockSize;
uniform float minSpacing;

uniform ivec2 viewportSize;
uniform int layerBase;
uniform int layerCount;
uniform float margin; // extra widening (sample units) against sub-pixel snapping

flat in ivec2 vSiteAndSlice[];
flat out int siteIndex;

// Whether a site within [lo, hi] (world, relative to the whole grid's first sample) may
// be the nearest somewhere in block b's cell (its samples widened by half a spacing;
// blocks count from the extent's first sample). The bound is widened by 1e-5 (relative)
// and 1e-4 spacing against float rounding.
bool mayWin(ivec3 b, vec3 lo, vec3 hi)
{
  vec3 cellLo = (vec3(b * blockSize + extentLo) - 0.5) * spacing;
  vec3 cellHi = cellLo + float(blockSize) * spacing;
  vec3 gap = max(max(lo - cellHi, cellLo - hi), vec3(0.0));
  float bound = blockBound[b.x + blockCounts.x * (b.y + blockCounts.y * b.z)];
  float limit = bound * (1.0 + 1e-5) + 1e-4 * minSpacing;
  return dot(gap, gap) <= limit * limit;
}

int blockOf(float index, int count)
{
  return clamp(int(floor((index + 0.5) / float(blockSize))), 0, count - 1);
}

void main()
{
  int id = vSiteAndSlice[0].x;
  int k = vSiteAndSlice[0].y;
  GpuSite s = sites[id];
  if (k < s.lo.z || k > s.hi.z || k < layerBase || k >= layerBase + layerCount)
  {
    return;
  }
  vec2 bufA[32];
  vec2 bufB[32];
  int n = 4;
  vec2 lo = vec2(s.lo.xy) - 0.25;
  vec2 hi = vec2(s.hi.xy) + 0.25;
  bufA[0] = lo;
  bufA[1] = vec2(hi.x, lo.y);
  bufA[2] = hi;
  bufA[3] = vec2(lo.x, hi.y);
  // The polygon is built in extent indices.
  vec3 anchorIndex = s.anchor.xyz / spacing - vec3(extentLo);
  int count = min(s.hi.w, MaxPlanes);
  for (int p = 0; p < count && n > 0; ++p)
  {
    vec4 pl = planes[s.lo.w + p];
    float c = pl.z * (float(k) - anchorIndex.z) + pl.w + margin * length(pl.xyz);
    int m = 0;
    for (int v = 0; v < n; ++v)
    {
      vec2 a = (p % 2 == 0) ? bufA[v] : bufB[v];
      vec2 b = (p % 2 == 0) ? bufA[(v + 1) % n] : bufB[(v + 1) % n];
      float fa = dot(pl.xy, a - anchorIndex.xy) + c;
      float fb = dot(pl.xy, b - anchorIndex.xy) + c;
      if (fa >= 0.0 && m < 32)
      {
        if (p % 2 == 0) bufB[m] = a; else bufA[m] = a;
        ++m;
      }
      if ((fa >= 0.0) != (fb >= 0.0) && m < 32)
      {
        vec2 x = a + (fa / (fa - fb)) * (b - a);
        if (p % 2 == 0) bufB[m] = x; else bufA[m] = x;
        ++m;
      }
    }
    n = m;
  }
  if (n < 3)
  {
    return;
  }
  bool inB = (count % 2) == 1;
  vec2 pmin = vec2(1e30), pmax = vec2(-1e30);
  for (int v = 0; v < n; ++v)
  {
    vec2 q = inB ? bufB[v] : bufA[v];
    pmin = min(pmin, q);
    pmax = max(pmax, q);
  }
  vec3 siteLo = siteBounds[2 * id].xyz, siteHi = siteBounds[2 * id + 1].xyz;
  int bw = blockOf(float(k), blockCounts.z);
  bool alive = false;
  for (int bv = blockOf(pmin.y, blockCounts.y); bv <= blockOf(pmax.y, blockCounts.y) && !alive; ++bv)
  {
    for (int bu = blockOf(pmin.x, blockCounts.x); bu <= blockOf(pmax.x, blockCounts.x) && !alive; ++bu)
    {
      alive = mayWin(ivec3(bu, bv, bw), siteLo, siteHi);
    }
  }
  if (!alive)
  {
    return;
  }
  // Convex polygon as a strip: v0, v1, v(n-1), v2, v(n-2), ...
  int left = 1, right = n - 1;
  for (int e = 0; e < n; ++e)
  {
    int v;
    if (e == 0) v = 0;
    else if (e % 2 == 1) v = left++;
    else v = right--;
    vec2 q = inB ? bufB[v] : bufA[v];
    vec2 window = q + 0.5;
    gl_Position = vec4(window / vec2(viewportSize) * 2.0 - 1.0, 0.0, 1.0);
    gl_Layer = k - layerBase;
    siteIndex = id;
    EmitVertex();
  }
  EndPrimitive();
}
