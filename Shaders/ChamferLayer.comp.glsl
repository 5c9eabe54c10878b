#version 450 core
// One wavefront layer of the chamfer transform (Martinek et al. (VMV 2011) §5.2), one invocation per
// lane texel (128 voxels of a z-lane):
//   next = (n(cur) | face neighbours | edge neighbours) & ~A,   A |= next,
// with n(w) = (w << 1) | (w >> 1) carried across texels and n'(w) = n(w) | w; the face
// neighbours enter as w (Manhattan) or n'(w); the edge neighbours not at all
// (Manhattan), as w (Chessboard18) or n'(w) (Chessboard26). Newly reached voxels get
// their layer index in the distance array, and are counted.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32ui, binding = 0) uniform readonly uimage2DArray Current;
layout(rgba32ui, binding = 1) uniform writeonly uimage2DArray Next;
layout(rgba32ui, binding = 2) uniform uimage2DArray Accumulated;
layout(std430, binding = 0) buffer Distances
{
  int distance[];
};
layout(std430, binding = 1) buffer Counts
{
  uint count[];
};
//DF::SampleGrid
uniform int Texels;
uniform int TexelBase;    // the first texel of this dispatch's slab
uniform int DistanceBase; // the voxel index where the bound part of `distance` starts
uniform int Metric; // 0 Manhattan, 1 Chessboard18, 2 Chessboard26
uniform int Layer;
uniform int CountSlot;

uvec4 Load(int x, int y, int texel)
{
  if (x < 0 || y < 0 || x >= Dims.x || y >= Dims.y || texel < 0 || texel >= Texels)
  {
    return uvec4(0u);
  }
  return imageLoad(Current, ivec3(x, y, texel));
}

// n(w) for a texel, with the neighbouring texels of the same lane for the carries.
uvec4 Shifted(int x, int y, int texel)
{
  uvec4 w = Load(x, y, texel);
  uvec4 below = Load(x, y, texel - 1), above = Load(x, y, texel + 1);
  uvec4 up = uvec4(w.x << 1u | below.w >> 31u, w.y << 1u | w.x >> 31u, w.z << 1u | w.y >> 31u,
    w.w << 1u | w.z >> 31u);
  uvec4 down = uvec4(w.x >> 1u | w.y << 31u, w.y >> 1u | w.z << 31u, w.z >> 1u | w.w << 31u,
    w.w >> 1u | above.x << 31u);
  return up | down;
}

void main()
{
  ivec3 at = ivec3(gl_GlobalInvocationID.xyz) + ivec3(0, 0, TexelBase);
  int x = at.x, y = at.y, texel = at.z;
  if (x >= Dims.x || y >= Dims.y || texel >= Texels)
  {
    return;
  }
  uvec4 acc = Shifted(x, y, texel);
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      if (dx == 0 && dy == 0)
      {
        continue;
      }
      bool diagonal = dx != 0 && dy != 0;
      if (diagonal && Metric == 0)
      {
        continue;
      }
      bool wide = diagonal ? Metric == 2 : Metric != 0;
      acc |= Load(x + dx, y + dy, texel);
      if (wide)
      {
        acc |= Shifted(x + dx, y + dy, texel);
      }
    }
  }
  // Bits past the last voxel stay clear.
  int valid = Dims.z - texel * 128;
  for (int c = 0; c < 4; ++c)
  {
    int bits = clamp(valid - 32 * c, 0, 32);
    acc[c] &= bits == 32 ? 0xffffffffu : ((1u << uint(bits)) - 1u);
  }
  uvec4 reached = imageLoad(Accumulated, at);
  uvec4 fresh = acc & ~reached;
  imageStore(Next, at, fresh);
  if (fresh == uvec4(0u))
  {
    return;
  }
  imageStore(Accumulated, at, reached | fresh);
  uint total = 0u;
  for (int c = 0; c < 4; ++c)
  {
    uint word = fresh[c];
    total += uint(bitCount(word));
    while (word != 0u)
    {
      int bit = findLSB(word);
      word &= word - 1u;
      int z = texel * 128 + c * 32 + bit;
      distance[x + Dims.x * (y + Dims.y * z) - DistanceBase] = Layer;
    }
  }
  atomicAdd(count[CountSlot], total);
}
