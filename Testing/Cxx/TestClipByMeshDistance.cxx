// vtkClipByMeshDistance: an image and the same grid as a vtkUnstructuredGrid clipped by
// bunny_small (closed) and aneurysm (open, winding sign).
// - the output equals vtkTableBasedClipDataSet's with vtkMeshDistanceFunction as its clip
//   function (the same points, in the same order, and the same number of cells);
// - every output point's Distance is on the kept side of Value; an input point's is its
//   exact signed distance (the point filter's); a point of the cut (interpolated to
//   Value) lies within a cell's diagonal of the exact cut;
// - the volume kept inside the closed bunny is its volume (vtkMassProperties) within 5%,
//   and the two sides' volumes add up to the grid's;
// - a new Value reuses the surface's hierarchy, a changed surface rebuilds it;
// - bad input: no surface, a surface without cells, a bad SignMode, a NaN Value, a NaN
//   point (named); an empty dataset gives an empty output.
// Usage: TestClipByMeshDistance DATA_DIR exact|errors
#include "TestSupport.h"
#include "vtkClipByMeshDistance.h"
#include "vtkMeshDistanceFilter.h"
#include "vtkMeshDistanceFunction.h"

#include "vtkAppendFilter.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkMassProperties.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTableBasedClipDataSet.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdio>
#include <string>

using vtkdf::testing::Failures;

namespace
{
void Check(bool ok, const std::string& what)
{
  if (!ok && Failures++ < 20)
  {
    std::printf("FAIL: %s\n", what.c_str());
  }
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

/// An n^3 image around the mesh's box, padded by a tenth of its size.
vtkSmartPointer<vtkImageData> GridAround(vtkPolyData* mesh, int n)
{
  double b[6];
  mesh->GetBounds(b);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  const double h = 1.2 * size / (n - 1);
  image->SetSpacing(h, h, h);
  image->SetOrigin(
    (b[0] + b[1] - 1.2 * size) / 2, (b[2] + b[3] - 1.2 * size) / 2, (b[4] + b[5] - 1.2 * size) / 2);
  return image;
}

/// The sum of the cells' volumes (each cell's tetrahedra, from its triangulation).
double Volume(vtkDataSet* data)
{
  double volume = 0;
  vtkNew<vtkIdList> ids;
  vtkNew<vtkPoints> points;
  for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c)
  {
    data->GetCell(c)->Triangulate(0, ids, points);
    for (vtkIdType t = 0; t + 3 < points->GetNumberOfPoints() + 1; t += 4)
    {
      double p[4][3];
      for (int k = 0; k < 4; ++k)
      {
        points->GetPoint(t + k, p[k]);
      }
      double u[3], v[3], w[3], n[3];
      for (int a = 0; a < 3; ++a)
      {
        u[a] = p[1][a] - p[0][a], v[a] = p[2][a] - p[0][a], w[a] = p[3][a] - p[0][a];
      }
      vtkMath::Cross(u, v, n);
      volume += std::fabs(vtkMath::Dot(n, w)) / 6;
    }
  }
  return volume;
}

/// The exact signed distances at the points of `data` (the point filter's).
vtkSmartPointer<vtkDataArray> ExactDistances(vtkDataSet* data, vtkPolyData* mesh, int sign)
{
  vtkNew<vtkMeshDistanceFilter> filter;
  filter->SetInputData(0, data);
  filter->SetSurfaceData(mesh);
  filter->SetSignMode(sign);
  filter->Update();
  return filter->GetOutput()->GetPointData()->GetArray("Distance");
}

/// One clip of `input` by `mesh`, checked.
void CheckClip(const std::string& what,
  vtkDataSet* input,
  vtkPolyData* mesh,
  int sign,
  double value,
  bool insideOut,
  double h)
{
  vtkNew<vtkClipByMeshDistance> clip;
  clip->SetInputData(0, input);
  clip->SetSurfaceData(mesh);
  clip->SetSignMode(sign);
  clip->SetValue(value);
  clip->SetInsideOut(insideOut);
  clip->Update();
  vtkUnstructuredGrid* out = clip->GetOutput();
  Check(clip->GetErrorCode() == 0 && out->GetNumberOfCells() > 0, what + ": no output");

  // The same cut through the implicit function.
  vtkNew<vtkMeshDistanceFunction> function;
  function->SetInput(mesh);
  function->SetSignMode(sign);
  vtkNew<vtkTableBasedClipDataSet> reference;
  reference->SetInputData(input);
  reference->SetClipFunction(function);
  reference->SetValue(value);
  reference->SetInsideOut(insideOut);
  reference->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  reference->Update();
  vtkUnstructuredGrid* expected = reference->GetOutput();
  bool samePoints = expected->GetNumberOfPoints() == out->GetNumberOfPoints() &&
    expected->GetNumberOfCells() == out->GetNumberOfCells();
  for (vtkIdType i = 0; samePoints && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    out->GetPoint(i, p);
    expected->GetPoint(i, q);
    samePoints = p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  }
  Check(samePoints, what + ": not the implicit function's cut");

  // Every point on the kept side: by the interpolated distance, and for the input's own
  // points by the exact one; the new points near the surface.
  vtkDataArray* interpolated = out->GetPointData()->GetArray("Distance");
  vtkSmartPointer<vtkDataArray> exact = ExactDistances(out, mesh, sign);
  if (!interpolated || !exact)
  {
    Check(false, what + ": no Distance array");
    return;
  }
  const double side = insideOut ? -1 : 1;
  double worstNew = 0;
  vtkIdType wrongSide = 0, newPoints = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const double d = interpolated->GetTuple1(i), e = exact->GetTuple1(i);
    double x[3], y[3];
    out->GetPoint(i, x);
    const vtkIdType source = input->FindPoint(x);
    if (source >= 0)
    {
      input->GetPoint(source, y);
    }
    const bool inputPoint =
      source >= 0 && std::sqrt(vtkMath::Distance2BetweenPoints(x, y)) <= 1e-9 * h;
    if (side * (d - value) < -1e-9 * h || (inputPoint && std::fabs(d - e) > 1e-9 * h))
    {
      // Every point on the kept side; an input point's value its exact distance (VTK
      // may compute an image's points to within a rounding of ours).
      ++wrongSide;
    }
    else if (!inputPoint && std::fabs(d - value) <= 1e-9 * h)
    {
      // A point of the cut.
      ++newPoints;
      worstNew = std::max(worstNew, std::fabs(e - value));
    }
  }
  Check(wrongSide == 0, what + ": " + std::to_string(wrongSide) + " points on the wrong side");
  Check(worstNew <= std::sqrt(3.0) * h,
    what + ": a new point " + std::to_string(worstNew) + " from the cut");
  std::printf("%s: %lld cells, %lld points (%lld new, within %.3g h of the cut), volume %.6g\n",
    what.c_str(),
    static_cast<long long>(out->GetNumberOfCells()),
    static_cast<long long>(out->GetNumberOfPoints()),
    static_cast<long long>(newPoints),
    worstNew / h,
    Volume(out));
}

