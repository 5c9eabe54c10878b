#include "LinearFactor/HausdorffCover.h"

#include "Common/Vector3.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vtkdf
{
namespace hausdorff
{
double CornerReach(const Piece& piece)
{
  double side2[3];
  for (int e = 0; e < 3; ++e)
  {
    const double* u = piece.X + 3 * e;
    const double* v = piece.X + 3 * ((e + 1) % 3);
    side2[e] =
      (u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) + (u[2] - v[2]) * (u[2] - v[2]);
  }
  if (piece.Segment)
  {
    return 0.5 * std::sqrt(side2[0]);
  }
  const double longest2 = std::max(std::max(side2[0], side2[1]), side2[2]);
  const double others2 = side2[0] + side2[1] + side2[2] - longest2;
  double u[3], v[3], n[3];
  for (int a = 0; a < 3; ++a)
  {
    u[a] = piece.X[3 + a] - piece.X[a];
    v[a] = piece.X[6 + a] - piece.X[a];
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  const double twiceArea = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (longest2 >= others2 || !(twiceArea > 0))
  {
    return std::sqrt(0.5 * longest2);
  }
  // R = abc / (4 area), and a little more for its rounding.
  return std::sqrt(side2[0] * side2[1] * side2[2]) / (2 * twiceArea) * (1 + 1e-9);
}

/// A triangle piece's frame: Origin its first corner, E1 along its first side, N its
/// unit normal, E2 = N x E1, and T its corners projected (E1, E2 coordinates).
struct PieceFrame
{
  const double* Origin = nullptr;
  double E1[3], E2[3], N[3];
  double T[3][2];
  /// False for a segment or a triangle without area.
  bool Set(const Piece& piece);
  /// x's coordinates along E1 and E2 into u; returns its height along N.
  double Project(const double* x, double u[2]) const;
};

namespace
{
/// Whether 2D convex polygons p (np corners) and q (nq corners), each counterclockwise
/// (a segment: two corners), are apart by more than `margin` along one of their edges'
/// normals.
bool Apart(const double (*p)[2], int np, const double (*q)[2], int nq, double margin)
{
  auto separates = [&](const double(*edges)[2], int n)
  {
    for (int e = 0; e < n; ++e)
    {
      const double* a = edges[e];
      const double* b = edges[(e + 1) % n];
      const double normal[2] = { b[1] - a[1], a[0] - b[0] };
      // The projections stay scaled by the normal's length (so does the margin).
      const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1]);
      if (!(length > 0))
      {
        continue;
      }
      double loP = HUGE_VAL, hiP = -HUGE_VAL, loQ = HUGE_VAL, hiQ = -HUGE_VAL;
      for (int i = 0; i < np; ++i)
      {
        const double v = p[i][0] * normal[0] + p[i][1] * normal[1];
        loP = std::min(loP, v), hiP = std::max(hiP, v);
      }
      for (int i = 0; i < nq; ++i)
      {
        const double v = q[i][0] * normal[0] + q[i][1] * normal[1];
        loQ = std::min(loQ, v), hiQ = std::max(hiQ, v);
      }
      const double gap = margin * length;
      if (hiP + gap < loQ || hiQ + gap < loP)
      {
        return true;
      }
    }
    return false;
  };
  return separates(p, np) || separates(q, nq);
}

bool LexicographicLess(const double* u, const double* v)
{
  return u[0] != v[0] ? u[0] < v[0] : (u[1] != v[1] ? u[1] < v[1] : u[2] < v[2]);
}

uint64_t PointHash(const double* x)
{
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int a = 0; a < 3; ++a)
  {
    uint64_t bits;
    const double v = x[a] == 0 ? 0.0 : x[a]; // -0 and 0 alike
    std::memcpy(&bits, &v, sizeof bits);
    h = (h ^ bits) * 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

/// The edge from u to v, keyed by its corners whichever way it runs.
CoverScratch::Edge MakeEdge(const double* u, const double* v)
{
  const bool forward = LexicographicLess(u, v);
  const double* lo = forward ? u : v;
  const double* hi = forward ? v : u;
  return { PointHash(lo) * 31 + PointHash(hi), lo, hi, forward };
}

/// Whether no edge of the boundary of the faces in `scratch` meets the piece's projection
/// (sorts scratch.Edges).
bool BoundaryAvoids(const PieceFrame& frame, CoverScratch& scratch, double margin);
bool BoundaryAvoids(const PieceFrame& frame, CoverScratch& scratch, double margin)
{
  // The boundary: the directed edges whose reverse no other face runs. Equal edges have
  // equal keys, so they sort next to each other (unless a collision separates them: then
  // they count as boundary, which only makes the bound give up).
  std::sort(scratch.Edges.begin(),
    scratch.Edges.end(),
    [](const CoverScratch::Edge& p, const CoverScratch::Edge& q) { return p.Key < q.Key; });
  for (size_t begin = 0; begin < scratch.Edges.size();)
  {
    const CoverScratch::Edge& e = scratch.Edges[begin];
    size_t end = begin;
    int net = 0;
    for (; end < scratch.Edges.size() && scratch.Edges[end].Key == e.Key &&
         SamePoint(scratch.Edges[end].From, e.From) && SamePoint(scratch.Edges[end].To, e.To);
         ++end)
    {
      net += scratch.Edges[end].Forward ? 1 : -1;
    }
    if (net != 0)
    {
      double segment[2][2];
      frame.Project(e.From, segment[0]);
      frame.Project(e.To, segment[1]);
      if (!Apart(segment, 2, frame.T, 3, margin))
      {
        return false;
      }
    }
    begin = end;
  }
  return true;
}
} // namespace

bool PieceFrame::Set(const Piece& piece)
{
  if (piece.Segment)
  {
    return false;
  }
  this->Origin = piece.X;
  double side[3];
  for (int a = 0; a < 3; ++a)
  {
    this->E1[a] = piece.X[3 + a] - piece.X[a];
    side[a] = piece.X[6 + a] - piece.X[a];
  }
  double* n = this->N;
  n[0] = this->E1[1] * side[2] - this->E1[2] * side[1];
  n[1] = this->E1[2] * side[0] - this->E1[0] * side[2];
  n[2] = this->E1[0] * side[1] - this->E1[1] * side[0];
  const double twiceArea = std::sqrt(Dot(n, n));
  const double first = std::sqrt(Dot(this->E1, this->E1));
  if (!(twiceArea > 0) || !(first > 0))
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    n[a] /= twiceArea;
    this->E1[a] /= first;
  }
  this->E2[0] = n[1] * this->E1[2] - n[2] * this->E1[1];
  this->E2[1] = n[2] * this->E1[0] - n[0] * this->E1[2];
  this->E2[2] = n[0] * this->E1[1] - n[1] * this->E1[0];
  for (int c = 0; c < 3; ++c)
  {
    this->Project(piece.X + 3 * c, this->T[c]);
  }
  return true;
}

double PieceFrame::Project(const double* x, double u[2]) const
{
  const double d[3] = { x[0] - this->Origin[0], x[1] - this->Origin[1], x[2] - this->Origin[2] };
  u[0] = Dot(d, this->E1);
  u[1] = Dot(d, this->E2);
  return Dot(d, this->N);
}

double CoverBound::FaceHeight(const Piece& piece, const PieceFrame& frame, const double* x) const
{
  double height = 0, u[2];
  for (int c = 0; c < 3; ++c)
  {
    height = std::max(height, std::fabs(frame.Project(x + 3 * c, u)));
  }
  // Over the part of T below or above it, a face is also no farther than its plane is
  // along n at T's corners (the distance along n to a plane is affine along T): the
  // tighter bound where the face is larger than the piece.
  double normal[3], e[3], f[3];
  for (int a = 0; a < 3; ++a)
  {
    e[a] = x[3 + a] - x[a];
    f[a] = x[6 + a] - x[a];
  }
  normal[0] = e[1] * f[2] - e[2] * f[1];
  normal[1] = e[2] * f[0] - e[0] * f[2];
  normal[2] = e[0] * f[1] - e[1] * f[0];
  const double length = std::sqrt(Dot(normal, normal));
  const double facing = length > 0 ? std::fabs(Dot(normal, frame.N)) / length : 0;
  if (facing > 0.1)
  {
    double along = 0;
    for (int c = 0; c < 3; ++c)
    {
      const double w[3] = {
        x[0] - piece.X[3 * c], x[1] - piece.X[3 * c + 1], x[2] - piece.X[3 * c + 2]
      };
      along = std::max(along, std::fabs(Dot(w, normal)) / length / facing);
    }
    // The division by `facing` (at least 0.1) enlarges the rounding tenfold at most.
    height = std::min(height, along * (1 + 1e-9) + 10 * this->Slack);
  }
  return height;
}

bool CoverBound::ProjectFaces(const Piece& piece,
  const PieceFrame& frame,
  double threshold,
  bool nearest,
  CoverScratch& scratch,
  double& margin) const
{
  // The faces over T lie about as far from it as its corners' nearest ones (a quarter
  // more allows for the surface's bending; faces beyond the threshold cannot bound the
  // piece below it). Any reach is sound: too short a one leaves a boundary over T.
  const double reach = std::min(threshold,
    1.25 * std::sqrt(std::max(std::max(piece.D2[0], piece.D2[1]), piece.D2[2])) + 1e-3 * threshold);
  double lo[3], hi[3], size = 0;
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::min(std::min(piece.X[a], piece.X[3 + a]), piece.X[6 + a]) - reach;
    hi[a] = std::max(std::max(piece.X[a], piece.X[3 + a]), piece.X[6 + a]) + reach;
    size = std::max(size, hi[a] - lo[a]);
  }
  if (nearest)
  {
    scratch.Found.clear();
    for (int k = 0; k < 4; ++k)
    {
      const int32_t i = piece.Near[k];
      if (i >= 0 && this->Target.IsFace(i) &&
        std::find(scratch.Found.begin(), scratch.Found.end(), i) == scratch.Found.end())
      {
        scratch.Found.push_back(i);
      }
    }
  }
  else if (!this->Target.GatherFaces(lo, hi, 256, scratch.Found))
  {
    return false; // too many faces: not worth it
  }
  // Rounding of the projections is far below this.
  margin = this->Slack + 1e-9 * size;
  scratch.Faces.clear();
  scratch.Edges.clear();
  for (const int32_t i : scratch.Found)
  {
    const nearest::Primitive corners = this->Target.Get(i);
    const double* x = corners.X;
    CoverScratch::Face face;
    for (int c = 0; c < 3; ++c)
    {
      face.X[c] = this->Target.Corner(i, c); // kept past this loop
      frame.Project(face.X[c], face.U[c]);
    }
    const double area = (face.U[1][0] - face.U[0][0]) * (face.U[2][1] - face.U[0][1]) -
      (face.U[1][1] - face.U[0][1]) * (face.U[2][0] - face.U[0][0]);
    if (!(std::fabs(area) > margin * size))
    {
      continue; // seen edge-on: left out (its neighbours' edges then bound S)
    }
    if (area < 0)
    {
      std::swap(face.U[1][0], face.U[2][0]);
      std::swap(face.U[1][1], face.U[2][1]);
      std::swap(face.X[1], face.X[2]);
    }
    face.Height = this->FaceHeight(piece, frame, x);
    scratch.Faces.push_back(face);
    for (int c = 0; c < 3; ++c)
    {
      scratch.Edges.push_back(MakeEdge(face.X[c], face.X[(c + 1) % 3]));
    }
  }
  return true;
}

