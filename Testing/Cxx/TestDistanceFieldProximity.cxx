// vtkDistanceFieldProximity against brute force on real meshes (bunny_small, cow,
// teapot, each scaled to a unit box) at several poses: overlapping, apart, a gap below
// one sample step, grazing contact, parallel faces, one model inside the other.
// - Colliding equals a test of every pair of triangles (exact predicates; boxes that do
//   not meet cannot touch) plus every vertex inside the other for containment (the
//   winding number as an exact sum of solid angles, or the pseudonormal of the closest
//   feature found over every triangle);
// - SeparationDistance equals the least distance over every pair of triangles
//   (corner-to-triangle and edge-to-edge, the segments' distance found here by its own
//   case analysis), within 1e-6 relative + 1e-12 of the diagonal;
// - MaximumPenetrationAB / BA equal the deepest of every vertex and face sample in the
//   interaction region inside the other (exact winding number), at its distance to every
//   triangle, within 1e-3 step; the contact normal within 1 degree of the direction to the
//   closest point;
// - without the contacts' list (ContactPoints off), the same answers and deepest points;
// - a deforming sequence through one filter equals a fresh filter on every frame, with
//   the topology reused after the first;
// - bad input (an empty model, a NaN coordinate, too many samples) is refused with a
//   message.
// Usage: TestDistanceFieldProximity DATA_DIR winding|pseudonormal
#include "UnitBoxMesh.h"
#include "vtkDistanceFieldProximity.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"

#include "Common/PointTriangleDistance.h"
#include "Proximity/MeshProximity.h"
#include "Segment/TriangleCrossings.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

namespace
{
int Failures = 0;
bool PseudoNormal = false;
bool GPU = false; // the searches on the GPU (Backend GPU), checked against the CPU too

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::printf("FAIL: %s\n", what.c_str());
    ++Failures;
  }
}

vtkSmartPointer<vtkPolyData> Box(double x0, double x1, double y0, double y1, double z0, double z1)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(x0, x1, y0, y1, z0, z1);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(clean->GetOutputPort());
  triangles->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(triangles->GetOutput());
  return mesh;
}

/// `mesh` rotated by `angle` about z, then moved by t.
vtkSmartPointer<vtkPolyData> Posed(vtkPolyData* mesh, double angle, const double t[3])
{
  auto posed = vtkSmartPointer<vtkPolyData>::New();
  posed->DeepCopy(mesh);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const double c = std::cos(angle), s = std::sin(angle);
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double x[3];
    mesh->GetPoint(i, x);
    points->InsertNextPoint(c * x[0] - s * x[1] + t[0], s * x[0] + c * x[1] + t[1], x[2] + t[2]);
  }
  posed->SetPoints(points);
  return posed;
}

struct Triangles
{
  std::vector<std::array<double, 9>> T;
  std::vector<std::array<double, 6>> Boxes;
  std::vector<std::array<double, 3>> Vertices; // the points the triangles use
  double Bounds[6];
  double Volume = 0; // six times the signed volume, summed in triangle order
};

Triangles Gather(vtkPolyData* mesh)
{
  Triangles t;
  std::vector<bool> used(mesh->GetNumberOfPoints(), false);
  const vtkIdType* ids;
  vtkIdType n;
  auto it = vtkSmartPointer<vtkCellArrayIterator>::Take(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    it->GetCurrentCell(n, ids);
    std::array<double, 9> p;
    std::array<double, 6> box{ { HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL } };
    for (int c = 0; c < 3; ++c)
    {
      mesh->GetPoint(ids[c], p.data() + 3 * c);
      used[ids[c]] = true;
      for (int k = 0; k < 3; ++k)
      {
        box[2 * k] = std::min(box[2 * k], p[3 * c + k]);
        box[2 * k + 1] = std::max(box[2 * k + 1], p[3 * c + k]);
      }
    }
    t.T.push_back(p);
    t.Boxes.push_back(box);
    t.Volume += p[0] * (p[4] * p[8] - p[5] * p[7]) - p[1] * (p[3] * p[8] - p[5] * p[6]) +
      p[2] * (p[3] * p[7] - p[4] * p[6]);
  }
  for (int k = 0; k < 3; ++k)
  {
    t.Bounds[2 * k] = HUGE_VAL;
    t.Bounds[2 * k + 1] = -HUGE_VAL;
  }
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    if (used[i])
    {
      std::array<double, 3> x;
      mesh->GetPoint(i, x.data());
      t.Vertices.push_back(x);
      for (int k = 0; k < 3; ++k)
      {
        t.Bounds[2 * k] = std::min(t.Bounds[2 * k], x[k]);
        t.Bounds[2 * k + 1] = std::max(t.Bounds[2 * k + 1], x[k]);
      }
    }
  }
  return t;
}

