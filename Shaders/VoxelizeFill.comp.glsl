#version 450 core
// The solid intervals of one view's lanes (Filters/Core/Voxels/Voxelizer.cxx FillIntervals,
// the same rule): a run of front bits then a run of back bits fills the bins after the
// run's first front up to its last back. One invocation per lane.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32ui, binding = 0) uniform readonly uimage2DArray Front;
layout(rgba32ui, binding = 1) uniform readonly uimage2DArray Back;
layout(rgba32ui, binding = 2) uniform uimage2DArray Solid; // cleared before
uniform ivec2 Lanes;
uniform int Texels; // texels (128 bits) per lane

void SetBits(ivec2 lane, int from, int to)
{
  for (int texel = from >> 7; texel <= (to >> 7); ++texel)
  {
    uvec4 value = imageLoad(Solid, ivec3(lane, texel));
    for (int c = 0; c < 4; ++c)
    {
      int lo = max(from, texel * 128 + c * 32) - (texel * 128 + c * 32);
      int hi = min(to, texel * 128 + c * 32 + 31) - (texel * 128 + c * 32);
      if (lo <= hi)
      {
        uint upper = hi == 31 ? 0xffffffffu : ((1u << uint(hi + 1)) - 1u);
        value[c] |= upper & ~((1u << uint(lo)) - 1u);
      }
    }
    imageStore(Solid, ivec3(lane, texel), value);
  }
}

void main()
{
  ivec2 lane = ivec2(gl_GlobalInvocationID.xy);
  if (lane.x >= Lanes.x || lane.y >= Lanes.y)
  {
    return;
  }
  const int Outside = 0, InFronts = 1, InBacks = 2;
  int phase = Outside, first = 0, last = 0;
  for (int texel = 0; texel < Texels; ++texel)
  {
    uvec4 front = imageLoad(Front, ivec3(lane, texel));
    uvec4 back = imageLoad(Back, ivec3(lane, texel));
    for (int c = 0; c < 4; ++c)
    {
      uint events = front[c] | back[c];
      while (events != 0u)
      {
        int bit = findLSB(events);
        events &= events - 1u;
        int z = texel * 128 + c * 32 + bit;
        if (((front[c] >> uint(bit)) & 1u) != 0u)
        {
          if (phase == InBacks && last > first)
          {
            SetBits(lane, first + 1, last);
          }
          if (phase != InFronts)
          {
            first = z;
            phase = InFronts;
          }
        }
        if (((back[c] >> uint(bit)) & 1u) != 0u && phase != Outside)
        {
          last = z;
          phase = InBacks;
        }
      }
    }
  }
  if (phase == InBacks && last > first)
  {
    SetBits(lane, first + 1, last);
  }
}
