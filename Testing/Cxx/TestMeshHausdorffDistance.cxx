// vtkMeshHausdorffDistance: certified intervals on cases whose answer is known, against
// dense sampling and brute force on real meshes, the same answer on any thread count, and
// bad input.
// - known: a square against a roof over it (A to B: h / sqrt(1 + 4 h^2), along the
//   ridge's line inside A's faces, where A's vertices are at distance 0; B to A: h) and
//   against a frame above it (A to B at A's centre, below the frame's hole), a
//   triangle against a copy above it with a hole off its centroid (A to B below the
//   hole's centre), an
//   equilateral triangle against the same triangle cut into three about its centroid,
//   raised by h (A to B: r h / sqrt(r^2 + h^2) at A's centroid, r the inradius; B to A:
//   h), a sphere mesh against itself scaled by 1.1 (B to A: 0.1 R at B's vertices; the
//   Hausdorff distance the same). Each interval holds the answer and is no wider than
//   RelativeError times the diagonal, for RelativeError 1e-6 and 1e-3.
// - brute: real meshes (closed, open, a soup, degenerate triangles, lines and vertex
//   cells) against moved copies: every point's Distance equal to the least distance over
//   the other mesh's primitives (1e-12 relative); each one-sided interval above the
//   largest distance at a dense sampling of the faces (the filter's own point queries,
//   tested exact elsewhere), its lower end within the accuracy of that, its width within
//   it; HausdorffPoints at the distance reported.
// - threads: one thread and the default give the same field data, bit for bit.
// - errors: no second input, a mesh without cells, RelativeError 0, NaN or above 1, an
//   accuracy below double precision at the meshes' coordinates, a NaN point; and
//   coordinates of 1e200 (their squares overflow), which are no error: the interval as
//   asked.
// Usage: TestMeshHausdorffDistance DATA_DIR known|brute|threads|errors
#include "MeshPrimitives.h"
#include "TestSupport.h"
#include "UnitBoxMesh.h"
#include "vtkMeshDistanceFilter.h"
#include "vtkMeshHausdorffDistance.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using vtkdf::testing::Collect;
using vtkdf::testing::Failures;
using vtkdf::testing::Primitives;
using vtkdf::testing::SquaredDistance;

namespace
{
void Check(bool ok, const std::string& what)
{
  if (!ok && Failures++ < 20)
  {
    std::printf("FAIL: %s\n", what.c_str());
  }
}

/// A mesh of double points and triangles, line and vertex cells.
vtkSmartPointer<vtkPolyData> MakeMesh(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::vector<vtkIdType>>& polys,
  const std::vector<std::vector<vtkIdType>>& lines = {},
  const std::vector<vtkIdType>& verts = {})
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (const auto& x : points)
  {
    pts->InsertNextPoint(x.data());
  }
  mesh->SetPoints(pts);
  vtkNew<vtkCellArray> p, l, v;
  for (const auto& cell : polys)
  {
    p->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
  }
  for (const auto& cell : lines)
  {
    l->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
  }
  for (const vtkIdType id : verts)
  {
    v->InsertNextCell(1, &id);
  }
  mesh->SetPolys(p);
  mesh->SetLines(l);
  mesh->SetVerts(v);
  return mesh;
}

/// The filter's answer as the test reads it from the field data.
struct Answer
{
  bool Ok = false;
  double Distance = 0, Lower = 0, Upper = 0;
  double OneSided[2] = { 0, 0 };
  double Bounds[2][2] = { { 0, 0 }, { 0, 0 } };
  double From[3] = { 0, 0, 0 }, To[3] = { 0, 0, 0 };
  int Source = -1;
  vtkSmartPointer<vtkPolyData> OutA, OutB;
};

