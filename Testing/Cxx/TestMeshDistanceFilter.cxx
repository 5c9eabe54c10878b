// vtkMeshDistanceFilter against brute force, on real meshes (bunny_small closed, plane
// open, boeing_soup a soup, scad_zero_area with degenerate triangles) and on a mesh of
// triangles, a polyline and vertex cells, at random points in the padded box and at
// adversarial ones: the vertices, edge midpoints and face centroids themselves (on the
// surface), offset from them along the normal by 1e-3 and 1e-9 of the size, midpoints of
// two vertices (often equidistant from several triangles), and points far away.
// - Distance within 1e-12 relative (+1e-15 of the size) of the least distance over every
//   primitive; |x - ClosestPoint| equal to it; ClosestCellId a closest cell (within
//   1e-12), the smallest one where the closest feature is a vertex;
// - ClosestBarycentric on that cell's sub-triangle gives ClosestPoint;
// - Gradient a unit vector along sign * (x - ClosestPoint);
// - WindingNumber mode: negative exactly where the exact winding number (a sum of solid
//   angles, computed here) has |w| > 1/2, wherever |w| is not within 1e-9 of 1/2 (and
//   no sliver seen edge-on leaves a solid angle to rounding);
//   PseudoNormal mode on the closed mesh: the same sign;
// - the answers at the samples of an image equal vtkLinearFactorDistanceField's there
//   (mixed_cells: quads, a concave hexagon, a strip, a polyline, vertices; a cube whose
//   faces hold samples), its ClosestSubTriangle, ClosestBarycentric and Gradient too, on
//   the site scan and the sample queries;
// - a mesh and its points scaled by 2^20 and 2^-30 give distances scaled exactly;
// - MaximumDistance: farther points hold the cap, cell -1, NaN closest points;
// - the hierarchy is reused for new points and rebuilt for a changed surface;
// - bad input: a NaN point (named), no surface cells, no second input, a negative cap.
// - vtkMeshDistanceFunction: its values and gradients the filter's, from many threads and
//   in a batch; through vtkClipPolyData, no kept point inside the exact winding number's
//   solid; without a surface, NoValue.
// Usage: TestMeshDistanceFilter DATA_DIR brute|grid|scale|cap|function|errors
#include "MeshPrimitives.h"
#include "TestSupport.h"
#include "UnitBoxMesh.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkMeshDistanceFilter.h"
#include "vtkMeshDistanceFunction.h"

#include "vtkCellArray.h"
#include "vtkClipPolyData.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataReader.h"
#include "vtkSMPTools.h"

#include "Common/PointTriangleDistance.h"
#include "Common/SampleGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
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

/// The triangles once each (the winding number's rule: a triangle repeated with the same
/// orientation, the same corners in the same cyclic order, counts once).
std::vector<std::array<double, 9>> DistinctTriangles(const Primitives& p)
{
  std::set<std::array<double, 9>> seen;
  std::vector<std::array<double, 9>> distinct;
  for (const auto& t : p.X)
  {
    std::array<double, 9> key = t;
    for (int turn = 1; turn < 3; ++turn)
    {
      std::array<double, 9> rotated;
      for (int k = 0; k < 9; ++k)
      {
        rotated[k] = t[(k + 3 * turn) % 9];
      }
      key = std::min(key, rotated);
    }
    if (seen.insert(key).second)
    {
      distinct.push_back(t);
    }
  }
  return distinct;
}

/// The winding number of the triangles at q (Van Oosterom and Strackee's solid angles,
/// summed in long double); `conditioned` false where a triangle's angle is not decided by
/// its double-precision terms (a sliver seen edge-on: both within rounding of 0).
double Winding(const std::vector<std::array<double, 9>>& triangles,
  const double q[3],
  bool& conditioned)
{
  long double sum = 0;
  conditioned = true;
  for (const std::array<double, 9>& t : triangles)
  {
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k)
    {
      a[k] = t[k] - q[k], b[k] = t[3 + k] - q[k], c[k] = t[6 + k] - q[k];
    }
    const double la = vtkMath::Norm(a), lb = vtkMath::Norm(b), lc = vtkMath::Norm(c);
    double bc[3];
    vtkMath::Cross(b, c, bc);
    const double det = vtkMath::Dot(a, bc);
    const double den =
      la * lb * lc + vtkMath::Dot(a, b) * lc + vtkMath::Dot(b, c) * la + vtkMath::Dot(c, a) * lb;
    const double scale = la * lb * lc;
    conditioned = conditioned && (std::fabs(det) > 1e-9 * scale || std::fabs(den) > 1e-9 * scale);
    sum += 2 * std::atan2(det, den);
  }
  return static_cast<double>(sum / (4 * vtkMath::Pi()));
}

