#version 450 core
// The nearest triangle of one model (the "other") to points of the second (the "self"),
// for the proximity queries (Filters/Core/Proximity/ProximityQuery.cxx): the search of
// ProximitySearch.h's NearestTriangle over the other model's box hierarchy, the nearer
// child first, nodes farther than the best pruned, in double precision with `precise`
// (Common/PointTriangleDistance.h operation for operation). One invocation a point:
// - Mode 0: the self model's points [First, Last);
// - Mode 1: face samples [First, Last) of a batch of the self model's triangles, each
//   Item (triangle, its first sample, its divisions n) standing for the barycentric
//   lattice points p0 + (i/n)(p1 - p0) + (j/n)(p2 - p0) other than the corners, in the
//   order of i, then j; the search starts from the triangle that is nearest to the
//   triangle's first corner (SelfHint, Mode 0's answer).
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer OtherPoints
{
  double otherPoint[]; // 3 per point
};
layout(std430, binding = 1) readonly buffer OtherTriangles
{
  int otherTriangle[]; // 3 point ids per triangle
};
layout(std430, binding = 2) readonly buffer OtherNodeBounds
{
  double nodeBound[]; // 6 per node: min xyz, max xyz
};
layout(std430, binding = 3) readonly buffer OtherNodeLinks
{
  ivec4 nodeLink[]; // left child (-1: a leaf), right child, first and end in the order
};
layout(std430, binding = 4) readonly buffer OtherOrder
{
  int orderedTriangle[]; // the triangles in the hierarchy's order
};
layout(std430, binding = 5) readonly buffer SelfPoints
{
  double selfPoint[];
};
layout(std430, binding = 6) readonly buffer SelfTriangles
{
  int selfTriangle[];
};
layout(std430, binding = 7) readonly buffer SelfHints
{
  int selfHint[]; // Mode 1: per self point, the other's triangle nearest to it
};
layout(std430, binding = 8) writeonly buffer Answers
{
  dvec4 answer[]; // closest point, squared distance
};
layout(std430, binding = 9) writeonly buffer AnswerTriangles
{
  int answerTriangle[];
};
layout(std430, binding = 10) readonly buffer Items
{
  ivec4 item[]; // Mode 1: triangle, first sample, divisions, unused
};
uniform int Mode;
uniform int First; // the point or sample of invocation 0
uniform int Last;  // one past the last of this dispatch
uniform int ItemCount;
uniform double BoxShrink; // 1 - 8 epsilon: box distances rounded down (TriangleBoxTree.h)

dvec3 OtherCorner(int t, int c)
{
  int p = otherTriangle[3 * t + c];
  return dvec3(otherPoint[3 * p], otherPoint[3 * p + 1], otherPoint[3 * p + 2]);
}

dvec3 SelfCorner(int t, int c)
{
  int p = selfTriangle[3 * t + c];
  return dvec3(selfPoint[3 * p], selfPoint[3 * p + 1], selfPoint[3 * p + 2]);
}

//DF::TriangleDistance

double SquaredDistanceToNode(int node, dvec3 x)
{
  precise double d2 = 0.0lf;
  for (int k = 0; k < 3; ++k)
  {
    precise double gap =
      max(0.0lf, max(x[k] - nodeBound[6 * node + 3 + k], nodeBound[6 * node + k] - x[k]));
    d2 += gap * gap;
  }
  precise double shrunk = d2 * BoxShrink;
  return shrunk;
}

// The nearest triangle to x, from `hint`'s distance when it is a triangle.
double Nearest(dvec3 x, int hint, out dvec3 closest, out int triangle)
{
  double best = packDouble2x32(uvec2(0u, 0x7ff00000u)); // +infinity
  closest = dvec3(0.0lf);
  triangle = hint;
  if (hint >= 0)
  {
    best = SquaredDistanceToTriangle(
      x, OtherCorner(hint, 0), OtherCorner(hint, 1), OtherCorner(hint, 2), closest);
  }
  // A median split halves every node: the depth stays below 64.
  int stack[66];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    int node = stack[--depth];
    if (SquaredDistanceToNode(node, x) > best)
    {
      continue;
    }
    ivec4 link = nodeLink[node];
    if (link.x < 0)
    {
      for (int i = link.z; i < link.w; ++i)
      {
        int t = orderedTriangle[i];
        dvec3 on;
        double d2 =
          SquaredDistanceToTriangle(x, OtherCorner(t, 0), OtherCorner(t, 1), OtherCorner(t, 2), on);
        if (d2 < best)
        {
          best = d2;
          closest = on;
          triangle = t;
        }
      }
      continue;
    }
    double left = SquaredDistanceToNode(link.x, x);
    double right = SquaredDistanceToNode(link.y, x);
    stack[depth++] = left <= right ? link.y : link.x;
    stack[depth++] = left <= right ? link.x : link.y;
  }
  return best;
}

// Samples of a lattice before row i (1 <= i < n): row 0 has n - 1 (not its two corners),
// row r >= 1 has n - r + 1, row n none.
int Before(int n, int i)
{
  return (n - 1) + (i - 1) * (n + 1) - ((i - 1) * i) / 2;
}

void main()
{
  int k = First + int(gl_GlobalInvocationID.x);
  if (k >= Last)
  {
    return;
  }
  dvec3 x;
  int hint = -1;
  if (Mode == 0)
  {
    x = dvec3(selfPoint[3 * k], selfPoint[3 * k + 1], selfPoint[3 * k + 2]);
  }
  else
  {
    // The item holding sample k: the last whose first sample is at most k.
    int lo = 0, hi = ItemCount - 1;
    while (lo < hi)
    {
      int mid = (lo + hi + 1) / 2;
      if (item[mid].y <= k)
      {
        lo = mid;
      }
      else
      {
        hi = mid - 1;
      }
    }
    ivec4 it = item[lo];
    int n = it.z, local = k - it.y;
    int i = 0, j = local + 1;
    if (local >= n - 1)
    {
      // The last row i in [1, n - 1] that starts at or before `local`.
      int a = 1, b = n - 1;
      while (a < b)
      {
        int mid = (a + b + 1) / 2;
        if (Before(n, mid) <= local)
        {
          a = mid;
        }
        else
        {
          b = mid - 1;
        }
      }
      i = a;
      j = local - Before(n, a);
    }
    dvec3 p0 = SelfCorner(it.x, 0), p1 = SelfCorner(it.x, 1), p2 = SelfCorner(it.x, 2);
    precise double u = double(i) / double(n), v = double(j) / double(n);
    precise dvec3 lattice = p0 + u * (p1 - p0) + v * (p2 - p0);
    x = lattice;
    hint = selfHint[selfTriangle[3 * it.x]];
  }
  dvec3 closest;
  int triangle;
  double d2 = Nearest(x, hint, closest, triangle);
  // Points keep their index (the samples' hints); samples their place in the dispatch.
  int at = Mode == 0 ? k : k - First;
  answer[at] = dvec4(closest, d2);
  answerTriangle[at] = triangle;
}