Answer Run(vtkPolyData* a, vtkPolyData* b, double relativeError)
{
  vtkNew<vtkMeshHausdorffDistance> filter;
  filter->SetInputData(a);
  filter->SetMeshBData(b);
  filter->SetRelativeError(relativeError);
  filter->Update();
  Answer answer;
  answer.OutA = filter->GetOutput(0);
  answer.OutB = filter->GetOutput(1);
  vtkFieldData* fd = answer.OutA->GetFieldData();
  vtkDataArray* bounds = fd->GetArray("HausdorffBounds");
  vtkDataArray* oneSided = fd->GetArray("OneSidedHausdorffDistance");
  vtkDataArray* oneBounds = fd->GetArray("OneSidedHausdorffBounds");
  vtkDataArray* points = fd->GetArray("HausdorffPoints");
  vtkDataArray* source = fd->GetArray("HausdorffSource");
  vtkDataArray* distance = fd->GetArray("HausdorffDistance");
  if (filter->GetErrorCode() || !bounds || !oneSided || !oneBounds || !points || !source ||
    !distance)
  {
    return answer;
  }
  answer.Ok = true;
  answer.Distance = distance->GetTuple1(0);
  answer.Lower = bounds->GetComponent(0, 0);
  answer.Upper = bounds->GetComponent(0, 1);
  for (int side = 0; side < 2; ++side)
  {
    answer.OneSided[side] = oneSided->GetComponent(0, side);
    answer.Bounds[side][0] = oneBounds->GetComponent(side, 0);
    answer.Bounds[side][1] = oneBounds->GetComponent(side, 1);
  }
  points->GetTuple(0, answer.From);
  points->GetTuple(1, answer.To);
  answer.Source = static_cast<int>(source->GetTuple1(0));
  Check(filter->GetHausdorffDistance() == answer.Distance &&
      filter->GetHausdorffBounds()[0] == answer.Lower &&
      filter->GetHausdorffBounds()[1] == answer.Upper,
    "the getters repeat the field data");
  return answer;
}

double Diagonal(vtkPolyData* a, vtkPolyData* b)
{
  double ba[6], bb[6];
  a->GetBounds(ba);
  b->GetBounds(bb);
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = std::max(ba[2 * k + 1], bb[2 * k + 1]) - std::min(ba[2 * k], bb[2 * k]);
    d2 += e * e;
  }
  return std::sqrt(d2);
}

/// The interval's shape: ordered, the value found inside it, at most `tolerance` wide,
/// the symmetric one the larger of the one-sided ones.
void CheckShape(const std::string& name, const Answer& r, double tolerance)
{
  Check(r.Ok, name + ": the filter ran");
  for (int side = 0; side < 2; ++side)
  {
    const std::string which = name + (side ? " B to A" : " A to B");
    const double lo = r.Bounds[side][0], hi = r.Bounds[side][1];
    Check(lo <= r.OneSided[side] && r.OneSided[side] <= hi,
      which + ": the distance found inside its interval");
    Check(hi - lo <= tolerance,
      which + ": interval " + std::to_string(hi - lo) + " wider than " + std::to_string(tolerance));
  }
  Check(r.Lower == std::max(r.Bounds[0][0], r.Bounds[1][0]) &&
      r.Upper == std::max(r.Bounds[0][1], r.Bounds[1][1]),
    name + ": the symmetric interval the larger one-sided ones");
  Check(r.Distance == std::max(r.OneSided[0], r.OneSided[1]) &&
      r.Source == (r.OneSided[1] > r.OneSided[0] ? 1 : 0),
    name + ": the Hausdorff distance the larger one-sided one, from its mesh");
  // hypot: coordinates of 1e200 would overflow a sum of squares.
  const double gap =
    std::hypot(std::hypot(r.From[0] - r.To[0], r.From[1] - r.To[1]), r.From[2] - r.To[2]);
  Check(std::fabs(gap - r.Distance) <= 1e-12 * (1 + r.Distance),
    name + ": HausdorffPoints " + std::to_string(gap) + " apart, not " +
      std::to_string(r.Distance));
}

/// `value` inside [lo, hi], allowing the rounding of the references' own arithmetic.
bool Holds(double lo, double hi, double value)
{
  const double slack = 1e-13 * (1 + std::fabs(value));
  return lo <= value + slack && value - slack <= hi;
}

