#version 450 core
// The three views rotated into z-lanes (Martinek et al. (VMV 2011) §4.1: voxel (i, j, k) is bit i[A] of
// lane (i[B], i[C]) of view A): OR of the boundary views, AND of the solid ones (whose
// lanes hold half-voxel bins: voxel k is bin 2k+1, after the guard bins). One
// invocation per z-lane texel (128 voxels).
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32ui, binding = 0) uniform readonly uimage2DArray Boundary0; // views along x, y, z
layout(rgba32ui, binding = 1) uniform readonly uimage2DArray Boundary1;
layout(rgba32ui, binding = 2) uniform readonly uimage2DArray Boundary2;
layout(rgba32ui, binding = 3) uniform readonly uimage2DArray Solid0;
layout(rgba32ui, binding = 4) uniform readonly uimage2DArray Solid1;
layout(rgba32ui, binding = 5) uniform readonly uimage2DArray Solid2;
layout(rgba32ui, binding = 6) uniform writeonly uimage2DArray BoundaryOut;
layout(rgba32ui, binding = 7) uniform writeonly uimage2DArray SolidOut;
//DF::SampleGrid
uniform int WantBoundary, WantSolid;
const int SolidGuard = 2;

// Bit `bit` of lane (x, y) of an image (images cannot be function arguments here).
#define Get(image, x, y, bit)                                                                      \
  (((imageLoad(image, ivec3(x, y, (bit) >> 7))[((bit) >> 5) & 3] >> uint((bit)&31)) & 1u) != 0u)

void main()
{
  ivec3 at = ivec3(gl_GlobalInvocationID.xyz);
  int i = at.x, j = at.y;
  if (i >= Dims.x || j >= Dims.y || at.z * 128 >= Dims.z)
  {
    return;
  }
  uvec4 boundary = uvec4(0u), solid = uvec4(0u);
  if (WantBoundary != 0)
  {
    boundary = imageLoad(Boundary2, ivec3(i, j, at.z));
  }
  for (int b = 0; b < 128; ++b)
  {
    int k = at.z * 128 + b;
    if (k >= Dims.z)
    {
      break;
    }
    uint bit = 1u << uint(b & 31);
    if (WantBoundary != 0 && (boundary[b >> 5] & bit) == 0u &&
      (Get(Boundary0, j, k, i) || Get(Boundary1, k, i, j)))
    {
      boundary[b >> 5] |= bit;
    }
    if (WantSolid != 0 && Get(Solid2, i, j, 2 * k + 1 + SolidGuard) &&
      Get(Solid0, j, k, 2 * i + 1 + SolidGuard) && Get(Solid1, k, i, 2 * j + 1 + SolidGuard))
    {
      solid[b >> 5] |= bit;
    }
  }
  if (WantBoundary != 0)
  {
    imageStore(BoundaryOut, at, boundary);
  }
  if (WantSolid != 0)
  {
    imageStore(SolidOut, at, solid);
  }
}
