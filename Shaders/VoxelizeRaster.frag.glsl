// The bits one triangle sets on one lane texel (blended with a logical OR):
// - boundary: the candidate voxels whose centre is within the distance limit;
// - solid: the half-voxel bin of the crossing, as a front (Out0) or back (Out1) bit.
uniform int Mode;
uniform int Na;
uniform ivec3 Axes;     // the view's A, B, C
//DF::SampleGrid
uniform double Limit2, Reach;

flat in int TriIndex;
layout(location = 0) out uvec4 Out0;
layout(location = 1) out uvec4 Out1;

uvec4 Bit(int i)
{
  const uvec4 words = uvec4(0u, 1u, 2u, 3u);
  return mix(uvec4(0u), uvec4(1u << uint(i & 31)), equal(words, uvec4(uint(i >> 5))));
}

void main()
{
  int64_t p = int64_t(gl_FragCoord.x), q = int64_t(gl_FragCoord.y);
  int base = gl_Layer * 128;
  if (Mode == 1)
  {
    Tri t = tris[TriIndex];
    i64vec3 e;
    if (!CoversCentre(t, p, q, e))
    {
      discard;
    }
    int at = SolidBit(DepthAt(t, e), Na) - base;
    if (at < 0 || at >= 128)
    {
      discard;
    }
    Out0 = t.Flags.x != 0 ? Bit(at) : uvec4(0u);
    Out1 = t.Flags.x != 0 ? uvec4(0u) : Bit(at);
    return;
  }
  BoundaryTri b = btris[TriIndex];
  int k0, k1;
  if (!BoundaryLaneCandidates(b, int(p), int(q), Reach, k0, k1))
  {
    discard;
  }
  k0 = max(k0, base);
  k1 = min(k1, base + 127);
  uvec4 bits = uvec4(0u);
  for (int k = k0; k <= k1; ++k)
  {
    const ivec3 axis = ivec3(0, 1, 2);
    ivec3 ijk = k * ivec3(equal(axis, ivec3(Axes.x))) + int(p) * ivec3(equal(axis, ivec3(Axes.y))) +
      int(q) * ivec3(equal(axis, ivec3(Axes.z)));
    precise dvec3 centre = Origin + dvec3(Lo + ijk) * Spacing;
    if (SquaredDistanceToTriangle(centre, b.P0.xyz, b.P1.xyz, b.P2.xyz) <= Limit2)
    {
      bits |= Bit(k - base);
    }
  }
  if (bits == uvec4(0u))
  {
    discard;
  }
  Out0 = bits;
  Out1 = uvec4(0u);
}
