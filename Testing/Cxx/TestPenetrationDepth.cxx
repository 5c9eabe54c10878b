// vtkPenetrationDepth (CPU, exact):
// - two unit cubes (vtkCubeSource: float points, so within 1e-7), Q shifted by 0.7 along x: depth
// 0.3, Direction +x (translating Q
//   separates), the field data and the line; Q at 1.5: apart, depth 0, separation 0.5;
//   Q moved by the answer touches P (depth and separation both 0);
// - the bundled hubo_ankle_convex4 (4 overlapping convex pieces, float points) against a
//   box through it: the same answer from one mesh and from a vtkMultiBlockDataSet of its
//   pieces, never below the deepest pair's depth (each pair run alone), and Q moved by it
//   touches P;
// - with the argument gpu, the same on the GPU, and the CPU backend's answer bit for bit;
// - bad input: a non-convex piece (and UseConvexHulls taking its hull), an open piece, no
//   polygons, a NaN point: errors that name the solid and the problem, no output.
#include "TestSupport.h"
#include "vtkPenetrationDepth.h"

#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>

namespace
{
/// A box whose faces share their corners (vtkCubeSource repeats them per face).
vtkSmartPointer<vtkPolyData> Box(double x0, double x1, double y0, double y1, double z0, double z1)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(x0, x1, y0, y1, z0, z1);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(cube->GetOutputPort());
  clean->Update();
  return clean->GetOutput();
}

vtkSmartPointer<vtkPolyData> Moved(vtkPolyData* mesh, const double t[3])
{
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(mesh);
  for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
  {
    double x[3];
    moved->GetPoint(i, x);
    moved->GetPoints()->SetPoint(i, x[0] + t[0], x[1] + t[1], x[2] + t[2]);
  }
  return moved;
}

struct Result
{
  bool Ok = false;
  double Depth = 0, Separation = 0, Direction[3] = { 0, 0, 0 };
  bool Intersecting = false;
  std::string Errors, Warnings;
  vtkSmartPointer<vtkPolyData> Output;
};

/// The backend of this run (the test's second argument: cpu or gpu).
int Backend = vtkPenetrationDepth::BACKEND_CPU;

Result Run(vtkDataObject* p,
  vtkDataObject* q,
  const std::function<void(vtkPenetrationDepth*)>& configure = {})
{
  vtkNew<vtkPenetrationDepth> f;
  vtkdf::testing::MessageRecorder recorder(f);
  f->SetSolidPData(p);
  f->SetSolidQData(q);
  f->SetBackend(Backend);
  if (configure)
  {
    configure(f);
  }
  f->Update();
  Result r;
  r.Ok = f->GetErrorCode() == 0 && f->GetOutput()->GetNumberOfPoints() == 2;
  r.Depth = f->GetLastPenetrationDepth();
  r.Separation = f->GetLastSeparationDistance();
  std::copy(f->GetLastDirection(), f->GetLastDirection() + 3, r.Direction);
  r.Intersecting = f->GetLastIntersecting();
  r.Errors = recorder.Errors;
  r.Warnings = recorder.Warnings;
  r.Output = vtkSmartPointer<vtkPolyData>::New();
  r.Output->ShallowCopy(f->GetOutput());
  return r;
}

