// The site's distance at the sample; the depth test keeps the nearest site. The vector
// is evaluated here rather than interpolated across the polygon, whose corners depend on
// the extent's culling: the same sample then gets the same bits in any extent.

uniform int layerBase;
uniform float depthScale;

flat in int siteIndex;
layout(location = 0) out float outDistance;
layout(location = 1) out int outSite;

void main()
{
  GpuSite s = sites[siteIndex];
  // The formula of a triangle (edge) is exact only inside its prism (slab): test those
  // planes exactly here, since the polygon was widened against sub-pixel snapping.
  int required = int(s.axis.w);
  vec3 indexPos = vec3(gl_FragCoord.xy - 0.5, float(gl_Layer + layerBase)) + vec3(extentLo);
  vec3 rel = indexPos - s.anchor.xyz / spacing;
  for (int p = 0; p < required; ++p)
  {
    vec4 pl = planes[s.lo.w + p];
    if (dot(pl.xyz, rel) + pl.w < 0.0)
    {
      discard;
    }
  }
  float d = length(distanceVectorAt(s, indexPos));
  gl_FragDepth = clamp(d * depthScale, 0.0, 1.0);
  outDistance = d;
  outSite = siteIndex;
}