void CheckKnown(const std::string& name,
  vtkPolyData* a,
  vtkPolyData* b,
  double aToB,
  double bToA,
  double vertexAToB)
{
  for (const double relative : { 1e-6, 1e-3 })
  {
    const std::string label = name + " (relative error " + std::to_string(relative) + ")";
    const double tolerance = relative * Diagonal(a, b);
    const Answer r = Run(a, b, relative);
    CheckShape(label, r, tolerance);
    Check(Holds(r.Bounds[0][0], r.Bounds[0][1], aToB),
      label + ": A to B [" + std::to_string(r.Bounds[0][0]) + ", " +
        std::to_string(r.Bounds[0][1]) + "] misses " + std::to_string(aToB));
    Check(Holds(r.Bounds[1][0], r.Bounds[1][1], bToA),
      label + ": B to A [" + std::to_string(r.Bounds[1][0]) + ", " +
        std::to_string(r.Bounds[1][1]) + "] misses " + std::to_string(bToA));
    Check(Holds(r.Lower, r.Upper, std::max(aToB, bToA)), label + ": the symmetric interval");
    // The vertices alone would have missed the faces' maximum.
    vtkDataArray* distance = r.OutA ? r.OutA->GetPointData()->GetArray("Distance") : nullptr;
    Check(distance && std::fabs(distance->GetRange()[1] - vertexAToB) <= 1e-12,
      label + ": A's vertices at their known distance");
  }
}

void Known()
{
  // A square and a roof over it, ridge at x = 1/2, height h.
  const double h = 0.25;
  auto square =
    MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 }, { 0, 2, 3 } });
  auto roof =
    MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0.5, 0, h }, { 0.5, 1, h } },
      { { 0, 4, 5 }, { 0, 5, 3 }, { 4, 1, 2 }, { 4, 2, 5 } });
  CheckKnown("square and roof", square, roof, h / std::sqrt(1 + 4 * h * h), h, 0);

  // The square and a frame 0.01 above it, around a hole [1/4, 3/4]^2: A's centre is
  // farthest from B, by the hole's half width and the height (faces that cover A's pieces
  // in part must not bound them).
  auto frame = MakeMesh({ { 0, 0, 0.01 },
                          { 1, 0, 0.01 },
                          { 1, 1, 0.01 },
                          { 0, 1, 0.01 },
                          { 0.25, 0.25, 0.01 },
                          { 0.75, 0.25, 0.01 },
                          { 0.75, 0.75, 0.01 },
                          { 0.25, 0.75, 0.01 } },
    { { 0, 1, 5 },
      { 0, 5, 4 },
      { 1, 2, 6 },
      { 1, 6, 5 },
      { 2, 3, 7 },
      { 2, 7, 6 },
      { 3, 0, 4 },
      { 3, 4, 7 } });
  CheckKnown("square and frame", square, frame, std::sqrt(0.25 * 0.25 + 0.01 * 0.01), 0.01, 0.01);

  // A triangle and a copy 0.01 above it with a square hole [0.15, 0.25]^2 off its
  // centroid: A's point below the hole's centre is farthest from B. Faces above most of
  // a piece must not bound the part of it below the hole.
  auto right = MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 } });
  auto holed = MakeMesh({ { 0, 0, 0.01 },
                          { 1, 0, 0.01 },
                          { 0, 1, 0.01 },
                          { 0.15, 0.15, 0.01 },
                          { 0.25, 0.15, 0.01 },
                          { 0.25, 0.25, 0.01 },
                          { 0.15, 0.25, 0.01 } },
    { { 0, 1, 4 }, { 0, 4, 3 }, { 1, 2, 5 }, { 1, 5, 4 }, { 2, 6, 5 }, { 2, 0, 3 }, { 2, 3, 6 } });
  CheckKnown(
    "triangle and holed copy", right, holed, std::sqrt(0.05 * 0.05 + 0.01 * 0.01), 0.01, 0.01);

  // An equilateral triangle and a tent over it, its apex h above the centroid.
  const double s3 = std::sqrt(3.0), r = s3 / 6, t = 0.1;
  auto triangle = MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, s3 / 2, 0 } }, { { 0, 1, 2 } });
  auto tent = MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, s3 / 2, 0 }, { 0.5, r, t } },
    { { 0, 1, 3 }, { 1, 2, 3 }, { 2, 0, 3 } });
  CheckKnown("triangle and tent", triangle, tent, r * t / std::sqrt(r * r + t * t), t, 0);

  // A sphere mesh and the same scaled by 1.1 about its centre: B's vertex 1.1 v is 0.1 |v|
  // from v, A's nearest point (A is convex and its vertices are equally far from the
  // centre); no point of B is farther from A (1.1 p is 0.1 |p| from p).
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(13);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  vtkPolyData* inner = sphere->GetOutput();
  auto outer = vtkSmartPointer<vtkPolyData>::New();
  outer->DeepCopy(inner);
  double farthest = 0;
  for (vtkIdType i = 0; i < outer->GetNumberOfPoints(); ++i)
  {
    double x[3];
    inner->GetPoint(i, x);
    farthest = std::max(farthest, 0.1 * vtkMath::Norm(x));
    outer->GetPoints()->SetPoint(i, 1.1 * x[0], 1.1 * x[1], 1.1 * x[2]);
  }
  for (const double relative : { 1e-6, 1e-3 })
  {
    const std::string label = "spheres (relative error " + std::to_string(relative) + ")";
    const Answer answer = Run(inner, outer, relative);
    CheckShape(label, answer, relative * Diagonal(inner, outer));
    Check(Holds(answer.Bounds[1][0], answer.Bounds[1][1], farthest), label + ": B to A");
    Check(Holds(answer.Lower, answer.Upper, farthest), label + ": the symmetric interval");
    Check(answer.Bounds[0][1] < farthest, label + ": A to B below B to A");
  }
}