double BoxGap2(const std::array<double, 6>& a, const std::array<double, 6>& b)
{
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double gap = std::max({ 0.0, b[2 * k] - a[2 * k + 1], a[2 * k] - b[2 * k + 1] });
    d2 += gap * gap;
  }
  return d2 * (1 - 1e-12);
}

/// Squared distance between segments p0p1 and q0q1: the interior critical point of
/// |p(s) - q(t)|^2 when it lies in the unit square, else the least of the four sides of
/// the square (each a point-to-segment distance).
double SegmentDistance2(const double* p0, const double* p1, const double* q0, const double* q1)
{
  double best = std::min({ vtkdf::SquaredDistanceToSegment(p0, q0, q1),
    vtkdf::SquaredDistanceToSegment(p1, q0, q1),
    vtkdf::SquaredDistanceToSegment(q0, p0, p1),
    vtkdf::SquaredDistanceToSegment(q1, p0, p1) });
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = p1[k] - p0[k];
    v[k] = q1[k] - q0[k];
    w[k] = p0[k] - q0[k];
  }
  auto dot = [](const double* x, const double* y)
  { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const double a = dot(u, u), b = dot(u, v), c = dot(v, v), d = dot(u, w), e = dot(v, w);
  const double det = a * c - b * b;
  if (det > 1e-30 * a * c)
  {
    const double s = (b * e - c * d) / det, t = (a * e - b * d) / det;
    if (s > 0 && s < 1 && t > 0 && t < 1)
    {
      double d2 = 0;
      for (int k = 0; k < 3; ++k)
      {
        const double g = w[k] + s * u[k] - t * v[k];
        d2 += g * g;
      }
      best = std::min(best, d2);
    }
  }
  return best;
}

double TriangleDistance2(const double* p, const double* q)
{
  double best = HUGE_VAL;
  for (int c = 0; c < 3; ++c)
  {
    best = std::min(best, vtkdf::SquaredDistanceToTriangle(p + 3 * c, q, q + 3, q + 6));
    best = std::min(best, vtkdf::SquaredDistanceToTriangle(q + 3 * c, p, p + 3, p + 6));
    for (int f = 0; f < 3; ++f)
    {
      best = std::min(
        best, SegmentDistance2(p + 3 * c, p + 3 * ((c + 1) % 3), q + 3 * f, q + 3 * ((f + 1) % 3)));
    }
  }
  return best;
}

/// The winding number at x: the triangles' solid angles (Van Oosterom and Strackee)
/// summed one by one.
double Winding(const Triangles& mesh, const double* x)
{
  double sum = 0;
  for (const auto& t : mesh.T)
  {
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k)
    {
      a[k] = t[k] - x[k];
      b[k] = t[3 + k] - x[k];
      c[k] = t[6 + k] - x[k];
    }
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    const double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
      a[2] * (b[0] * c[1] - b[1] * c[0]);
    const double den = la * lb * lc + (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * lc +
      (b[0] * c[0] + b[1] * c[1] + b[2] * c[2]) * la +
      (c[0] * a[0] + c[1] * a[1] + c[2] * a[2]) * lb;
    sum += 2 * std::atan2(det, den);
  }
  return sum / (4 * M_PI);
}

/// Squared distance from x to the nearest triangle, with its closest point.
double Nearest2(const Triangles& mesh, const double* x, double closest[3])
{
  double best = HUGE_VAL;
  for (const auto& t : mesh.T)
  {
    double on[3];
    const double d2 = vtkdf::SquaredDistanceToTriangle(x, t.data(), t.data() + 3, t.data() + 6, on);
    if (d2 < best)
    {
      best = d2;
      std::copy(on, on + 3, closest);
    }
  }
  return best;
}

std::array<double, 3> UnitNormal(const double* t)
{
  const double u[3] = { t[3] - t[0], t[4] - t[1], t[5] - t[2] };
  const double v[3] = { t[6] - t[0], t[7] - t[1], t[8] - t[2] };
  std::array<double, 3> n{
    { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] }
  };
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& c : n)
  {
    c = length > 0 ? c / length : 0;
  }
  return n;
}

