#version 450 core
// The sites and their domain planes, as LinearFactorGPU.cxx uploads them; prepended to
// the domain shaders (GLSL has no #include). Positions are relative to the whole grid's
// first sample, so that a sample's value does not depend on the extent computed (a slab
// of a distributed run gives the whole grid's bits); regions are extent indices.
struct GpuSite
{
  vec4 anchor; // xyz: anchor relative to the whole grid's first sample (world units); w: type
  vec4 axis;   // edge tangent or face normal
  ivec4 lo;    // region, sample indices relative to the extent; w: first plane
  ivec4 hi;    // w: number of planes (w of anchor packs nothing else)
};
layout(std430, binding = 0) readonly buffer Sites { GpuSite sites[]; };
// Domain planes in sample-index space, relative to the anchor.
layout(std430, binding = 1) readonly buffer Planes { vec4 planes[]; };

uniform vec3 spacing;
uniform ivec3 extentLo; // the extent's first sample, in indices of the whole grid

// The site's distance vector at a sample (indices of the whole grid): the affine function
// of the linear factorization (Sud et al. (I3D 2006) section 3), evaluated exactly.
vec3 distanceVectorAt(GpuSite s, vec3 indexPos)
{
  vec3 r = s.anchor.xyz - indexPos * spacing;
  int type = int(s.anchor.w);
  if (type == 1)
  {
    return r - dot(r, s.axis.xyz) * s.axis.xyz;
  }
  if (type == 2)
  {
    return dot(r, s.axis.xyz) * s.axis.xyz;
  }
  return r;
}