/// Points on every primitive: a barycentric grid of `k` steps on each triangle, k + 1
/// points on each segment, each vertex cell's point.
vtkSmartPointer<vtkPolyData> SamplePrimitives(const Primitives& p, int k)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const std::array<double, 9>& t : p.X)
  {
    const bool point =
      t[0] == t[3] && t[1] == t[4] && t[2] == t[5] && t[3] == t[6] && t[4] == t[7] && t[5] == t[8];
    for (int i = 0; i <= k; ++i)
    {
      for (int j = 0; j <= k - i; ++j)
      {
        const double u = double(i) / k, v = double(j) / k;
        points->InsertNextPoint(t[0] + u * (t[3] - t[0]) + v * (t[6] - t[0]),
          t[1] + u * (t[4] - t[1]) + v * (t[7] - t[1]),
          t[2] + u * (t[5] - t[2]) + v * (t[8] - t[2]));
        if (point)
        {
          break;
        }
      }
      if (point)
      {
        break;
      }
    }
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  return cloud;
}

/// The largest distance from the samples of `from`'s primitives to `to`.
double SampledMaximum(vtkPolyData* from, vtkPolyData* to)
{
  vtkNew<vtkMeshDistanceFilter> probe;
  probe->SetInputData(0, SamplePrimitives(Collect(from), 12));
  probe->SetSurfaceData(to);
  probe->ComputeClosestPointOff();
  probe->ComputeClosestCellIdOff();
  probe->ComputeBarycentricOff();
  probe->ComputeGradientOff();
  probe->Update();
  return probe->GetOutput()->GetFieldData()->GetArray("MaximumAbsoluteDistance")->GetTuple1(0);
}

/// Every point's distance to `to`'s primitives, the least over all of them.
void CheckPointDistances(const std::string& name, vtkPolyData* out, vtkPolyData* to)
{
  vtkDataArray* distance = out->GetPointData()->GetArray("Distance");
  Check(distance && distance->GetNumberOfTuples() == out->GetNumberOfPoints(),
    name + ": a Distance per point");
  if (!distance)
  {
    return;
  }
  const Primitives prims = Collect(to);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    double best2 = HUGE_VAL;
    for (const auto& t : prims.X)
    {
      best2 = std::min(best2, SquaredDistance(x, t));
    }
    const double expected = std::sqrt(best2);
    Check(std::fabs(distance->GetTuple1(i) - expected) <= 1e-12 * expected + 1e-15,
      name + ": point " + std::to_string(i) + " at " + std::to_string(distance->GetTuple1(i)) +
        ", brute force " + std::to_string(expected));
  }
}