/// Whether x is inside by the angle-weighted pseudonormal (Baerentzen and Aanaes) of its
/// closest feature on the mesh: the feature from the closest point's barycentric
/// coordinates, its normal summed over every triangle with a corner (or two) at the
/// feature's coordinates, turned outward by the sign of the mesh's volume. With
/// `distance2` and `c`, Nearest2's answer as well.
bool PseudoNormalInside(const Triangles& mesh,
  const double* x,
  double* distance2 = nullptr,
  double* closest = nullptr)
{
  double own[3];
  double* c = closest ? closest : own;
  double best = HUGE_VAL;
  size_t nearest = 0;
  for (size_t t = 0; t < mesh.T.size(); ++t)
  {
    double on[3];
    const auto& q = mesh.T[t];
    const double d2 = vtkdf::SquaredDistanceToTriangle(x, q.data(), q.data() + 3, q.data() + 6, on);
    if (d2 < best)
    {
      best = d2;
      nearest = t;
      std::copy(on, on + 3, c);
    }
  }
  if (distance2)
  {
    *distance2 = best;
  }
  if (!(best > 0))
  {
    return false;
  }
  const double* q = mesh.T[nearest].data();
  // Barycentric coordinates of c from the Gram matrix of the two sides.
  double e0[3], e1[3], r[3];
  for (int k = 0; k < 3; ++k)
  {
    e0[k] = q[3 + k] - q[k];
    e1[k] = q[6 + k] - q[k];
    r[k] = c[k] - q[k];
  }
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const double a = dot(e0, e0), b = dot(e0, e1), d = dot(e1, e1);
  const double det = a * d - b * b;
  double lambda[3] = { 1, 0, 0 };
  if (det > 0)
  {
    lambda[1] = (d * dot(r, e0) - b * dot(r, e1)) / det;
    lambda[2] = (a * dot(r, e1) - b * dot(r, e0)) / det;
    lambda[0] = 1 - lambda[1] - lambda[2];
  }
  std::vector<int> on;
  for (int k = 0; k < 3; ++k)
  {
    if (lambda[k] > 1e-9)
    {
      on.push_back(k);
    }
  }
  auto same = [](const double* u, const double* v)
  { return u[0] == v[0] && u[1] == v[1] && u[2] == v[2]; };
  std::array<double, 3> normal{ { 0, 0, 0 } };
  for (const auto& t : mesh.T)
  {
    const double* p = t.data();
    if (on.size() == 1)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (same(p + 3 * k, q + 3 * on[0]))
        {
          const auto n = UnitNormal(p);
          const double* here = p + 3 * k;
          const double* next = p + 3 * ((k + 1) % 3);
          const double* previous = p + 3 * ((k + 2) % 3);
          double u[3], v[3];
          for (int j = 0; j < 3; ++j)
          {
            u[j] = next[j] - here[j];
            v[j] = previous[j] - here[j];
          }
          const double lu = std::sqrt(dot(u, u)), lv = std::sqrt(dot(v, v));
          const double angle =
            lu > 0 && lv > 0 ? std::acos(std::max(-1.0, std::min(1.0, dot(u, v) / (lu * lv)))) : 0;
          for (int j = 0; j < 3; ++j)
          {
            normal[j] += angle * n[j];
          }
        }
      }
    }
    else if (on.size() == 2)
    {
      int corners = 0;
      for (int k = 0; k < 3; ++k)
      {
        corners += same(p + 3 * k, q + 3 * on[0]) || same(p + 3 * k, q + 3 * on[1]);
      }
      if (corners >= 2)
      {
        const auto n = UnitNormal(p);
        for (int j = 0; j < 3; ++j)
        {
          normal[j] += n[j];
        }
      }
    }
  }
  if (on.size() == 3)
  {
    normal = UnitNormal(q);
  }
  const double away[3] = { x[0] - c[0], x[1] - c[1], x[2] - c[2] };
  return (mesh.Volume < 0 ? -1 : 1) * dot(away, normal.data()) < 0;
}

/// Inside by the rule under test.
bool Inside(const Triangles& mesh, const double* x)
{
  return PseudoNormal ? PseudoNormalInside(mesh, x) : std::fabs(Winding(mesh, x)) > 0.5;
}

struct Brute
{
  bool Colliding = false;
  double Separation = HUGE_VAL;
  double DepthAB = 0, DepthBA = 0;
  std::array<double, 3> NormalAB{ { 0, 0, 0 } }, NormalBA{ { 0, 0, 0 } };
  int64_t InsideAB = 0, InsideBA = 0;
};

