#version 450 core
// An upper bound U of each query's distance to the boundary of a union of convex pieces
// (Filters/Core/Union/UnionClosestPointGPU.h), in double precision: over a block of the
// pieces' faces, the least distance from the query O to the nearest point x of a face
// that is certainly a boundary point: x is on its own piece's face, so x + e n is outside
// that piece for small e > 0 (n the face's outward normal), and x lies outside every other
// piece by more than Tolerance (its box, or one of its face planes), so x + e n is outside
// the union while x is in it. One invocation a (query, block of BlockFaces faces); the
// host takes the least of a query's blocks. U only seeds the exact search on the CPU,
// which finds the same answer from any seed.
//
// Every loop iteration spends one of IterationBudget, and an invocation whose budget runs
// out stops, keeping only the points it finished testing, and says so: Mesa's llvmpipe
// silently ends a shader's loops after 65535 iterations of its SIMD vector in all
// (gallivm's loop limiter), which would cut a coverage test short and accept a covered
// point.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Corners
{
  double corner[]; // xyz of every face's corners, face after face
};
layout(std430, binding = 1) readonly buffer FaceRecords
{
  ivec4 faceRecord[]; // piece, first corner, corner count, unused
};
layout(std430, binding = 2) readonly buffer FacePlanes
{
  dvec4 facePlane[]; // outward unit normal, offset: inside where dot(n, x) <= offset
};
layout(std430, binding = 3) readonly buffer PieceRecords
{
  ivec2 pieceRecord[]; // first face, face count
};
layout(std430, binding = 4) readonly buffer PieceBoxes
{
  double pieceBox[]; // 6 per piece: min xyz, max xyz
};
layout(std430, binding = 5) readonly buffer Queries
{
  double query[]; // xyz per query of this dispatch
};
layout(std430, binding = 6) writeonly buffer BlockBounds
{
  double blockBound[]; // per (query of the dispatch, block): the least squared distance, or -1
};
layout(std430, binding = 7) writeonly buffer BlockStops
{
  uint blockStopped[]; // per (query of the dispatch, block): 1 when the budget ran out
};
uniform int QueryCount; // how many queries this dispatch answers
uniform int Blocks;     // blocks of faces per query
uniform int BlockFaces; // faces a block
uniform int FaceCount, PieceCount;
uniform double Tolerance;
uniform int IterationBudget;

int budget; // the loop iterations this invocation has left

dvec3 CornerAt(int k)
{
  return dvec3(corner[3 * k], corner[3 * k + 1], corner[3 * k + 2]);
}

// The nearest point of face f to o: o's projection on the face's plane when the face
// holds it, else the nearest point of its outline.
dvec3 NearestOnFace(int f, dvec3 o)
{
  const ivec4 record = faceRecord[f];
  const dvec3 n = facePlane[f].xyz;
  const dvec3 p = o - (dot(n, o) - facePlane[f].w) * n;
  bool holds = true;
  double best = -1;
  dvec3 nearest = p;
  dvec3 a = CornerAt(record.y + record.z - 1);
  for (int k = 0; k < record.z && budget > 0; ++k, --budget)
  {
    const dvec3 b = CornerAt(record.y + k);
    const dvec3 e = b - a;
    // Counter-clockwise seen from outside: the face lies on the left of each edge.
    holds = holds && dot(cross(e, p - a), n) >= 0;
    const double ee = dot(e, e);
    const double t = ee > 0 ? clamp(dot(o - a, e) / ee, 0.0lf, 1.0lf) : 0.0lf;
    const dvec3 x = a + t * e;
    const double d2 = dot(o - x, o - x);
    if (best < 0 || d2 < best)
    {
      best = d2;
      nearest = x;
    }
    a = b;
  }
  return holds ? p : nearest;
}

// Whether piece j holds x, within Tolerance: x is in its box and on the inner side of
// every face plane (or the budget ran out: then it may).
bool PieceHolds(int j, dvec3 x)
{
  const dvec3 lo = dvec3(pieceBox[6 * j], pieceBox[6 * j + 1], pieceBox[6 * j + 2]) - Tolerance;
  const dvec3 hi = dvec3(pieceBox[6 * j + 3], pieceBox[6 * j + 4], pieceBox[6 * j + 5]) + Tolerance;
  if (x.x < lo.x || x.y < lo.y || x.z < lo.z || x.x > hi.x || x.y > hi.y || x.z > hi.z)
  {
    return false;
  }
  const ivec2 faces = pieceRecord[j];
  for (int g = faces.x; g < faces.x + faces.y && budget > 0; ++g, --budget)
  {
    if (dot(facePlane[g].xyz, x) - facePlane[g].w > Tolerance)
    {
      return false;
    }
  }
  return true;
}

// Whether x lies outside every piece but `self` by more than Tolerance, all tested
// within the budget.
bool OutsideOtherPieces(dvec3 x, int self)
{
  for (int j = 0; j < PieceCount && budget > 0; ++j, --budget)
  {
    if (j != self && PieceHolds(j, x))
    {
      return false;
    }
  }
  return budget > 0;
}

void main()
{
  const int index = int(gl_GlobalInvocationID.x);
  if (index >= QueryCount * Blocks)
  {
    return;
  }
  const int q = index / Blocks;
  const int begin = (index % Blocks) * BlockFaces;
  const int end = min(FaceCount, begin + BlockFaces);
  const dvec3 o = dvec3(query[3 * q], query[3 * q + 1], query[3 * q + 2]);
  double best = -1;
  budget = IterationBudget;
  for (int f = begin; f < end && budget > 0; ++f, --budget)
  {
    const dvec3 x = NearestOnFace(f, o);
    const double d2 = dot(o - x, o - x);
    if (budget > 0 && (best < 0 || d2 < best) && OutsideOtherPieces(x, faceRecord[f].x))
    {
      best = d2;
    }
  }
  blockBound[index] = best;
  blockStopped[index] = budget > 0 ? 0u : 1u;
}
