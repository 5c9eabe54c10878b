// vtkUnionClosestPoint and vtkPenetrationDepth on convex hulls as exporters write them
// (an STL file shares no point: a corner repeats a rounding apart, and zero-area sliver
// triangles join its copies), on the backend of the argument (cpu or gpu):
// - three triangulated hulls (a box, a sphere's polyhedron, a slab), each with corners
//   repeated 0, 1e-18, 1e-14 and 1e-10 of its diagonal apart (double points) or 0 and
//   3e-7 apart (float points, as STL stores them), the fan around each such corner split
//   between the copies and closed by two slivers: accepted, and every query's distance,
//   closest point and piece equal to those of the clean hulls within 1e-9 of the
//   diagonal (1e-6 for float points); the penetration depth and direction of the
//   repeated-corner hulls against a box equal to the clean hulls';
// - a corner repeated 1e-3 of the diagonal apart (a real notch, beyond the tolerance):
//   still refused, naming the piece.
#include "TestSupport.h"
#include "vtkPenetrationDepth.h"
#include "vtkUnionClosestPoint.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace
{
std::string Backend = "cpu";

/// A closed triangulated convex piece with its own points (the sources make double ones).
vtkSmartPointer<vtkPolyData> Triangulated(vtkAlgorithm* source)
{
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(clean->GetOutputPort());
  triangles->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(triangles->GetOutput()->GetPoints());
  mesh->SetPolys(triangles->GetOutput()->GetPolys());
  return mesh;
}

std::vector<vtkSmartPointer<vtkPolyData>> CleanPieces()
{
  vtkNew<vtkCubeSource> box;
  box->SetBounds(0, 1, 0, 1, 0, 1);
  box->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(1.6, 0.5, 0.5);
  ball->SetRadius(0.7);
  ball->SetThetaResolution(12);
  ball->SetPhiResolution(8);
  ball->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkNew<vtkCubeSource> slab;
  slab->SetBounds(0.2, 2.0, 0.3, 0.7, 0.9, 1.3);
  slab->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  return { Triangulated(box), Triangulated(ball), Triangulated(slab) };
}

/// `piece` with corners `corners` repeated as an exporter repeats them: a copy `apart`
/// times the piece's diagonal away, used by half of the fan of triangles around the
/// corner, and two sliver triangles (corner, neighbour, copy) that close the seams.
vtkSmartPointer<vtkPolyData> Exported(vtkPolyData* piece,
  std::initializer_list<vtkIdType> corners,
  double apart,
  bool single)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(piece);
  const double diagonal = piece->GetLength();
  std::vector<std::array<vtkIdType, 3>> triangles;
  vtkIdType count;
  const vtkIdType* ids;
  for (mesh->GetPolys()->InitTraversal(); mesh->GetPolys()->GetNextCell(count, ids);)
  {
    triangles.push_back({ ids[0], ids[1], ids[2] });
  }
  for (const vtkIdType v : corners)
  {
    double x[3];
    mesh->GetPoint(v, x);
    const vtkIdType copy = mesh->GetPoints()->InsertNextPoint(
      x[0] + apart * diagonal, x[1] - 0.5 * apart * diagonal, x[2] + 0.25 * apart * diagonal);
    // The fan around v, in order: (v, a, b) is followed by the triangle (v, b, c).
    std::map<vtkIdType, size_t> byFirst; // a -> the triangle (v, a, b)
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (triangles[t][k] == v)
        {
          std::array<vtkIdType, 3>& tri = triangles[t];
          std::rotate(tri.begin(), tri.begin() + k, tri.end());
          byFirst[tri[1]] = t;
        }
      }
    }
    std::vector<size_t> fan{ byFirst.begin()->second };
    while (fan.size() < byFirst.size())
    {
      fan.push_back(byFirst.at(triangles[fan.back()][2]));
    }
    const size_t half = fan.size() / 2;
    const vtkIdType seam1 = triangles[fan[0]][2];    // between fan[0] (v) and fan[1] (copy)
    const vtkIdType seam2 = triangles[fan[half]][2]; // between fan[half] (copy) and the next (v)
    for (size_t k = 1; k <= half; ++k)
    {
      triangles[fan[k]][0] = copy;
    }
    triangles.push_back({ v, seam1, copy });
    triangles.push_back({ copy, seam2, v });
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& t : triangles)
  {
    polys->InsertNextCell(3, t.data());
  }
  mesh->SetPolys(polys);
  if (single)
  {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->DeepCopy(mesh->GetPoints());
    mesh->SetPoints(points);
  }
  return mesh;
}

vtkSmartPointer<vtkPolyData> Append(const std::vector<vtkSmartPointer<vtkPolyData>>& pieces)
{
  vtkNew<vtkAppendPolyData> append;
  for (const auto& piece : pieces)
  {
    append->AddInputData(piece);
  }
  append->Update();
  return append->GetOutput();
}

vtkSmartPointer<vtkPolyData> Queries()
{
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> x(-0.5, 2.7), yz(-0.6, 1.8);
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 200; ++i)
  {
    points->InsertNextPoint(x(random), yz(random), yz(random));
  }
  auto queries = vtkSmartPointer<vtkPolyData>::New();
  queries->SetPoints(points);
  return queries;
}

vtkSmartPointer<vtkPolyData> Union(vtkPolyData* pieces, vtkPolyData* queries, std::string& errors)
{
  vtkNew<vtkUnionClosestPoint> f;
  vtkdf::testing::MessageRecorder recorder(f);
  f->SetInputData(0, pieces);
  f->SetQueryData(queries);
  vtkdf::testing::UseBackend(f.Get(), Backend);
  f->Update();
  errors = recorder.Errors;
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(f->GetOutput());
  return out;
}