/// The deepest of `self`'s vertices and face samples in `region` inside `other`.
void Penetration(const Triangles& self,
  const Triangles& other,
  const double region[6],
  double step,
  double& depth,
  std::array<double, 3>& normal,
  int64_t& inside)
{
  std::vector<std::array<double, 3>> samples;
  auto in = [&](const double* x)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (x[k] < region[2 * k] || x[k] > region[2 * k + 1])
      {
        return false;
      }
    }
    return true;
  };
  for (const auto& x : self.Vertices)
  {
    if (in(x.data()))
    {
      samples.push_back(x);
    }
  }
  for (const auto& t : self.T)
  {
    const auto lattice = vtkdf::FaceSamples(t.data(), step);
    // Every point but the three corners (the first, the (n+1)-th and the last).
    const size_t n =
      static_cast<size_t>(std::lround((std::sqrt(8.0 * lattice.size() + 1) - 3) / 2));
    for (size_t k = 0; k < lattice.size(); ++k)
    {
      if (k != 0 && k != n && k != lattice.size() - 1 && in(lattice[k].data()))
      {
        samples.push_back(lattice[k]);
      }
    }
  }
  std::vector<double> depths(samples.size(), -1);
  std::vector<std::array<double, 3>> closest(samples.size());
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(samples.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        // The pseudonormal's test finds the nearest point on its way.
        double d2;
        if (PseudoNormal ? PseudoNormalInside(other, samples[i].data(), &d2, closest[i].data())
                         : Inside(other, samples[i].data()))
        {
          depths[i] =
            std::sqrt(PseudoNormal ? d2 : Nearest2(other, samples[i].data(), closest[i].data()));
        }
      }
    });
  depth = 0;
  inside = 0;
  int64_t deepest = -1;
  for (size_t i = 0; i < samples.size(); ++i)
  {
    if (depths[i] >= 0)
    {
      ++inside;
      if (deepest < 0 || depths[i] > depth)
      {
        depth = depths[i];
        deepest = static_cast<int64_t>(i);
      }
    }
  }
  normal = { { 0, 0, 0 } };
  if (deepest >= 0 && depth > 0)
  {
    for (int k = 0; k < 3; ++k)
    {
      normal[k] = (closest[deepest][k] - samples[deepest][k]) / depth;
    }
  }
}

Brute BruteForce(vtkPolyData* meshA, vtkPolyData* meshB, double step, const double region[6])
{
  const Triangles a = Gather(meshA), b = Gather(meshB);
  Brute r;
  std::atomic<bool> touching(false);
  std::mutex lock;
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(a.T.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      double best = HUGE_VAL;
      for (vtkIdType i = begin; i < end; ++i)
      {
        vtkdf::Point3 p[3];
        for (int c = 0; c < 3; ++c)
        {
          p[c] = { { a.T[i][3 * c], a.T[i][3 * c + 1], a.T[i][3 * c + 2] } };
        }
        for (size_t j = 0; j < b.T.size(); ++j)
        {
          const double gap2 = BoxGap2(a.Boxes[i], b.Boxes[j]);
          if (gap2 == 0)
          {
            vtkdf::Point3 q[3];
            for (int c = 0; c < 3; ++c)
            {
              q[c] = { { b.T[j][3 * c], b.T[j][3 * c + 1], b.T[j][3 * c + 2] } };
            }
            if (vtkdf::ClosedTrianglesIntersect(p, q))
            {
              touching = true;
            }
          }
          if (gap2 <= best)
          {
            best = std::min(best, TriangleDistance2(a.T[i].data(), b.T[j].data()));
          }
        }
      }
      std::lock_guard<std::mutex> guard(lock);
      r.Separation = std::min(r.Separation, best);
    });
  r.Separation = std::sqrt(r.Separation);
  Penetration(a, b, region, step, r.DepthAB, r.NormalAB, r.InsideAB);
  Penetration(b, a, region, step, r.DepthBA, r.NormalBA, r.InsideBA);
  r.Colliding = touching || r.InsideAB > 0 || r.InsideBA > 0;
  return r;
}

double Field(vtkPolyData* output, const char* name, int component = 0)
{
  vtkDataArray* array = output->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, component) : std::nan("");
}

void Configure(vtkDistanceFieldProximity* f, int resolution)
{
  f->SetResolution(resolution);
  if (GPU)
  {
    f->SetBackendToGPU();
  }
  else
  {
    f->SetBackendToCPU();
  }
  if (PseudoNormal)
  {
    f->SetSignModeToPseudoNormal();
  }
}