/// The query points: random ones in the box padded by half its size, the surface's
/// vertices, edge midpoints and centroids on it and off it along the face normal, two
/// vertices' midpoints, and points far away.
vtkSmartPointer<vtkPolyData> QueryPoints(const Primitives& p, double size, const double centre[3])
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(7);
  for (int i = 0; i < 300; ++i)
  {
    double x[3];
    for (int k = 0; k < 3; ++k)
    {
      x[k] = centre[k] + size * (random->GetNextRangeValue(-1, 1));
    }
    points->InsertNextPoint(x);
  }
  const size_t step = std::max<size_t>(1, p.X.size() / 60);
  for (size_t i = 0; i < p.X.size(); i += step)
  {
    const std::array<double, 9>& t = p.X[i];
    double u[3], v[3], n[3];
    for (int k = 0; k < 3; ++k)
    {
      u[k] = t[3 + k] - t[k], v[k] = t[6 + k] - t[k];
    }
    vtkMath::Cross(u, v, n);
    const double length = vtkMath::Norm(n);
    for (int where = 0; where < 3; ++where)
    {
      double x[3];
      for (int k = 0; k < 3; ++k)
      {
        x[k] = where == 0
          ? t[k]
          : (where == 1 ? 0.5 * (t[k] + t[3 + k]) : (t[k] + t[3 + k] + t[6 + k]) / 3);
      }
      points->InsertNextPoint(x);
      for (const double offset : { 1e-3, -1e-3, 1e-9 })
      {
        if (length > 0)
        {
          points->InsertNextPoint(x[0] + offset * size * n[0] / length,
            x[1] + offset * size * n[1] / length,
            x[2] + offset * size * n[2] / length);
        }
      }
    }
    const std::array<double, 9>& other = p.X[(i * 7 + 3) % p.X.size()];
    points->InsertNextPoint(
      0.5 * (t[0] + other[3]), 0.5 * (t[1] + other[4]), 0.5 * (t[2] + other[5]));
  }
  points->InsertNextPoint(centre[0] + 1e3 * size, centre[1], centre[2]);
  points->InsertNextPoint(centre[0], centre[1] - 1e6 * size, centre[2] + 5 * size);
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  return cloud;
}

vtkDataArray* PointArray(vtkDataSet* data, const char* name)
{
  return data->GetPointData()->GetArray(name);
}

