//VTK::System::Dec
//VTK::Output::Dec
//DF::SlabCommon

// One fragment a pixel walks its ray's slabs front to back (Yamazaki et al., SMI 2003,
// section 4, where a slice's fragment stood for one slab). Each slab is sampled where the
// ray enters and leaves it, which decides what the paper's vertex generation diagram
// tabulated: whether an interface lies in the slab (two regions, eq. 7), where (eq. 6)
// and in which colour (the region on the viewer's side). An opaque surface ends the ray
// at its first interface; translucent ones are composited until the pixel is opaque or
// the ray meets opaque geometry.

uniform sampler3D field;          // per voxel: distance (a signed field's signed value),
                                  // region index; linear filtering
uniform sampler2D regionColors;   // one texel per region
uniform int regionColorCount;
uniform vec3 spacing;             // voxel spacing, physical units
uniform float regionOffset;
uniform float opacity;
uniform sampler3D closestPoints;   // per voxel, physical coordinates
uniform mat4 indexToPhysical;
uniform mat3 physicalToWorldNormal;

ivec3 dims()
{
  return ivec3(gridSize + 0.5);
}

vec2 voxel(ivec3 i)
{
  vec2 texel = texelFetch(field, clamp(i, ivec3(0), dims() - 1), 0).xy;
  return vec2(abs(texel.x), texel.y);
}

// The cell around index-space point p: its first voxel, and p's place in it.
ivec3 cellOf(vec3 p, out vec3 t)
{
  vec3 q = clamp(p, vec3(0.0), vec3(dims() - 1));
  ivec3 b = clamp(ivec3(floor(q)), ivec3(0), max(dims() - 2, ivec3(0)));
  t = q - vec3(b);
  return b;
}

// The eight voxels of the cell around index-space point p, and p's place in it.
void cellAt(vec3 p, out vec2 c[8], out vec3 t)
{
  ivec3 b = cellOf(p, t);
  for (int k = 0; k < 8; ++k)
  {
    c[k] = voxel(b + ivec3(k & 1, (k >> 1) & 1, k >> 2));
  }
}

// The distance relative to region r (positive in r, negative elsewhere), interpolated:
// across two regions, the signed field's interpolation.
float relativeTo(vec2 c[8], vec3 t, float r)
{
  float v[8];
  for (int k = 0; k < 8; ++k)
  {
    v[k] = c[k].y == r ? c[k].x : -c[k].x;
  }
  return trilinear(v, t);
}

// The stored value (segmented or signed) of a voxel, and back.
float encoded(vec2 c)
{
#if SEGMENTED
  return c.x + regionOffset * c.y;
#else
  return c.y > 0.5 ? -c.x : c.x;
#endif
}
vec2 decoded(float f)
{
#if SEGMENTED
  float r = floor(f / regionOffset);
  return vec2(f - r * regionOffset, r);
#else
  return vec2(abs(f), f < 0.0 ? 1.0 : 0.0);
#endif
}

// (distance, region) at index-space point p.
vec2 sampleField(vec3 p)
{
  vec2 c[8];
  vec3 t;
  cellAt(p, c, t);
  int nearest = int(t.x > 0.5) + 2 * int(t.y > 0.5) + 4 * int(t.z > 0.5);
#if INTERPOLATION == 1
  return c[nearest];
#elif INTERPOLATION == 2
  float v[8];
  for (int k = 0; k < 8; ++k)
  {
    v[k] = encoded(c[k]);
  }
  return decoded(trilinear(v, t));
#else
  float r = c[nearest].y;
  float inside = relativeTo(c, t, r);
  if (inside >= 0.0)
  {
    return vec2(inside, r);
  }
  // p lies beyond r's interface: in the region of the nearest voxel of another region.
  float best = 1e30;
  float other = r;
  for (int k = 0; k < 8; ++k)
  {
    vec3 corner = vec3(k & 1, (k >> 1) & 1, k >> 2);
    float d = dot(t - corner, t - corner);
    if (c[k].y != r && d < best)
    {
      best = d;
      other = c[k].y;
    }
  }
  return vec2(max(relativeTo(c, t, other), 0.0), other);
#endif
}

