// The bits the triangles set on the lanes of one view, by the CPU's rules
// (Filters/Core/Voxels/Voxelizer.cxx, RasterizeBoundaryTriangle and
// RasterizeSolidTriangle): an invocation sets a triangle up (VoxelizeCommon.glsl) and
// walks the lanes of its rectangle. No invocation walks a large triangle alone: Mesa's
// llvmpipe silently ends a shader's loops after 65535 iterations of a SIMD vector (a
// 12-triangle box at 256^3 lost half its boundary voxels that way). So a rectangle is cut
// in tiles of TileSide x TileSide lanes; the first pass (TilePass 0, an invocation a
// triangle) walks the rectangles of a single tile, the second (TilePass 1) those of more,
// over the triangles the host listed as possibly that large (LargeTriangles, a superset),
// with tile gl_GlobalInvocationID.y, then every gl_NumWorkGroups.y-th after it.
// - boundary (Mode 0): of the triangles whose plane faces this view most, the candidate
//   voxels of each lane whose centre is within the distance limit, into FirstLanes;
// - solid (Mode 1): the half-voxel bin of the crossing at each lane centre the triangle
//   covers, into FirstLanes (a triangle facing the view) or SecondLanes; the triangles
//   too far from the grid to snap are counted in FarCount.
// The words are laid out as the lane textures' texels (texel (layer, q, p), four 32-bit
// words, 128 bits along the lane) so that the buffers copy into them as they are. A
// pass holds the layers [FirstLayer, FirstLayer + Layers): what one storage block holds.
layout(local_size_x = 64) in;

uniform int Mode; // 0: boundary, 1: solid, 2: the points into voxel units (PointUnits)
uniform int Nb, Nc, Na;
uniform ivec3 Axes; // the view's A, B, C
uniform double Limit2, Reach;
uniform dvec3 Reaches;      // the reach along x, y, z (BoundaryReach)
uniform double Orientation; // the mesh's: +1 when its triangles face outward
uniform int Count, Base;    // the triangles (points); the first of this dispatch
uniform int FirstLayer, Layers;
uniform int TilePass; // 0: every triangle, a rectangle of one tile; 1: LargeTriangles

const int TileSide = 16;

layout(std430, binding = 2) buffer FirstLanes
{
  uint firstLanes[];
};
layout(std430, binding = 3) buffer SecondLanes
{
  uint secondLanes[];
};
layout(std430, binding = 4) buffer FarCount
{
  uint farCount;
};
layout(std430, binding = 6) readonly buffer LargeTriangles
{
  int largeTriangle[];
};

// The word holding bit `bit` of lane (p, q), or -1 outside this pass's layers.
int Word(int p, int q, int bit)
{
  int layer = (bit >> 7) - FirstLayer;
  if (layer < 0 || layer >= Layers)
  {
    return -1;
  }
  return 4 * ((layer * Nc + q) * Nb + p) + ((bit >> 5) & 3);
}

// The tiles of a lane rectangle (p0, p1, q0, q1): how many, and tile t's lanes.
int TileCount(ivec4 rect)
{
  return rect.y < rect.x || rect.w < rect.z
    ? 0
    : ((rect.y - rect.x) / TileSide + 1) * ((rect.w - rect.z) / TileSide + 1);
}

// The tiles of `rect` this invocation walks: [first, tiles) by `step`; none when the
// rectangle belongs to the other pass.
void TileRange(ivec4 rect, out int first, out int tiles, out int step)
{
  tiles = TileCount(rect);
  const bool mine = TilePass == 0 ? tiles <= 1 : tiles > 1;
  first = TilePass == 0 ? 0 : int(gl_GlobalInvocationID.y);
  step = TilePass == 0 ? 1 : int(gl_NumWorkGroups.y);
  tiles = mine ? tiles : 0;
}

ivec4 Tile(int t, ivec4 rect)
{
  const int along = (rect.y - rect.x) / TileSide + 1;
  const int p = rect.x + (t % along) * TileSide, q = rect.z + (t / along) * TileSide;
  return ivec4(p, min(rect.y, p + TileSide - 1), q, min(rect.w, q + TileSide - 1));
}

// The solid rule at lane (p, q): the bin of triangle t's crossing, when it covers the
// lane's centre.
void SolidLane(Tri t, int p, int q)
{
  i64vec3 e;
  if (CoversCentre(t, int64_t(p), int64_t(q), e))
  {
    const int at = SolidBit(DepthAt(t, e), Na);
    const int word = Word(p, q, at);
    const uint bit = 1u << uint(at & 31);
    if (word >= 0 && t.Flags.x != 0)
    {
      atomicOr(firstLanes[word], bit);
    }
    else if (word >= 0)
    {
      atomicOr(secondLanes[word], bit);
    }
  }
}

