#version 450 core
#extension GL_ARB_gpu_shader_int64 : require
// The voxelizer's per-lane rules on the GPU. They repeat Filters/Core/Voxels/VoxelizerRules.h
// operation for operation (64-bit integers, IEEE doubles, `precise` so that nothing is
// fused or reordered), so that the GPU and CPU passes set the same bits.

// One triangle as a view sees it (VoxelGPU.cxx packs it from ProjectedTriangle).
struct Tri
{
  i64vec4 X;   // snapped lane-plane x of the corners, counter-clockwise; w: twice the area
  i64vec4 Y;   // snapped lane-plane y; w unused
  dvec4 Z;     // depths along the view axis (voxel units); w unused
  dvec4 P0;    // world-space corners
  dvec4 P1;
  dvec4 P2;
  ivec4 Flags; // x: entering (faces the viewer); y, z, w: edge 0, 1, 2 owns its lanes
};
layout(std430, binding = 0) readonly buffer Triangles
{
  Tri tris[];
};

// One triangle set up for the boundary rule (VoxelizerRules.h's BoundaryTriangle).
struct BoundaryTri
{
  dvec4 X;     // lane-plane x of the corners (lane units); w: orientation (+1, -1; 0: box only)
  dvec4 Y;     // lane-plane y; w: depth change per lane along x
  dvec4 Z;     // depths (voxels); w: depth change per lane along y
  dvec4 Slack; // growth of the three edge functions by the reaches; w: depth spread
  dvec4 P0;    // corners in the grid's coordinates
  dvec4 P1;
  dvec4 P2;
  ivec4 Rect;  // lanes x0, x1, y0, y1 of the grown bounding box
  ivec4 Depth; // x, y: the voxels of the grown depth range
};
layout(std430, binding = 1) readonly buffer BoundaryTriangles
{
  BoundaryTri btris[];
};

const int64_t Subpixel = 256l;
const int SolidGuard = 2;

int64_t FloorDiv(int64_t a, int64_t b)
{
  return a >= 0l ? a / b : -((-a + b - 1l) / b);
}

// The edge function of the directed edge (x0, y0) -> (x1, y1) at the centre of lane (p, q).
// The shaders name vector components explicitly: NVIDIA's compiler rejects some dynamic
// indexing of 64-bit vectors ("invalid operand variable" when the program links).
int64_t Edge(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t p, int64_t q)
{
  return (x1 - x0) * (q * Subpixel - y0) - (y1 - y0) * (p * Subpixel - x0);
}

// A lane centre on an edge belongs to the triangle whose edge owns it (the tie rule).
bool Covers(int64_t e, int owns)
{
  return e > 0l || (e == 0l && owns != 0);
}

bool CoversCentre(Tri t, int64_t p, int64_t q, out i64vec3 e)
{
  e.x = Edge(t.X.x, t.Y.x, t.X.y, t.Y.y, p, q);
  e.y = Edge(t.X.y, t.Y.y, t.X.z, t.Y.z, p, q);
  e.z = Edge(t.X.z, t.Y.z, t.X.x, t.Y.x, p, q);
  return Covers(e.x, t.Flags.y) && Covers(e.y, t.Flags.z) && Covers(e.z, t.Flags.w);
}

double DepthAt(Tri t, i64vec3 e)
{
  precise double depth =
    (double(e.y) * t.Z.x + double(e.z) * t.Z.y + double(e.x) * t.Z.z) / double(t.X.w);
  return depth;
}

int SolidBit(double depth, int na)
{
  precise double u = 2.0lf * depth + 1.0lf;
  return int(floor(min(max(u, -1.0lf), 2.0lf * double(na)))) + SolidGuard;
}

double Dot(dvec3 u, dvec3 v)
{
  precise double d = u.x * v.x + u.y * v.y + u.z * v.z;
  return d;
}

// Whether lane centre (x, y) lies outside the edge (x0, y0) -> (x1, y1) grown by slack, for a
// triangle of orientation w.
bool OutsideGrownEdge(
  double w, double x0, double y0, double x1, double y1, double slack, double x, double y)
{
  precise double e = w * ((x1 - x0) * (y - y0) - (y1 - y0) * (x - x0));
  return e + slack < 0.0lf;
}

// The voxels [k0, k1] of lane (p, q) that may lie within reach of the triangle.
bool BoundaryLaneCandidates(BoundaryTri t, int p, int q, double reach, out int k0, out int k1)
{
  double zmin = min(t.Z.x, min(t.Z.y, t.Z.z));
  double zmax = max(t.Z.x, max(t.Z.y, t.Z.z));
  precise double lo = zmin - reach, hi = zmax + reach;
  k0 = 0;
  k1 = -1;
  if (t.X.w != 0.0lf)
  {
    const double x = double(p), y = double(q);
    if (OutsideGrownEdge(t.X.w, t.X.x, t.Y.x, t.X.y, t.Y.y, t.Slack.x, x, y) ||
      OutsideGrownEdge(t.X.w, t.X.y, t.Y.y, t.X.z, t.Y.z, t.Slack.y, x, y) ||
      OutsideGrownEdge(t.X.w, t.X.z, t.Y.z, t.X.x, t.Y.x, t.Slack.z, x, y))
    {
      return false;
    }
    precise double depth = t.Z.x + t.Y.w * (x - t.X.x) + t.Z.w * (y - t.Y.x);
    lo = max(depth - t.Slack.w, zmin) - reach;
    hi = min(depth + t.Slack.w, zmax) + reach;
  }
  k0 = max(t.Depth.x, int(ceil(max(lo, -1.0lf))));
  k1 = min(t.Depth.y, int(floor(min(hi, double(t.Depth.y) + 1.0lf))));
  return k0 <= k1;
}

// The boundary rule's distance (Shaders/TriangleDistance.glsl).
//DF::TriangleDistance