// The distance relative to region r at p, interpolated.
// On a signed field (FILTERED_MARCH), the texture unit's filtered signed value: the same
// interpolation (across its two regions, the distance relative to either is the signed
// field's interpolation, up to the sign), in one fetch instead of eight.
float relativeAt(vec3 p, float r)
{
#if FILTERED_MARCH
  float f = texture(field, (p + 0.5) / gridSize).r;
  return r == 0.0 ? f : -f;
#else
  vec2 c[8];
  vec3 t;
  cellAt(p, c, t);
  return relativeTo(c, t, r);
#endif
}

// The gradient (per index step) of the distance relative to region r at p.
vec3 gradientTo(vec3 p, float r)
{
  return vec3(relativeAt(p + vec3(0.5, 0.0, 0.0), r) - relativeAt(p - vec3(0.5, 0.0, 0.0), r),
    relativeAt(p + vec3(0.0, 0.5, 0.0), r) - relativeAt(p - vec3(0.0, 0.5, 0.0), r),
    relativeAt(p + vec3(0.0, 0.0, 0.5), r) - relativeAt(p - vec3(0.0, 0.0, 0.5), r));
}

// The normal at p on region r's side from the voxels' closest points: the directions from
// each voxel's closest point to the voxel (flipped for voxels of other regions), blended
// trilinearly.
vec3 closestPointNormal(vec3 p, float r)
{
  vec3 t;
  ivec3 b = cellOf(p, t);
  vec3 n = vec3(0.0);
  for (int k = 0; k < 8; ++k)
  {
    ivec3 corner = ivec3(k & 1, (k >> 1) & 1, k >> 2);
    ivec3 index = b + corner;
    vec3 w3 = mix(vec3(1.0) - t, t, vec3(corner));
    vec3 away = (indexToPhysical * vec4(vec3(index), 1.0)).xyz -
      texelFetch(closestPoints, index, 0).xyz;
    float len = length(away);
    if (len > 0.0)
    {
      n += (voxel(index).y == r ? 1.0 : -1.0) * (w3.x * w3.y * w3.z / len) * away;
    }
  }
  return physicalToWorldNormal * n;
}

// Eq. 7 on the cell around p: whether one of its edges joins voxels of two regions whose
// distances add up to at most the edge's length (with a relative tolerance: a sheet on a
// voxel plane gives exactly the length). A surface that crosses an edge always passes
// (triangle inequality); where two regions meet beyond an open boundary, none does, so
// open boundaries stay open, and end where the polygonizer ends them.
bool surfaceInCell(vec3 p)
{
  vec2 c[8];
  vec3 t;
  cellAt(p, c, t);
  for (int k = 0; k < 8; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      int m = k | (1 << a);
      if (m != k && c[k].y != c[m].y && c[k].x + c[m].x <= spacing[a] * 1.001)
      {
        return true;
      }
    }
  }
  return false;
}

// The interface in the slab from index-space point a to b, whose ends sampled front and
// back, if any: where (the fraction t of the way).
bool interfaceIn(vec3 a, vec3 b, vec2 front, vec2 back, out float t)
{
  if (front.y == back.y)
  {
    return false;
  }
  float sum = front.x + back.x;
  // Eq. 6: the interface lies u / (u + v) of the way.
  t = sum > 0.0 ? front.x / sum : 0.0;
#if INTERPOLATION == 0
  {
    // Region-aware sampling refines it to the zero of the interpolated distance relative
    // to the front region along the slab (regula falsi from eq. 6's estimate): the surface
    // the interpolant describes, and a point in a cell that holds both regions.
    float lo = 0.0;
    float hi = 1.0;
    float gLo = relativeAt(a, front.y);
    float gHi = relativeAt(b, front.y);
    if (gLo >= 0.0 && gHi < 0.0)
    {
      for (int k = 0; k < 4; ++k)
      {
        float s = clamp(lo + (hi - lo) * gLo / (gLo - gHi), lo, hi);
        float g = relativeAt(mix(a, b, s), front.y);
        if (g >= 0.0)
        {
          lo = s;
          gLo = g;
        }
        else
        {
          hi = s;
          gHi = g;
        }
      }
      t = lo + (hi - lo) * gLo / (gLo - gHi);
    }
  }
#endif
  vec3 hit = mix(a, b, t);
  if (any(lessThan(hit, vec3(-1e-3))) || any(greaterThan(hit, vec3(dims() - 1) + 1e-3)))
  {
    return false;
  }
#if INTERPOLATION == 1
  // Nearest sampling, the paper's eq. 7 on the two voxels sampled: a surface lies between
  // them only if their distances add up to at most their distance apart.
  vec3 last = vec3(dims() - 1);
  vec3 apart = (round(clamp(b, vec3(0.0), last)) - round(clamp(a, vec3(0.0), last))) * spacing;
  return sum <= length(apart) * 1.001;
#else
  return surfaceInCell(hit);
#endif
}

