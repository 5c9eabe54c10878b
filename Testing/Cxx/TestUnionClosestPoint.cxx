// vtkUnionClosestPoint, on the backend of the argument (cpu or gpu, both exact):
// - two unit cubes side by side as one mesh (two connected components): from
//   (0.9, 0.5, 0.5) the boundary is 0.5 away (inside), not 0.1; from (2.5, 0.5, 0.5), 0.5
//   (outside); the output's first points are the queries, then their closest points, one
//   line each, and the arrays agree (|Distance| = |ClosestPoint - query|, Direction unit);
// - the same pieces as a vtkMultiBlockDataSet: the same answers, ClosestPiece the same;
// - a query far outside (1e6 away): exact;
// - progress and abort at 30 % (an empty output, no error; then a complete run);
// - with the argument gpu: the CPU backend's answers bit for bit; views asked for
//   (GenerateViewImages, deprecated): a warning and an empty output 1;
// - bad input: an open piece, a non-convex piece, a NaN query, no polygons: errors that
//   name the problem, no output.
#include "TestSupport.h"
#include "vtkUnionClosestPoint.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace
{
/// A unit cube whose faces share their corners (vtkCubeSource repeats them per face).
vtkSmartPointer<vtkPolyData> Cube(double x)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(x, x + 1, 0, 1, 0, 1);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(cube->GetOutputPort());
  clean->Update();
  return clean->GetOutput();
}

/// The backend of this run (the test's argument: cpu or gpu).
int Backend = vtkUnionClosestPoint::BACKEND_CPU;

