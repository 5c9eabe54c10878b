#version 450 core
// Writes `Value` into the distance array at every voxel set in a z-lane image (the zero
// set, with Value = 0, counted in count[0]), or negates the distance there (Negate = 1,
// the solid's voxels).
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32ui, binding = 0) uniform readonly uimage2DArray Mask;
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
uniform int Value;
uniform int Negate;

void main()
{
  ivec3 at = ivec3(gl_GlobalInvocationID.xyz) + ivec3(0, 0, TexelBase);
  if (at.x >= Dims.x || at.y >= Dims.y || at.z >= Texels)
  {
    return;
  }
  uvec4 bits = imageLoad(Mask, at);
  if (Negate == 0)
  {
    atomicAdd(count[0], uint(bitCount(bits.x) + bitCount(bits.y) + bitCount(bits.z) + bitCount(bits.w)));
  }
  for (int c = 0; c < 4; ++c)
  {
    uint word = bits[c];
    while (word != 0u)
    {
      int bit = findLSB(word);
      word &= word - 1u;
      int z = at.z * 128 + c * 32 + bit;
      int index = at.x + Dims.x * (at.y + Dims.y * z) - DistanceBase;
      distance[index] = Negate != 0 ? -distance[index] : Value;
    }
  }
}
