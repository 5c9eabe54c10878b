#include "Union/UnionClosestPoint.h"

#include "Common/Vector3.h"
#include "Union/PlanarPolygon.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>

namespace vtkdf
{

namespace
{
using planar::Clip;
using planar::HalfPlane;
using planar::Polygon;
using planar::V2;
} // namespace

bool UnionClosestPoint::PieceContains(size_t i, const double x[3]) const
{
  const ConvexPiece& piece = this->Pieces[i];
  for (size_t f = 0; f < piece.Faces.size(); ++f)
  {
    if (Dot(&piece.Planes[4 * f], x) - piece.Planes[4 * f + 3] > this->Tolerance)
    {
      return false;
    }
  }
  return true;
}

bool UnionClosestPoint::Contains(const double x[3]) const
{
  for (size_t i = 0; i < this->Pieces.size(); ++i)
  {
    if (this->PieceContains(i, x))
    {
      return true;
    }
  }
  return false;
}

namespace
{
struct Frame
{
  double Origin[3], U[3], V[3], N[3];
  V2 To2D(const double x[3]) const
  {
    const double d[3] = { x[0] - Origin[0], x[1] - Origin[1], x[2] - Origin[2] };
    return { Dot(d, U), Dot(d, V) };
  }
};

/// The nearest point to p of segment a + t e, t in what is left of [0, 1] once the open
/// intervals `removed` (any range) are taken out; false when nothing is left.
bool NearestOnRest(const V2& a,
  const V2& e,
  std::vector<std::pair<double, double>> removed,
  const V2& p,
  double& best,
  V2& at)
{
  std::sort(removed.begin(), removed.end());
  const double ee = e.X * e.X + e.Y * e.Y;
  const double ideal = ee > 0 ? ((p.X - a.X) * e.X + (p.Y - a.Y) * e.Y) / ee : 0;
  bool any = false;
  auto consider = [&](double lo, double hi)
  {
    const double t = std::min(hi, std::max(lo, ideal));
    const V2 x{ a.X + t * e.X, a.Y + t * e.Y };
    const double d2 = (x.X - p.X) * (x.X - p.X) + (x.Y - p.Y) * (x.Y - p.Y);
    if (!any || d2 < best)
    {
      best = d2;
      at = x;
    }
    any = true;
  };
  double free = 0; // the start of what is not yet known to be covered
  for (const auto& r : removed)
  {
    if (!(r.first < r.second) || r.second <= free)
    {
      continue;
    }
    if (r.first > 1)
    {
      break;
    }
    if (r.first >= free)
    {
      consider(free, r.first); // [free, r.first]: r.first is outside the open interval
    }
    free = r.second;
    if (free > 1)
    {
      return any;
    }
  }
  consider(free, 1);
  return true;
}
} // namespace

namespace
{
/// A face of the union's pieces, by its distance from the query (a lower bound of any
/// boundary point on it); Face indexes the frames and outlines of FaceList.
struct Candidate
{
  double Bound;
  int64_t Piece, Face;
};

/// Every face of the pieces in its own plane (a frame and the outline in it), and the
/// faces in the order of their distance from the query.
struct FaceList
{
  std::vector<Candidate> Order;
  std::vector<Frame> Frames;
  std::vector<std::vector<V2>> Outlines;
  std::vector<int64_t> FaceOf; // frame index -> the face's index in its piece