/// Every answer at every point against brute force.
void CheckBruteForce(const std::string& name, vtkPolyData* mesh, int sign, bool closed)
{
  const Primitives prims = Collect(mesh);
  const std::vector<std::array<double, 9>> distinct = DistinctTriangles(prims);
  double b[6];
  mesh->GetBounds(b);
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  vtkSmartPointer<vtkPolyData> cloud = QueryPoints(prims, size, centre);
  vtkNew<vtkMeshDistanceFilter> filter;
  filter->SetInputData(0, cloud);
  filter->SetSurfaceData(mesh);
  filter->SetSignMode(sign);
  filter->ComputeWindingNumberOn();
  filter->ComputeClosestFeatureOn();
  filter->Update();
  vtkDataSet* out = filter->GetOutput();
  vtkDataArray* distance = PointArray(out, "Distance");
  vtkDataArray* closest = PointArray(out, "ClosestPoint");
  vtkDataArray* cells = PointArray(out, "ClosestCellId");
  vtkDataArray* bary = PointArray(out, "ClosestBarycentric");
  vtkDataArray* sub = PointArray(out, "ClosestSubTriangle");
  vtkDataArray* gradient = PointArray(out, "Gradient");
  vtkDataArray* winding = PointArray(out, "WindingNumber");
  vtkDataArray* feature = PointArray(out, "ClosestFeature");
  if (!distance || !closest || !cells || !bary || !sub || !gradient || !winding || !feature)
  {
    Check(false, name + ": an array is missing");
    return;
  }
  const std::string what = name + " sign " + std::to_string(sign);
  int windingChecked = 0;
  double largest = 0;
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    double q[3];
    cloud->GetPoint(i, q);
    const std::string at = what + " point " + std::to_string(i);
    double best2 = HUGE_VAL;
    for (const auto& t : prims.X)
    {
      best2 = std::min(best2, SquaredDistance(q, t));
    }
    const double exact = std::sqrt(best2), d = distance->GetTuple1(i);
    const double tolerance = 1e-12 * exact + 1e-15 * size;
    largest = std::max(largest, std::fabs(std::fabs(d) - exact) / (exact + 1e-15 * size));
    Check(std::fabs(std::fabs(d) - exact) <= tolerance,
      at + ": distance " + std::to_string(d) + " against " + std::to_string(exact));
    double c[3];
    closest->GetTuple(i, c);
    Check(std::fabs(std::sqrt(vtkMath::Distance2BetweenPoints(q, c)) - exact) <= 1e-11 * size,
      at + ": the closest point is not at the distance");
    const vtkIdType cell = static_cast<vtkIdType>(cells->GetTuple1(i));
    // The cell's own distance, and the smallest cell with a corner at the closest point
    // (the rule where that point is a vertex).
    double cellBest2 = HUGE_VAL;
    vtkIdType smallestTied = -1;
    for (size_t k = 0; k < prims.X.size(); ++k)
    {
      if (prims.Cell[k] == cell)
      {
        cellBest2 = std::min(cellBest2, SquaredDistance(q, prims.X[k]));
      }
      const auto& t = prims.X[k];
      for (int corner = 0; corner < 3; ++corner)
      {
        if (t[3 * corner] == c[0] && t[3 * corner + 1] == c[1] && t[3 * corner + 2] == c[2] &&
          (smallestTied < 0 || prims.Cell[k] < smallestTied))
        {
          smallestTied = prims.Cell[k];
        }
      }
    }
    // The cell holds the closest feature: its distance differs only by rounding.
    Check(std::sqrt(cellBest2) <= exact + tolerance + 1e-13 * size,
      at + ": ClosestCellId " + std::to_string(cell) + " is not a closest cell (" +
        vtkdf::FormatNumber(std::sqrt(cellBest2)) + " against " + vtkdf::FormatNumber(exact) + ")");
    double w[3];
    bary->GetTuple(i, w);
    if (feature->GetTuple1(i) == 0)
    {
      Check(cell == smallestTied,
        at + ": a vertex's cell " + std::to_string(cell) + ", not the smallest " +
          std::to_string(smallestTied));
    }
    // The barycentric coordinates on the cell's sub-triangle.
    const vtkIdType s = static_cast<vtkIdType>(sub->GetTuple1(i));
    bool found = false;
    for (size_t k = 0; k < prims.X.size(); ++k)
    {
      if (prims.Cell[k] == cell && prims.Sub[k] == s)
      {
        found = true;
        const auto& t = prims.X[k];
        double error = 0;
        for (int a = 0; a < 3; ++a)
        {
          error =
            std::max(error, std::fabs(w[0] * t[a] + w[1] * t[3 + a] + w[2] * t[6 + a] - c[a]));
        }
        Check(error <= 1e-10 * size, at + ": the barycentric coordinates miss the closest point");
        Check(
          std::fabs(w[0] + w[1] + w[2] - 1) <= 1e-12 && std::min({ w[0], w[1], w[2] }) >= -1e-12,
          at + ": barycentric coordinates outside the triangle");
      }
    }
    Check(
      found, at + ": no sub-triangle " + std::to_string(s) + " in cell " + std::to_string(cell));
    double g[3];
    gradient->GetTuple(i, g);
    Check(std::fabs(vtkMath::Norm(g) - 1) <= 1e-9 || (vtkMath::Norm(g) == 0 && d == 0),
      at + ": the gradient is not a unit vector: " + vtkdf::FormatNumber(vtkMath::Norm(g)) +
        ", distance " + vtkdf::FormatNumber(d));
    if (exact > 1e-6 * size)
    {
      double expected[3];
      for (int k = 0; k < 3; ++k)
      {
        expected[k] = (d < 0 ? -1 : 1) * (q[k] - c[k]) / exact;
      }
      Check(vtkMath::Dot(expected, g) > 1 - 1e-9, at + ": the gradient's direction");
    }
    // The signs against the exact winding number.
    bool conditioned;
    const double exactWinding = Winding(distinct, q, conditioned);
    if (conditioned && std::fabs(std::fabs(exactWinding) - 0.5) > 1e-9 && exact > 1e-12 * size)
    {
      ++windingChecked;
      const bool inside = std::fabs(exactWinding) > 0.5;
      // On the surface (within rounding) w has no value to compare.
      Check(exact < 1e-6 * size || std::fabs(winding->GetTuple1(i) - exactWinding) <= 2e-3,
        at + ": w " + std::to_string(winding->GetTuple1(i)) + " against " +
          std::to_string(exactWinding));
      if (sign == vtkMeshDistanceFilter::WINDING_NUMBER ||
        (sign == vtkMeshDistanceFilter::PSEUDO_NORMAL && closed && exact > 1e-6 * size))
      {
        Check((d < 0) == inside,
          at + ": inside " + std::to_string(inside) + " (w " + vtkdf::FormatNumber(exactWinding) +
            ", the filter's " + vtkdf::FormatNumber(winding->GetTuple1(i)) + "), distance " +
            vtkdf::FormatNumber(d));
      }
    }
    if (sign == vtkMeshDistanceFilter::UNSIGNED)
    {
      Check(d >= 0, at + ": a negative unsigned distance");
    }
  }
  std::printf(
    "%s: %lld points, largest difference %.3g of 1e-12 |d| + 1e-15 size, %d winding signs checked, "
    "%lld primitive distances evaluated\n",
    what.c_str(),
    static_cast<long long>(cloud->GetNumberOfPoints()),
    largest,
    windingChecked,
    static_cast<long long>(filter->GetLastEvaluations()));
}