vtkSmartPointer<vtkPolyData> Run(vtkDataObject* pieces,
  vtkPolyData* queries,
  std::string* errors = nullptr,
  const std::function<void(vtkUnionClosestPoint*)>& configure = {},
  std::string* warnings = nullptr)
{
  vtkNew<vtkUnionClosestPoint> f;
  vtkdf::testing::MessageRecorder recorder(f);
  f->SetInputData(0, pieces);
  f->SetQueryData(queries);
  f->SetBackend(Backend);
  if (configure)
  {
    configure(f);
  }
  f->Update();
  if (errors)
  {
    *errors = recorder.Errors;
  }
  if (warnings)
  {
    *warnings = recorder.Warnings;
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(f->GetOutput());
  return out;
}

/// The unit cube with its top face's centre pushed down to z = 0.7 (four triangles): not
/// convex; its convex hull is the unit cube.
vtkSmartPointer<vtkPolyData> DentedCube()
{
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 2; ++k)
  {
    for (int j = 0; j < 2; ++j)
    {
      for (int i = 0; i < 2; ++i)
      {
        points->InsertNextPoint(i, j, k);
      }
    }
  }
  const vtkIdType centre = points->InsertNextPoint(0.5, 0.5, 0.7);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quads[5][4] = {
    { 0, 2, 3, 1 }, { 0, 1, 5, 4 }, { 1, 3, 7, 5 }, { 3, 2, 6, 7 }, { 2, 0, 4, 6 }
  };
  for (const auto& q : quads)
  {
    polys->InsertNextCell(4, q);
  }
  const vtkIdType top[4] = { 4, 5, 7, 6 };
  for (int e = 0; e < 4; ++e)
  {
    const vtkIdType t[3] = { top[e], top[(e + 1) % 4], centre };
    polys->InsertNextCell(3, t);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

vtkSmartPointer<vtkPolyData> Queries(std::initializer_list<std::array<double, 3>> points)
{
  vtkNew<vtkPoints> p;
  for (const auto& x : points)
  {
    p->InsertNextPoint(x.data());
  }
  auto q = vtkSmartPointer<vtkPolyData>::New();
  q->SetPoints(p);
  return q;
}

void CheckAnswers(vtkPolyData* out, const char* name)
{
  const double expected[2] = { -0.5, 0.5 };
  vtkDataArray* d = out->GetPointData()->GetArray("Distance");
  vtkDataArray* c = out->GetPointData()->GetArray("ClosestPoint");
  vtkDataArray* dir = out->GetPointData()->GetArray("Direction");
  vtkDataArray* in = out->GetPointData()->GetArray("Inside");
  CHECK(d && c && dir && in && out->GetNumberOfPoints() == 4 && out->GetNumberOfLines() == 2,
    "%s: the output's shape",
    name);
  if (!d || !c || !dir || !in || out->GetNumberOfPoints() != 4)
  {
    return;
  }
  for (int i = 0; i < 2; ++i)
  {
    double q[3], x[3], closest[3], u[3];
    out->GetPoint(i, q);
    out->GetPoint(i + 2, x);
    c->GetTuple(i, closest);
    dir->GetTuple(i, u);
    const double length = std::sqrt(vtkMath::Distance2BetweenPoints(q, x));
    std::printf("%s: query %d distance %.9f (inside %g), closest %g %g %g\n",
      name,
      i,
      d->GetTuple1(i),
      in->GetTuple1(i),
      x[0],
      x[1],
      x[2]);
    CHECK(std::fabs(d->GetTuple1(i) - expected[i]) < 1e-6, "%s: query %d distance", name, i);
    CHECK(std::fabs(length - std::fabs(d->GetTuple1(i))) < 1e-6 &&
        std::fabs(vtkMath::Norm(u) - 1) < 1e-6 &&
        std::fabs(closest[0] - x[0]) + std::fabs(closest[1] - x[1]) + std::fabs(closest[2] - x[2]) <
          1e-6,
      "%s: query %d's arrays disagree",
      name,
      i);
    CHECK((in->GetTuple1(i) == 1) == (i == 0), "%s: query %d's Inside", name, i);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 1, "cpu|gpu"))
  {
    return 2;
  }
  Backend = std::string(argv[1]) == "gpu" ? vtkUnionClosestPoint::BACKEND_GPU
                                          : vtkUnionClosestPoint::BACKEND_CPU;
  auto queries = Queries({ { 0.9, 0.5, 0.5 }, { 2.5, 0.5, 0.5 } });
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(Cube(0));
  append->AddInputData(Cube(1));
  append->Update();
  CheckAnswers(Run(append->GetOutput(), queries), "one mesh");
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, Cube(0));
  blocks->SetBlock(1, Cube(1));
  CheckAnswers(Run(blocks, queries), "multiblock");
  {
    // A query far outside: the pieces are a speck seen from it, and the answer is still
    // exact (the nearest corner region of the second cube, 1e6 - 2 along x).
    auto far = Run(append->GetOutput(), Queries({ { 1e6, 0.5, 0.5 } }));
    vtkDataArray* d = far->GetPointData()->GetArray("Distance");
    double x[3] = { 0, 0, 0 };
    if (far->GetNumberOfPoints() == 2)
    {
      far->GetPoint(1, x);
    }
    CHECK(d && std::fabs(d->GetTuple1(0) - (1e6 - 2)) < 1e-3 && std::fabs(x[0] - 2) < 1e-9,
      "a query far outside: %.17g (%g %g %g)",
      d ? d->GetTuple1(0) : 0,
      x[0],
      x[1],
      x[2]);
  }
  {
    // Progress and abort: 3000 queries, aborted at 30 %: the run stops within a block
    // (a twentieth of the queries on the CPU; a batch or 64 certified queries on the GPU)
    // with an empty output and no error; asked again, it runs to the end.
    std::vector<std::array<double, 3>> points;
    for (int k = 0; k < 3000; ++k)
    {
      points.push_back(
        { -0.5 + 3.0 * (k % 17) / 16, -0.5 + 2.0 * (k % 13) / 12, -0.5 + 2.0 * (k % 11) / 10 });
    }
    vtkNew<vtkPoints> p;
    for (const auto& x : points)
    {
      p->InsertNextPoint(x.data());
    }
    vtkNew<vtkPolyData> many;
    many->SetPoints(p);
    vtkNew<vtkUnionClosestPoint> f;
    f->SetInputData(0, append->GetOutput());
    f->SetQueryData(many);
    f->SetBackend(Backend);
    struct Progress
    {
      vtkUnionClosestPoint* Filter;
      std::vector<double> Values;
      double AbortedAt = -1;
    } progress{ f, {}, -1 };
    vtkNew<vtkCallbackCommand> observer;
    observer->SetClientData(&progress);
    observer->SetCallback(
      [](vtkObject*, unsigned long, void* client, void* call)
      {
        auto* r = static_cast<Progress*>(client);
        const double value = *static_cast<double*>(call);
        r->Values.push_back(value);
        if (r->AbortedAt < 0 && value >= 0.3)
        {
          r->AbortedAt = value;
          r->Filter->SetAbortExecute(1);
        }
      });
    f->AddObserver(vtkCommand::ProgressEvent, observer);
    vtkdf::testing::MessageRecorder recorder(f);
    f->Update();
    const double last = progress.Values.empty() ? -1 : progress.Values.back();
    std::printf("abort: %zu progress values, aborted at %.3f, last %.3f, %lld output points\n",
      progress.Values.size(),
      progress.AbortedAt,
      last,
      static_cast<long long>(f->GetOutput()->GetNumberOfPoints()));
    CHECK(progress.AbortedAt >= 0.3 && progress.AbortedAt < 0.6 && last < 0.7 &&
        f->GetOutput()->GetNumberOfPoints() == 0 && recorder.Errors.empty() &&
        f->GetErrorCode() == 0,
      "abort at 30 %%: aborted at %g, last progress %g, errors: %s",
      progress.AbortedAt,
      last,
      recorder.Errors.c_str());
    f->RemoveObserver(observer);
    f->SetAbortExecute(0);
    f->Modified();
    f->Update();
    CHECK(f->GetOutput()->GetNumberOfPoints() == 6000, "after the abort, the run completes");
  }
  if (Backend == vtkUnionClosestPoint::BACKEND_GPU)
  {
    // The GPU ran, and gave the CPU backend's answers bit for bit.
    vtkPolyData* answers[2];
    vtkNew<vtkUnionClosestPoint> gpu, cpu;
    for (vtkUnionClosestPoint* f : { gpu.Get(), cpu.Get() })
    {
      f->SetInputData(0, append->GetOutput());
      f->SetQueryData(queries);
      f->SetBackend(f == gpu ? Backend : vtkUnionClosestPoint::BACKEND_CPU);
      f->Update();
      answers[f == gpu ? 0 : 1] = f->GetOutput();
    }
    int differ = 0;
    for (const char* name : { "Distance", "ClosestPoint", "ClosestPiece", "Inside" })
    {
      vtkDataArray* a = answers[0]->GetPointData()->GetArray(name);
      vtkDataArray* b = answers[1]->GetPointData()->GetArray(name);
      for (vtkIdType k = 0; a && b && k < a->GetNumberOfValues(); ++k)
      {
        differ += a->GetComponent(k / a->GetNumberOfComponents(), k % a->GetNumberOfComponents()) !=
          b->GetComponent(k / b->GetNumberOfComponents(), k % b->GetNumberOfComponents());
      }
      differ += !a || !b || a->GetNumberOfValues() != b->GetNumberOfValues();
    }
    CHECK(gpu->GetLastBackend() == vtkUnionClosestPoint::BACKEND_GPU && differ == 0 &&
        answers[0]->GetNumberOfPoints() > 0,
      "GPU = CPU: %d values differ, renderer %s",
      differ,
      gpu->GetLastRenderer());
  }
  {
    // GenerateViewImages (deprecated): no views any more, on either backend: a warning and
    // an empty output 1.
    std::string warnings;
    vtkSmartPointer<vtkUnionClosestPoint> kept;
    Run(
      append->GetOutput(),
      queries,
      nullptr,
      [&kept](vtkUnionClosestPoint* f)
      {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
        f->GenerateViewImagesOn();
#pragma GCC diagnostic pop
        kept = f;
      },
      &warnings);
    auto* views =
      kept ? vtkPartitionedDataSet::SafeDownCast(kept->GetOutputDataObject(1)) : nullptr;
    CHECK(warnings.find("GenerateViewImages") != std::string::npos && views &&
        views->GetNumberOfPartitions() == 0,
      "views: %s",
      warnings.c_str());
  }

  std::string errors;
  {
    // An open cube: one face removed.
    auto cube = Cube(0);
    vtkNew<vtkPolyData> open;
    open->SetPoints(cube->GetPoints());
    vtkNew<vtkCellArray> polys;
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 1; c < cube->GetNumberOfCells(); ++c)
    {
      cube->GetCellPoints(c, ids);
      polys->InsertNextCell(ids);
    }
    open->SetPolys(polys);
    auto out = Run(open, queries, &errors);
    CHECK(errors.find("Piece 0 is not a closed convex polytope") != std::string::npos &&
        out->GetNumberOfPoints() == 0,
      "open piece: %s",
      errors.c_str());
  }
  {
    // A non-convex piece: a cube with one corner pushed in.
    auto cube = Cube(0);
    vtkNew<vtkPolyData> dented;
    dented->DeepCopy(cube);
    double x[3];
    dented->GetPoint(0, x);
    for (double& v : x)
    {
      v = v == 0 ? 0.4 : (v == 1 ? 0.6 : v);
    }
    dented->GetPoints()->SetPoint(0, x);
    Run(dented, queries, &errors);
    CHECK(errors.find("not convex") != std::string::npos, "non-convex piece: %s", errors.c_str());
  }
  {
    // PieceArray: the two cubes merged into one point set (one connected component, whose
    // shared faces make it no closed polytope) are two pieces by a cell-data array.
    vtkNew<vtkCleanPolyData> merged;
    merged->SetInputConnection(append->GetOutputPort());
    merged->Update();
    vtkPolyData* mesh = merged->GetOutput();
    Run(mesh, queries, &errors);
    CHECK(errors.find("not a closed convex polytope") != std::string::npos,
      "merged cubes as one component: %s",
      errors.c_str());
    vtkNew<vtkIntArray> ids;
    ids->SetName("Piece");
    for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
    {
      ids->InsertNextValue(c < 6 ? 0 : 1); // the first cube's six faces, then the second's
    }
    mesh->GetCellData()->AddArray(ids);
    CheckAnswers(
      Run(mesh, queries, &errors, [](vtkUnionClosestPoint* f) { f->SetPieceArray("Piece"); }),
      "PieceArray");
    Run(mesh, queries, &errors, [](vtkUnionClosestPoint* f) { f->SetPieceArray("Nope"); });
    CHECK(errors.find("PieceArray 'Nope'") != std::string::npos,
      "missing PieceArray: %s",
      errors.c_str());
  }
  {
    // UseConvexHulls: a dented cube is refused, or replaced by its hull (the unit cube),
    // with a warning: 1.0 from (0.5, 0.5, 2) (0.3 deeper to the dent), -0.5 from its centre.
    auto dented = DentedCube();
    auto probes = Queries({ { 0.5, 0.5, 2 }, { 0.5, 0.5, 0.5 } });
    Run(dented, probes, &errors);
    CHECK(errors.find("UseConvexHulls") != std::string::npos, "dented cube: %s", errors.c_str());
    std::string warnings;
    auto out = Run(
      dented, probes, &errors, [](vtkUnionClosestPoint* f) { f->UseConvexHullsOn(); }, &warnings);
    vtkDataArray* d = out->GetPointData()->GetArray("Distance");
    std::printf("dented cube's hull: distances %g and %g; %s",
      d ? d->GetTuple1(0) : NAN,
      d ? d->GetTuple1(1) : NAN,
      warnings.c_str());
    CHECK(errors.empty() && d && std::fabs(d->GetTuple1(0) - 1.0) < 1e-9 &&
        std::fabs(d->GetTuple1(1) + 0.5) < 1e-9,
      "the hull's answers are wrong: %s",
      errors.c_str());
    CHECK(warnings.find("replaced by their convex hulls") != std::string::npos,
      "no warning about the hulls");
    // A flat piece has no hull.
    vtkNew<vtkPolyData> square;
    vtkNew<vtkPoints> corners;
    for (const auto& c :
      { std::array<double, 3>{ 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } })
    {
      corners->InsertNextPoint(c.data());
    }
    vtkNew<vtkCellArray> quad;
    const vtkIdType q[4] = { 0, 1, 2, 3 };
    quad->InsertNextCell(4, q);
    square->SetPoints(corners);
    square->SetPolys(quad);
    Run(square, probes, &errors, [](vtkUnionClosestPoint* f) { f->UseConvexHullsOn(); });
    CHECK(errors.find("has no convex hull") != std::string::npos, "flat piece: %s", errors.c_str());
  }
  {
    auto bad = Queries({ { std::numeric_limits<double>::quiet_NaN(), 0, 0 } });
    Run(append->GetOutput(), bad, &errors);
    CHECK(errors.find("not finite") != std::string::npos, "NaN query: %s", errors.c_str());
  }
  {
    vtkNew<vtkPolyData> empty;
    Run(empty, queries, &errors);
    CHECK(errors.find("no polygons") != std::string::npos, "no polygons: %s", errors.c_str());
  }
  return vtkdf::testing::Verdict();
}