void Exact(const std::string& data)
{
  vtkSmartPointer<vtkPolyData> bunny = Read(data + "/bunny_small.vtp");
  vtkSmartPointer<vtkImageData> image = GridAround(bunny, 20);
  vtkNew<vtkAppendFilter> toGrid;
  toGrid->SetInputData(image);
  toGrid->Update();
  vtkUnstructuredGrid* grid = toGrid->GetOutput();
  const double h = image->GetSpacing()[0];
  CheckClip("bunny image inside", image, bunny, 2, 0, true, h);
  CheckClip("bunny grid inside", grid, bunny, 2, 0, true, h);
  CheckClip("bunny image outside", image, bunny, 2, 0, false, h);
  CheckClip("bunny image pseudonormal", image, bunny, 1, 0, true, h);
  CheckClip("bunny image shell", image, bunny, 0, 3 * h, true, h);
  vtkSmartPointer<vtkPolyData> vessel = Read(data + "/aneurysm.vtp");
  vtkSmartPointer<vtkImageData> vesselGrid = GridAround(vessel, 16);
  CheckClip("aneurysm image winding", vesselGrid, vessel, 2, 0, true, vesselGrid->GetSpacing()[0]);

  // Volumes: inside the bunny its own, both sides the grid's.
  auto clipVolume = [&](bool insideOut)
  {
    vtkNew<vtkClipByMeshDistance> clip;
    clip->SetInputData(0, image);
    clip->SetSurfaceData(bunny);
    clip->SetInsideOut(insideOut);
    clip->Update();
    return Volume(clip->GetOutput());
  };
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(bunny);
  mass->Update();
  const double inside = clipVolume(true), outside = clipVolume(false);
  const double box = std::pow(19 * h, 3);
  std::printf("volumes: inside %.6g (the bunny's %.6g), outside %.6g, sum %.9g of %.9g\n",
    inside,
    mass->GetVolume(),
    outside,
    inside + outside,
    box);
  // The linear interpolant's cut of a coarse grid (20^3) falls short of a curved surface.
  Check(std::fabs(inside - mass->GetVolume()) <= 0.05 * mass->GetVolume(),
    "the kept volume is not the bunny's");
  // Up to the triangulation of the cut cells' curved quadrilateral faces, which may take
  // different diagonals on the two sides.
  Check(std::fabs(inside + outside - box) <= 1e-4 * box, "the two sides do not fill the grid");

  // The hierarchy: reused for a new Value, rebuilt for a changed surface.
  vtkNew<vtkClipByMeshDistance> clip;
  clip->SetInputData(0, image);
  clip->SetSurfaceData(bunny);
  clip->Update();
  Check(clip->GetLastBuiltHierarchy(), "the first run did not build the hierarchy");
  clip->SetValue(h);
  clip->Update();
  Check(!clip->GetLastBuiltHierarchy(), "a new Value rebuilt the hierarchy");
  vtkNew<vtkTransform> move;
  move->Translate(h / 3, 0, 0);
  vtkNew<vtkTransformPolyDataFilter> moved;
  moved->SetInputData(bunny);
  moved->SetTransform(move);
  moved->Update();
  clip->SetSurfaceData(moved->GetOutput());
  clip->Update();
  Check(clip->GetLastBuiltHierarchy(), "a new surface did not rebuild the hierarchy");
}