void Solid(int index)
{
  Tri t;
  bool far;
  if (!ProjectTriangle(index, Axes.x, Orientation, t, far))
  {
    if (far && TilePass == 0)
    {
      atomicAdd(farCount, 1u);
    }
    return;
  }
  int64_t xmin = min(t.X.x, min(t.X.y, t.X.z)), xmax = max(t.X.x, max(t.X.y, t.X.z));
  int64_t ymin = min(t.Y.x, min(t.Y.y, t.Y.z)), ymax = max(t.Y.x, max(t.Y.y, t.Y.z));
  int p0 = int(max(0l, -FloorDiv(-xmin, Subpixel)));
  int p1 = int(min(int64_t(Nb - 1), FloorDiv(xmax, Subpixel)));
  int q0 = int(max(0l, -FloorDiv(-ymin, Subpixel)));
  int q1 = int(min(int64_t(Nc - 1), FloorDiv(ymax, Subpixel)));
  const ivec4 rect = ivec4(p0, p1, q0, q1);
  int first, tiles, step;
  TileRange(rect, first, tiles, step);
  for (int tile = first; tile < tiles; tile += step)
  {
    const ivec4 r = Tile(tile, rect);
    for (int q = r.z; q <= r.w; ++q)
    {
      for (int p = r.x; p <= r.y; ++p)
      {
        SolidLane(t, p, q);
      }
    }
  }
}

// The boundary rule along lane (p, q): the candidate voxels within the distance limit
// of triangle b.
void BoundaryLane(BoundaryTri b, int p, int q)
{
  int k0, k1;
  if (BoundaryLaneCandidates(b, p, q, Reach, k0, k1))
  {
    const ivec3 axis = ivec3(0, 1, 2);
    k0 = max(k0, FirstLayer * 128);
    k1 = min(k1, (FirstLayer + Layers) * 128 - 1);
    // The bits of one word gather before one atomic; a bit another triangle has set
    // already is not evaluated again (as on the CPU: a stale read only costs work).
    int word = -1;
    uint bits = 0u, known = 0u;
    for (int k = k0; k <= k1; ++k)
    {
      int w = Word(p, q, k);
      if (w != word)
      {
        if (bits != 0u)
        {
          atomicOr(firstLanes[word], bits);
        }
        word = w;
        bits = 0u;
        known = firstLanes[w];
      }
      uint bit = 1u << uint(k & 31);
      if ((known & bit) != 0u)
      {
        continue;
      }
      ivec3 ijk = k * ivec3(equal(axis, ivec3(Axes.x))) +
        p * ivec3(equal(axis, ivec3(Axes.y))) + q * ivec3(equal(axis, ivec3(Axes.z)));
      precise dvec3 centre = Origin + dvec3(Lo + ijk) * Spacing;
      if (SquaredDistanceToTriangle(centre, b.P0.xyz, b.P1.xyz, b.P2.xyz) <= Limit2)
      {
        bits |= bit;
      }
    }
    if (bits != 0u)
    {
      atomicOr(firstLanes[word], bits);
    }
  }
}

// The same tile loop as Solid's: one function holding both rules' triangles ran 15-20 %
// slower on llvmpipe.
void Boundary(int index)
{
  BoundaryTri b;
  if (!SetupBoundaryTriangle(index, Axes.x, Reaches, b))
  {
    return;
  }
  const ivec4 rect = ivec4(b.Rect);
  int first, tiles, step;
  TileRange(rect, first, tiles, step);
  for (int tile = first; tile < tiles; tile += step)
  {
    const ivec4 r = Tile(tile, rect);
    for (int q = r.z; q <= r.w; ++q)
    {
      for (int p = r.x; p <= r.y; ++p)
      {
        BoundaryLane(b, p, q);
      }
    }
  }
}

void main()
{
  int index = Base + int(gl_GlobalInvocationID.x);
  if (index >= Count)
  {
    return;
  }
  index = TilePass == 0 ? index : largeTriangle[index];
  if (Mode == 0)
  {
    Boundary(index);
  }
  else if (Mode == 1)
  {
    Solid(index);
  }
  else
  {
    uint at = 3u * uint(index);
    dvec3 v = VoxelUnits(dvec3(points[at], points[at + 1u], points[at + 2u]));
    units[at] = v.x;
    units[at + 1u] = v.y;
    units[at + 2u] = v.z;
  }
}
