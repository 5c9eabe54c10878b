// vtkDistanceFieldBlend on segmented fields of concentric spheres of radii 0.5 and 0.8:
// - T = 0 and T = 1 give the inputs exactly (every array, every sample);
// - T = 0.25, 0.5, 0.75: the interface (eq. 6 points on grid edges between the two
//   regions) lies within half a spacing of the sphere of radius 0.5 + 0.3 T, all around;
// - a closed box with an inner wall at x = -0.3 and at x = 0.35 (three regions): at T =
//   0.25, 0.5, 0.75 the wall (where the chambers meet along the box's axis) is at
//   -0.3 + 0.65 T within half a spacing, and the moving chambers' other walls stay put:
//   no sample in the band the wall sweeps is put nearer a surface than both inputs'
//   blended distance and the moving wall's allow (the signed blend of the plain distances
//   collapsed to 0 all along the box's faces there);
// - an open disk into a bowl of the same rim (their regions meet beyond the rim without
//   a sheet, in other places): at T = 0.25, 0.5, 0.75 the polygonized blend has no
//   surface more than a spacing beyond the rim (1.46 at T = 0.5 when the blend took |s|
//   across the seams too), and its middle at the blended depth within half a spacing;
// - refused, with a message naming the problem: fields of other regions (a T-junction's
//   segmentation), other grids, missing arrays, T outside [0, 1] or NaN.
#include "TestShapes.h"
#include "TestSupport.h"
#include "vtkDistanceFieldBlend.h"
#include "vtkSegmentedDistanceContour.h"
#include "vtkSegmentedDistanceField.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
const double Centre[3] = { 0.03, -0.02, 0.01 };

vtkSmartPointer<vtkImageData> Segmented(vtkPolyData* mesh, double spacing = 0.05)
{
  vtkNew<vtkSegmentedDistanceField> f;
  f->SetInputData(mesh);
  f->SetBackendToCPU();
  f->ExplicitGridOn();
  f->SetGridOrigin(-1.013, -1.007, -1.021);
  f->SetGridSpacing(spacing, spacing, spacing);
  const int n = static_cast<int>(std::lround(2 / spacing)) + 1;
  f->SetGridDimensions(n, n, n);
  f->Update();
  return f->GetOutput();
}

vtkSmartPointer<vtkPolyData> Sphere(double radius)
{
  vtkNew<vtkSphereSource> source;
  source->SetCenter(Centre[0], Centre[1], Centre[2]);
  source->SetRadius(radius);
  source->SetThetaResolution(96);
  source->SetPhiResolution(64);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

vtkSmartPointer<vtkImageData> Blend(vtkImageData* a,
  vtkImageData* b,
  double t,
  std::string* errors = nullptr)
{
  vtkNew<vtkDistanceFieldBlend> blend;
  vtkdf::testing::MessageRecorder recorder(blend);
  blend->SetInputData(0, a);
  blend->SetInputData(1, b);
  blend->SetT(t);
  blend->Update();
  if (errors)
  {
    *errors = recorder.Errors;
  }
  return blend->GetOutput();
}

bool SameArray(vtkImageData* x, vtkImageData* y, const char* name)
{
  vtkDataArray* a = x->GetPointData()->GetArray(name);
  vtkDataArray* b = y->GetPointData()->GetArray(name);
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples())
  {
    return false;
  }
  for (vtkIdType v = 0; v < a->GetNumberOfTuples(); ++v)
  {
    if (a->GetTuple1(v) != b->GetTuple1(v))
    {
      return false;
    }
  }
  return true;
}

/// The radii of the interface points (eq. 6) on the grid edges between two regions.
void InterfaceRadii(vtkImageData* field, double& lo, double& hi, long long& count)
{
  vtkDataArray* d = field->GetPointData()->GetArray("Distance");
  vtkDataArray* r = field->GetPointData()->GetArray("RegionIndex");
  int dims[3];
  field->GetDimensions(dims);
  const double w = field->GetSpacing()[0];
  lo = HUGE_VAL, hi = -HUGE_VAL, count = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        const vtkIdType v = i + dims[0] * (j + vtkIdType(dims[1]) * k);
        const vtkIdType step[3] = { 1, dims[0], vtkIdType(dims[0]) * dims[1] };
        const int at[3] = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          if (at[a] + 1 >= dims[a])
          {
            continue;
          }
          const vtkIdType u = v + step[a];
          const double du = d->GetTuple1(v), dv = d->GetTuple1(u);
          if (r->GetTuple1(v) == r->GetTuple1(u) || du + dv > w * (1 + 1e-5))
          {
            continue;
          }
          double p[3], q[3];
          field->GetPoint(v, p);
          field->GetPoint(u, q);
          const double t = du + dv > 0 ? du / (du + dv) : 0.5;
          double r2 = 0;
          for (int c = 0; c < 3; ++c)
          {
            const double x = p[c] + t * (q[c] - p[c]) - Centre[c];
            r2 += x * x;
          }
          lo = std::min(lo, std::sqrt(r2));
          hi = std::max(hi, std::sqrt(r2));
          ++count;
        }
      }
    }
  }
}
} // namespace

