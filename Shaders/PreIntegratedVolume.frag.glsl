//VTK::System::Dec
//VTK::Output::Dec
//DF::SlabCommon

// Pre-integrated compositing of a scalar volume (Engel, Kraus, Ertl 2001), ray cast: one
// fragment a pixel walks its ray's slabs front to back, cut where the ray leaves the
// volume or meets opaque geometry, and stops once the pixel is opaque. The table of
// averages holds, per (front value, back value), the slab's average extinction (a) and
// its extinction-weighted average colour (rgb), so that a slab of any length d is exact:
// alpha = 1 - exp(-d * a); the ray's first and last slabs, cut short, use it. The whole
// steps between use the step table, made from it for their one length: the loop has no
// exponential.

uniform sampler3D scalars;        // the scalar volume, linear filtering: the value, or
                                  // with STORED_GRADIENT the value and its central
                                  // differences, normalized (16-bit signed):
uniform float packedGradientScale; // differences = scale * texel.gba
uniform sampler2D preIntegrated;  // RGBA: average colour, average extinction
uniform sampler2D preIntegratedStep; // RGBA (half floats): premultiplied colour, opacity
                                     // of a whole step
uniform vec2 scalarRange;         // the table's first and last values
uniform vec2 tableMap;            // texel.r -> table coordinate: texel.r * x + y (the
                                  // value's, or with STORED_GRADIENT the normalized one's)