  FaceList(const std::vector<ConvexPiece>& pieces, const double o[3])
  {
    for (size_t i = 0; i < pieces.size(); ++i)
    {
      const ConvexPiece& piece = pieces[i];
      for (size_t f = 0; f < piece.Faces.size(); ++f)
      {
        this->Add(piece, i, f, o);
      }
    }
    std::sort(this->Order.begin(),
      this->Order.end(),
      [](const Candidate& a, const Candidate& b)
      { return a.Bound != b.Bound ? a.Bound < b.Bound : a.Face < b.Face; });
  }

private:
  void Add(const ConvexPiece& piece, size_t i, size_t f, const double o[3])
  {
    const std::vector<double>& c = piece.Faces[f];
    Frame frame;
    std::copy(&c[0], &c[0] + 3, frame.Origin);
    std::copy(&piece.Planes[4 * f], &piece.Planes[4 * f] + 3, frame.N);
    double u[3] = { c[3] - c[0], c[4] - c[1], c[5] - c[2] };
    const double lu = std::sqrt(Dot(u, u));
    for (int a = 0; a < 3; ++a)
    {
      frame.U[a] = u[a] / lu;
    }
    const double* n = frame.N;
    frame.V[0] = n[1] * frame.U[2] - n[2] * frame.U[1];
    frame.V[1] = n[2] * frame.U[0] - n[0] * frame.U[2];
    frame.V[2] = n[0] * frame.U[1] - n[1] * frame.U[0];
    std::vector<V2> outline;
    for (size_t k = 0; k < c.size(); k += 3)
    {
      outline.push_back(frame.To2D(&c[k]));
    }
    // Distance from o to the face polygon.
    const V2 p = frame.To2D(o);
    const double h = Dot(n, o) - piece.Planes[4 * f + 3];
    bool inside = true;
    double best = HUGE_VAL;
    V2 unused;
    for (size_t k = 0; k < outline.size(); ++k)
    {
      const V2 a = outline[k], b = outline[(k + 1) % outline.size()];
      const V2 e{ b.X - a.X, b.Y - a.Y };
      inside = inside && (e.Y * (p.X - a.X) - e.X * (p.Y - a.Y)) <= 0;
      double d2;
      NearestOnRest(a, e, {}, p, d2, unused);
      best = std::min(best, d2);
    }
    this->Order.push_back({ std::sqrt(h * h + (inside ? 0 : best)),
      static_cast<int64_t>(i),
      static_cast<int64_t>(this->Frames.size()) });
    this->Frames.push_back(frame);
    this->Outlines.push_back(outline);
    this->FaceOf.push_back(static_cast<int64_t>(f));
  }
};

/// The nearest boundary point of one face: its distance (HUGE_VAL when none) and the point.
struct FaceResult
{
  double Distance = HUGE_VAL;
  double Closest[3] = { 0, 0, 0 };
};

/// The search of one face for its nearest boundary point: the face's points that no
/// other piece covers (with the tolerance's slack, strict on the face's outer side), of
/// which the nearest to the query's projection is the face's part of the answer.
class FaceSearch
{
public:
  FaceSearch(const UnionClosestPoint& u,
    const FaceList& faces,
    const Candidate& candidate,
    const double o[3])
    : Union(u)
    , Tol(u.Tolerance)
    , Piece(candidate.Piece)
    , FacePlane(faces.Frames[candidate.Face])
    , Outline(faces.Outlines[candidate.Face])
  {
    const int64_t f = faces.FaceOf[candidate.Face];
    this->P = this->FacePlane.To2D(o);
    this->H = Dot(this->FacePlane.N, o) - u.Pieces[this->Piece].Planes[4 * f + 3];
  }

  /// Fills `result` when the face has a boundary point nearer than `limit`.
  void Run(double limit, FaceResult& result)
  {
    if (!this->CutToLimit(limit))
    {
      return;
    }
    this->Bound();
    if (this->CoveredByRecentOrAny() || this->CollectSections())
    {
      return;
    }
    this->NearestFree();
    if (this->Planar < HUGE_VAL)
    {
      result.Distance = std::sqrt(this->H * this->H + this->Planar);
      for (int a = 0; a < 3; ++a)
      {
        result.Closest[a] = this->FacePlane.Origin[a] + this->Nearest.X * this->FacePlane.U[a] +
          this->Nearest.Y * this->FacePlane.V[a];
      }
    }
  }

private:
  bool CutToLimit(double limit);
  /// The face as far as the limit matters: the window when cut, else the outline.
  const std::vector<V2>& Cut() const { return this->Window.empty() ? this->Outline : this->Window; }
  void Bound();
  bool CoversFace(size_t j) const;
  bool CoveredByRecentOrAny();
  bool CollectSections();
  enum class Cover
  {
    None,        // the piece leaves the face uncovered
    Part,        // its section covers a part
    Whole,       // the face lies in the piece's inner ball
    WholeNoPlane // no plane of the piece cuts the face
  };
  Cover Section(size_t j, std::vector<HalfPlane>& section) const;
  void NearestFree();
  void SectionBoxes();
  void Edge(const V2& a, const V2& e, const double m[2], size_t skip);