double FieldValue(vtkPolyData* out, const char* name, int component = 0)
{
  vtkDataArray* array = out->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, component) : std::numeric_limits<double>::quiet_NaN();
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR cpu|gpu"))
  {
    return 2;
  }
  Backend = std::string(argv[2]) == "gpu" ? vtkPenetrationDepth::BACKEND_GPU
                                          : vtkPenetrationDepth::BACKEND_CPU;
  // Two cubes overlapping by 0.3.
  auto p = Box(0, 1, 0, 1, 0, 1);
  {
    auto q = Box(0.7, 1.7, 0.2, 0.9, 0.1, 0.8);
    Result r = Run(p, q);
    CHECK(r.Ok && r.Intersecting && std::fabs(r.Depth - 0.3) < 1e-7 &&
        std::fabs(r.Direction[0] - 1) < 1e-12 && r.Separation == 0,
      "cubes: depth %.17g direction %g %g %g (expected 0.3 along +x)",
      r.Depth,
      r.Direction[0],
      r.Direction[1],
      r.Direction[2]);
    CHECK(FieldValue(r.Output, "PenetrationDepth") == r.Depth &&
        FieldValue(r.Output, "Direction", 0) == r.Direction[0] &&
        FieldValue(r.Output, "Intersecting") == 1 &&
        FieldValue(r.Output, "WitnessPieces", 0) == 0 &&
        FieldValue(r.Output, "WitnessPieces", 1) == 0 &&
        !r.Output->GetFieldData()->GetArray("SeparationDistance") &&
        r.Output->GetNumberOfLines() == 1,
      "cubes: the field data and the line");
    double a[3], b[3];
    r.Output->GetPoint(0, a);
    r.Output->GetPoint(1, b);
    CHECK(std::fabs(b[0] - a[0] - 0.3) < 1e-7 && std::fabs(a[0] - 0.7) < 1e-7,
      "cubes: the line runs from Q's trailing corner (x = %g) by the translation (%g)",
      a[0],
      b[0] - a[0]);
    const double t[3] = {
      r.Depth * r.Direction[0], r.Depth * r.Direction[1], r.Depth * r.Direction[2]
    };
    Result touching = Run(p, Moved(q, t));
    CHECK(touching.Ok && touching.Depth < 1e-12 && touching.Separation < 1e-12,
      "cubes: Q moved by the answer touches P (depth %g, separation %g)",
      touching.Depth,
      touching.Separation);
  }
  {
    auto q = Box(1.5, 2.5, 0.2, 0.9, 0.1, 0.8);
    Result r = Run(p, q);
    CHECK(r.Ok && !r.Intersecting && r.Depth == 0 && std::fabs(r.Separation - 0.5) < 1e-12 &&
        std::fabs(r.Direction[0] + 1) < 1e-12 &&
        FieldValue(r.Output, "SeparationDistance") == r.Separation &&
        FieldValue(r.Output, "Intersecting") == 0,
      "apart cubes: separation %.17g direction %g (expected 0.5 along -x)",
      r.Separation,
      r.Direction[0]);
  }

  // hubo_ankle_convex4 against a box through it.
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((std::string(argv[1]) + "/hubo_ankle_convex4.vtp").c_str());
  reader->Update();
  vtkPolyData* hubo = reader->GetOutput();
  double bounds[6];
  hubo->GetBounds(bounds);
  auto box = Box(bounds[0] + 0.3 * (bounds[1] - bounds[0]),
    bounds[0] + 0.6 * (bounds[1] - bounds[0]),
    bounds[2] + 0.2 * (bounds[3] - bounds[2]),
    bounds[2] + 0.5 * (bounds[3] - bounds[2]),
    bounds[4] - 0.1 * (bounds[5] - bounds[4]),
    bounds[4] + 0.4 * (bounds[5] - bounds[4]));
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  Result global = Run(hubo, box);
  CHECK(global.Ok && global.Intersecting, "hubo: %s", global.Errors.c_str());
  vtkNew<vtkMultiBlockDataSet> blocks;
  double pairMax = 0;
  {
    vtkNew<vtkPolyDataConnectivityFilter> regions;
    regions->SetInputData(hubo);
    regions->SetExtractionModeToAllRegions();
    regions->Update();
    const int count = regions->GetNumberOfExtractedRegions();
    CHECK(count == 4, "hubo: 4 pieces (%d)", count);
    for (int k = 0; k < count; ++k)
    {
      vtkNew<vtkPolyDataConnectivityFilter> one;
      one->SetInputData(hubo);
      one->SetExtractionModeToSpecifiedRegions();
      one->AddSpecifiedRegion(k);
      one->Update();
      auto piece = vtkSmartPointer<vtkPolyData>::New();
      piece->DeepCopy(one->GetOutput());
      blocks->SetBlock(k, piece);
      Result pair = Run(piece, box);
      CHECK(pair.Ok, "hubo: piece %d alone: %s", k, pair.Errors.c_str());
      pairMax = std::max(pairMax, pair.Depth);
    }
  }
  Result composite = Run(blocks, box);
  std::printf("hubo against a box: depth %.9g (pieces alone: at most %.9g), from blocks %.9g\n",
    global.Depth,
    pairMax,
    composite.Depth);
  CHECK(composite.Ok && std::fabs(composite.Depth - global.Depth) <= 1e-9 * diagonal,
    "hubo: the same depth from a vtkMultiBlockDataSet (%.17g vs %.17g)",
    composite.Depth,
    global.Depth);
  CHECK(global.Depth >= pairMax - 1e-9 * diagonal,
    "hubo: the global depth (%.17g) is never below a pair's (%.17g)",
    global.Depth,
    pairMax);
  {
    const double t[3] = { global.Depth * global.Direction[0],
      global.Depth * global.Direction[1],
      global.Depth * global.Direction[2] };
    Result touching = Run(hubo, Moved(box, t));
    // The moved box's points are rounded to float: touching within a few float roundings.
    CHECK(
      touching.Ok && touching.Depth <= 1e-6 * diagonal && touching.Separation <= 1e-6 * diagonal,
      "hubo: Q moved by the answer touches P (depth %g, separation %g)",
      touching.Depth,
      touching.Separation);
  }

  if (Backend == vtkPenetrationDepth::BACKEND_GPU)
  {
    // The CPU backend's answer, bit for bit.
    Result r = Run(hubo, box, [](vtkPenetrationDepth* f) { f->SetBackendToCPU(); });
    CHECK(r.Ok && r.Depth == global.Depth && r.Direction[0] == global.Direction[0] &&
        r.Direction[1] == global.Direction[1] && r.Direction[2] == global.Direction[2],
      "GPU = CPU: %.17g (CPU %.17g)",
      global.Depth,
      r.Depth);
  }

  // Bad input.
  {
    // A non-convex piece: a cube with one corner pushed in.
    auto dented = Box(0, 1, 0, 1, 0, 1);
    double x[3];
    dented->GetPoint(0, x);
    for (double& v : x)
    {
      v = v == 0 ? 0.4 : 0.6;
    }
    dented->GetPoints()->SetPoint(0, x);
    Result r = Run(p, dented);
    CHECK(!r.Ok &&
        r.Errors.find("Solid Q (input 1): Piece 0 is not a closed convex polytope") !=
          std::string::npos &&
        r.Output->GetNumberOfPoints() == 0,
      "non-convex piece: %s",
      r.Errors.c_str());
    r = Run(p, dented, [](vtkPenetrationDepth* f) { f->UseConvexHullsOn(); });
    CHECK(r.Ok && r.Warnings.find("1 of 1 pieces of solid Q") != std::string::npos,
      "UseConvexHulls: %s",
      r.Warnings.c_str());
  }
  {
    auto cube = Box(0, 1, 0, 1, 0, 1);
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
    Result r = Run(open, p);
    CHECK(!r.Ok &&
        r.Errors.find("Solid P (input 0): Piece 0 is not a closed convex polytope: "
                      "open") != std::string::npos,
      "open piece: %s",
      r.Errors.c_str());
  }
  {
    vtkNew<vtkPolyData> empty;
    Result r = Run(p, empty);
    CHECK(!r.Ok && r.Errors.find("no polygons") != std::string::npos,
      "no polygons: %s",
      r.Errors.c_str());
  }
  {
    auto nan = Box(0, 1, 0, 1, 0, 1);
    nan->GetPoints()->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0, 0);
    Result r = Run(nan, p);
    CHECK(!r.Ok && r.Errors.find("Solid P") != std::string::npos &&
        r.Errors.find("NaN coordinate") != std::string::npos,
      "NaN point: %s",
      r.Errors.c_str());
  }
  {
    vtkNew<vtkPenetrationDepth> f;
    std::ostringstream os;
    f->Print(os);
    CHECK(os.str().find("LastPenetrationDepth") != std::string::npos, "PrintSelf");
  }
  return vtkdf::testing::Verdict();
}