/// One pose: the filter against brute force; returns the filter's separation.
double Compare(const char* name, vtkPolyData* a, vtkPolyData* b, int resolution, double margin = 0)
{
  vtkNew<vtkDistanceFieldProximity> f;
  Configure(f, resolution);
  f->SetContactMargin(margin);
  f->SetModelAData(a);
  f->SetModelBData(b);
  const auto start = std::chrono::steady_clock::now();
  f->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Check(f->GetErrorCode() == 0, std::string(name) + ": the filter failed");
  if (f->GetErrorCode() != 0)
  {
    return 0;
  }
  Check(std::string(f->GetLastBackend()) == (GPU ? "gpu" : "cpu"), std::string(name) + ": backend");
  vtkPolyData* out = f->GetOutput(0);
  const double step = Field(out, "Step");
  double region[6];
  for (int k = 0; k < 6; ++k)
  {
    region[k] = Field(out, "InteractionRegion", k);
  }
  // The region: the boxes' overlap grown by the margin.
  double ba[6], bb[6];
  a->GetBounds(ba);
  b->GetBounds(bb);
  double expected[6];
  bool empty = false;
  for (int k = 0; k < 3; ++k)
  {
    expected[2 * k] = std::max(ba[2 * k], bb[2 * k]) - margin;
    expected[2 * k + 1] = std::min(ba[2 * k + 1], bb[2 * k + 1]) + margin;
    empty = empty || expected[2 * k] > expected[2 * k + 1];
  }
  for (int k = 0; k < 6; ++k)
  {
    Check(empty ? region[0] > region[1] : region[k] == expected[k], std::string(name) + ": region");
  }
  const Brute r = BruteForce(a, b, step, region);
  double diagonal = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double side = std::max(ba[2 * k + 1], bb[2 * k + 1]) - std::min(ba[2 * k], bb[2 * k]);
    diagonal += side * side;
  }
  diagonal = std::sqrt(diagonal);
  const bool colliding = Field(out, "Colliding") != 0;
  const double separation = Field(out, "SeparationDistance");
  const double ab = Field(out, "MaximumPenetrationAB"), ba2 = Field(out, "MaximumPenetrationBA");
  std::printf("%-28s colliding %d (brute %d)  separation %.12g (brute %.12g)  penetration AB "
              "%.9g (%.9g) BA %.9g (%.9g)  step %.4g  inside %lld/%lld  %.3f s\n",
    name,
    colliding,
    r.Colliding,
    separation,
    r.Colliding ? 0.0 : r.Separation,
    ab,
    r.DepthAB,
    ba2,
    r.DepthBA,
    step,
    static_cast<long long>(r.InsideAB),
    static_cast<long long>(r.InsideBA),
    seconds);
  Check(colliding == r.Colliding, std::string(name) + ": Colliding");
  if (!r.Colliding)
  {
    Check(std::fabs(separation - r.Separation) <= 1e-6 * r.Separation + 1e-12 * diagonal,
      std::string(name) + ": SeparationDistance");
    // The closest pair's line is that long.
    vtkPoints* points = out->GetPoints();
    double p[3], q[3];
    points->GetPoint(0, p);
    points->GetPoint(1, q);
    const double length = std::sqrt(vtkMath::Distance2BetweenPoints(p, q));
    Check(std::fabs(length - separation) <= 1e-9 * diagonal, std::string(name) + ": witness line");
  }
  Check(std::fabs(ab - r.DepthAB) <= 1e-3 * step, std::string(name) + ": MaximumPenetrationAB");
  Check(std::fabs(ba2 - r.DepthBA) <= 1e-3 * step, std::string(name) + ": MaximumPenetrationBA");
  auto normal = [&](const char* array, const std::array<double, 3>& expected, double depth)
  {
    if (depth < 0.01 * step)
    {
      return;
    }
    double dot = 0;
    for (int k = 0; k < 3; ++k)
    {
      dot += Field(out, array, k) * expected[k];
    }
    Check(dot >= std::cos(M_PI / 180), std::string(name) + ": " + array);
  };
  normal("ContactNormalAB", r.NormalAB, r.DepthAB);
  normal("ContactNormalBA", r.NormalBA, r.DepthBA);
  // Without the contacts' list (fewer exact distances), the same answers.
  {
    vtkNew<vtkDistanceFieldProximity> lean;
    Configure(lean, resolution);
    lean->SetContactMargin(margin);
    lean->SetContactPoints(false);
    lean->SetModelAData(a);
    lean->SetModelBData(b);
    lean->Update();
    for (const char* array :
      { "Colliding", "SeparationDistance", "MaximumPenetrationAB", "MaximumPenetrationBA" })
    {
      Check(Field(lean->GetOutput(0), array) == Field(out, array),
        std::string(name) + ": " + array + " without the contacts");
    }
    for (int k = 0; k < 3; ++k)
    {
      Check(Field(lean->GetOutput(0), "DeepestPointAB", k) == Field(out, "DeepestPointAB", k) &&
          Field(lean->GetOutput(0), "DeepestPointBA", k) == Field(out, "DeepestPointBA", k),
        std::string(name) + ": the deepest points without the contacts");
    }
    Check(lean->GetOutput(1)->GetNumberOfPoints() == 0, std::string(name) + ": no contact listed");
    Check(lean->GetLastPointQueries() <= f->GetLastPointQueries(),
      std::string(name) + ": no more exact distances without the contacts");
  }
  // The contacts: every sample inside the other, with its depth; the deepest among them.
  vtkPolyData* contacts = f->GetOutput(1);
  Check(contacts->GetNumberOfPoints() == r.InsideAB + r.InsideBA, std::string(name) + ": contacts");
  if (GPU)
  {
    // The GPU's searches against the CPU's: the same answers to rounding.
    vtkNew<vtkDistanceFieldProximity> cpu;
    Configure(cpu, resolution);
    cpu->SetBackendToCPU();
    cpu->SetContactMargin(margin);
    cpu->SetModelAData(a);
    cpu->SetModelBData(b);
    cpu->Update();
    const double tolerance = 1e-12 * diagonal;
    for (const char* array :
      { "Colliding", "SeparationDistance", "MaximumPenetrationAB", "MaximumPenetrationBA" })
    {
      Check(std::fabs(Field(cpu->GetOutput(0), array) - Field(out, array)) <= tolerance,
        std::string(name) + ": " + array + " as the CPU's");
    }
    Check(cpu->GetOutput(1)->GetNumberOfPoints() == contacts->GetNumberOfPoints(),
      std::string(name) + ": contacts as the CPU's");
    vtkDataArray* gpuDepth = contacts->GetPointData()->GetArray("Depth");
    vtkDataArray* cpuDepth = cpu->GetOutput(1)->GetPointData()->GetArray("Depth");
    double worst = 0;
    for (vtkIdType i = 0; gpuDepth && cpuDepth && i < gpuDepth->GetNumberOfTuples() &&
         i < cpuDepth->GetNumberOfTuples();
         ++i)
    {
      worst =
        std::max(worst, std::fabs(gpuDepth->GetComponent(i, 0) - cpuDepth->GetComponent(i, 0)));
    }
    for (int port : { 2, 3 })
    {
      vtkDataArray* x = f->GetOutput(port)->GetPointData()->GetArray("DistanceToOther");
      vtkDataArray* y = cpu->GetOutput(port)->GetPointData()->GetArray("DistanceToOther");
      for (vtkIdType i = 0; x && y && i < x->GetNumberOfTuples(); ++i)
      {
        const double u = x->GetComponent(i, 0), v = y->GetComponent(i, 0);
        worst = std::isnan(u) && std::isnan(v) ? worst : std::max(worst, std::fabs(u - v));
      }
    }
    std::printf("%-28s GPU against CPU: contact depths and point distances differ by %.3g "
                "(%.3g of the diagonal)\n",
      name,
      worst,
      worst / diagonal);
    Check(worst <= tolerance, std::string(name) + ": depths and distances as the CPU's");
  }
  vtkDataArray* depth = contacts->GetPointData()->GetArray("Depth");
  double deepest = 0;
  for (vtkIdType i = 0; depth && i < depth->GetNumberOfTuples(); ++i)
  {
    deepest = std::max(deepest, depth->GetComponent(i, 0));
  }
  Check(depth && deepest == std::max(ab, ba2), std::string(name) + ": contact depths");
  // DistanceToOther: each vertex's signed distance to the other model, brute force on a few.
  const Triangles tb = Gather(b);
  vtkDataArray* toOther = f->GetOutput(2)->GetPointData()->GetArray("DistanceToOther");
  Check(toOther && toOther->GetNumberOfTuples() == a->GetNumberOfPoints(),
    std::string(name) + ": DistanceToOther");
  for (vtkIdType i = 0; toOther && i < a->GetNumberOfPoints(); i += 97)
  {
    double x[3], c[3];
    a->GetPoint(i, x);
    const double d = std::sqrt(Nearest2(tb, x, c));
    const double expected = Inside(tb, x) ? -d : d;
    Check(toOther->GetComponent(i, 0) == expected, std::string(name) + ": DistanceToOther value");
  }
  return r.Colliding ? 0 : r.Separation;
}

