// What both ray-casting shaders of vtkSegmentedDistanceVolumeMapper share (substituted for
// //DF::SlabCommon after their outputs): the fragment's ray, the view and the grid, the
// lighting parameters, where a ray meets the volume's box, the slabs between the sample
// planes, trilinear interpolation, and the headlight.
//
// One fragment a pixel: the box's back faces are drawn (its front faces culled, so that
// an eye inside the box still has them), and the fragment casts the ray from the eye
// through its point. The ray is sampled where it crosses the planes at depths
// firstSliceDepth + k * sliceSpacing along the view direction (the planes a slice-based
// renderer would draw), so a slab is the stretch between two planes, plus a first one from
// where the ray enters the box (or the near plane) to the first plane.

in vec3 positionWC;               // the fragment's point, world and index coordinates
in vec3 positionI;

uniform vec3 gridSize;            // samples per axis
uniform mat4 worldToClip;
uniform mat3 indexToWorldNormal;
uniform vec3 eyeWC;
uniform vec3 eyeI;                // the eye, index coordinates
uniform vec3 viewDirWC;
uniform vec3 viewDirI;            // the view direction, index coordinates (not unit)
uniform float sliceSpacing;       // world units, along viewDirWC
uniform float inverseSliceSpacing;
uniform float firstSliceDepth;    // the first plane's depth along viewDirWC from the eye
uniform int sliceCount;
uniform float nearDepth;          // the near clipping plane's depth
uniform float ambient;
uniform float diffuse;
uniform float specular;
uniform float specularPower;
#if OPAQUE_DEPTH
uniform sampler2D opaqueDepth;    // the depth buffer before the volume was drawn
uniform ivec2 viewportOrigin;     // the window pixel of opaqueDepth's first texel
#endif
uniform sampler3D leaps;          // per brick of BRICK_SIZE^3 cells: the Chebyshev distance
                                  // in bricks to the nearest brick that may add to the
                                  // picture (/ 255)
uniform vec3 lastBrick;           // leaps' size - 1

// The fragment's ray as points origin + s * step, in world and index coordinates, s being
// the depth along the view direction from the eye, and its unit direction. The ray is the
// pixel's, whichever face of the box the fragment is on. The vertex shader hands over the
// fragment's point in both spaces (interpolation is exact for affine maps), so that no
// matrix is applied per pixel.
void rayOfFragment(out vec3 dir, out vec3 originWC, out vec3 stepWC, out vec3 originI,
  out vec3 stepI)
{
  vec3 toPoint = positionWC - eyeWC;
  float depth = dot(toPoint, viewDirWC);
#if PARALLEL
  dir = viewDirWC;
  stepWC = viewDirWC;
  stepI = viewDirI;
  originWC = positionWC - depth * viewDirWC; // at depth 0
  originI = positionI - depth * viewDirI;
#else
  dir = normalize(toPoint);
  float perDepth = 1.0 / max(depth, 1e-30);
  stepWC = toPoint * perDepth;
  stepI = (positionI - eyeI) * perDepth;
  originWC = eyeWC;
  originI = eyeI;
#endif
}

// The depths between which the ray p + s * step (index space) is inside the volume's box,
// from the step's inverse; empty (enter > leave) when it misses it.
void boxInterval(vec3 p, vec3 inverseStep, out float enter, out float leave)
{
  vec3 t0 = -p * inverseStep;
  vec3 t1 = (gridSize - 1.0 - p) * inverseStep;
  vec3 near = min(t0, t1);
  vec3 far = max(t0, t1);
  enter = max(near.x, max(near.y, near.z));
  leave = min(far.x, min(far.y, far.z));
}

