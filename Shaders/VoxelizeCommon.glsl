#version 450 core
#extension GL_ARB_gpu_shader_int64 : require
// The voxelizer's per-lane rules on the GPU. They repeat Filters/Core/VoxelizerRules.h
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

const int64_t Subpixel = 256l;
const int SolidGuard = 2;

int64_t FloorDiv(int64_t a, int64_t b)
{
  return a >= 0l ? a / b : -((-a + b - 1l) / b);
}

int64_t Edge(Tri t, int k, int64_t p, int64_t q)
{
  int k1 = (k + 1) % 3;
  return (t.X[k1] - t.X[k]) * (q * Subpixel - t.Y[k]) - (t.Y[k1] - t.Y[k]) * (p * Subpixel - t.X[k]);
}

bool Owns(Tri t, int k)
{
  return (k == 0 ? t.Flags.y : (k == 1 ? t.Flags.z : t.Flags.w)) != 0;
}

bool CoversCentre(Tri t, int64_t p, int64_t q, out int64_t e[3])
{
  for (int k = 0; k < 3; ++k)
  {
    e[k] = Edge(t, k, p, q);
    if (!(e[k] > 0l || (e[k] == 0l && Owns(t, k))))
    {
      return false;
    }
  }
  return true;
}

bool OverlapsCell(Tri t, int64_t p, int64_t q, out int64_t e[3])
{
  int64_t halfCell = Subpixel / 2l;
  for (int k = 0; k < 3; ++k)
  {
    int k1 = (k + 1) % 3;
    e[k] = Edge(t, k, p, q);
    if (e[k] + halfCell * (abs(t.X[k1] - t.X[k]) + abs(t.Y[k1] - t.Y[k])) < 0l)
    {
      return false;
    }
  }
  return true;
}

double DepthAt(Tri t, int64_t e[3])
{
  precise double depth =
    (double(e[1]) * t.Z[0] + double(e[2]) * t.Z[1] + double(e[0]) * t.Z[2]) / double(t.X.w);
  return depth;
}

double DepthSpread(Tri t)
{
  precise double slopeP = -(double(t.Y[2] - t.Y[1]) * t.Z[0] + double(t.Y[0] - t.Y[2]) * t.Z[1] +
                             double(t.Y[1] - t.Y[0]) * t.Z[2]) /
    double(t.X.w) * double(Subpixel);
  precise double slopeQ = (double(t.X[2] - t.X[1]) * t.Z[0] + double(t.X[0] - t.X[2]) * t.Z[1] +
                            double(t.X[1] - t.X[0]) * t.Z[2]) /
    double(t.X.w) * double(Subpixel);
  precise double spread = 0.5lf * (abs(slopeP) + abs(slopeQ));
  return spread;
}

void BoundaryCandidates(Tri t, double depth, double spread, double reach, int na, out int k0, out int k1)
{
  double zmin = min(t.Z[0], min(t.Z[1], t.Z[2]));
  double zmax = max(t.Z[0], max(t.Z[1], t.Z[2]));
  precise double lo = max(depth - spread, zmin) - reach;
  precise double hi = min(depth + spread, zmax) + reach;
  k0 = int(max(ceil(lo), 0.0lf));
  k1 = int(min(floor(hi), double(na) - 1.0lf));
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

double SquaredDistanceToTriangle(dvec3 p, dvec3 a, dvec3 b, dvec3 c)
{
  precise dvec3 ab = b - a, ac = c - a, ap = p - a, bp = p - b, cp = p - c;
  precise double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  precise double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  precise double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  precise double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  precise double v = 0.0lf, w = 0.0lf;
  if (d1 <= 0.0lf && d2 <= 0.0lf)
  {
    v = 0.0lf;
    w = 0.0lf;
  }
  else if (d3 >= 0.0lf && d4 <= d3)
  {
    v = 1.0lf;
    w = 0.0lf;
  }
  else if (vc <= 0.0lf && d1 >= 0.0lf && d3 <= 0.0lf)
  {
    v = d1 / (d1 - d3);
    w = 0.0lf;
  }
  else if (d6 >= 0.0lf && d5 <= d6)
  {
    v = 0.0lf;
    w = 1.0lf;
  }
  else if (vb <= 0.0lf && d2 >= 0.0lf && d6 <= 0.0lf)
  {
    v = 0.0lf;
    w = d2 / (d2 - d6);
  }
  else if (va <= 0.0lf && (d4 - d3) >= 0.0lf && (d5 - d6) >= 0.0lf)
  {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    v = 1.0lf - w;
  }
  else
  {
    precise double denominator = 1.0lf / (va + vb + vc);
    v = vb * denominator;
    w = vc * denominator;
  }
  precise double sum = 0.0lf;
  for (int k = 0; k < 3; ++k)
  {
    precise double e = a[k] + v * ab[k] + w * ac[k] - p[k];
    sum += e * e;
  }
  return sum;
}