void Errors(const std::string& data)
{
  vtkSmartPointer<vtkPolyData> bunny = Read(data + "/bunny_small.vtp");
  vtkSmartPointer<vtkImageData> image = GridAround(bunny, 8);
  struct Case
  {
    std::string Name, Error;
  };
  auto run = [&](const std::string& name, const std::string& error, auto setup)
  {
    vtkNew<vtkClipByMeshDistance> clip;
    clip->SetInputData(0, image);
    clip->SetSurfaceData(bunny);
    setup(clip.Get());
    vtkdf::testing::MessageRecorder messages(clip);
    clip->Update();
    Check(messages.Expect(name, clip->GetOutput()->GetNumberOfPoints(), error, "", false), name);
  };
  run("no surface", "port 1", [](vtkClipByMeshDistance* c) { c->RemoveAllInputConnections(1); });
  vtkNew<vtkPolyData> noCells;
  noCells->SetPoints(bunny->GetPoints());
  run("no surface cells", "surface", [&](vtkClipByMeshDistance* c) { c->SetSurfaceData(noCells); });
  run("sign mode", "SignMode must be", [](vtkClipByMeshDistance* c) { c->SetSignMode(7); });
  run("value", "Value must be finite", [](vtkClipByMeshDistance* c) { c->SetValue(NAN); });
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(NAN, 0, 0);
  cloud->SetPoints(points);
  run("nan point", "point 1", [&](vtkClipByMeshDistance* c) { c->SetInputData(0, cloud); });
  // No points: an empty output, no error.
  vtkNew<vtkImageData> nothing;
  vtkNew<vtkClipByMeshDistance> clip;
  clip->SetInputData(0, nothing);
  clip->SetSurfaceData(bunny);
  clip->Update();
  Check(clip->GetErrorCode() == 0 && clip->GetOutput()->GetNumberOfCells() == 0,
    "an empty dataset: not an empty output");
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR exact|errors"))
  {
    return 2;
  }
  const std::string data = argv[1], mode = argv[2];
  if (mode == "exact")
  {
    Exact(data);
  }
  else if (mode == "errors")
  {
    Errors(data);
  }
  else
  {
    std::printf("unknown mode %s\n", mode.c_str());
    return 2;
  }
  return vtkdf::testing::Verdict();
}