/// A few triangles with a polyline and two vertex cells.
vtkSmartPointer<vtkPolyData> MixedPrimitives()
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const double x[][3] = { { 0, 0, 0 },
    { 1, 0, 0 },
    { 0, 1, 0 },
    { 1, 1, 0.2 },
    { 2, 0, 1 },
    { 2, 1, 1 },
    { 2.5, 0.5, 1.5 },
    { -1, -1, 1 },
    { 0.5, 0.5, 2 } };
  for (const auto& p : x)
  {
    points->InsertNextPoint(p);
  }
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> verts, lines, polys;
  const vtkIdType v0[] = { 7 }, v1[] = { 8, 7 };
  verts->InsertNextCell(1, v0);
  verts->InsertNextCell(2, v1);
  const vtkIdType line[] = { 4, 5, 6, 4 };
  lines->InsertNextCell(4, line);
  const vtkIdType t0[] = { 0, 1, 2 }, t1[] = { 1, 3, 2 }, t2[] = { 2, 1, 0 };
  polys->InsertNextCell(3, t0);
  polys->InsertNextCell(3, t1);
  polys->InsertNextCell(3, t2); // a duplicate of the first, flipped
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  mesh->SetPolys(polys);
  return mesh;
}

void Brute(const std::string& data)
{
  for (const char* name : { "bunny_small", "plane", "boeing_soup", "scad_zero_area" })
  {
    auto mesh = vtkdf::testing::ReadUnitBoxMesh(data + "/" + name + ".vtp");
    const bool closed = std::string(name) == "bunny_small";
    for (int sign : { 0, 1, 2 })
    {
      CheckBruteForce(name, mesh, sign, closed);
    }
  }
  CheckBruteForce("mixed primitives", MixedPrimitives(), 2, false);
}

/// The grid filter's ClosestSubTriangle, ClosestBarycentric and Gradient against the
/// point filter's at the same samples, where the two name the same closest cell.
void CompareSurfaceArrays(vtkImageData* image,
  vtkDataSet* points,
  const std::string& what,
  vtkIdType sameCells)
{
  vtkPointData* pd = image->GetPointData();
  vtkDataArray* cells = pd->GetArray("ClosestCellId");
  vtkDataArray* sub = pd->GetArray("ClosestSubTriangle");
  vtkDataArray* bary = pd->GetArray("ClosestBarycentric");
  vtkDataArray* gradient = pd->GetArray("Gradient");
  vtkDataArray* distance = pd->GetArray("Distance");
  vtkDataArray* expectedCells = PointArray(points, "ClosestCellId");
  vtkDataArray* expectedSub = PointArray(points, "ClosestSubTriangle");
  vtkDataArray* expectedBary = PointArray(points, "ClosestBarycentric");
  vtkDataArray* expectedGradient = PointArray(points, "Gradient");
  if (!cells || !sub || !bary || !gradient || !distance || !expectedCells || !expectedSub ||
    !expectedBary || !expectedGradient)
  {
    Check(false, what + ": a surface array is missing");
    return;
  }
  const vtkIdType n = image->GetNumberOfPoints();
  vtkIdType compared = 0, otherSub = 0, onSurface = 0;
  double largestBary = 0, largestGradient = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (cells->GetTuple1(i) != expectedCells->GetTuple1(i))
    {
      continue;
    }
    ++compared;
    onSurface += distance->GetTuple1(i) == 0;
    if (sub->GetTuple1(i) != expectedSub->GetTuple1(i))
    {
      ++otherSub;
      continue;
    }
    double b[3], e[3], g[3], eg[3];
    bary->GetTuple(i, b);
    expectedBary->GetTuple(i, e);
    gradient->GetTuple(i, g);
    expectedGradient->GetTuple(i, eg);
    for (int k = 0; k < 3; ++k)
    {
      largestBary = std::max(largestBary, std::fabs(b[k] - e[k]));
      largestGradient = std::max(largestGradient, std::fabs(g[k] - eg[k]));
    }
    Check(std::fabs(vtkMath::Norm(g) - 1) <= 1e-6 || vtkMath::Norm(eg) == 0,
      what + " sample " + std::to_string(i) + ": the gradient is not a unit vector");
  }
  // Float arrays against double ones.
  Check(largestBary <= 1e-5,
    what + ": barycentric coordinates differ by " + std::to_string(largestBary));
  Check(largestGradient <= 1e-5, what + ": gradients differ by " + std::to_string(largestGradient));
  // A sample on the boundary of two of a cell's triangles may name either.
  Check(otherSub <= compared / 200, what + ": " + std::to_string(otherSub) + " other triangles");
  Check(compared == sameCells && (onSurface > 0) == (what.find("cube") == 0),
    what + ": " + std::to_string(compared) + " samples compared, " + std::to_string(onSurface) +
      " on the surface");
  std::printf("%s: %lld samples compared, %lld on the surface, %lld other triangles, "
              "barycentric within %.2g, gradient within %.2g\n",
    what.c_str(),
    static_cast<long long>(compared),
    static_cast<long long>(onSurface),
    static_cast<long long>(otherSub),
    largestBary,
    largestGradient);
}