// The interpolated value at an index-space point and, when shading, the gradient there
// (per two index steps), by the texture unit's trilinear filtering: one fetch where eight
// texelFetch calls cost three times as much on a software rasterizer. Its weights have 8
// fractional bits on most GPUs: a value is off by at most 1/256 of the difference between
// neighbouring voxels, well inside the pre-integration table's steps. The gradient is the
// central differences of the interpolated values a voxel each way (over half a voxel the
// gradient of the trilinear interpolant shows every cell face: rings around the axes on a
// sphere); stored per voxel, they are interpolated like the values (the same numbers:
// interpolation is linear in the voxels), with the value in 16 bits over the array's
// range (1/65,535 of it: finer than the largest table). The value comes back as its
// coordinate in the tables, once a sample rather than once a slab each end (outside the
// first and last entries' centres the tables' clamped linear filtering gives those
// entries, as clamping the value to their range would).
vec4 sampleAt(vec3 p)
{
  vec4 texel = texture(scalars, p);
#if STORED_GRADIENT
  texel.gba *= packedGradientScale;
#endif
#if DIFFERENCED_GRADIENT
  vec3 e = 1.0 / gridSize;
  texel.gba = vec3(texture(scalars, p + vec3(e.x, 0.0, 0.0)).r -
      texture(scalars, p - vec3(e.x, 0.0, 0.0)).r,
    texture(scalars, p + vec3(0.0, e.y, 0.0)).r - texture(scalars, p - vec3(0.0, e.y, 0.0)).r,
    texture(scalars, p + vec3(0.0, 0.0, e.z)).r - texture(scalars, p - vec3(0.0, 0.0, e.z)).r);
#endif
  texel.r = texel.r * tableMap.x + tableMap.y;
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

// The premultiplied colour of a slab of world length d whose ends have the table
// coordinates front and back, lit with the mean of its ends' headlight factors (each end lit by its own
// normal, as a ray caster lights its samples: a thin sheet's two sides stay lit): from the
// table of averages, for the slabs cut short by the volume's box, the near plane or opaque
// geometry.
vec4 slabColor(float front, float back, vec2 light, float d)
{
  vec4 entry = texture(preIntegrated, vec2(front, back));
  float alpha = d > 0.0 ? 1.0 - exp(-d * entry.a) : 0.0;
  return vec4((entry.rgb * light.x + vec3(light.y)) * alpha, alpha);
}

// The same for a whole step (world length sliceSpacing), from the table made for that
// length: no exponential in the ray's loop.
vec4 stepColor(float front, float back, vec2 light)
{
  vec4 entry = texture(preIntegratedStep, vec2(front, back));
  return vec4(entry.rgb * light.x + vec3(light.y * entry.a), entry.a);
}

// The ray's samples, as a fractional index, at its depth s (the ray's parameter along the
// view direction): sample k lies at the distance firstSliceDepth + k * sliceSpacing from
// the eye.
float sampleIndex(float s, float worldPerDepth)
{
  return (s * worldPerDepth - firstSliceDepth) * inverseSliceSpacing;
}

void main()
{
  vec3 dir, originWC, stepWC, originI, stepI, inverseStepI;
  float start, leave;
  if (!castRay(dir, originWC, stepWC, originI, stepI, inverseStepI, start, leave))
  {
    discard;
  }
  // The ray's samples lie sliceSpacing apart along it, at the distances
  // firstSliceDepth + k * sliceSpacing from the eye (on the sample planes in a parallel
  // projection, on spheres around the eye in a perspective one), so that every whole step
  // has the same length; as depths s along the view direction (the ray's parameter):
  float worldPerDepth = length(stepWC);
  float depthPerWorld = inversesqrt(dot(stepWC, stepWC));
  float spacing = sliceSpacing * depthPerWorld;
  float offset = firstSliceDepth * depthPerWorld;
  // Samples k0 .. k1 lie strictly between start and leave (or, after a leap, at them); the
  // slabs run from start to k0, from each to the next, and from k1 to leave.
  int k0 = max(0, int(floor(sampleIndex(start, worldPerDepth))) + 1);
  int k1 = int(ceil(sampleIndex(leave, worldPerDepth))) - 1;
#if LEAP
  // Leaping over transparent bricks (their slabs add exactly nothing): a ray through them
  // only is discarded; one that starts in them starts at the last sample within reach
  // (the slab from start to it has no length); one that ends in them ends at the first
  // sample within reach of its end, seen backwards.
  float reach = leapReach(originI, stepI, inverseStepI, start);
  if (reach >= leave)
  {
    discard;
  }
  int skip = int(floor(sampleIndex(reach, worldPerDepth)));
  if (skip >= k0)
  {
    start = offset + float(skip) * spacing;
    k0 = skip;
  }
  float reachBack = leapReach(originI + leave * stepI, -stepI, -inverseStepI, 0.0);
  int stop = int(ceil(sampleIndex(leave - reachBack, worldPerDepth)));
  if (stop >= k0 && stop <= k1)
  {
    k1 = stop;
    leave = offset + float(stop) * spacing;
  }
#endif
  // The ray in texture coordinates.
  vec3 originT = (originI + 0.5) / gridSize;
  vec3 stepT = stepI / gridSize;
  vec4 sum = vec4(0.0);
  float s = start;
  float next = k0 <= k1 ? offset + float(k0) * spacing : leave;
  vec4 back = sampleAt(originT + next * stepT);
  vec2 backLight = sampleLight(back, dir);
  // The first slab, cut by the box or the near plane; after a leap it has no length and
  // adds nothing (on a GPU, neighbouring rays skip its fetches together).
  if (next > s)
  {
    vec4 entry = sampleAt(originT + s * stepT);
    vec2 entryLight = sampleLight(entry, dir);
    sum = slabColor(entry.r, back.r, 0.5 * (entryLight + backLight), (next - s) * worldPerDepth);
  }
  vec4 front = back;
  vec2 frontLight = backLight;
  s = next;
  // Front to back: each slab's back value is the next one's front value.
  bool rest = k0 <= k1;
  for (int k = k0 + 1; k <= k1; ++k)
  {
    next = offset + float(k) * spacing;
    back = sampleAt(originT + next * stepT);
    backLight = sampleLight(back, dir);
    sum += (1.0 - sum.a) * stepColor(front.r, back.r, 0.5 * (frontLight + backLight));
    // What lies behind would change no 8-bit channel by half a step.
    if (sum.a >= 0.998)
    {
      rest = false;
      break;
    }
    front = back;
    frontLight = backLight;
    s = next;
  }
  // The last slab, cut by the box or opaque geometry (none after a leap to its end).
  if (rest && sum.a < 0.998 && leave > s)
  {
    back = sampleAt(originT + leave * stepT);
    backLight = sampleLight(back, dir);
    sum += (1.0 - sum.a) *
      slabColor(front.r, back.r, 0.5 * (frontLight + backLight), (leave - s) * worldPerDepth);
  }
  if (sum.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = sum;
}