  const UnionClosestPoint& Union;
  const double Tol;
  const int64_t Piece;
  const Frame& FacePlane; // the face's plane, the frame of its 2D coordinates
  std::vector<V2> Outline;
  // The face cut to the square around P that holds every point nearer than the limit
  // (empty without a limit): it bounds which pieces are asked about the face. The face's
  // sections and nearest point are taken on the whole outline all the same, so that a
  // face's answer has the same bits whatever limit it was searched with (a seeded search
  // and the unseeded one, the serial search and the chunked one).
  std::vector<V2> Window;
  V2 P;
  double H;
  // The (cut) face's box and bounding sphere, in 3D.
  double FaceLo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL };
  double FaceHi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  double FaceCentre[3] = { 0, 0, 0 };
  double FaceRadius = 0;
  // The sections S_j that cover the face's outer side, their parts within the face and
  // the parts' boxes.
  std::vector<std::vector<HalfPlane>> Sections;
  std::vector<Polygon> Parts;
  std::vector<std::array<double, 4>> Boxes;
  std::vector<std::pair<double, double>> Removed;
  // The nearest free point so far: its squared distance in the plane, and where.
  double Planar = HUGE_VAL;
  V2 Nearest{ 0, 0 };
};

/// Only the face's points nearer than `limit` can improve the answer: the face is cut to
/// the square around O's projection that holds them (exact: the nearest point of what is
/// left within that disk is the same, and the cut's new edges are farther). False when
/// nothing is left.
bool FaceSearch::CutToLimit(double limit)
{
  if (!(limit < HUGE_VAL))
  {
    return true;
  }
  const V2& p = this->P;
  const double r =
    std::sqrt(std::max(0.0, limit * limit - this->H * this->H)) * (1 + 1e-9) + this->Tol;
  Polygon cut;
  cut.Corners = this->Outline;
  cut.Source.assign(this->Outline.size(), -1);
  const HalfPlane square[4] = { { { 1, 0 }, p.X + r },
    { { -1, 0 }, -(p.X - r) },
    { { 0, 1 }, p.Y + r },
    { { 0, -1 }, -(p.Y - r) } };
  for (const HalfPlane& side : square)
  {
    cut = Clip(cut, side, -1);
    if (cut.Corners.empty())
    {
      return false;
    }
  }
  this->Window = cut.Corners;
  return true;
}

/// The (cut) face's box and bounding sphere, in 3D.
void FaceSearch::Bound()
{
  const std::vector<V2>& outline = this->Cut();
  std::vector<std::array<double, 3>> corners3;
  for (const V2& c : outline)
  {
    std::array<double, 3> x;
    for (int a = 0; a < 3; ++a)
    {
      x[a] = this->FacePlane.Origin[a] + c.X * this->FacePlane.U[a] + c.Y * this->FacePlane.V[a];
      this->FaceLo[a] = std::min(this->FaceLo[a], x[a]);
      this->FaceHi[a] = std::max(this->FaceHi[a], x[a]);
      this->FaceCentre[a] += x[a] / outline.size();
    }
    corners3.push_back(x);
  }
  const double* centre = this->FaceCentre;
  for (const auto& c : corners3)
  {
    this->FaceRadius = std::max(this->FaceRadius,
      std::sqrt((c[0] - centre[0]) * (c[0] - centre[0]) + (c[1] - centre[1]) * (c[1] - centre[1]) +
        (c[2] - centre[2]) * (c[2] - centre[2])));
  }
  // The sphere must hold every corner.
  this->FaceRadius = this->FaceRadius * (1 + 1e-12) + this->Tol * 1e-3;
}

/// Whether piece j covers the whole (cut) face: every plane of it holds on every corner
/// with the strict slack (the same rule as the sections, which then keep none).
bool FaceSearch::CoversFace(size_t j) const
{
  const double tol = this->Tol;
  const ConvexPiece& other = this->Union.Pieces[j];
  for (size_t k = 0; k < other.Faces.size(); ++k)
  {
    const double* plane = &other.Planes[4 * k];
    if (Dot(plane, this->FaceCentre) - plane[3] + this->FaceRadius < -tol)
    {
      continue;
    }
    const double a[2] = { Dot(plane, this->FacePlane.U), Dot(plane, this->FacePlane.V) };
    const double b = plane[3] - Dot(plane, this->FacePlane.Origin);
    if (a[0] * a[0] + a[1] * a[1] < 1e-24)
    {
      if (!(0 <= b + (Dot(plane, this->FacePlane.N) > 0 ? -tol : tol)))
      {
        return false;
      }
      continue;
    }
    for (const V2& c : this->Cut())
    {
      if (!(a[0] * c.X + a[1] * c.Y < b - tol))
      {
        return false;
      }
    }
  }
  return true;
}

// Deep inside many overlapping pieces most faces are covered whole by one piece, often
// the one that covered the faces visited just before on this thread: those first.
thread_local std::vector<size_t> Recent;
thread_local const UnionClosestPoint* RecentOwner = nullptr;

void Remember(size_t j)
{
  Recent.insert(Recent.begin(), j);
  if (Recent.size() > 8)
  {
    Recent.pop_back();
  }
}

/// Whether a recent covering piece, then any piece whose box holds the face's, covers
/// it whole (a piece that does not fails at its first plane that cuts it), before any
/// section is built.
bool FaceSearch::CoveredByRecentOrAny()
{
  if (RecentOwner != &this->Union)
  {
    Recent.clear();
    RecentOwner = &this->Union;
  }
  const size_t own = static_cast<size_t>(this->Piece);
  for (size_t r = 0; r < Recent.size(); ++r)
  {
    const size_t j = Recent[r];
    if (j != own && j < this->Union.Pieces.size() && this->CoversFace(j))
    {
      std::rotate(Recent.begin(), Recent.begin() + r, Recent.begin() + r + 1);
      return true;
    }
  }
  for (size_t j = 0; j < this->Union.Pieces.size(); ++j)
  {
    const ConvexPiece& other = this->Union.Pieces[j];
    if (j == own || other.Lo[0] > this->FaceLo[0] || other.Hi[0] < this->FaceHi[0] ||
      other.Lo[1] > this->FaceLo[1] || other.Hi[1] < this->FaceHi[1] ||
      other.Lo[2] > this->FaceLo[2] || other.Hi[2] < this->FaceHi[2])
    {
      continue; // its box does not hold the face's
    }
    if (this->CoversFace(j))
    {
      Remember(j);
      return true;
    }
  }
  return false;
}

/// The section of piece j on the face: the half-planes of its planes that cut the face.
FaceSearch::Cover FaceSearch::Section(size_t j, std::vector<HalfPlane>& section) const
{
  const double tol = this->Tol;
  const ConvexPiece& other = this->Union.Pieces[j];
  const double* centre = this->FaceCentre;
  // The face inside the piece's inner ball: covered whole, no plane needed.
  const double toCentre = std::sqrt((centre[0] - other.Centre[0]) * (centre[0] - other.Centre[0]) +
    (centre[1] - other.Centre[1]) * (centre[1] - other.Centre[1]) +
    (centre[2] - other.Centre[2]) * (centre[2] - other.Centre[2]));
  if (toCentre + this->FaceRadius < other.InnerRadius - 2 * tol)
  {
    return Cover::Whole;
  }
  for (size_t k = 0; k < other.Faces.size(); ++k)
  {
    const double* plane = &other.Planes[4 * k];
    // First by the face's bounding sphere: most planes are far from the face.
    const double centreSide = Dot(plane, centre) - plane[3];
    if (centreSide + this->FaceRadius < -tol)
    {
      continue;
    }
    if (centreSide - this->FaceRadius > tol)
    {
      return Cover::None;
    }
    const double a[2] = { Dot(plane, this->FacePlane.U), Dot(plane, this->FacePlane.V) };
    const double b = plane[3] - Dot(plane, this->FacePlane.Origin);
    // Strict where the plane faces like the face (x + e n must stay inside).
    const double slack = Dot(plane, this->FacePlane.N) > 0 ? -tol : tol;
    if (a[0] * a[0] + a[1] * a[1] < 1e-24) // the plane is parallel to the face
    {
      if (!(0 <= b + slack))
      {
        return Cover::None;
      }
      continue;
    }
    // Only the planes that cut the face matter (most of a large piece's do not): one
    // that holds every corner even with the strict slack holds on the whole face and
    // just beyond it; one that no corner meets even with the loose slack leaves the
    // face uncovered by this piece.
    double most = -HUGE_VAL, least = HUGE_VAL;
    for (const V2& c : this->Outline)
    {
      const double value = a[0] * c.X + a[1] * c.Y;
      most = std::max(most, value);
      least = std::min(least, value);
    }
    if (most < b - tol)
    {
      continue;
    }
    if (least > b + tol)
    {
      return Cover::None;
    }
    section.push_back({ { a[0], a[1] }, b + slack });
  }
  // No plane cuts the face: every one holds on all of it, and the face has no boundary
  // point (common deep inside many overlapping pieces).
  return section.empty() ? Cover::WholeNoPlane : Cover::Part;
}

/// The sections of the pieces near the face and their parts within it; true when one
/// piece covers the whole face.
bool FaceSearch::CollectSections()
{
  const double tol = this->Tol;
  Polygon face;
  face.Corners = this->Outline;
  face.Source.assign(this->Outline.size(), -1);
  for (size_t j = 0; j < this->Union.Pieces.size(); ++j)
  {
    const ConvexPiece& other = this->Union.Pieces[j];
    if (j == static_cast<size_t>(this->Piece) || other.Lo[0] > this->FaceHi[0] + tol ||
      other.Hi[0] < this->FaceLo[0] - tol || other.Lo[1] > this->FaceHi[1] + tol ||
      other.Hi[1] < this->FaceLo[1] - tol || other.Lo[2] > this->FaceHi[2] + tol ||
      other.Hi[2] < this->FaceLo[2] - tol)
    {
      continue;
    }
    std::vector<HalfPlane> section;
    const Cover cover = this->Section(j, section);
    if (cover == Cover::None)
    {
      continue;
    }
    if (cover != Cover::Part)
    {
      if (cover == Cover::WholeNoPlane)
      {
        Remember(j);
      }
      return true;
    }
    Polygon part = face;
    for (size_t k = 0; k < section.size() && !part.Corners.empty(); ++k)
    {
      part = Clip(part, section[k], static_cast<int>(k));
    }
    if (part.Corners.empty())
    {
      continue;
    }
    this->Sections.push_back(section);
    this->Parts.push_back(part);
  }
  return false;
}

/// The parts' boxes, grown by what the slacks can move their edges, so that a section
/// whose part is far from an edge is not asked about it.
void FaceSearch::SectionBoxes()
{
  this->Boxes.resize(this->Parts.size());
  for (size_t s = 0; s < this->Parts.size(); ++s)
  {
    double margin = this->Tol;
    for (const HalfPlane& hp : this->Sections[s])
    {
      margin = std::max(margin, 8 * this->Tol / std::sqrt(hp.A[0] * hp.A[0] + hp.A[1] * hp.A[1]));
    }
    std::array<double, 4>& box = this->Boxes[s];
    box = { HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (const V2& c : this->Parts[s].Corners)
    {
      box = {
        std::min(box[0], c.X), std::min(box[1], c.Y), std::max(box[2], c.X), std::max(box[3], c.Y)
      };
    }
    box = { box[0] - margin, box[1] - margin, box[2] + margin, box[3] + margin };
  }
}

/// The nearest point of the face that no section covers: the query's projection itself
/// when free, else the nearest free point of the face's edges and of the parts' edges.
void FaceSearch::NearestFree()
{
  const double tol = this->Tol;
  const std::vector<V2>& outline = this->Outline;
  const V2& p = this->P;
  // P itself, when in the face and in no section.
  bool inFace = true;
  for (size_t k = 0; k < outline.size(); ++k)
  {
    const V2 a = outline[k], b = outline[(k + 1) % outline.size()];
    const double e[2] = { b.X - a.X, b.Y - a.Y };
    inFace = inFace && (e[1] * (p.X - a.X) - e[0] * (p.Y - a.Y)) / std::hypot(e[0], e[1]) <= tol;
  }
  bool covered = false;
  for (const auto& section : this->Sections)
  {
    bool in = true;
    for (const HalfPlane& hp : section)
    {
      in = in && hp.A[0] * p.X + hp.A[1] * p.Y <= hp.B;
    }
    covered = covered || in;
  }
  if (inFace && !covered)
  {
    this->Planar = 0;
    this->Nearest = p;
  }
  this->SectionBoxes();
  if (!(this->Planar > 0))
  {
    return;
  }
  for (size_t k = 0; k < outline.size(); ++k)
  {
    const V2 a = outline[k], b = outline[(k + 1) % outline.size()];
    const V2 e{ b.X - a.X, b.Y - a.Y };
    const double length = std::hypot(e.X, e.Y);
    const double inward[2] = { -e.Y / length, e.X / length };
    this->Edge(a, e, inward, this->Sections.size());
  }
  for (size_t s = 0; s < this->Parts.size(); ++s)
  {
    const Polygon& part = this->Parts[s];
    for (size_t k = 0; k < part.Corners.size(); ++k)
    {
      if (part.Source[k] < 0)
      {
        continue; // on the face's edge: done above
      }
      const V2 a = part.Corners[k], b = part.Corners[(k + 1) % part.Corners.size()];
      const V2 e{ b.X - a.X, b.Y - a.Y };
      const HalfPlane& hp = this->Sections[s][part.Source[k]];
      const double length = std::hypot(hp.A[0], hp.A[1]);
      const double outward[2] = { hp.A[0] / length, hp.A[1] / length };
      this->Edge(a, e, outward, s);
    }
  }
}

/// An edge (a, e) whose side `m` (unit, in the plane) must be free of every section but
/// `skip`: the sections' covering intervals removed, the nearest point of the rest.
void FaceSearch::Edge(const V2& a, const V2& e, const double m[2], size_t skip)
{
  const double tol = this->Tol;
  // No point of the edge can beat the best of this face: skip it.
  double unused;
  V2 at;
  if (NearestOnRest(a, e, {}, this->P, unused, at) && unused >= this->Planar)
  {
    return;
  }
  const double edgeBox[4] = { std::min(a.X, a.X + e.X),
    std::min(a.Y, a.Y + e.Y),
    std::max(a.X, a.X + e.X),
    std::max(a.Y, a.Y + e.Y) };
  std::vector<std::pair<double, double>>& removed = this->Removed;
  removed.clear();
  for (size_t s = 0; s < this->Sections.size(); ++s)
  {
    const std::array<double, 4>& box = this->Boxes[s];
    if (s == skip || box[0] > edgeBox[2] || box[2] < edgeBox[0] || box[1] > edgeBox[3] ||
      box[3] < edgeBox[1])
    {
      continue;
    }
    // Covered(), with y + e m inside: strict where m points out of the half-plane.
    double lo = -HUGE_VAL, hi = HUGE_VAL;
    for (const HalfPlane& hp : this->Sections[s])
    {
      const double bound = hp.B + (hp.A[0] * m[0] + hp.A[1] * m[1] > 0 ? -tol : tol);
      const double alpha = hp.A[0] * e.X + hp.A[1] * e.Y;
      const double beta = bound - (hp.A[0] * a.X + hp.A[1] * a.Y);
      if (alpha > 0)
      {
        hi = std::min(hi, beta / alpha);
      }
      else if (alpha < 0)
      {
        lo = std::max(lo, beta / alpha);
      }
      else if (beta < 0)
      {
        lo = HUGE_VAL, hi = -HUGE_VAL;
      }
      if (!(lo < hi))
      {
        break;
      }
    }
    if (lo < 0 && hi > 1)
    {
      return; // one section covers the whole edge
    }
    if (lo < hi)
    {
      removed.emplace_back(lo, hi);
    }
  }
  double d2;
  if (NearestOnRest(a, e, removed, this->P, d2, at) && d2 < this->Planar)
  {
    this->Planar = d2;
    this->Nearest = at;
  }
}
} // namespace

UnionAnswer UnionClosestPoint::Query(const double o[3], double bound) const
{
  UnionAnswer answer;
  answer.Inside = this->Contains(o);
  const FaceList faces(this->Pieces, o);
  const std::vector<Candidate>& order = faces.Order;
  // Faces in order, a chunk at a time (in parallel when For is set): the best answer so
  // far bounds which faces of the next chunk are visited. The chunks do not depend on the
  // threads, so neither do the answer and the count.
  double best = bound;
  const size_t chunk = this->For ? 64 : 1;
  std::vector<FaceResult> results;
  for (size_t begin = 0; begin < order.size() && order[begin].Bound < best; begin += chunk)
  {
    size_t end = std::min(order.size(), begin + chunk);
    while (end > begin && order[end - 1].Bound >= best)
    {
      --end; // sorted: the rest of the chunk is farther too
    }
    results.assign(end - begin, FaceResult());
    const double limit = best;
    auto work = [&](int64_t first, int64_t last)
    {
      for (int64_t k = first; k < last; ++k)
      {
        FaceSearch(*this, faces, order[begin + k], o).Run(limit, results[k]);
      }
    };
    if (this->For && end - begin > 1)
    {
      this->For(static_cast<int64_t>(end - begin), 4, work);
    }
    else
    {
      work(0, static_cast<int64_t>(end - begin));
    }
    answer.FacesVisited += static_cast<int64_t>(end - begin);
    for (size_t k = 0; k < results.size(); ++k)
    {
      if (results[k].Distance < best)
      {
        best = results[k].Distance;
        answer.Piece = order[begin + k].Piece;
        std::copy(results[k].Closest, results[k].Closest + 3, answer.Closest);
      }
    }
  }
  answer.Distance = answer.Inside ? -best : best;
  return answer;
}

} // namespace vtkdf