/// The filter on an image's samples against vtkLinearFactorDistanceField on that grid:
/// mixed_cells at resolution 24, on both routes, and a cube of quads whose faces hold
/// samples (the gradient there the pseudonormal).
void Grid(const std::string& data)
{
  vtkNew<vtkPolyDataReader> reader;
  reader->SetFileName((data + "/mixed_cells.vtk").c_str());
  reader->Update();
  vtkNew<vtkCubeSource> cube;
  cube->Update();
  // The cube lies on the grid's lines: samples on its diagonal planes are equidistant
  // from two faces, and the site scan's ties go to the lower site (faces in the sites'
  // order), the queries' to the smaller cell: there the cells may differ.
  struct Case
  {
    std::string Name;
    vtkPolyData* Mesh;
    int Route;
    vtkIdType TieShare; // at most n / TieShare samples may name another cell
    bool GPU = false;
  };
  const Case cases[] = { { "mixed_cells scan", reader->GetOutput(), 1, 200 },
    { "mixed_cells queries", reader->GetOutput(), 2, 200 },
    { "cube scan", cube->GetOutput(), 1, 5 },
    { "cube queries", cube->GetOutput(), 2, 200 },
    { "cube scan gpu", cube->GetOutput(), 1, 5, true } };
  for (const Case& c : cases)
  {
    for (int sign : { 0, 1, 2 })
    {
      const std::string what = c.Name + " sign " + std::to_string(sign);
      vtkNew<vtkLinearFactorDistanceField> field;
      field->SetInputData(c.Mesh);
      if (c.Mesh == cube->GetOutput())
      {
        // Samples every 1/8 from -1: the faces at +-0.5 hold samples.
        field->ExplicitGridOn();
        field->SetGridOrigin(-1, -1, -1);
        field->SetGridSpacing(0.125, 0.125, 0.125);
        field->SetGridDimensions(17, 17, 17);
      }
      else
      {
        field->SetResolution(24);
      }
      field->SetSignMode(sign);
      field->SetRoute(c.Route);
      field->ComputeClosestBarycentricOn();
      field->ComputeGradientOn();
      field->SetBackend(
        c.GPU ? vtkDistanceFieldAlgorithm::BACKEND_GPU : vtkDistanceFieldAlgorithm::BACKEND_CPU);
      field->Update();
      vtkImageData* image = field->GetOutput();
      Check(image->GetNumberOfPoints() > 0, what + ": no field");
      vtkNew<vtkImageData> samples;
      samples->CopyStructure(image);
      vtkNew<vtkMeshDistanceFilter> filter;
      filter->SetInputData(0, samples);
      filter->SetSurfaceData(c.Mesh);
      filter->SetSignMode(sign);
      filter->Update();
      vtkDataArray* expected = image->GetPointData()->GetArray("Distance");
      vtkDataArray* expectedCells = image->GetPointData()->GetArray("ClosestCellId");
      vtkDataArray* distance = PointArray(filter->GetOutput(), "Distance");
      vtkDataArray* cells = PointArray(filter->GetOutput(), "ClosestCellId");
      if (!expected || !expectedCells || !distance || !cells)
      {
        Check(false, "grid: an array is missing");
        continue;
      }
      const vtkIdType n = image->GetNumberOfPoints();
      vtkIdType otherCells = 0;
      double largest = 0;
      for (vtkIdType i = 0; i < n; ++i)
      {
        const double e = expected->GetTuple1(i), d = distance->GetTuple1(i);
        largest = std::max(largest, std::fabs(d - e));
        Check(std::fabs(d - e) <= 1e-6 * std::fabs(e) + 1e-6,
          what + " sample " + std::to_string(i) + ": " + std::to_string(d) +
            " against the field's " + std::to_string(e));
        otherCells += cells->GetTuple1(i) != expectedCells->GetTuple1(i);
      }
      // Samples within rounding of two features may name either.
      Check(
        otherCells <= n / c.TieShare, what + ": " + std::to_string(otherCells) + " other cells");
      std::printf("grid %s: %lld samples, largest difference %.3g, %lld other cells\n",
        what.c_str(),
        static_cast<long long>(n),
        largest,
        static_cast<long long>(otherCells));
      CompareSurfaceArrays(image, filter->GetOutput(), what, n - otherCells);
    }
  }
  // A narrow band: beyond it no closest cell, no triangle, NaN coordinates and gradient.
  for (int route : { 1, 2 })
  {
    vtkNew<vtkLinearFactorDistanceField> field;
    field->SetInputData(reader->GetOutput());
    field->SetResolution(24);
    field->SetSignModeToWindingNumber();
    field->SetRoute(route);
    field->SetMaximumDistance(0.1);
    field->ComputeClosestBarycentricOn();
    field->ComputeGradientOn();
    field->ComputeClosestCellIdOff();
    field->ComputeDistanceOff();
    field->SetBackendToCPU();
    field->Update();
    vtkPointData* pd = field->GetOutput()->GetPointData();
    vtkDataArray* sub = pd->GetArray("ClosestSubTriangle");
    vtkDataArray* bary = pd->GetArray("ClosestBarycentric");
    vtkDataArray* gradient = pd->GetArray("Gradient");
    if (!sub || !bary || !gradient || pd->GetArray("ClosestCellId") || pd->GetArray("Distance"))
    {
      Check(false, "band: the arrays are not the ones asked for");
      continue;
    }
    vtkIdType beyond = 0;
    for (vtkIdType i = 0; i < sub->GetNumberOfTuples(); ++i)
    {
      const bool none = sub->GetTuple1(i) < 0;
      beyond += none;
      Check(none == std::isnan(bary->GetComponent(i, 0)) &&
          none == std::isnan(gradient->GetComponent(i, 2)),
        "band route " + std::to_string(route) + " sample " + std::to_string(i));
    }
    Check(beyond > 0 && beyond < sub->GetNumberOfTuples(), "band: no sample beyond it");
    std::printf("band route %d: %lld samples beyond\n", route, static_cast<long long>(beyond));
  }
}

