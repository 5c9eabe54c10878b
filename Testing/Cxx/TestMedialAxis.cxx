// vtkMedialAxisFilter on analytic shapes at 64^3, compared with their exact medial axes
// (symmetric Hausdorff distance, in voxels, between the marked voxels and samples of the
// exact axis):
// - sphere: its centre (theta 60: voxels that straddle the centre off-axis see their
//   closest points at down to 70.5 degrees);
// - box: the whole medial surface (bisector planes of the faces; theta 60, below the
//   smallest separation angle, 90 degrees);
// - capped cylinder: its axis, between the points one radius from the caps (theta 120,
//   above the 90 degrees of the cones between caps and side; a grid that puts the axis
//   between two voxels);
// - torus: its core circle (theta 120).
// Also: thinness (no medial voxel with all 6 neighbours medial), theta monotone (the set
// for a larger theta is a subset), the point output has one point per medial voxel,
// and on the GPU the same voxels as on the CPU.
//
// usage: TestMedialAxis cpu|gpu
#include "vtkLinearFactorDistanceField.h"

#include "TestSupport.h"
#include "vtkMedialAxisFilter.h"

#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace
{
std::string Backend = "cpu";
using Point = std::array<double, 3>;

vtkSmartPointer<vtkPolyData> Triangulated(vtkAlgorithm* source)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

struct Result
{
  vtkSmartPointer<vtkImageData> Field;
  std::vector<Point> Marked;
  std::vector<char> Mask;
  vtkIdType Points = 0;
};

/// An explicit grid (null: the default grid at resolution 64).
struct Grid
{
  double Origin[3], Spacing[3];
  int Dims[3];
};
const Grid* ExplicitGrid = nullptr;

Result Medial(vtkPolyData* mesh, double theta, const std::string& backend)
{
  vtkNew<vtkMedialAxisFilter> f;
  f->SetInputData(mesh);
  f->SetResolution(64);
  if (ExplicitGrid)
  {
    f->ExplicitGridOn();
    f->SetGridOrigin(const_cast<double*>(ExplicitGrid->Origin));
    f->SetGridSpacing(const_cast<double*>(ExplicitGrid->Spacing));
    f->SetGridDimensions(const_cast<int*>(ExplicitGrid->Dims));
  }
  f->SetSeparationAngle(theta);
  f->SetRegionToInside();
  testsupport::UseBackend(f.GetPointer(), backend);
  f->Update();
  Result r;
  r.Field = vtkSmartPointer<vtkImageData>::New();
  r.Field->DeepCopy(f->GetOutput());
  r.Points = f->GetMedialPoints()->GetNumberOfPoints();
  auto* medial = vtkUnsignedCharArray::SafeDownCast(r.Field->GetPointData()->GetArray("Medial"));
  if (!medial || std::string(f->GetLastBackend()) != backend)
  {
    std::printf("FAIL: no Medial array, or not run on %s\n", backend.c_str());
    ++testsupport::Failures;
    return r;
  }
  r.Mask.resize(medial->GetNumberOfTuples());
  for (vtkIdType v = 0; v < medial->GetNumberOfTuples(); ++v)
  {
    r.Mask[v] = medial->GetValue(v) != 0;
    if (r.Mask[v])
    {
      Point p;
      r.Field->GetPoint(v, p.data());
      r.Marked.push_back(p);
    }
  }
  return r;
}

double Distance(const Point& a, const Point& b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/// The largest distance from a point of `from` to the nearest point of `to`.
double Directed(const std::vector<Point>& from, const std::vector<Point>& to)
{
  double worst = 0;
  for (const Point& p : from)
  {
    double best = HUGE_VAL;
    for (const Point& q : to)
    {
      best = std::min(best, Distance(p, q));
    }
    worst = std::max(worst, best);
  }
  return worst;
}

void Check(const std::string& name,
  vtkPolyData* mesh,
  double theta,
  const std::vector<Point>& exact,
  bool thin)
{
  Result r = Medial(mesh, theta, Backend);
  if (r.Mask.empty())
  {
    return;
  }
  const double h = r.Field->GetSpacing()[0];
  const double toExact = r.Marked.empty() ? HUGE_VAL : Directed(r.Marked, exact) / h;
  const double fromExact = r.Marked.empty() ? HUGE_VAL : Directed(exact, r.Marked) / h;
  int dims[3];
  r.Field->GetDimensions(dims);
  int64_t full = 0;
  for (int k = 1; k + 1 < dims[2]; ++k)
  {
    for (int j = 1; j + 1 < dims[1]; ++j)
    {
      for (int i = 1; i + 1 < dims[0]; ++i)
      {
        const int64_t v = i + int64_t(dims[0]) * (j + int64_t(dims[1]) * k);
        const int64_t sx = 1, sy = dims[0], sz = int64_t(dims[0]) * dims[1];
        full += r.Mask[v] && r.Mask[v - sx] && r.Mask[v + sx] && r.Mask[v - sy] && r.Mask[v + sy] &&
          r.Mask[v - sz] && r.Mask[v + sz];
      }
    }
  }
  std::printf("%-10s theta %5.1f %dx%dx%d: %zu medial voxels, Hausdorff %.2f (to the axis) / %.2f "
              "(from it) voxels, %lld with 6 medial neighbours\n",
    name.c_str(),
    theta,
    dims[0],
    dims[1],
    dims[2],
    r.Marked.size(),
    toExact,
    fromExact,
    (long long)full);
  if (!(toExact <= 1.5 && fromExact <= 1.5))
  {
    std::printf("FAIL: %s: Hausdorff distance above 1.5 voxels\n", name.c_str());
    ++testsupport::Failures;
  }
  if (thin && full > 0)
  {
    std::printf("FAIL: %s: %lld medial voxels are not thin\n", name.c_str(), (long long)full);
    ++testsupport::Failures;
  }
  if (r.Points != static_cast<vtkIdType>(r.Marked.size()))
  {
    std::printf("FAIL: %s: %lld points for %zu medial voxels\n",
      name.c_str(),
      (long long)r.Points,
      r.Marked.size());
    ++testsupport::Failures;
  }
  if (Backend == "gpu")
  {
    // From the mesh, the GPU keeps its own field on the GPU (scan, finalize and medial
    // pass there; its medial voxels passed the checks above on their own). Where two
    // sites are equally near (on the medial surface itself) it may pick the other one,
    // and the closest point jumps: reported, not compared.
    Result cpuRun = Medial(mesh, theta, "cpu");
    int64_t differ = 0;
    for (size_t v = 0; v < r.Mask.size() && v < cpuRun.Mask.size(); ++v)
    {
      differ += r.Mask[v] != cpuRun.Mask[v];
    }
    std::printf("%-10s GPU field and medial pass vs CPU: %lld of %zu voxels differ\n",
      name.c_str(),
      (long long)differ,
      cpuRun.Marked.size());
    if (cpuRun.Mask.size() != r.Mask.size())
    {
      std::printf("FAIL: %s: the GPU's own field has another grid\n", name.c_str());
      ++testsupport::Failures;
    }
    // The medial pass on both backends, from the same field (computed once, on the CPU:
    // the two backends' fields agree to 1e-5 spacing, not bit for bit).
    vtkNew<vtkLinearFactorDistanceField> field;
    field->SetInputData(mesh);
    field->ExplicitGridOn();
    field->SetGridOrigin(r.Field->GetOrigin());
    field->SetGridSpacing(r.Field->GetSpacing());
    field->SetGridDimensions(dims);
    field->SetSignModeToPseudoNormal();
    field->ComputeClosestPointOn();
    field->SetBackendToCPU();
    field->Update();
    std::vector<char> masks[2];
    for (int b = 0; b < 2; ++b)
    {
      vtkNew<vtkMedialAxisFilter> f;
      f->SetInputConnection(field->GetOutputPort());
      f->SetSeparationAngle(theta);
      if (b == 0)
      {
        f->SetBackendToGPU();
      }
      else
      {
        f->SetBackendToCPU();
      }
      f->Update();
      auto* medial =
        vtkUnsignedCharArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("Medial"));
      for (vtkIdType v = 0; medial && v < medial->GetNumberOfTuples(); ++v)
      {
        masks[b].push_back(medial->GetValue(v) != 0);
      }
    }
    if (masks[0].empty() || masks[0] != masks[1])
    {
      std::printf(
        "FAIL: %s: GPU and CPU mark different voxels from the same field\n", name.c_str());
      ++testsupport::Failures;
    }
  }
}
} // namespace