void CheckAgainstSampling(const std::string& name, vtkPolyData* a, vtkPolyData* b)
{
  for (const double relative : { 1e-6, 1e-3 })
  {
    const std::string label = name + " (relative error " + std::to_string(relative) + ")";
    const double tolerance = relative * Diagonal(a, b);
    const Answer r = Run(a, b, relative);
    CheckShape(label, r, tolerance);
    const double sampled[2] = { SampledMaximum(a, b), SampledMaximum(b, a) };
    for (int side = 0; side < 2; ++side)
    {
      const std::string which = label + (side ? " B to A" : " A to B");
      // The true value is at least the samples' largest and at most Upper.
      Check(sampled[side] <= r.Bounds[side][1] * (1 + 1e-12) + 1e-15,
        which + ": a sample at " + std::to_string(sampled[side]) + " above the upper bound " +
          std::to_string(r.Bounds[side][1]));
      Check(r.Bounds[side][0] >= sampled[side] - tolerance,
        which + ": the lower bound " + std::to_string(r.Bounds[side][0]) +
          " further than the accuracy below a sample at " + std::to_string(sampled[side]));
    }
    if (relative == 1e-6)
    {
      CheckPointDistances(label + " A", r.OutA, b);
      CheckPointDistances(label + " B", r.OutB, a);
    }
  }
}

/// A copy of `mesh` with each point moved by up to `amount` along each axis.
vtkSmartPointer<vtkPolyData> Jittered(vtkPolyData* mesh, double amount, int seed)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(mesh);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(seed);
  for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
  {
    double x[3];
    copy->GetPoint(i, x);
    for (double& c : x)
    {
      c += amount * random->GetNextRangeValue(-1, 1);
    }
    copy->GetPoints()->SetPoint(i, x);
  }
  return copy;
}

void Brute(const std::string& data)
{
  auto bunny = vtkdf::testing::ReadUnitBoxMesh(data + "/bunny_small.vtp");
  CheckAgainstSampling("bunny_small, jittered", bunny, Jittered(bunny, 0.01, 3));
  auto plane = vtkdf::testing::ReadUnitBoxMesh(data + "/plane.vtp");
  auto bent = Jittered(plane, 0, 1);
  for (vtkIdType i = 0; i < bent->GetNumberOfPoints(); ++i)
  {
    double x[3];
    bent->GetPoint(i, x);
    bent->GetPoints()->SetPoint(i, x[0], x[1] + 0.05 * std::sin(7 * x[0]) * x[2], x[2]);
  }
  CheckAgainstSampling("plane (open), bent", plane, bent);
  const double offset[3] = { 0.003, -0.002, 0.001 };
  CheckAgainstSampling("boeing_soup, turned and moved",
    vtkdf::testing::ReadUnitBoxMesh(data + "/boeing_soup.vtp"),
    vtkdf::testing::ReadUnitBoxMesh(data + "/boeing_soup.vtp", 0.02, offset));
  CheckAgainstSampling("scad_zero_area (degenerate triangles), turned",
    vtkdf::testing::ReadUnitBoxMesh(data + "/scad_zero_area.vtp"),
    vtkdf::testing::ReadUnitBoxMesh(data + "/scad_zero_area.vtp", 0.1));
  // Lines and vertex cells with a triangle, against a jittered square.
  auto mixed = MakeMesh({ { 0, 0, 0 },
                          { 1, 0, 0.1 },
                          { 1, 1, 0 },
                          { 0, 1, -0.1 },
                          { 0.2, 0.3, 0.2 },
                          { 0.8, 0.5, -0.2 },
                          { 0.5, 0.5, 0.3 } },
    { { 0, 1, 2 } },
    { { 2, 3, 4, 5 } },
    { 6, 3 });
  auto square = MakeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0.5, 0.5, 0.02 } },
    { { 0, 1, 4 }, { 1, 2, 4 }, { 2, 3, 4 }, { 3, 0, 4 } });
  CheckAgainstSampling("lines, vertices and a triangle", mixed, square);
}

