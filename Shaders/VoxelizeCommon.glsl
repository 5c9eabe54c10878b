#version 450 core
#extension GL_ARB_gpu_shader_int64 : require
// The voxelizer's per-triangle set-ups and per-lane rules on the GPU. They repeat
// Filters/Core/Voxels/VoxelizerRules.h operation for operation (64-bit integers, IEEE
// doubles with correctly rounded quotients, `precise` so that nothing is fused or
// reordered), so that the GPU and CPU passes set the same bits.
//DF::SampleGrid
//DF::CorrectlyRounded

// The mesh: xyz per point, three point ids per triangle.
layout(std430, binding = 0) readonly buffer MeshPoints
{
  double points[];
};
layout(std430, binding = 1) readonly buffer MeshTriangles
{
  uint corners[];
};
// The points in voxel units (VoxelUnits), computed once a run.
layout(std430, binding = 5) buffer PointUnits
{
  double units[];
};

// One triangle as a view sees it (VoxelizerRules.h's ProjectedTriangle).
struct Tri
{
  i64vec4 X;   // snapped lane-plane x of the corners, counter-clockwise; w: twice the area
  i64vec4 Y;   // snapped lane-plane y; w unused
  dvec4 Z;     // depths along the view axis (voxel units); w unused
  ivec4 Flags; // x: entering (faces the viewer); y, z, w: edge 0, 1, 2 owns its lanes
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

const int64_t Subpixel = 256l;
const double SnapRange = 4194304.0lf;
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
  precise double weighted = double(e.y) * t.Z.x + double(e.z) * t.Z.y + double(e.x) * t.Z.z;
  return DivRN(weighted, double(t.X.w));
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

// The (B, C, A) components of a vector along (x, y, z) for the view along A = `a`.
dvec3 InView(dvec3 v, int a)
{
  return a == 0 ? v.yzx : (a == 1 ? v.zxy : v.xyz);
}

// Corner k of triangle t, in the world.
dvec3 Corner(int t, int k)
{
  uint at = 3u * corners[3 * t + k];
  return dvec3(points[at], points[at + 1u], points[at + 2u]);
}

// A point in voxel units along each axis (ComputeCorners).
dvec3 VoxelUnits(dvec3 p)
{
  precise dvec3 d = p - Origin;
  precise dvec3 v =
    dvec3(DivRN(d.x, Spacing.x), DivRN(d.y, Spacing.y), DivRN(d.z, Spacing.z)) - dvec3(Lo);
  return v;
}

// Corner k of triangle t in voxel units.
dvec3 VoxelCorner(int t, int k)
{
  uint at = 3u * corners[3 * t + k];
  return dvec3(units[at], units[at + 1u], units[at + 2u]);
}

int64_t RoundHalfAway(double x)
{
  int64_t whole = int64_t(x);
  precise double fraction = x - double(whole);
  return whole + (fraction >= 0.5lf ? 1l : 0l) - (fraction <= -0.5lf ? 1l : 0l);
}

i64vec3 Snap(dvec3 v)
{
  return i64vec3(RoundHalfAway(v.x * double(Subpixel)), RoundHalfAway(v.y * double(Subpixel)),
    RoundHalfAway(v.z * double(Subpixel)));
}

// Triangle t projected for view `a` (ProjectTriangle): false when it covers no lane
// (seen edge-on) or lies too far from the grid (`far` is then set).
bool ProjectTriangle(int t, int a, double orientation, out Tri tri, out bool far)
{
  dvec3 v0 = InView(VoxelCorner(t, 0), a);
  dvec3 v1 = InView(VoxelCorner(t, 1), a);
  dvec3 v2 = InView(VoxelCorner(t, 2), a);
  far = !(abs(v0.x) < SnapRange && abs(v1.x) < SnapRange && abs(v2.x) < SnapRange &&
    abs(v0.y) < SnapRange && abs(v1.y) < SnapRange && abs(v2.y) < SnapRange);
  if (far)
  {
    return false;
  }
  i64vec3 x = Snap(dvec3(v0.x, v1.x, v2.x)), y = Snap(dvec3(v0.y, v1.y, v2.y));
  dvec3 z = dvec3(v0.z, v1.z, v2.z);
  int64_t area = (x.y - x.x) * (y.z - y.x) - (y.y - y.x) * (x.z - x.x);
  if (area == 0l)
  {
    return false; // seen edge-on: the other views cover it
  }
  // The projected area has the sign of the normal's A component.
  bool entering = double(area) * orientation < 0.0lf;
  if (area < 0l)
  {
    x = x.xzy;
    y = y.xzy;
    z = z.xzy;
    area = -area;
  }
  i64vec3 dx = x.yzx - x, dy = y.yzx - y;
  tri.X = i64vec4(x, area);
  tri.Y = i64vec4(y, 0l);
  tri.Z = dvec4(z, 0.0lf);
  tri.Flags = ivec4(entering ? 1 : 0,
    dy.x < 0l || (dy.x == 0l && dx.x < 0l) ? 1 : 0,
    dy.y < 0l || (dy.y == 0l && dx.y < 0l) ? 1 : 0,
    dy.z < 0l || (dy.z == 0l && dx.z < 0l) ? 1 : 0);
  return true;
}

// Triangle t set up for the boundary rule when the view its plane faces most is `view`
// (SetupBoundaryTriangle; `reaches`: BoundaryReach along x, y, z): false when it is
// another view's, or when no voxel of the grid can be within reach of it.
bool SetupBoundaryTriangle(int t, int view, dvec3 reaches, out BoundaryTri b)
{
  dvec3 v0 = VoxelCorner(t, 0), v1 = VoxelCorner(t, 1), v2 = VoxelCorner(t, 2);
  precise dvec3 u = v1 - v0, w = v2 - v0, wu = w - u;
  precise dvec3 n = dvec3(u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x);
  precise double uu = u.x * u.x + u.y * u.y + u.z * u.z;
  precise double ww = w.x * w.x + w.y * w.y + w.z * w.z;
  precise double wuwu = wu.x * wu.x + wu.y * wu.y + wu.z * wu.z;
  precise double longest2 = max(uu, max(ww, wuwu));
  precise double n2 = n.x * n.x + n.y * n.y + n.z * n.z;
  precise double planarLimit = 1e-18lf * longest2 * longest2;
  // A usable plane: the sine of the triangle's largest angle above 1e-9 or so.
  bool planar = n2 > planarLimit;
  dvec3 lo = min(min(v0, v1), v2), hi = max(max(v0, v1), v2);
  precise dvec3 extent = hi - lo;
  dvec3 key = planar ? abs(n) : abs(extent);
  int a = 0;
  if (key.y > key.x)
  {
    a = 1;
  }
  if (key.z > (a == 0 ? key.x : key.y))
  {
    a = 2;
  }
  if (a != view)
  {
    return false;
  }
  // Edge functions in double stay exact enough within 2^22 lanes of the grid.
  planar = planar && all(lessThan(abs(lo), dvec3(SnapRange))) &&
    all(lessThan(abs(hi), dvec3(SnapRange)));
  dvec3 r = InView(reaches, a); // rb, rc, ra
  dvec3 size = InView(dvec3(Dims), a);
  dvec3 vlo = InView(lo, a), vhi = InView(hi, a);
  // The grown box, clamped in double before the conversion to int.
  precise dvec3 grownLo = vlo - r, grownHi = vhi + r;
  ivec3 first = ivec3(ceil(min(max(grownLo, dvec3(-1.0lf)), size)));
  ivec3 last = ivec3(floor(min(max(grownHi, dvec3(-1.0lf)), size)));
  ivec3 n3 = ivec3(size);
  b.Rect = ivec4(max(0, first.x), min(n3.x - 1, last.x), max(0, first.y), min(n3.y - 1, last.y));
  b.Depth = ivec4(max(0, first.z), min(n3.z - 1, last.z), 0, 0);
  if (b.Rect.x > b.Rect.y || b.Rect.z > b.Rect.w || b.Depth.x > b.Depth.y)
  {
    return false;
  }
  dvec3 c0 = InView(v0, a), c1 = InView(v1, a), c2 = InView(v2, a);
  dvec3 x = dvec3(c0.x, c1.x, c2.x), y = dvec3(c0.y, c1.y, c2.y), z = dvec3(c0.z, c1.z, c2.z);
  double orientation = 0.0lf, gradP = 0.0lf, gradQ = 0.0lf, spread = 0.0lf;
  dvec3 slack = dvec3(0.0lf);
  if (planar)
  {
    // n_A is twice the projected area: not zero for the view the plane faces most.
    dvec3 nv = InView(n, a);
    orientation = nv.z > 0.0lf ? 1.0lf : -1.0lf;
    precise dvec3 along = abs(x.yzx - x) * r.y + abs(y.yzx - y) * r.x;
    slack = along;
    gradP = DivRN(-nv.x, nv.z);
    gradQ = DivRN(-nv.y, nv.z);
    precise double s = abs(gradP) * r.x + abs(gradQ) * r.y;
    spread = s;
  }
  b.X = dvec4(x, orientation);
  b.Y = dvec4(y, gradP);
  b.Z = dvec4(z, gradQ);
  b.Slack = dvec4(slack, spread);
  b.P0 = dvec4(Corner(t, 0), 0.0lf);
  b.P1 = dvec4(Corner(t, 1), 0.0lf);
  b.P2 = dvec4(Corner(t, 2), 0.0lf);
  return true;
}

// The boundary rule's distance (Shaders/TriangleDistance.glsl).
//DF::TriangleDistance
