#version 450 core
// The sites and their domain planes, as LinearFactorGPU.cxx uploads them; prepended to
// the domain shaders (GLSL has no #include).
struct GpuSite
{
  vec4 anchor; // xyz: anchor relative to the extent's first sample (world units); w: type
  vec4 axis;   // edge tangent or face normal
  ivec4 lo;    // region, sample indices relative to the extent; w: first plane
  ivec4 hi;    // w: number of planes (w of anchor packs nothing else)
};
layout(std430, binding = 0) readonly buffer Sites { GpuSite sites[]; };
// Domain planes in sample-index space, relative to the anchor.
layout(std430, binding = 1) readonly buffer Planes { vec4 planes[]; };