/// B moved so that its closest point to A goes `fraction` of the way to A's.
vtkSmartPointer<vtkPolyData> Closer(vtkPolyData* a, vtkPolyData* b, double fraction)
{
  vtkNew<vtkDistanceFieldProximity> f;
  f->SetModelAData(a);
  f->SetModelBData(b);
  f->Update();
  double p[3], q[3];
  f->GetOutput(0)->GetPoints()->GetPoint(0, p);
  f->GetOutput(0)->GetPoints()->GetPoint(1, q);
  const double t[3] = {
    fraction * (p[0] - q[0]), fraction * (p[1] - q[1]), fraction * (p[2] - q[2])
  };
  return Posed(b, 0, t);
}

class ErrorText : public vtkCommand
{
public:
  static ErrorText* New() { return new ErrorText; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Text = static_cast<const char*>(data);
  }
  std::string Text;
};

void BadInput(vtkPolyData* good)
{
  auto refused = [&](const char* what,
                   vtkPolyData* a,
                   vtkPolyData* b,
                   const char* words,
                   vtkTypeInt64 maximum = 50000000)
  {
    vtkNew<vtkDistanceFieldProximity> f;
    vtkNew<ErrorText> error;
    f->AddObserver(vtkCommand::ErrorEvent, error);
    Configure(f, 64);
    f->SetModelAData(a);
    f->SetModelBData(b);
    f->SetMaximumSamples(maximum);
    f->Update();
    std::printf("%-28s -> %s\n", what, error->Text.c_str());
    Check(f->GetErrorCode() != 0 && error->Text.find(words) != std::string::npos &&
        f->GetOutput(0)->GetNumberOfPoints() == 0 && f->GetOutput(2)->GetNumberOfPoints() == 0,
      std::string("bad input: ") + what);
  };
  vtkNew<vtkPolyData> empty;
  refused("empty A", empty, good, "Model A");
  refused("empty B", good, empty, "Model B");
  auto nan = vtkSmartPointer<vtkPolyData>::New();
  nan->DeepCopy(good);
  nan->GetPoints()->SetPoint(3, std::nan(""), 0, 0);
  refused("NaN in B", good, nan, "Model B");
  refused("too many samples", good, good, "over the limit", 10);
}

