#version 450 core
// The side label of every sample (Filters/Core/Segment/SegmentRegions.cxx SideLabel, the
// same arithmetic in double precision, `precise`, with IEEE's square roots and quotients,
// SqrtRN and DivRN, from the closest points the CPU's regions read: the world floats
// taken to the local frame): among the triangles at the sample's
// closest feature, the one whose wedge is nearest in angle to the direction from the
// closest point to the sample; the label is 2 patch + side (-1: no site, or a triangle
// without a patch). Reads the nearest sites and closest points that the GPU scan and its
// finalize left in GL buffers.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer NearestSites
{
  int site[];
};
layout(std430, binding = 1) readonly buffer ClosestPoints
{
  float closest[];
};
layout(std430, binding = 2) writeonly buffer Labels
{
  int label[];
};
layout(std430, binding = 3) readonly buffer SiteTriangles
{
  int siteTriangle[]; // per site: its triangle (SurfacePatches numbering) and its type
};
layout(std430, binding = 4) readonly buffer Triangles
{
  int triangle[]; // per triangle: its 3 corner keys, its patch (-1: none), flipped (0, 1)
};
layout(std430, binding = 5) readonly buffer Positions
{
  double position[]; // per point id: xyz
};
layout(std430, binding = 6) readonly buffer CornerTriangles
{
  int corners[]; // per key: where its triangles start (KeyCount + 1 entries), then them
};
//DF::SampleGrid
uniform int KeyCount;
uniform int First, Last;                     // voxels of this dispatch
uniform int SiteBase, ClosestBase, LabelBase; // first elements of the bound ranges
uniform dvec3 FrameOrigin;  // the local frame (GridFrame): local = (world - origin) / scale
uniform double FrameInverse; // 1 / scale, a power of two
//DF::CorrectlyRounded

int Key(int t, int k)
{
  return triangle[5 * t + k];
}

dvec3 Position(int key)
{
  return dvec3(position[3 * key], position[3 * key + 1], position[3 * key + 2]);
}

dvec3 Corner(int t, int k)
{
  return Position(Key(t, k));
}

double Dot(dvec3 a, dvec3 b)
{
  precise double c = a.x * b.x + a.y * b.y + a.z * b.z;
  return c;
}

dvec3 Cross(dvec3 a, dvec3 b)
{
  precise dvec3 c = dvec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return c;
}

bool Normalize(inout dvec3 v)
{
  precise double length = SqrtRN(Dot(v, v));
  if (!(length > 0.0lf))
  {
    return false;
  }
  v = dvec3(DivRN(v.x, length), DivRN(v.y, length), DivRN(v.z, length));
  return true;
}

// Without its rounding error: e - s f, component by component, as the CPU does.
dvec3 Less(dvec3 e, double s, dvec3 f)
{
  precise dvec3 r = dvec3(e.x - s * f.x, e.y - s * f.y, e.z - s * f.z);
  return r;
}

double SegmentDistance2(dvec3 a, dvec3 b, dvec3 c)
{
  precise dvec3 e = b - a;
  precise dvec3 f = c - a;
  double ee = Dot(e, e);
  double s = ee > 0.0lf ? min(1.0lf, max(0.0lf, DivRN(Dot(e, f), ee))) : 0.0lf;
  dvec3 g = Less(f, s, e);
  return Dot(g, g);
}

double EdgeWedgeCosine(int f, int ka, int kb, dvec3 a, dvec3 e, dvec3 u)
{
  int third = 0;
  while (third < 2 && (Key(f, third) == ka || Key(f, third) == kb))
  {
    ++third;
  }
  precise dvec3 inward = Corner(f, third) - a;
  inward = Less(inward, Dot(inward, e), e);
  dvec3 across = Less(u, Dot(u, e), e);
  if (!Normalize(inward) || !Normalize(across))
  {
    return -2.0lf;
  }
  return Dot(across, inward);
}

double VertexWedgeCosine(int f, int kv, dvec3 u, out int edgeEnd)
{
  edgeEnd = -1;
  int k = 0;
  while (k < 2 && Key(f, k) != kv)
  {
    ++k;
  }
  dvec3 v = Corner(f, k);
  precise dvec3 e1 = Corner(f, (k + 1) % 3) - v;
  precise dvec3 e2 = Corner(f, (k + 2) % 3) - v;
  if (!Normalize(e1) || !Normalize(e2))
  {
    return -2.0lf;
  }
  dvec3 n = Cross(e1, e2);
  if (!Normalize(n))
  {
    return -2.0lf;
  }
  double un = Dot(u, n);
  dvec3 projection = Less(u, un, n);
  if (Dot(Cross(e1, projection), n) >= 0.0lf && Dot(Cross(projection, e2), n) >= 0.0lf)
  {
    precise double rest = 1.0lf - un * un;
    return SqrtRN(max(0.0lf, rest)); // the projection lies in the wedge
  }
  bool first = Dot(u, e1) >= Dot(u, e2);
  edgeEnd = Key(f, first ? (k + 1) % 3 : (k + 2) % 3);
  return first ? Dot(u, e1) : Dot(u, e2);
}