// The depth where the ray from depth start to leave meets the opaque geometry drawn before
// the volume (OPAQUE_DEPTH: rays blended over the window), or leave. Clip coordinates are
// linear along the ray, so the depth where the window depth is reached is exact.
float opaqueCut(vec3 originWC, vec3 stepWC, float start, float leave)
{
#if !OPAQUE_DEPTH
  return leave;
#else
  float z = 2.0 * texelFetch(opaqueDepth, ivec2(gl_FragCoord.xy) - viewportOrigin, 0).r - 1.0;
  vec4 origin = worldToClip * vec4(originWC, 1.0);
  vec4 step = worldToClip * vec4(stepWC, 0.0);
  // (origin.z + s step.z) / (origin.w + s step.w) = z; clip depth grows along the ray, so
  // geometry behind leave gives a depth beyond it.
  return clamp((z * origin.w - origin.z) / (step.z - z * step.w), start, leave);
#endif
}

// The fragment's ray (rayOfFragment), with its index-space step's inverse (a zero
// component made tiny, so that a ray along a face of the box stays finite), and the depths
// it spends in the volume: from where it enters the box (or the near plane) to where it
// leaves it or meets the opaque geometry. False when it misses the volume.
bool castRay(out vec3 dir, out vec3 originWC, out vec3 stepWC, out vec3 originI,
  out vec3 stepI, out vec3 inverseStepI, out float start, out float leave)
{
  rayOfFragment(dir, originWC, stepWC, originI, stepI);
  inverseStepI = 1.0 / mix(stepI, vec3(1e-30), lessThan(abs(stepI), vec3(1e-30)));
  float enter;
  boxInterval(originI, inverseStepI, enter, leave);
  start = max(enter, nearDepth);
  if (!(leave > start))
  {
    return false;
  }
  leave = opaqueCut(originWC, stepWC, start, leave);
  return true;
}

// How far (in depth) the ray can leap from depth s: to where it leaves the cube of bricks
// around s's brick that holds none that may add to the picture (less a thousandth of a
// voxel); s where s's own brick may.
float leapReach(vec3 originI, vec3 stepI, vec3 inverseStepI, float s)
{
  vec3 p = originI + s * stepI;
  // Truncation is floor for p >= 0 (p is in the box, to rounding).
  ivec3 b = ivec3(clamp(p * (1.0 / float(BRICK_SIZE)), vec3(0.0), lastBrick));
  float r = floor(texelFetch(leaps, b, 0).r * 255.0 + 0.5);
  // The cube's far side along each axis, on the side the inverse step points to (a zero
  // step's huge inverse then leaves the axis out, whichever way the ray is walked).
  vec3 far = mix((vec3(b) - (r - 1.0)) * float(BRICK_SIZE) + 1e-3,
    (vec3(b) + r) * float(BRICK_SIZE) - 1e-3, greaterThanEqual(inverseStepI, vec3(0.0)));
  vec3 t = (far - p) * inverseStepI;
  return r < 1.0 ? s : s + max(min(t.x, min(t.y, t.z)), 0.0);
}

// The first sample plane at or beyond depth s, and plane k's depth.
int planeAtOrAfter(float s)
{
  return max(0, int(ceil((s - firstSliceDepth) / sliceSpacing)));
}
float planeDepth(int k)
{
  return firstSliceDepth + float(k) * sliceSpacing;
}

// The trilinear interpolation of a cell's eight values (x fastest) at t in [0, 1]^3.
float trilinear(float v[8], vec3 t)
{
  vec4 x = mix(vec4(v[0], v[2], v[4], v[6]), vec4(v[1], v[3], v[5], v[7]), t.x);
  vec2 y = mix(x.xz, x.yw, t.y);
  return mix(y.x, y.y, t.z);
}

// A headlight's factors for a normal n (world, any length; zero: unlit directions) seen
// along dir: what multiplies the colour (ambient + diffuse) and what adds to it (specular).
vec2 headlightFactors(vec3 n, vec3 dir)
{
  float len = length(n);
  float facing = len > 0.0 ? abs(dot(n / len, dir)) : 1.0;
  float highlight = specular > 0.0 ? pow(facing, max(specularPower, 1.0)) : 0.0;
  return vec2(ambient + diffuse * facing, specular * highlight);
}

// A headlight on color.
vec3 headlight(vec3 color, vec3 n, vec3 dir)
{
  vec2 factors = headlightFactors(n, dir);
  return color * factors.x + vec3(factors.y);
}
