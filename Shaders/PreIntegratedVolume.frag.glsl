//VTK::System::Dec
//VTK::Output::Dec
//DF::SlabCommon

// Pre-integrated compositing of a scalar volume (Engel, Kraus, Ertl 2001). One fragment
// of a view-aligned slice stands for the slab between this slice and the next one along
// its ray, cut where the ray leaves the volume or meets opaque geometry. The table holds,
// per (front value, back value), the slab's average extinction (a) and its
// extinction-weighted average colour (rgb), so the slab's length enters exactly:
// alpha = 1 - exp(-length * a).

uniform sampler3D scalars;        // the scalar volume (read with texelFetch)
uniform sampler2D preIntegrated;  // RGBA: average colour, average extinction
uniform sampler2D opaqueDepth;    // the depth buffer before the volume was drawn
uniform int useOpaqueDepth;
uniform ivec2 viewportOrigin;
uniform vec2 scalarRange;         // the table's first and last values
uniform float tableSize;

// Trilinear interpolation in full float precision: texture filtering's weights have a few
// bits of precision only (8 on most hardware and llvmpipe), which bands smooth fields
// into rings, in the values and worse in their central differences.
float valueAt(vec3 index)
{
  ivec3 last = ivec3(gridSize + 0.5) - 1;
  vec3 q = clamp(index, vec3(0.0), vec3(last));
  ivec3 b = min(ivec3(floor(q)), max(last - 1, ivec3(0)));
  vec3 t = q - vec3(b);
  float v[8];
  for (int k = 0; k < 8; ++k)
  {
    v[k] = texelFetch(scalars, min(b + ivec3(k & 1, (k >> 1) & 1, k >> 2), last), 0).r;
  }
  return trilinear(v, t);
}

// The premultiplied colour of the slab from index-space point a to b, of world length d.
vec4 slabColor(vec3 a, vec3 b, float d, vec3 dir)
{
  float front = valueAt(a);
  float back = valueAt(b);
  vec2 table = (clamp((vec2(front, back) - scalarRange.x) / (scalarRange.y - scalarRange.x),
                  0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize;
  vec4 entry = texture(preIntegrated, table);
  float alpha = 1.0 - exp(-d * entry.a);
  vec3 color = entry.rgb;
  if (shade == 1)
  {
    // The normal at the slab's midpoint, by central differences a voxel each way: over
    // half a voxel the gradient of the trilinear interpolant shows every cell face (rings
    // around the axes on a sphere).
    vec3 m = 0.5 * (a + b);
    vec3 g;
    for (int k = 0; k < 3; ++k)
    {
      vec3 e = vec3(0.0);
      e[k] = 1.0;
      g[k] = valueAt(m + e) - valueAt(m - e);
    }
    // Where the field is flat (under 1% of its range over two voxels) the gradient's
    // direction is noise: no directional shading there.
    float flatBelow = 0.01 * (scalarRange.y - scalarRange.x);
    color = headlight(color, length(g) > flatBelow ? indexToWorldNormal * g : vec3(0.0), dir);
  }
  return vec4(color * alpha, alpha);
}

// The parameter along [front, back] (clip coordinates) where the depth reaches z.
float depthCut(vec4 front, vec4 back, float z)
{
  float ndc = 2.0 * z - 1.0;
  float denominator = (back.z - front.z) - ndc * (back.w - front.w);
  return abs(denominator) > 1e-30 ? (ndc * front.w - front.z) / denominator : 1.0;
}

void main()
{
  vec3 dir, frontWC, backWC, frontI, backI;
  slabOfFragment(dir, frontWC, backWC, frontI, backI);

  // Cut the slab where the ray leaves the volume...
  float cut = 1.0;
  vec3 stepI = backI - frontI;
  vec3 last = gridSize - 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (stepI[a] > 0.0)
    {
      cut = min(cut, (last[a] - frontI[a]) / stepI[a]);
    }
    else if (stepI[a] < 0.0)
    {
      cut = min(cut, -frontI[a] / stepI[a]);
    }
  }
  // ... and where it meets opaque geometry.
  if (useOpaqueDepth == 1)
  {
    float z = texelFetch(opaqueDepth, ivec2(gl_FragCoord.xy) - viewportOrigin, 0).r;
    vec4 frontClip = worldToClip * vec4(frontWC, 1.0);
    vec4 backClip = worldToClip * vec4(backWC, 1.0);
    if (0.5 * backClip.z / backClip.w + 0.5 > z)
    {
      cut = min(cut, depthCut(frontClip, backClip, z));
    }
  }
  if (cut <= 0.0)
  {
    discard;
  }
  vec4 slab = slabColor(frontI, mix(frontI, backI, cut), cut * length(backWC - frontWC), dir);
  // A ray that enters the volume through a side between the previous slice and this one
  // has that stretch in front of this slice, which no slice covers: add it, in front.
  vec3 previousI = frontI - stepI;
  float enter = entryAlong(previousI, stepI);
  if (enter > 0.0 && enter < 1.0)
  {
    vec4 ahead = slabColor(mix(previousI, frontI, enter), frontI,
      (1.0 - enter) * length(backWC - frontWC), dir);
    slab = ahead + (1.0 - ahead.a) * slab;
  }
  gl_FragData[0] = slab;
}
