#version 450 core
// One point per (site, run of 32 slices); the geometry shader builds the polygons.
layout(location = 0) in ivec2 siteAndSlice;
flat out ivec2 vSiteAndSlice;
void main()
{
  vSiteAndSlice = siteAndSlice;
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
