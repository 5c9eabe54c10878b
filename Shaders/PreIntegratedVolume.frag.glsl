//VTK::System::Dec
//VTK::Output::Dec
//DF::SlabCommon

// Pre-integrated compositing of a scalar volume (Engel, Kraus, Ertl 2001), ray cast: one
// fragment a pixel walks its ray's slabs front to back, cut where the ray leaves the
// volume or meets opaque geometry, and stops once the pixel is opaque. The table holds,
// per (front value, back value), the slab's average extinction (a) and its
// extinction-weighted average colour (rgb), so the slab's length enters exactly:
// alpha = 1 - exp(-length * a).

uniform sampler3D scalars;        // the scalar volume, linear filtering: the value, or
                                  // with STORED_GRADIENT the value and its central
                                  // differences, normalized (16-bit signed):
uniform float packedValueOffset;  // value = offset + scale * texel.r
uniform float packedValueScale;
uniform float packedGradientScale; // differences = scale * texel.gba
uniform sampler2D preIntegrated;  // RGBA: average colour, average extinction
uniform vec2 scalarRange;         // the table's first and last values
uniform vec2 tableMap;            // value -> table coordinate: value * x + y ...
uniform vec2 tableEnds;           // ... clamped to the first and last entries' centres

// The interpolated value at an index-space point and, when shading, the gradient there
// (per two index steps), by the texture unit's trilinear filtering: one fetch where eight
// texelFetch calls cost three times as much on a software rasterizer. Its weights have 8
// fractional bits on most GPUs: a value is off by at most 1/256 of the difference between
// neighbouring voxels, well inside the pre-integration table's steps. The gradient is the
// central differences of the interpolated values a voxel each way (over half a voxel the
// gradient of the trilinear interpolant shows every cell face: rings around the axes on a
// sphere); stored per voxel, they are interpolated like the values (the same numbers:
// interpolation is linear in the voxels), with the value in 16 bits over the array's
// range (1/65,535 of it: finer than the largest table).
vec4 sampleAt(vec3 index)
{
  vec3 p = (index + 0.5) / gridSize;
  vec4 texel = texture(scalars, p);
#if STORED_GRADIENT
  texel = vec4(packedValueOffset + packedValueScale * texel.r, packedGradientScale * texel.gba);
#endif
#if DIFFERENCED_GRADIENT
  vec3 e = 1.0 / gridSize;
  texel.gba = vec3(texture(scalars, p + vec3(e.x, 0.0, 0.0)).r -
      texture(scalars, p - vec3(e.x, 0.0, 0.0)).r,
    texture(scalars, p + vec3(0.0, e.y, 0.0)).r - texture(scalars, p - vec3(0.0, e.y, 0.0)).r,
    texture(scalars, p + vec3(0.0, 0.0, e.z)).r - texture(scalars, p - vec3(0.0, 0.0, e.z)).r);
#endif
  return texel;
}

// The headlight's factors at a sample (value, gradient): where the field is flat (under 1%
// of its range over two voxels) the gradient's direction is noise, and it is unlit.
vec2 sampleLight(vec4 sample, vec3 dir)
{
#if SHADE
  float flatBelow = 0.01 * (scalarRange.y - scalarRange.x);
  return headlightFactors(
    length(sample.gba) > flatBelow ? indexToWorldNormal * sample.gba : vec3(0.0), dir);
#else
  return vec2(1.0, 0.0);
#endif
}

// The premultiplied colour of a slab of world length d whose ends have the values front
// and back, lit with the mean of its ends' headlight factors (each end lit by its own
// normal, as a ray caster lights its samples: a thin sheet's two sides stay lit).
vec4 slabColor(float front, float back, vec2 light, float d)
{
  vec2 table = clamp(vec2(front, back) * tableMap.x + tableMap.y, tableEnds.x, tableEnds.y);
  vec4 entry = texture(preIntegrated, table);
  float alpha = 1.0 - exp(-d * entry.a);
  return vec4((entry.rgb * light.x + vec3(light.y)) * alpha, alpha);
}

void main()
{
  vec3 dir, originWC, stepWC, originI, stepI, inverseStepI;
  float start, leave;
  if (!castRay(dir, originWC, stepWC, originI, stepI, inverseStepI, start, leave))
  {
    discard;
  }
  float worldPerDepth = length(stepWC);
  // Front to back: each slab's back value is the next one's front value. The slabs end
  // at the planes strictly between start and leave, and at leave.
  int first = planeAtOrAfter(start);
  first += planeDepth(first) <= start ? 1 : 0;
  int ends = max(min(planeAtOrAfter(leave), sliceCount) - first + 1, 1);
  vec4 sum = vec4(0.0);
  float s = start;
  vec4 front = sampleAt(originI + s * stepI);
  vec2 frontLight = sampleLight(front, dir);
  for (int j = 0; j < ends; ++j)
  {
#if LEAP
    // Leap over the slabs in transparent bricks (they add exactly nothing) to the last
    // plane within reach.
    float reach = leapReach(originI, stepI, inverseStepI, s);
    if (reach >= leave)
    {
      break;
    }
    int last = int(floor((reach - firstSliceDepth) / sliceSpacing)) - first;
    bool leap = last >= j;
    j = max(j, last);
#else
    bool leap = false;
#endif
    float next = j + 1 < ends ? planeDepth(first + j) : leave;
    vec4 back = sampleAt(originI + next * stepI);
    vec2 backLight = sampleLight(back, dir);
    if (!leap)
    {
      vec2 light = 0.5 * (frontLight + backLight);
      sum += (1.0 - sum.a) * slabColor(front.r, back.r, light, (next - s) * worldPerDepth);
      // What lies behind would change no 8-bit channel by half a step.
      if (sum.a >= 0.998)
      {
        break;
      }
    }
    front = back;
    frontLight = backLight;
    s = next;
  }
  if (sum.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = sum;
}