// The range of key k's triangles in `corners`, loaded by the caller and passed on: with
// the loads inside AroundEdge, Mesa 22.3's llvmpipe read 0 for corners[ka + 1] there
// once the caller had loaded corners[kv + 1] (kv = ka) for its own loop (found on
// bunny_small: 20 samples labelled against the CPU).
ivec2 TrianglesAt(int k)
{
  return ivec2(corners[k], corners[k + 1]) + KeyCount + 1;
}

// Around the edge (ka, kb): the triangle whose half-plane is nearest in angle to u, in
// the order of the sorted intersection of the two keys' triangles (`at`, `bt`: their
// ranges).
int AroundEdge(int ka, ivec2 at, int kb, ivec2 bt, dvec3 a, dvec3 b, dvec3 u, int chosen)
{
  precise dvec3 e = b - a;
  Normalize(e);
  double best = -3.0lf;
  for (int i = at.x; i < at.y; ++i)
  {
    int f = corners[i];
    bool onBoth = false;
    for (int j = bt.x; j < bt.y && !onBoth; ++j)
    {
      onBoth = corners[j] == f;
    }
    if (!onBoth)
    {
      continue;
    }
    double cosine = EdgeWedgeCosine(f, ka, kb, a, e, u);
    if (cosine > best)
    {
      best = cosine;
      chosen = f;
    }
  }
  return chosen;
}

void main()
{
  int at = First + int(gl_GlobalInvocationID.x);
  if (at >= Last)
  {
    return;
  }
  int s = site[at - SiteBase];
  int t = s < 0 ? -1 : siteTriangle[2 * s];
  if (t < 0 || triangle[5 * t + 3] < 0)
  {
    label[at - LabelBase] = -1;
    return;
  }
  int feature = siteTriangle[2 * s + 1];
  ivec3 ijk = ivec3(at % Dims.x, (at / Dims.x) % Dims.y, at / (Dims.x * Dims.y));
  precise dvec3 p = Origin + dvec3(Lo + ijk) * Spacing;
  int cb = 3 * at - ClosestBase;
  // Times a power of two: exact, as the CPU's quotient (GridFrame::ToLocal).
  precise dvec3 c =
    (dvec3(closest[cb], closest[cb + 1], closest[cb + 2]) - FrameOrigin) * FrameInverse;
  precise dvec3 u = p - c;
  bool away = Normalize(u);
  int chosen = t;
  if (away && feature == 1)
  {
    // The triangle's edge nearest to the closest point.
    int edge = 0;
    double nearest = SegmentDistance2(Corner(t, 0), Corner(t, 1), c);
    for (int k = 1; k < 3; ++k)
    {
      double d2 = SegmentDistance2(Corner(t, k), Corner(t, (k + 1) % 3), c);
      if (d2 < nearest)
      {
        nearest = d2;
        edge = k;
      }
    }
    int ka = Key(t, edge), kb = Key(t, (edge + 1) % 3);
    chosen = AroundEdge(ka, TrianglesAt(ka), kb, TrianglesAt(kb), Corner(t, edge),
      Corner(t, (edge + 1) % 3), u, chosen);
  }
  else if (away && feature == 0)
  {
    // The triangle's corner nearest to the closest point, and every triangle at it.
    int corner = 0;
    precise dvec3 g0 = Corner(t, 0) - c;
    double nearest = Dot(g0, g0);
    for (int k = 1; k < 3; ++k)
    {
      precise dvec3 g = Corner(t, k) - c;
      if (Dot(g, g) < nearest)
      {
        nearest = Dot(g, g);
        corner = k;
      }
    }
    int kv = Key(t, corner);
    ivec2 vt = TrianglesAt(kv);
    double best = -3.0lf;
    int bestEnd = -1;
    for (int i = vt.x; i < vt.y; ++i)
    {
      int f = corners[i];
      int end;
      double cosine = VertexWedgeCosine(f, kv, u, end);
      if (cosine > best)
      {
        best = cosine;
        bestEnd = end;
        chosen = f;
      }
    }
    if (bestEnd >= 0)
    {
      // Nearest to an edge direction, which two or more wedges share: the triangles
      // around that edge decide, as for an edge.
      chosen =
        AroundEdge(kv, vt, bestEnd, TrianglesAt(bestEnd), Position(kv), Position(bestEnd), u, chosen);
    }
  }
  precise dvec3 n = Cross(Corner(chosen, 1) - Corner(chosen, 0), Corner(chosen, 2) - Corner(chosen, 0));
  precise double length = SqrtRN(Dot(n, n));
  double scale = DivRN(triangle[5 * chosen + 4] != 0 ? -1.0lf : 1.0lf, length > 0.0lf ? length : 1.0lf);
  n = dvec3(n.x * scale, n.y * scale, n.z * scale);
  // On the sheet (u = 0) or in its plane: the front, by convention.
  int side = away && Dot(u, n) < 0.0lf ? 1 : 0;
  label[at - LabelBase] = 2 * triangle[5 * chosen + 3] + side;
}
