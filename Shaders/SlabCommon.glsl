// What both slice shaders of vtkSegmentedDistanceVolumeMapper share (substituted for
// //DF::SlabCommon after their outputs): the slice fragment's position, the view and the
// grid, the lighting parameters, the slab along the fragment's ray, where a segment
// enters the volume's box, trilinear interpolation, and the headlight.

in vec3 positionWC;

uniform vec3 gridSize;            // samples per axis
uniform mat4 worldToIndex;
uniform mat4 worldToClip;
uniform mat3 indexToWorldNormal;
uniform vec3 eyeWC;
uniform vec3 viewDirWC;
uniform int parallelProjection;
uniform float sliceSpacing;       // world units, along viewDirWC
uniform int shade;
uniform float ambient;
uniform float diffuse;
uniform float specular;
uniform float specularPower;

// The slab this fragment stands for: from its slice to the next one along its ray, in
// world and index coordinates, and the ray's direction.
void slabOfFragment(out vec3 dir, out vec3 frontWC, out vec3 backWC, out vec3 frontI,
  out vec3 backI)
{
  dir = parallelProjection == 1 ? viewDirWC : normalize(positionWC - eyeWC);
  float along = sliceSpacing / max(dot(dir, viewDirWC), 1e-6);
  frontWC = positionWC;
  backWC = positionWC + along * dir;
  frontI = (worldToIndex * vec4(frontWC, 1.0)).xyz;
  backI = (worldToIndex * vec4(backWC, 1.0)).xyz;
}

// Where the segment from p along step (index space) enters the volume's box, as a
// fraction of step: 0 when p is inside, > 1 when it never does.
float entryAlong(vec3 p, vec3 step)
{
  vec3 last = gridSize - 1.0;
  float enter = 0.0;
  float leave = 1e30;
  for (int a = 0; a < 3; ++a)
  {
    if (abs(step[a]) < 1e-30)
    {
      if (p[a] < 0.0 || p[a] > last[a])
      {
        return 2.0;
      }
      continue;
    }
    float t0 = -p[a] / step[a];
    float t1 = (last[a] - p[a]) / step[a];
    enter = max(enter, min(t0, t1));
    leave = min(leave, max(t0, t1));
  }
  return enter <= leave ? enter : 2.0;
}

// The trilinear interpolation of a cell's eight values (x fastest) at t in [0, 1]^3.
float trilinear(float v[8], vec3 t)
{
  vec4 x = mix(vec4(v[0], v[2], v[4], v[6]), vec4(v[1], v[3], v[5], v[7]), t.x);
  vec2 y = mix(x.xz, x.yw, t.y);
  return mix(y.x, y.y, t.z);
}

// A headlight on color: n (world, any length; zero: unlit directions) seen along dir.
vec3 headlight(vec3 color, vec3 n, vec3 dir)
{
  float len = length(n);
  float facing = len > 0.0 ? abs(dot(n / len, dir)) : 1.0;
  float highlight = specular > 0.0 ? pow(facing, max(specularPower, 1.0)) : 0.0;
  return color * (ambient + diffuse * facing) + vec3(specular * highlight);
}