int main()
{
  auto small = Segmented(Sphere(0.5));
  auto large = Segmented(Sphere(0.8));
  CHECK(small->GetNumberOfPoints() > 0 && large->GetNumberOfPoints() > 0, "no fields");
  for (const double t : { 0.0, 1.0 })
  {
    auto b = Blend(small, large, t);
    vtkImageData* expected = t == 0 ? small : large;
    for (const char* name : { "Distance", "RegionIndex", "SegmentedDistance" })
    {
      CHECK(SameArray(b, expected, name), "T = %g: %s is not the input's", t, name);
    }
  }
  const double h = 0.05;
  for (const double t : { 0.25, 0.5, 0.75 })
  {
    auto b = Blend(small, large, t);
    double lo, hi;
    long long count;
    InterfaceRadii(b, lo, hi, count);
    const double radius = 0.5 + 0.3 * t;
    std::printf("T = %.2f: %lld interface points at radii %.4f to %.4f (expected %.4f, "
                "spacing %.3f)\n",
      t,
      count,
      lo,
      hi,
      radius,
      h);
    CHECK(count > 1000 && lo > radius - 0.5 * h && hi < radius + 0.5 * h,
      "T = %g: the interface is not the sphere of radius %g",
      t,
      radius);
  }

  // A moving wall inside a closed box.
  auto left = Segmented(vtkdf::testing::WalledBox(-0.3, false, 0.8), 0.05);
  auto right = Segmented(vtkdf::testing::WalledBox(0.35, false, 0.8), 0.05);
  for (const double t : { 0.25, 0.5, 0.75 })
  {
    auto b = Blend(left, right, t);
    vtkDataArray* r = b->GetPointData()->GetArray("RegionIndex");
    vtkDataArray* d = b->GetPointData()->GetArray("Distance");
    vtkDataArray* ra = left->GetPointData()->GetArray("RegionIndex");
    vtkDataArray* da = left->GetPointData()->GetArray("Distance");
    vtkDataArray* db = right->GetPointData()->GetArray("Distance");
    int dims[3];
    b->GetDimensions(dims);
    const double* origin = b->GetOrigin();
    // Along the box's axis (y = z = 0): where the left chamber's region gives way.
    const int j = static_cast<int>(std::lround((0 - origin[1]) / h));
    const int k = static_cast<int>(std::lround((0 - origin[2]) / h));
    const int leftChamber = static_cast<int>(ra->GetTuple1(
      static_cast<vtkIdType>(std::lround((-0.6 - origin[0]) / h)) + dims[0] * (j + dims[1] * k)));
    double wall = std::nan("");
    for (int i = 0; i + 1 < dims[0]; ++i)
    {
      const vtkIdType p = i + dims[0] * (j + dims[1] * k), q = p + 1;
      if (static_cast<int>(r->GetTuple1(p)) == leftChamber &&
        static_cast<int>(r->GetTuple1(q)) != leftChamber && origin[0] + i * h > -0.7)
      {
        const double u = d->GetTuple1(p), v = d->GetTuple1(q);
        wall = origin[0] + (i + u / (u + v)) * h;
        break;
      }
    }
    // No collapse: every sample's blended distance is at least the smaller of the inputs'
    // blend and its distance to the moving wall's blended place, less a spacing.
    const double expectedWall = -0.3 + 0.65 * t;
    long long collapsed = 0;
    for (vtkIdType p = 0; p < b->GetNumberOfPoints(); ++p)
    {
      const double x = origin[0] + (p % dims[0]) * h;
      const double floor =
        std::min((1 - t) * da->GetTuple1(p) + t * db->GetTuple1(p), std::abs(x - expectedWall)) - h;
      collapsed += d->GetTuple1(p) < floor;
    }
    std::printf("T = %.2f: walled box, the wall at x = %.4f (expected %.4f); %lld samples "
                "nearer a surface than they should be\n",
      t,
      wall,
      expectedWall,
      collapsed);
    CHECK(std::abs(wall - expectedWall) < 0.5 * h, "T = %g: the wall is not where it should be", t);
    CHECK(collapsed == 0, "T = %g: %lld samples collapsed onto a spurious surface", t, collapsed);
  }

  {
    // An open disk into a bowl of the same rim (radius 0.7 at z = 0; the bowl's bottom at
    // z = -0.4): the two regions meet beyond the rim without a sheet, at other places in
    // the two fields (seams). The blend's surface is a shallower bowl: its bottom at
    // z = -0.4 T, and nothing beyond the rim.
    auto dish = [](double depth)
    {
      vtkNew<vtkPoints> points;
      vtkNew<vtkCellArray> polys;
      const int rings = 12, around = 48;
      points->InsertNextPoint(0, 0, -depth);
      for (int i = 1; i <= rings; ++i)
      {
        const double r = 0.7 * i / rings;
        for (int k = 0; k < around; ++k)
        {
          const double a = 2 * M_PI * k / around;
          points->InsertNextPoint(r * std::cos(a), r * std::sin(a), -depth * (1 - r * r / 0.49));
        }
      }
      auto id = [&](int i, int k) { return i == 0 ? 0 : 1 + (i - 1) * around + k % around; };
      for (int i = 0; i < rings; ++i)
      {
        for (int k = 0; k < around; ++k)
        {
          const vtkIdType t0[3] = { id(i, k), id(i + 1, k), id(i + 1, k + 1) };
          polys->InsertNextCell(3, t0);
          if (i > 0)
          {
            const vtkIdType t1[3] = { id(i, k), id(i + 1, k + 1), id(i, k + 1) };
            polys->InsertNextCell(3, t1);
          }
        }
      }
      vtkNew<vtkPolyData> mesh;
      mesh->SetPoints(points);
      mesh->SetPolys(polys);
      return vtkSmartPointer<vtkPolyData>(mesh);
    };
    auto disk = Segmented(dish(0), 0.05);
    auto bowl = Segmented(dish(0.4), 0.05);
    for (const double t : { 0.25, 0.5, 0.75 })
    {
      auto b = Blend(disk, bowl, t);
      vtkNew<vtkSegmentedDistanceContour> contour;
      contour->SetInputData(b);
      contour->Update();
      vtkPolyData* surface = contour->GetOutput();
      double beyond = 0, bottom = HUGE_VAL;
      for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
      {
        double x[3];
        surface->GetPoint(p, x);
        const double r = std::hypot(x[0], x[1]);
        beyond = std::max(beyond, r - 0.7);
        if (r < 0.1)
        {
          bottom = std::min(bottom, std::abs(x[2] + 0.4 * t * (1 - r * r / 0.49)));
        }
      }
      std::printf("T = %.2f: disk into bowl, %lld triangles; the surface reaches %.3f spacings "
                  "beyond the rim; at the middle %.3f spacings from z = %.2f\n",
        t,
        static_cast<long long>(surface->GetNumberOfCells()),
        beyond / h,
        bottom / h,
        -0.4 * t);
      CHECK(beyond <= h, "T = %g: a sheet beyond the rim (%.3f spacings)", t, beyond / h);
      CHECK(bottom <= 0.5 * h, "T = %g: the bowl's middle is not at its blended depth", t);
    }
  }

  // Refusals.
  std::string errors;
  {
    // A T-junction: three regions, another table.
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> polys;
    for (int s = 0; s < 3; ++s)
    {
      const double a = 0.3 + 2.1 * s, c = std::cos(a), n = std::sin(a);
      const vtkIdType o = points->InsertNextPoint(0, 0, -0.6);
      points->InsertNextPoint(0.6 * c, 0.6 * n, -0.6);
      points->InsertNextPoint(0.6 * c, 0.6 * n, 0.6);
      points->InsertNextPoint(0, 0, 0.6);
      const vtkIdType t0[3] = { o, o + 1, o + 2 }, t1[3] = { o, o + 2, o + 3 };
      polys->InsertNextCell(3, t0);
      polys->InsertNextCell(3, t1);
    }
    vtkNew<vtkPolyData> junction;
    junction->SetPoints(points);
    junction->SetPolys(polys);
    auto other = Segmented(junction);
    Blend(small, other, 0.5, &errors);
    CHECK(errors.find("regions do not mean the same") != std::string::npos,
      "other regions: %s",
      errors.c_str());
  }
  Blend(small, Segmented(Sphere(0.8), 0.1), 0.5, &errors);
  CHECK(errors.find("different grids") != std::string::npos, "other grid: %s", errors.c_str());
  {
    vtkNew<vtkImageData> bare;
    bare->ShallowCopy(large);
    bare->GetPointData()->RemoveArray("RegionIndex");
    Blend(small, bare, 0.5, &errors);
    CHECK(errors.find("no point-data array RegionIndex") != std::string::npos,
      "missing array: %s",
      errors.c_str());
  }
  for (const double t : { -0.1, 2.0, std::nan("") })
  {
    Blend(small, large, t, &errors);
    CHECK(
      errors.find("T must lie in [0, 1]") != std::string::npos, "T = %g: %s", t, errors.c_str());
  }
  return vtkdf::testing::Verdict();
}