// The colour of the interface at hit (index space), seen along dir from region r.
vec3 surfaceColor(vec3 hit, float r, vec3 dir)
{
  vec3 color = texelFetch(regionColors, ivec2(int(r) % regionColorCount, 0), 0).rgb;
#if SHADE
  // A headlight; the normal points into the viewer's region.
#if CLOSEST_POINT_NORMALS
  vec3 n = closestPointNormal(hit, r);
#else
  vec3 n = indexToWorldNormal * gradientTo(hit, r);
#endif
  color = headlight(color, n, dir);
#endif
  return color;
}

// The sample the march compares at an index-space point: on a signed field sampled
// region-aware or linearly, the filtered signed value (its sign is the region: one fetch);
// otherwise the sample.
vec2 marchSample(vec3 p)
{
#if FILTERED_MARCH
  float f = texture(field, (p + 0.5) / gridSize).r;
  return vec2(abs(f), f < 0.0 ? 1.0 : 0.0);
#else
  return sampleField(p);
#endif
}

void main()
{
  // Translucent surfaces stop at opaque geometry (opaque ones meet the depth test).
  vec3 dir, originWC, stepWC, originI, stepI, inverseStepI;
  float s, leave;
  if (!castRay(dir, originWC, stepWC, originI, stepI, inverseStepI, s, leave))
  {
    discard;
  }
  vec4 sum = vec4(0.0);
  int k = planeAtOrAfter(s);
  vec2 front = marchSample(originI + s * stepI);
  while (s < leave && k <= sliceCount)
  {
    // March to the next slab whose ends lie in two regions: the loop a pixel spends its
    // time in, so it only samples; the decision below runs once a candidate.
    float next = leave;
    vec2 back = front;
    bool candidate = false;
    for (; s < leave && k <= sliceCount; ++k)
    {
#if LEAP
      // Leap over the bricks without two regions (one region all through) to the last
      // plane within reach.
      float reach = leapReach(originI, stepI, inverseStepI, s);
      if (reach >= leave)
      {
        s = leave;
        break;
      }
      k = max(k, int(floor((reach - firstSliceDepth) / sliceSpacing)));
#endif
      next = k < sliceCount ? min(planeDepth(k), leave) : leave;
      if (next <= s)
      {
        continue;
      }
      back = marchSample(originI + next * stepI);
      if (back.y != front.y)
      {
        candidate = true;
        ++k;
        break;
      }
      front = back;
      s = next;
    }
    if (!candidate)
    {
      break;
    }
    vec3 a = originI + s * stepI;
    vec3 b = originI + next * stepI;
    float t;
    if (interfaceIn(a, b, front, back, t))
    {
      vec3 hitWC = originWC + mix(s, next, t) * stepWC;
      vec3 color = surfaceColor(mix(a, b, t), front.y, dir);
      if (opacity >= 1.0)
      {
        vec4 clip = worldToClip * vec4(hitWC, 1.0);
        gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
        gl_FragData[0] = vec4(color, 1.0);
        return;
      }
      sum += (1.0 - sum.a) * vec4(color * opacity, opacity);
      // What lies behind would change no 8-bit channel by half a step.
      if (sum.a >= 0.998)
      {
        break;
      }
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
