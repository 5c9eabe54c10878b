#version 450 core
// The field from the nearest site of every voxel, on the GPU (LinearFactorScan.cxx
// Finalize, the same double arithmetic, `precise`, with IEEE's square root): signed
// distance and closest point in world units, the CPU's floats.
layout(local_size_x = 64) in;
struct Site
{
  dvec4 anchor; // xyz; w: type (0 vertex, 1 edge, 2 face)
  dvec4 axis;   // edge tangent or face normal
  dvec4 normal; // pseudonormal, for the sign
};
layout(std430, binding = 0) readonly buffer Sites
{
  Site sites[];
};
layout(std430, binding = 1) readonly buffer Ids
{
  int ids[];
};
layout(std430, binding = 2) writeonly buffer Distances
{
  float distance[];
};
layout(std430, binding = 3) writeonly buffer ClosestPoints
{
  float closest[];
};
//DF::SampleGrid
uniform int Signed;
uniform dvec3 FrameOrigin; // the local frame (GridFrame): world = origin + scale local
uniform double FrameScale;
uniform int First, Last;                      // voxels of this dispatch
uniform int IdBase, DistanceBase, ClosestBase; // first elements of the bound ranges
//DF::CorrectlyRounded

void main()
{
  int at = First + int(gl_GlobalInvocationID.x);
  if (at >= Last)
  {
    return;
  }
  ivec3 ijk = ivec3(at % Dims.x, (at / Dims.x) % Dims.y, at / (Dims.x * Dims.y));
  precise dvec3 x = Origin + dvec3(Lo + ijk) * Spacing;
  int id = ids[at - IdBase];
  int c = 3 * at - ClosestBase;
  if (id < 0)
  {
    distance[at - DistanceBase] = uintBitsToFloat(0x7f800000u); // no site: +infinity
    // One assignment each: a chained one reads the write-only buffer (NVIDIA refuses it).
    const float noPoint = uintBitsToFloat(0x7fc00000u);
    closest[c] = noPoint;
    closest[c + 1] = noPoint;
    closest[c + 2] = noPoint;
    return;
  }
  Site s = sites[id];
  precise dvec3 r = s.anchor.xyz - x;
  int type = int(s.anchor.w);
  if (type == 1)
  {
    precise double along = r.x * s.axis.x + r.y * s.axis.y + r.z * s.axis.z;
    r = r - s.axis.xyz * along;
  }
  else if (type == 2)
  {
    precise double across = r.x * s.axis.x + r.y * s.axis.y + r.z * s.axis.z;
    r = s.axis.xyz * across;
  }
  precise double length = SqrtRN(r.x * r.x + r.y * r.y + r.z * r.z);
  precise double world = length * FrameScale;
  float value = float(world);
  if (Signed != 0)
  {
    precise double side = r.x * s.normal.x + r.y * s.normal.y + r.z * s.normal.z;
    value = side > 0.0lf ? -value : value;
  }
  distance[at - DistanceBase] = value;
  precise dvec3 point = FrameOrigin + FrameScale * (x + r);
  closest[c] = float(point.x);
  closest[c + 1] = float(point.y);
  closest[c + 2] = float(point.z);
}
