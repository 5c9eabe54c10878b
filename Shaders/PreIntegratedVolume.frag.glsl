//VTK::System::Dec
//VTK::Output::Dec
//DF::SlabCommon

// Pre-integrated compositing of a scalar volume (Engel, Kraus, Ertl 2001), ray cast: one
// fragment a pixel walks its ray's slabs front to back, cut where the ray leaves the
// volume or meets opaque geometry, and stops once the pixel is opaque. The table holds,
// per (front value, back value), the slab's average extinction (a) and its
// extinction-weighted average colour (rgb), so the slab's length enters exactly:
// alpha = 1 - exp(-length * a).

uniform sampler3D scalars;        // the scalar volume (read with texelFetch)
uniform sampler2D preIntegrated;  // RGBA: average colour, average extinction
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

// The premultiplied colour of a slab of world length d whose ends have the values front
// and back, shaded at its midpoint m (index space).
vec4 slabColor(float front, float back, vec3 m, float d, vec3 dir)
{
  vec2 table = (clamp((vec2(front, back) - scalarRange.x) / (scalarRange.y - scalarRange.x),
                  0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize;
  vec4 entry = texture(preIntegrated, table);
  float alpha = 1.0 - exp(-d * entry.a);
  vec3 color = entry.rgb;
  if (shade == 1 && alpha > 0.0)
  {
    // The normal by central differences a voxel each way: over half a voxel the gradient
    // of the trilinear interpolant shows every cell face (rings around the axes on a
    // sphere).
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

void main()
{
  vec3 dir, originWC, stepWC;
  if (!rayOfFragment(dir, originWC, stepWC))
  {
    discard;
  }
  vec3 originI = (worldToIndex * vec4(originWC, 1.0)).xyz;
  vec3 stepI = mat3(worldToIndex) * stepWC;
  float enter, leave;
  boxInterval(originI, stepI, enter, leave);
  float start = max(enter, nearDepth);
  if (!(leave > start))
  {
    discard;
  }
  leave = opaqueCut(originWC, stepWC, start, leave);
  float worldPerDepth = length(stepWC);
  // Front to back: each slab's back value is the next one's front value.
  vec4 sum = vec4(0.0);
  float s = start;
  float front = valueAt(originI + s * stepI);
  for (int k = planeAtOrAfter(s); s < leave && k <= sliceCount; ++k)
  {
    float next = k < sliceCount ? min(planeDepth(k), leave) : leave;
    if (next <= s)
    {
      continue;
    }
    float back = valueAt(originI + next * stepI);
    vec4 slab =
      slabColor(front, back, originI + (0.5 * (s + next)) * stepI, (next - s) * worldPerDepth, dir);
    sum += (1.0 - sum.a) * slab;
    // What lies behind would change no 8-bit channel by half a step.
    if (sum.a >= 0.998)
    {
      break;
    }
    front = back;
    s = next;
  }
  if (sum.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = sum;
}