void Threads(const std::string& data)
{
  auto bunny = vtkdf::testing::ReadUnitBoxMesh(data + "/bunny_small.vtp");
  auto jittered = Jittered(bunny, 0.02, 5);
  const Answer many = Run(bunny, jittered, 1e-7);
  vtkSMPTools::Initialize(1);
  const Answer one = Run(bunny, jittered, 1e-7);
  CheckShape("threads", many, 1e-7 * Diagonal(bunny, jittered));
  bool same = many.Ok && one.Ok && many.Distance == one.Distance && many.Lower == one.Lower &&
    many.Upper == one.Upper;
  for (int side = 0; side < 2; ++side)
  {
    same = same && many.Bounds[side][0] == one.Bounds[side][0] &&
      many.Bounds[side][1] == one.Bounds[side][1];
  }
  for (int k = 0; k < 3; ++k)
  {
    same = same && many.From[k] == one.From[k] && many.To[k] == one.To[k];
  }
  Check(same, "one thread and several give the same answer");
}

void Errors()
{
  auto triangle = vtkdf::testing::Triangle();
  auto expectError = [&](const std::string& name,
                       vtkPolyData* a,
                       vtkPolyData* b,
                       double relative,
                       const std::string& words)
  {
    vtkNew<vtkMeshHausdorffDistance> filter;
    vtkdf::testing::MessageRecorder messages(filter);
    filter->SetInputData(a);
    if (b)
    {
      filter->SetMeshBData(b);
    }
    filter->SetRelativeError(relative);
    filter->Update();
    // A missing input stops the pipeline before the filter runs: no error code then.
    Check(!b || filter->GetErrorCode() != 0, name + ": an error code");
    Check(messages.Errors.find(words) != std::string::npos,
      name + ": the error says \"" + words + "\": " + messages.Errors);
    Check(filter->GetOutput(0)->GetNumberOfPoints() == 0 &&
        filter->GetOutput(1)->GetNumberOfPoints() == 0,
      name + ": empty outputs");
  };
  expectError("no mesh B", triangle, nullptr, 1e-6, "port 1");
  vtkNew<vtkPolyData> empty;
  expectError("A without cells", empty, triangle, 1e-6, "Mesh A");
  expectError("B without cells", triangle, empty, 1e-6, "Mesh B");
  expectError("relative error 0", triangle, triangle, 0, "RelativeError");
  expectError("relative error NaN", triangle, triangle, NAN, "RelativeError");
  expectError("relative error 2", triangle, triangle, 2, "RelativeError");
  auto far = vtkdf::testing::Triangle();
  for (vtkIdType i = 0; i < 3; ++i)
  {
    double x[3];
    far->GetPoint(i, x);
    far->GetPoints()->SetPoint(i, x[0] + 1e9, x[1], x[2]);
  }
  expectError("an accuracy below rounding", far, far, 1e-12, "double precision");
  // Coordinates of 1e200 (whose squares overflow) against a small mesh at the origin:
  // the interval still holds the farthest corner's distance and is no wider than asked.
  auto huge = MakeMesh({ { 0, 0, 0 }, { 1e200, 0, 0 }, { 1e200, 1e200, 0 } }, { { 0, 1, 2 } });
  {
    const Answer r = Run(huge, triangle, 1e-6);
    CheckShape("coordinates of 1e200", r, 1e-6 * std::hypot(1e200, 1e200));
    Check(std::fabs(r.Bounds[0][0] - std::hypot(1e200, 1e200)) <= 1e-6 * 1e200,
      "coordinates of 1e200: A to B at the far corner's distance, " +
        std::to_string(r.Bounds[0][0]));
  }
  auto nan = vtkdf::testing::Triangle(NAN);
  expectError("a NaN point", nan, triangle, 1e-6, "Mesh A");
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR known|brute|threads|errors"))
  {
    return 2;
  }
  const std::string data = argv[1], mode = argv[2];
  if (mode == "known")
  {
    Known();
  }
  else if (mode == "brute")
  {
    Brute(data);
  }
  else if (mode == "threads")
  {
    Threads(data);
  }
  else if (mode == "errors")
  {
    Errors();
  }
  else
  {
    std::printf("unknown mode %s\n", mode.c_str());
    return 2;
  }
  return vtkdf::testing::Verdict();
}