void Deforming(vtkPolyData* a, vtkPolyData* b)
{
  vtkNew<vtkDistanceFieldProximity> kept;
  Configure(kept, 32);
  double reusedSeconds = 0, freshSeconds = 0;
  for (int frame = 0; frame < 6; ++frame)
  {
    // A wave along A, B sliding through it.
    auto deformed = vtkSmartPointer<vtkPolyData>::New();
    deformed->DeepCopy(a);
    vtkPoints* points = deformed->GetPoints();
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      double x[3];
      points->GetPoint(i, x);
      x[0] += 0.05 * std::sin(8 * x[1] + frame);
      points->SetPoint(i, x);
    }
    const double t[3] = { 0.75 - 0.12 * frame, 0.1, 0 };
    auto moved = Posed(b, 0.2 * frame, t);
    kept->SetModelAData(deformed);
    kept->SetModelBData(moved);
    kept->Update();
    vtkNew<vtkDistanceFieldProximity> fresh;
    Configure(fresh, 32);
    fresh->SetModelAData(deformed);
    fresh->SetModelBData(moved);
    fresh->Update();
    if (frame > 0)
    {
      reusedSeconds += kept->GetLastSeconds();
      freshSeconds += fresh->GetLastSeconds();
    }
    const std::string name = "frame " + std::to_string(frame);
    Check(kept->GetLastReusedTopology() == (frame == 0 ? 0 : 3), name + ": reused topology");
    Check(fresh->GetLastReusedTopology() == 0, name + ": a fresh filter reuses nothing");
    if (GPU)
    {
      // The topology stays on the GPU: later frames send only coordinates.
      Check(frame == 0 ? kept->GetLastBytesToDevice() == fresh->GetLastBytesToDevice()
                       : kept->GetLastBytesToDevice() < fresh->GetLastBytesToDevice(),
        name + ": bytes sent to the GPU");
      std::printf("%s: %lld bytes to the GPU kept, %lld fresh; %lld back\n",
        name.c_str(),
        static_cast<long long>(kept->GetLastBytesToDevice()),
        static_cast<long long>(fresh->GetLastBytesToDevice()),
        static_cast<long long>(kept->GetLastBytesFromDevice()));
    }
    for (const char* array : { "Colliding",
           "SeparationDistance",
           "MaximumPenetrationAB",
           "MaximumPenetrationBA",
           "PointQueries" })
    {
      Check(Field(kept->GetOutput(0), array) == Field(fresh->GetOutput(0), array),
        name + ": " + array + " as a fresh filter's");
    }
    Check(kept->GetOutput(1)->GetNumberOfPoints() == fresh->GetOutput(1)->GetNumberOfPoints(),
      name + ": contacts as a fresh filter's");
    for (int port : { 2, 3 })
    {
      vtkDataArray* x = kept->GetOutput(port)->GetPointData()->GetArray("DistanceToOther");
      vtkDataArray* y = fresh->GetOutput(port)->GetPointData()->GetArray("DistanceToOther");
      bool same = x && y && x->GetNumberOfTuples() == y->GetNumberOfTuples();
      for (vtkIdType i = 0; same && i < x->GetNumberOfTuples(); ++i)
      {
        const double u = x->GetComponent(i, 0), v = y->GetComponent(i, 0);
        same = u == v || (std::isnan(u) && std::isnan(v));
      }
      Check(same, name + ": DistanceToOther as a fresh filter's");
    }
    std::printf("%s: colliding %d separation %.9g penetration %.6g / %.6g, %.4f s kept, %.4f s "
                "fresh\n",
      name.c_str(),
      kept->GetLastColliding() ? 1 : 0,
      kept->GetLastSeparationDistance(),
      kept->GetLastPenetrationAB(),
      kept->GetLastPenetrationBA(),
      kept->GetLastSeconds(),
      fresh->GetLastSeconds());
  }
  std::printf("deforming: frames 1-5 took %.4f s reusing the topology, %.4f s fresh\n",
    reusedSeconds,
    freshSeconds);
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::printf("usage: %s DATA_DIR winding|pseudonormal [cpu|gpu]\n", argv[0]);
    return 2;
  }
  const std::string data = argv[1];
  PseudoNormal = std::string(argv[2]) == "pseudonormal";
  GPU = argc > 3 && std::string(argv[3]) == "gpu";
  auto bunny = vtkdf::testing::ReadUnitBoxMesh(data + "/bunny_small.vtp");
  auto cow = vtkdf::testing::ReadUnitBoxMesh(data + "/cow.vtp");
  auto teapot = vtkdf::testing::ReadUnitBoxMesh(data + "/teapot.vtp");

  const double overlap[3] = { 0.35, 0.1, 0.05 };
  Compare("bunny / bunny overlapping", bunny, Posed(bunny, 0.7, overlap), 24);
  const double apart[3] = { 1.1, 0.3, -0.1 };
  auto cowApart = Posed(cow, 2.0, apart);
  Compare("bunny / cow apart", bunny, cowApart, 24, 0.05);
  // A gap of a fifth of the step at 24 samples (about 0.004 of the unit box), then
  // grazing: B moved all the way to A's closest point.
  auto near = Closer(bunny, cowApart, 1 - 0.04 / 1.0);
  Compare("bunny / cow gap below a step", bunny, near, 24, 0.05);
  Compare("bunny / cow grazing", bunny, Closer(bunny, near, 1.0), 24, 0.05);
  if (!PseudoNormal)
  {
    // The teapot is open (unwelded patches): the winding number's inside.
    const double into[3] = { 0.3, 0.0, 0.1 };
    Compare("teapot / cow overlapping", teapot, Posed(cow, 0.5, into), 24);
    const double away[3] = { 0.2, 0.9, 0.0 };
    Compare("teapot / bunny apart", teapot, Posed(bunny, 1.0, away), 24);
  }
  // Parallel faces 1e-3 apart, and a box inside another (no pair of triangles meets).
  Compare(
    "boxes, parallel faces", Box(0, 1, 0, 1, 0, 1), Box(1.001, 2, 0.25, 0.75, 0.5, 1.5), 16, 0.01);
  Compare("box inside a box", Box(0, 1, 0, 1, 0, 1), Box(0.2, 0.6, 0.3, 0.5, 0.4, 0.7), 16);
  const double deep[3] = { 0.05, 0.02, 0.0 };
  Compare("cow / cow deep", cow, Posed(cow, 0.3, deep), 20);

  Deforming(bunny, cow);
  BadInput(bunny);
  std::printf("%d failures\n", Failures);
  return Failures == 0 ? 0 : 1;
}
