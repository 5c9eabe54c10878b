#version 450 core
// Copies one batch of nearest-site ids (the scan's R32I layers) into a buffer that holds
// the whole field's ids, so that the field can be finished on the GPU.
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32i, binding = 0) uniform readonly iimage2DArray Ids;
layout(std430, binding = 4) writeonly buffer Resident
{
  int ids[];
};
uniform ivec2 Size;
uniform int Layers;
uniform int Offset; // element of the bound range where this batch's first voxel goes

void main()
{
  ivec3 at = ivec3(gl_GlobalInvocationID.xyz);
  if (at.x >= Size.x || at.y >= Size.y || at.z >= Layers)
  {
    return;
  }
  ids[Offset + at.x + Size.x * (at.y + Size.y * at.z)] = imageLoad(Ids, at).r;
}