/// The largest difference of Distance, ClosestPoint and ClosestPiece between two outputs
/// (infinite when their shapes differ).
double Difference(vtkPolyData* a, vtkPolyData* b)
{
  double worst = 0;
  for (const char* name : { "Distance", "ClosestPoint", "ClosestPiece" })
  {
    vtkDataArray* x = a->GetPointData()->GetArray(name);
    vtkDataArray* y = b->GetPointData()->GetArray(name);
    if (!x || !y || x->GetNumberOfTuples() != y->GetNumberOfTuples() || x->GetNumberOfTuples() == 0)
    {
      return HUGE_VAL;
    }
    for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < x->GetNumberOfComponents(); ++c)
      {
        worst = std::max(worst, std::fabs(x->GetComponent(i, c) - y->GetComponent(i, c)));
      }
    }
  }
  return worst;
}

struct Depth
{
  bool Ok = false;
  double Value = 0, Direction[3] = { 0, 0, 0 };
  std::string Errors;
};

Depth Penetration(vtkPolyData* p, vtkPolyData* q)
{
  vtkNew<vtkPenetrationDepth> f;
  vtkdf::testing::MessageRecorder recorder(f);
  f->SetSolidPData(p);
  f->SetSolidQData(q);
  vtkdf::testing::UseBackend(f.Get(), Backend);
  f->Update();
  Depth d;
  d.Ok = f->GetErrorCode() == 0 && f->GetOutput()->GetNumberOfPoints() == 2;
  d.Value = f->GetLastPenetrationDepth();
  std::copy(f->GetLastDirection(), f->GetLastDirection() + 3, d.Direction);
  d.Errors = recorder.Errors;
  return d;
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 1, "cpu|gpu"))
  {
    return 2;
  }
  Backend = argv[1];
  const std::vector<vtkSmartPointer<vtkPolyData>> clean = CleanPieces();
  const vtkSmartPointer<vtkPolyData> queries = Queries();
  vtkNew<vtkCubeSource> boxSource;
  boxSource->SetBounds(0.8, 1.9, 0.2, 0.8, 0.1, 0.9);
  boxSource->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  const vtkSmartPointer<vtkPolyData> box = Triangulated(boxSource);

  for (const bool single : { false, true })
  {
    std::vector<vtkSmartPointer<vtkPolyData>> reference;
    for (const auto& piece : clean)
    {
      reference.push_back(Exported(piece, {}, 0, single)); // the same points, stored alike
    }
    std::string errors;
    const auto expected = Union(Append(reference), queries, errors);
    CHECK(
      errors.empty(), "clean hulls (%s points): %s", single ? "float" : "double", errors.c_str());
    const Depth expectedDepth = Penetration(Append(reference), box);
    CHECK(expectedDepth.Ok && expectedDepth.Value > 0.1,
      "clean hulls' penetration depth: %s",
      expectedDepth.Errors.c_str());
    const double tolerance = (single ? 1e-6 : 1e-9) * Append(reference)->GetLength();
    const std::vector<double> aparts =
      single ? std::vector<double>{ 0, 3e-7 } : std::vector<double>{ 0, 1e-18, 1e-14, 1e-10 };
    for (const double apart : aparts)
    {
      std::vector<vtkSmartPointer<vtkPolyData>> exported;
      for (const auto& piece : clean)
      {
        exported.push_back(
          Exported(piece, { 0, 3, piece->GetNumberOfPoints() - 1 }, apart, single));
      }
      const auto mesh = Append(exported);
      const auto actual = Union(mesh, queries, errors);
      const double difference = Difference(expected, actual);
      std::printf("%s points, corners repeated %g of the diagonal apart: union answers differ "
                  "by %.3g, ",
        single ? "float" : "double",
        apart,
        difference);
      CHECK(errors.empty() && difference <= tolerance,
        "union of hulls with corners repeated %g apart: %s (difference %g)",
        apart,
        errors.c_str(),
        difference);
      const Depth depth = Penetration(mesh, box);
      const double depthDifference = std::fabs(depth.Value - expectedDepth.Value) +
        std::fabs(depth.Direction[0] - expectedDepth.Direction[0]) +
        std::fabs(depth.Direction[1] - expectedDepth.Direction[1]) +
        std::fabs(depth.Direction[2] - expectedDepth.Direction[2]);
      std::printf("penetration depth %.9f (clean %.9f)\n", depth.Value, expectedDepth.Value);
      CHECK(depth.Ok && depthDifference <= tolerance,
        "penetration depth of hulls with corners repeated %g apart: %s (difference %g)",
        apart,
        depth.Errors.c_str(),
        depthDifference);
    }
  }

  // A copy 1e-3 of the diagonal away is a notch in the surface, not a rounding: refused.
  {
    std::vector<vtkSmartPointer<vtkPolyData>> exported{
      clean[0], Exported(clean[1], { 0 }, 1e-3, false), clean[2]
    };
    std::string errors;
    const auto out = Union(Append(exported), queries, errors);
    CHECK(out->GetNumberOfPoints() == 0 &&
        errors.find("Piece 1 is not a closed convex polytope") != std::string::npos,
      "a corner repeated 1e-3 of the diagonal apart is accepted: %s",
      errors.c_str());
  }
  return vtkdf::testing::Verdict();
}