/// Distances of a mesh and its points scaled by 2^k: the same answers, scaled exactly.
void Scale(const std::string& data)
{
  auto mesh = vtkdf::testing::ReadUnitBoxMesh(data + "/plane.vtp");
  const Primitives prims = Collect(mesh);
  const double centre[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkPolyData> cloud = QueryPoints(prims, 1, centre);
  auto run = [&](double factor)
  {
    auto scaled = [factor](vtkPolyData* in)
    {
      auto out = vtkSmartPointer<vtkPolyData>::New();
      out->DeepCopy(in);
      for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
      {
        double x[3];
        out->GetPoint(i, x);
        out->GetPoints()->SetPoint(i, x[0] * factor, x[1] * factor, x[2] * factor);
      }
      return out;
    };
    vtkNew<vtkMeshDistanceFilter> filter;
    filter->SetInputData(0, scaled(cloud));
    filter->SetSurfaceData(scaled(mesh));
    filter->SetSignModeToWindingNumber();
    filter->Update();
    std::vector<double> d;
    vtkDataArray* a = PointArray(filter->GetOutput(), "Distance");
    for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
    {
      d.push_back(a->GetTuple1(i) / factor);
    }
    return d;
  };
  const std::vector<double> one = run(1);
  for (const double factor : { std::ldexp(1.0, 20), std::ldexp(1.0, -30) })
  {
    const std::vector<double> other = run(factor);
    Check(
      !one.empty() && one == other, "scaled by " + std::to_string(factor) + ": other distances");
  }
  std::printf("scale: %zu points, the same at 2^20 and 2^-30\n", one.size());
}

/// MaximumDistance, and the hierarchy kept between runs.
void Cap(const std::string& data)
{
  auto mesh = vtkdf::testing::ReadUnitBoxMesh(data + "/bunny_small.vtp");
  const Primitives prims = Collect(mesh);
  const double centre[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkPolyData> cloud = QueryPoints(prims, 1, centre);
  for (int sign : { 0, 1, 2 })
  {
    vtkNew<vtkMeshDistanceFilter> whole, capped;
    for (vtkMeshDistanceFilter* f : { whole.Get(), capped.Get() })
    {
      f->SetInputData(0, cloud);
      f->SetSurfaceData(mesh);
      f->SetSignMode(sign);
    }
    capped->SetMaximumDistance(0.05);
    whole->Update();
    capped->Update();
    vtkDataArray* d = PointArray(whole->GetOutput(), "Distance");
    vtkDataArray* dc = PointArray(capped->GetOutput(), "Distance");
    vtkDataArray* cell = PointArray(capped->GetOutput(), "ClosestCellId");
    vtkDataArray* closest = PointArray(capped->GetOutput(), "ClosestPoint");
    vtkIdType beyond = 0;
    for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
    {
      const double full = d->GetTuple1(i), value = dc->GetTuple1(i);
      const std::string at = "cap sign " + std::to_string(sign) + " point " + std::to_string(i);
      if (std::fabs(full) <= 0.05)
      {
        Check(value == full, at + ": within the cap, another distance");
      }
      else
      {
        ++beyond;
        const double expected = sign == 1 ? NAN : (sign == 2 && full < 0 ? -0.05 : 0.05);
        Check(sign == 1 ? std::isnan(value) : value == expected, at + ": not the cap");
        Check(cell->GetTuple1(i) == -1 && std::isnan(closest->GetComponent(i, 0)),
          at + ": a closest feature beyond the cap");
      }
    }
    Check(beyond > 0 && beyond == capped->GetLastPointsBeyond(), "cap: points beyond");
    std::printf("cap sign %d: %lld of %lld points beyond\n",
      sign,
      static_cast<long long>(beyond),
      static_cast<long long>(cloud->GetNumberOfPoints()));
  }
  // The hierarchy: built once, kept for new points, rebuilt for a changed surface.
  vtkNew<vtkMeshDistanceFilter> filter;
  filter->SetInputData(0, cloud);
  filter->SetSurfaceData(mesh);
  filter->Update();
  Check(filter->GetLastBuiltHierarchy(), "the first run builds the hierarchy");
  vtkNew<vtkPolyData> fewer;
  fewer->DeepCopy(cloud);
  fewer->GetPoints()->SetNumberOfPoints(10);
  filter->SetInputData(0, fewer);
  filter->Update();
  Check(!filter->GetLastBuiltHierarchy(), "new points rebuild the hierarchy");
  Check(filter->GetOutput()->GetNumberOfPoints() == 10, "the output has the new points");
  mesh->GetPoints()->SetPoint(0, 5, 5, 5);
  mesh->GetPoints()->Modified();
  filter->Update();
  Check(filter->GetLastBuiltHierarchy(), "a changed surface keeps the old hierarchy");
  const double d0 = PointArray(filter->GetOutput(), "Distance")->GetTuple1(0);
  double q[3];
  fewer->GetPoint(0, q);
  double best2 = HUGE_VAL;
  for (const auto& t : Collect(mesh).X)
  {
    best2 = std::min(best2, SquaredDistance(q, t));
  }
  Check(std::fabs(d0 - std::sqrt(best2)) <= 1e-12, "the changed surface's distance");
}

/// vtkMeshDistanceFunction: its values and gradients equal the filter's, one at a time
/// from many threads and in a batch; through vtkClipPolyData it keeps exactly the
/// points where the exact distance is not negative, and cuts every edge whose ends the
/// exact distance signs apart; without a valid surface, NoValue.
void Function(const std::string& data)
{
  auto mesh = vtkdf::testing::ReadUnitBoxMesh(data + "/plane.vtp");
  const Primitives prims = Collect(mesh);
  const std::vector<std::array<double, 9>> distinct = DistinctTriangles(prims);
  const double centre[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkPolyData> cloud = QueryPoints(prims, 1, centre);
  vtkNew<vtkMeshDistanceFilter> filter;
  filter->SetInputData(0, cloud);
  filter->SetSurfaceData(mesh);
  filter->SetSignModeToWindingNumber();
  filter->Update();
  vtkDataArray* expected = PointArray(filter->GetOutput(), "Distance");
  vtkDataArray* expectedGradient = PointArray(filter->GetOutput(), "Gradient");
  vtkNew<vtkMeshDistanceFunction> function;
  function->SetInput(mesh);
  const vtkIdType n = cloud->GetNumberOfPoints();
  std::vector<double> one(n), gradients(3 * n);
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        double x[3];
        cloud->GetPoint(i, x);
        one[i] = function->FunctionValue(x);
        function->FunctionGradient(x, gradients.data() + 3 * i);
      }
    });
  vtkNew<vtkDoubleArray> batch;
  function->FunctionValue(cloud->GetPoints()->GetData(), batch);
  vtkIdType differ = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double g[3];
    expectedGradient->GetTuple(i, g);
    differ += one[i] != expected->GetTuple1(i) || batch->GetValue(i) != expected->GetTuple1(i) ||
      g[0] != gradients[3 * i] || g[1] != gradients[3 * i + 1] || g[2] != gradients[3 * i + 2];
  }
  Check(differ == 0, "function: " + std::to_string(differ) + " values other than the filter's");

  // A plane of points across the surface, clipped where the distance is negative.
  vtkNew<vtkPlaneSource> sheet;
  sheet->SetOrigin(-0.6, -0.6, 0.01);
  sheet->SetPoint1(0.6, -0.6, 0.01);
  sheet->SetPoint2(-0.6, 0.6, 0.01);
  sheet->SetResolution(60, 60);
  sheet->Update();
  vtkNew<vtkClipPolyData> clip;
  clip->SetInputConnection(sheet->GetOutputPort());
  clip->SetClipFunction(function);
  clip->GenerateClippedOutputOn();
  clip->Update();
  auto exactSide = [&](const double x[3])
  {
    bool conditioned;
    return std::fabs(Winding(distinct, x, conditioned)) > 0.5;
  };
  vtkPolyData* sheetPoints = sheet->GetOutput();
  vtkIdType kept = 0, keptWrong = 0;
  for (vtkIdType i = 0; i < clip->GetOutput()->GetNumberOfPoints(); ++i)
  {
    double x[3];
    clip->GetOutput()->GetPoint(i, x);
    if (sheetPoints->FindPoint(x) >= 0)
    {
      double y[3];
      sheetPoints->GetPoint(sheetPoints->FindPoint(x), y);
      if (y[0] == x[0] && y[1] == x[1] && y[2] == x[2])
      {
        ++kept;
        keptWrong += exactSide(x); // a kept point lies outside (distance >= 0)
      }
    }
  }
  Check(kept > 0 && keptWrong == 0,
    "clip: " + std::to_string(keptWrong) + " of " + std::to_string(kept) + " kept points inside");
  Check(clip->GetClippedOutput()->GetNumberOfPoints() > 0, "clip: nothing clipped away");
  std::printf("function: %lld points equal to the filter's; clip kept %lld points, none inside\n",
    static_cast<long long>(n),
    static_cast<long long>(kept));

  vtkNew<vtkMeshDistanceFunction> none;
  none->SetNoValue(-7);
  double origin[3] = { 0, 0, 0 };
  Check(none->FunctionValue(origin) == -7, "no input: not NoValue"); // and an error, once
}