int main(int argc, char* argv[])
{
  Backend = argc > 1 ? argv[1] : "cpu";
  const double pi = 3.14159265358979323846;

  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(1);
    sphere->SetThetaResolution(96);
    sphere->SetPhiResolution(96);
    Check("sphere", Triangulated(sphere), 60, { Point{ 0, 0, 0 } }, true);
  }
  {
    // Box [-1,1] x [-0.7,0.7] x [-0.5,0.5]: the points whose two nearest faces are
    // equally near, at least two voxels deep (pairs within one spacing of the surface do
    // not count, so the discrete axis starts about 1.5 spacings deep).
    vtkNew<vtkCubeSource> box;
    box->SetXLength(2);
    box->SetYLength(1.4);
    box->SetZLength(1);
    auto mesh = Triangulated(box);
    const double half[3] = { 1, 0.7, 0.5 };
    const double h = 2.4 / 63, step = h / 4;
    std::vector<Point> exact;
    for (double x = -half[0]; x <= half[0]; x += step)
    {
      for (double y = -half[1]; y <= half[1]; y += step)
      {
        for (double z = -half[2]; z <= half[2]; z += step)
        {
          double d[6] = {
            x + half[0], half[0] - x, y + half[1], half[1] - y, z + half[2], half[2] - z
          };
          std::sort(d, d + 6);
          if (d[0] >= 3 * h && d[1] - d[0] <= step)
          {
            exact.push_back(Point{ x, y, z });
          }
        }
      }
    }
    Check("box", mesh, 60, exact, false);
    // Theta monotone: the set for 100 degrees within the set for 60.
    Result low = Medial(mesh, 60, Backend), high = Medial(mesh, 100, Backend);
    int64_t outside = 0;
    for (size_t v = 0; v < low.Mask.size() && v < high.Mask.size(); ++v)
    {
      outside += high.Mask[v] && !low.Mask[v];
    }
    std::printf(
      "box        theta 100 vs 60: %zu vs %zu medial voxels, %lld not in the larger set\n",
      high.Marked.size(),
      low.Marked.size(),
      (long long)outside);
    if (outside || high.Marked.empty() || high.Marked.size() >= low.Marked.size())
    {
      std::printf("FAIL: theta is not monotone\n");
      ++testsupport::Failures;
    }
  }
  {
    vtkNew<vtkCylinderSource> cylinder; // axis along y, radius 0.5, height 2
    cylinder->SetRadius(0.5);
    cylinder->SetHeight(2);
    cylinder->SetResolution(160);
    cylinder->CappingOn();
    std::vector<Point> exact;
    for (double y = -0.5; y <= 0.5; y += 0.005)
    {
      exact.push_back(Point{ 0, y, 0 });
    }
    // A 1D axis is seen by the pairs that straddle it: at 2 atan(h / 2 delta) for a pair
    // whose line passes at delta from it, only 90 degrees when it runs through the middle
    // of four lanes. This grid puts it between two voxels of a lane (180 degrees), so that
    // theta can exceed the 90 degrees of the cones between caps and side.
    const double h = 2.4 / 63;
    const Grid grid = { { -18.5 * h, -1.2, -18 * h }, { h, h, h }, { 38, 64, 37 } };
    ExplicitGrid = &grid;
    Check("cylinder", Triangulated(cylinder), 120, exact, true);
    ExplicitGrid = nullptr;
  }
  {
    vtkNew<vtkParametricTorus> torus;
    torus->SetRingRadius(1);
    torus->SetCrossSectionRadius(0.35);
    vtkNew<vtkParametricFunctionSource> source;
    source->SetParametricFunction(torus);
    source->SetUResolution(160);
    source->SetVResolution(64);
    std::vector<Point> exact;
    for (int s = 0; s < 1000; ++s)
    {
      const double t = 2 * pi * s / 1000;
      exact.push_back(Point{ std::cos(t), std::sin(t), 0 });
    }
    Check("torus", Triangulated(source), 120, exact, true);
  }
  return testsupport::Verdict();
}