bool CoverBound::operator()(const Piece& piece,
  double threshold,
  bool nearest,
  double& bound,
  CoverScratch& scratch) const
{
  PieceFrame frame;
  double margin;
  if (!frame.Set(piece) || !this->ProjectFaces(piece, frame, threshold, nearest, scratch, margin) ||
    !BoundaryAvoids(frame, scratch, margin))
  {
    return false;
  }
  // Covered where one face's projection holds T's centroid; bounded by the heights of
  // the faces over T.
  const double(*t)[2] = frame.T;
  const double centroid[2] = { (t[0][0] + t[1][0] + t[2][0]) / 3,
    (t[0][1] + t[1][1] + t[2][1]) / 3 };
  bool covered = false;
  bound = 0;
  for (const CoverScratch::Face& face : scratch.Faces)
  {
    if (Apart(face.U, 3, t, 3, margin))
    {
      continue;
    }
    bound = std::max(bound, face.Height);
    bool inside = true;
    for (int c = 0; c < 3 && inside; ++c)
    {
      const double* a = face.U[c];
      const double* b = face.U[(c + 1) % 3];
      inside = (b[0] - a[0]) * (centroid[1] - a[1]) - (b[1] - a[1]) * (centroid[0] - a[0]) >= 0;
    }
    covered = covered || inside;
  }
  bound = bound * (1 + 1e-9) + this->Slack;
  return covered;
}
} // namespace hausdorff
} // namespace vtkdf