void Errors()
{
  auto expectError = [](vtkMeshDistanceFilter* filter, const std::string& text)
  {
    vtkdf::testing::MessageRecorder recorder(filter);
    filter->Update();
    const bool ok = recorder.Errors.find(text) != std::string::npos;
    Check(ok, "expected an error with '" + text + "', got '" + recorder.Errors + "'");
  };
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 2, 3);
  points->InsertNextPoint(0, NAN, 0);
  cloud->SetPoints(points);
  {
    vtkNew<vtkMeshDistanceFilter> filter;
    filter->SetInputData(0, cloud);
    filter->SetSurfaceData(vtkdf::testing::Triangle());
    expectError(filter, "point 2 has a NaN");
  }
  {
    vtkNew<vtkMeshDistanceFilter> filter;
    filter->SetInputData(0, cloud);
    vtkNew<vtkPolyData> empty;
    empty->SetPoints(points);
    filter->SetSurfaceData(empty);
    expectError(filter, "surface");
  }
  {
    vtkNew<vtkMeshDistanceFilter> filter;
    filter->SetInputData(0, cloud);
    filter->SetSurfaceData(vtkdf::testing::Triangle());
    filter->SetMaximumDistance(-1);
    expectError(filter, "MaximumDistance");
  }
  {
    vtkNew<vtkMeshDistanceFilter> filter;
    filter->SetInputData(0, cloud);
    filter->SetSurfaceData(vtkdf::testing::Triangle());
    filter->SetSignMode(7);
    expectError(filter, "SignMode");
  }
  {
    vtkNew<vtkMeshDistanceFilter> filter;
    filter->SetInputData(0, cloud);
    expectError(filter, "port 1");
  }
  {
    // No points: empty arrays, no error.
    vtkNew<vtkMeshDistanceFilter> filter;
    vtkNew<vtkPolyData> none;
    vtkNew<vtkPoints> nothing;
    none->SetPoints(nothing);
    filter->SetInputData(0, none);
    filter->SetSurfaceData(vtkdf::testing::Triangle());
    filter->Update();
    vtkDataArray* d = PointArray(filter->GetOutput(), "Distance");
    Check(filter->GetErrorCode() == 0 && d && d->GetNumberOfTuples() == 0,
      "no points: an empty Distance array");
  }
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR brute|grid|scale|cap|function|errors"))
  {
    return 2;
  }
  const std::string data = argv[1], mode = argv[2];
  if (mode == "brute")
  {
    Brute(data);
  }
  else if (mode == "grid")
  {
    Grid(data);
  }
  else if (mode == "scale")
  {
    Scale(data);
  }
  else if (mode == "cap")
  {
    Cap(data);
  }
  else if (mode == "function")
  {
    Function(data);
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
