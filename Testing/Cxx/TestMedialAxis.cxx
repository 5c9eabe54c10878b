// vtkMedialAxisFilter on analytic shapes, rotated by arbitrary angles and offset by
// fractions of a voxel from the grid, compared with their exact medial axes. For each
// shape and theta there are two exact sets: what must be found (every point of it within
// a tolerance of a medial voxel) and what may be found (every medial voxel within the
// tolerance of it); they differ where the true separation angle equals theta.
// - capped cylinder (radius R, half-length L): its axis |z| <= L - R must be found at
//   theta 100, 120 and 150 (1.5 voxels), and at theta >= 120 nothing else may be (the
//   cones between caps and side, true separation 90 degrees, are gone);
// - sphere: its centre found at theta 120, 150 and 170 (sqrt(3) voxels), nothing else;
// - torus: its core circle at theta 60, 90 and 120 (1.5 voxels);
// - box: its bisector planes (90 degrees between adjacent faces, 180 between opposite
//   ones) at theta 60, 90 and 120, those at least 3 spacings deep must be found;
// - the outside of the box and of the sphere (convex: no medial axis): nothing, at theta
//   30, 60 and 90, however near the surface (the fan test of MedialAxis.h).
// Also: thinness (no medial voxel with all 6 neighbours medial) on the sphere, cylinder
// and torus, theta monotone (the set for a larger theta is a subset), one output point
// per medial voxel, and on the GPU the same voxels as on the CPU from the same field.
//
// usage: TestMedialAxis cpu|gpu [PLACEMENTS]: the first PLACEMENTS of the three placements
// (rotation and offset) of every shape (all three by default).
#include "vtkLinearFactorDistanceField.h"

#include "TestSupport.h"
#include "vtkMedialAxisFilter.h"

#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace
{
std::string Backend = "cpu";
using Point = std::array<double, 3>;

double Distance(const Point& a, const Point& b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/// Points in buckets of a given size, for nearest-point queries up to 3 bucket sizes.
class PointSet
{
public:
  PointSet(const std::vector<Point>& points, double bucket)
    : Size(bucket)
    , Points(points)
  {
    for (size_t i = 0; i < points.size(); ++i)
    {
      this->Buckets[this->Key(points[i], 0, 0, 0)].push_back(i);
    }
  }

  /// The distance from p to the nearest point, or HUGE_VAL when none lies within 3 sizes.
  double Nearest(const Point& p) const
  {
    double best = HUGE_VAL;
    for (int dz = -3; dz <= 3; ++dz)
    {
      for (int dy = -3; dy <= 3; ++dy)
      {
        for (int dx = -3; dx <= 3; ++dx)
        {
          auto it = this->Buckets.find(this->Key(p, dx, dy, dz));
          if (it == this->Buckets.end())
          {
            continue;
          }
          for (size_t i : it->second)
          {
            best = std::min(best, Distance(p, this->Points[i]));
          }
        }
      }
    }
    return best <= 3 * this->Size ? best : HUGE_VAL;
  }

  /// The largest distance from a point of `from` to this set (HUGE_VAL: beyond 3 sizes).
  double Directed(const std::vector<Point>& from) const
  {
    double worst = 0;
    for (const Point& p : from)
    {
      worst = std::max(worst, this->Nearest(p));
    }
    return worst;
  }

private:
  std::array<long long, 3> Key(const Point& p, int dx, int dy, int dz) const
  {
    return { static_cast<long long>(std::floor(p[0] / this->Size)) + dx,
      static_cast<long long>(std::floor(p[1] / this->Size)) + dy,
      static_cast<long long>(std::floor(p[2] / this->Size)) + dz };
  }
  double Size;
  std::vector<Point> Points;
  std::map<std::array<long long, 3>, std::vector<size_t>> Buckets;
};

/// A shape in its own frame, placed by a rotation and a translation.
struct Placement
{
  vtkNew<vtkTransform> Transform;
  Point Apply(const Point& p) const
  {
    Point q;
    this->Transform->TransformPoint(p.data(), q.data());
    return q;
  }
};

vtkSmartPointer<vtkPolyData> Placed(vtkAlgorithm* source, const Placement& placement)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkTransformPolyDataFilter> moved;
  moved->SetInputConnection(triangles->GetOutputPort());
  moved->SetTransform(placement.Transform);
  moved->Update();
  return moved->GetOutput();
}

/// The signed field with closest points on a grid of spacing h around the mesh, its
/// origin offset by `offset` spacings (fractions: the grid falls anywhere). Computed on
/// the CPU, so that both backends' medial passes start from the same field.
vtkSmartPointer<vtkImageData> Field(vtkPolyData* mesh, double h, const double offset[3])
{
  double b[6];
  mesh->GetBounds(b);
  double origin[3];
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = (std::floor(b[2 * a] / h) - 3 + offset[a]) * h;
    dims[a] = static_cast<int>(std::ceil((b[2 * a + 1] - origin[a]) / h)) + 4;
  }
  vtkNew<vtkLinearFactorDistanceField> field;
  field->SetInputData(mesh);
  field->ExplicitGridOn();
  field->SetGridOrigin(origin);
  field->SetGridSpacing(h, h, h);
  field->SetGridDimensions(dims);
  field->SetSignModeToPseudoNormal();
  field->ComputeClosestPointOn();
  field->SetBackendToCPU(); // the medial pass is under test (the GPU's field: see main)
  field->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(field->GetOutput());
  return image;
}

struct Result
{
  std::vector<Point> Marked;
  std::vector<char> Mask;
  std::vector<float> Angle;
  vtkIdType Points = 0;
  int Dims[3] = { 0, 0, 0 };
};

Result Medial(vtkImageData* field, double theta, bool inside, const std::string& backend)
{
  vtkNew<vtkMedialAxisFilter> f;
  f->SetInputData(field);
  f->SetSeparationAngle(theta);
  if (inside)
  {
    f->SetRegionToInside();
  }
  else
  {
    f->SetRegionToOutside();
  }
  vtkdf::testing::UseBackend(f.GetPointer(), backend);
  f->Update();
  Result r;
  vtkImageData* out = f->GetOutput();
  out->GetDimensions(r.Dims);
  r.Points = f->GetMedialPoints()->GetNumberOfPoints();
  auto* medial = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("Medial"));
  if (!medial || std::string(f->GetLastBackend()) != backend)
  {
    std::printf("FAIL: no Medial array, or not run on %s\n", backend.c_str());
    ++vtkdf::testing::Failures;
    return r;
  }
  r.Mask.resize(medial->GetNumberOfTuples());
  vtkDataArray* angle = out->GetPointData()->GetArray("SeparationAngle");
  for (vtkIdType v = 0; angle && v < angle->GetNumberOfTuples(); ++v)
  {
    r.Angle.push_back(static_cast<float>(angle->GetTuple1(v)));
  }
  for (vtkIdType v = 0; v < medial->GetNumberOfTuples(); ++v)
  {
    r.Mask[v] = medial->GetValue(v) != 0;
    if (r.Mask[v])
    {
      Point p;
      out->GetPoint(v, p.data());
      r.Marked.push_back(p);
    }
  }
  return r;
}

/// Medial voxels with all 6 face neighbours medial.
int64_t Thick(const Result& r)
{
  const int* n = r.Dims;
  const int64_t sx = 1, sy = n[0], sz = int64_t(n[0]) * n[1];
  int64_t full = 0;
  for (int k = 1; k + 1 < n[2]; ++k)
  {
    for (int j = 1; j + 1 < n[1]; ++j)
    {
      for (int i = 1; i + 1 < n[0]; ++i)
      {
        const int64_t v = i + sy * j + sz * k;
        full += r.Mask[v] && r.Mask[v - sx] && r.Mask[v + sx] && r.Mask[v - sy] && r.Mask[v + sy] &&
          r.Mask[v - sz] && r.Mask[v + sz];
      }
    }
  }
  return full;
}

/// One shape on one grid at several thetas: what must and may be found, in voxels.
struct Expectation
{
  double Theta;
  std::vector<Point> Must; // every point within Tolerance of a medial voxel
  std::vector<Point> May;  // every medial voxel within Tolerance of a point (empty: none)
  bool CheckMay = true;
};

void Check(const std::string& name,
  vtkImageData* field,
  double h,
  double tolerance,
  bool inside,
  bool thin,
  const std::vector<Expectation>& cases)
{
  std::vector<char> previous;
  double previousTheta = 0;
  for (const Expectation& e : cases)
  {
    Result r = Medial(field, e.Theta, inside, Backend);
    if (r.Mask.empty())
    {
      return;
    }
    const double found =
      e.Must.empty() ? 0 : PointSet(r.Marked, 2 * h).Directed(e.Must) / h; // from the axis
    const double stray = !e.CheckMay ? 0
      : r.Marked.empty()             ? 0
      : e.May.empty()                ? HUGE_VAL
                                     : PointSet(e.May, 2 * h).Directed(r.Marked) / h;
    const int64_t thick = Thick(r);
    std::printf("%-16s theta %5.1f %3dx%3dx%3d: %6zu medial voxels; exact axis to them %.2f, "
                "them to the axis %s voxels; %lld with 6 medial neighbours\n",
      name.c_str(),
      e.Theta,
      r.Dims[0],
      r.Dims[1],
      r.Dims[2],
      r.Marked.size(),
      found,
      !e.CheckMay           ? "(not checked)"
        : stray == HUGE_VAL ? "> 6"
                            : std::to_string(stray).substr(0, 4).c_str(),
      (long long)thick);
    if (!(found <= tolerance))
    {
      std::printf("FAIL: %s theta %g: part of the exact axis is farther than %.2f voxels from "
                  "every medial voxel\n",
        name.c_str(),
        e.Theta,
        tolerance);
      ++vtkdf::testing::Failures;
    }
    if (e.CheckMay && !(stray <= tolerance))
    {
      std::printf("FAIL: %s theta %g: medial voxels farther than %.2f voxels from the exact "
                  "axis\n",
        name.c_str(),
        e.Theta,
        tolerance);
      ++vtkdf::testing::Failures;
    }
    if (thin && thick > 0)
    {
      std::printf("FAIL: %s theta %g: %lld medial voxels are not thin\n",
        name.c_str(),
        e.Theta,
        (long long)thick);
      ++vtkdf::testing::Failures;
    }
    if (r.Points != static_cast<vtkIdType>(r.Marked.size()))
    {
      std::printf("FAIL: %s: %lld points for %zu medial voxels\n",
        name.c_str(),
        (long long)r.Points,
        r.Marked.size());
      ++vtkdf::testing::Failures;
    }
    // Theta monotone: this (larger) theta keeps a subset of the previous one's voxels.
    if (!previous.empty() && e.Theta > previousTheta)
    {
      int64_t outside = 0;
      for (size_t v = 0; v < previous.size(); ++v)
      {
        outside += r.Mask[v] && !previous[v];
      }
      if (outside)
      {
        std::printf("FAIL: %s: %lld voxels medial at theta %g but not at %g\n",
          name.c_str(),
          (long long)outside,
          e.Theta,
          previousTheta);
        ++vtkdf::testing::Failures;
      }
    }
    previous = r.Mask;
    previousTheta = e.Theta;
    // Both backends' medial pass from the same field mark the same voxels, with the same
    // apertures (the same double arithmetic).
    if (Backend == "gpu")
    {
      const Result cpu = Medial(field, e.Theta, inside, "cpu");
      if (cpu.Mask != r.Mask || cpu.Angle != r.Angle || r.Angle.size() != r.Mask.size())
      {
        size_t differ = 0, first = 0;
        for (size_t v = cpu.Mask.size(); v-- > 0;)
        {
          const bool same = v < r.Mask.size() && v < r.Angle.size() && v < cpu.Angle.size() &&
            cpu.Mask[v] == r.Mask[v] && cpu.Angle[v] == r.Angle[v];
          differ += same ? 0 : 1;
          first = same ? first : v;
        }
        std::printf("FAIL: %s theta %g: GPU and CPU mark different voxels or apertures from "
                    "the same field (%zu voxels; the first, %zu: medial %d / %d, angle %.9g / "
                    "%.9g, GPU / CPU)\n",
          name.c_str(),
          e.Theta,
          differ,
          first,
          first < r.Mask.size() ? int(r.Mask[first]) : -1,
          int(cpu.Mask[first]),
          first < r.Angle.size() ? r.Angle[first] : -1.0f,
          first < cpu.Angle.size() ? cpu.Angle[first] : -1.0f);
        ++vtkdf::testing::Failures;
      }
    }
  }
}

/// Grid offsets, in spacings, and rotations (degrees about x, y, z) that put the shapes
/// nowhere special.
const double Offsets[3][3] = { { 0.13, 0.71, 0.42 }, { 0.5, 0.5, 0.5 }, { 0.87, 0.29, 0.06 } };
const double Rotations[3][3] = { { 23, 41, 67 }, { 0, 0, 0 }, { 71, 13, 29 } };

void Place(Placement& p, int variant)
{
  p.Transform->PostMultiply();
  p.Transform->RotateX(Rotations[variant][0]);
  p.Transform->RotateY(Rotations[variant][1]);
  p.Transform->RotateZ(Rotations[variant][2]);
  p.Transform->Translate(0.011 * variant, -0.007 * variant, 0.003 * variant);
}

/// The medial set of the box [-a, a] (half sizes `half`), sampled at `step`: points whose
/// two nearest faces are equally near (within step), with the angle between those
/// faces' normals (90 or 180 degrees) at least `least`, and at least `depth` deep.
std::vector<Point> BoxAxis(const double half[3], double step, double least, double depth)
{
  std::vector<Point> points;
  for (double x = -half[0]; x <= half[0]; x += step)
  {
    for (double y = -half[1]; y <= half[1]; y += step)
    {
      for (double z = -half[2]; z <= half[2]; z += step)
      {
        const double p[3] = { x, y, z };
        std::array<std::pair<double, int>, 6> d;
        for (int a = 0; a < 3; ++a)
        {
          d[2 * a] = { p[a] + half[a], a };
          d[2 * a + 1] = { half[a] - p[a], a };
        }
        std::sort(d.begin(), d.end());
        if (d[0].first < depth || d[1].first - d[0].first > step)
        {
          continue;
        }
        // Opposite faces (one axis): 180 degrees; adjacent ones: 90. Where a third face
        // is as near, either pair.
        double separation = d[0].second == d[1].second ? 180 : 90;
        if (d[2].first - d[0].first <= step)
        {
          separation = std::max(separation,
            std::max(d[0].second == d[2].second ? 180.0 : 90.0,
              d[1].second == d[2].second ? 180.0 : 90.0));
        }
        if (separation >= least)
        {
          points.push_back(Point{ x, y, z });
        }
      }
    }
  }
  return points;
}

std::vector<Point> Transformed(const std::vector<Point>& points, const Placement& placement)
{
  std::vector<Point> out;
  for (const Point& p : points)
  {
    out.push_back(placement.Apply(p));
  }
  return out;
}
} // namespace

int main(int argc, char* argv[])
{
  Backend = argc > 1 ? argv[1] : "cpu";
  const int placements = argc > 2 ? std::atoi(argv[2]) : 3;
  const double pi = 3.14159265358979323846;
  const double h = 0.025;

  for (int variant = 0; variant < placements && variant < 3; ++variant)
  {
    const std::string tag = "#" + std::to_string(variant);
    Placement placement;
    Place(placement, variant);
    const double* offset = Offsets[variant];
    {
      // The capped cylinder a new user tried: radius 0.3, half-length 0.6 (axis z).
      const double R = 0.3, L = 0.6;
      vtkNew<vtkCylinderSource> source; // axis y
      source->SetRadius(R);
      source->SetHeight(2 * L);
      source->SetResolution(160);
      source->CappingOn();
      Placement along;
      along.Transform->PostMultiply();
      along.Transform->RotateX(90); // y to z
      along.Transform->Concatenate(placement.Transform);
      auto mesh = Placed(source, along);
      std::vector<Point> axis;
      for (double z = -(L - R); z <= L - R + 1e-12; z += 0.1 * h)
      {
        axis.push_back(along.Apply(Point{ 0, z, 0 }));
      }
      auto field = Field(mesh, h, offset);
      Check("cylinder " + tag,
        field,
        h,
        1.5,
        true,
        true,
        { { 100, axis, {}, false }, { 120, axis, axis }, { 150, axis, axis } });
    }
    {
      vtkNew<vtkSphereSource> source;
      source->SetRadius(0.5);
      source->SetThetaResolution(96);
      source->SetPhiResolution(96);
      auto mesh = Placed(source, placement);
      const std::vector<Point> centre = { placement.Apply(Point{ 0, 0, 0 }) };
      auto field = Field(mesh, h, offset);
      Check("sphere " + tag,
        field,
        h,
        std::sqrt(3.0),
        true,
        true,
        { { 120, centre, centre }, { 150, centre, centre }, { 170, centre, centre } });
      Check("sphere outside " + tag,
        field,
        h,
        0,
        false,
        true,
        { { 30, {}, {} }, { 60, {}, {} }, { 90, {}, {} } });
    }
    {
      vtkNew<vtkParametricTorus> torus;
      torus->SetRingRadius(0.6);
      torus->SetCrossSectionRadius(0.2);
      vtkNew<vtkParametricFunctionSource> source;
      source->SetParametricFunction(torus);
      source->SetUResolution(160);
      source->SetVResolution(64);
      auto mesh = Placed(source, placement);
      std::vector<Point> circle;
      for (int s = 0; s < 2000; ++s)
      {
        const double t = 2 * pi * s / 2000;
        circle.push_back(placement.Apply(Point{ 0.6 * std::cos(t), 0.6 * std::sin(t), 0 }));
      }
      auto field = Field(mesh, h, offset);
      Check("torus " + tag,
        field,
        h,
        1.5,
        true,
        true,
        { { 60, circle, circle }, { 90, circle, circle }, { 120, circle, circle } });
    }
    {
      const double half[3] = { 0.6, 0.45, 0.3 };
      vtkNew<vtkCubeSource> source;
      source->SetXLength(2 * half[0]);
      source->SetYLength(2 * half[1]);
      source->SetZLength(2 * half[2]);
      auto mesh = Placed(source, placement);
      const double step = h / 4;
      // At theta 90 the planes between adjacent faces (exactly 90 degrees) may or may
      // not be found; those deeper than 3 spacings with more than theta must be.
      auto field = Field(mesh, h, offset);
      Check("box " + tag,
        field,
        h,
        1.5,
        true,
        false,
        { { 60,
            Transformed(BoxAxis(half, step, 90, 3 * h), placement),
            Transformed(BoxAxis(half, step, 90, 0), placement) },
          { 90,
            Transformed(BoxAxis(half, step, 180, 3 * h), placement),
            Transformed(BoxAxis(half, step, 90, 0), placement) },
          { 120,
            Transformed(BoxAxis(half, step, 180, 3 * h), placement),
            Transformed(BoxAxis(half, step, 180, 0), placement) } });
      Check("box outside " + tag,
        field,
        h,
        0,
        false,
        true,
        { { 30, {}, {} }, { 60, {}, {} }, { 90, {}, {} } });
    }
  }

  // From the mesh, the GPU keeps its own field on the GPU (scan, finalize and medial
  // pass there): the CPU's arithmetic throughout, so every array equals the CPU
  // backend's, bit for bit, and the centre is found.
  {
    vtkNew<vtkSphereSource> source;
    source->SetRadius(0.5);
    source->SetThetaResolution(64);
    source->SetPhiResolution(64);
    Placement placement;
    Place(placement, 0);
    auto mesh = Placed(source, placement);
    const Point centre = placement.Apply(Point{ 0, 0, 0 });
    std::vector<std::string> bytes[2];
    int64_t count = 0;
    for (int b = 0; b < 2; ++b)
    {
      vtkNew<vtkMedialAxisFilter> f;
      f->SetInputData(mesh);
      f->SetResolution(48);
      f->SetSeparationAngle(150);
      vtkdf::testing::UseBackend(f.GetPointer(), b == 0 ? Backend : "cpu");
      f->Update();
      for (const char* name : { "Medial", "SeparationAngle", "Radius" })
      {
        vtkDataArray* array = f->GetOutput()->GetPointData()->GetArray(name);
        bytes[b].push_back(array ? std::string(static_cast<const char*>(array->GetVoidPointer(0)),
                                     array->GetNumberOfTuples() * array->GetDataTypeSize())
                                 : std::string());
      }
      auto* medial =
        vtkUnsignedCharArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("Medial"));
      const double spacing = f->GetOutput()->GetSpacing()[0];
      double worst = 0;
      count = 0;
      for (vtkIdType v = 0; medial && v < medial->GetNumberOfTuples(); ++v)
      {
        if (medial->GetValue(v) != 0)
        {
          ++count;
          Point p;
          f->GetOutput()->GetPoint(v, p.data());
          worst = std::max(worst, Distance(p, centre) / spacing);
        }
      }
      if (b == 0)
      {
        std::printf("sphere from the mesh on the %s: %lld medial voxels, the farthest %.2f "
                    "voxels from the centre\n",
          Backend.c_str(),
          static_cast<long long>(count),
          worst);
        if (!medial || count == 0 || !(worst <= std::sqrt(3.0)))
        {
          std::printf("FAIL: the sphere's centre from the mesh\n");
          ++vtkdf::testing::Failures;
        }
      }
    }
    const char* names[3] = { "Medial", "SeparationAngle", "Radius" };
    for (int a = 0; a < 3; ++a)
    {
      if (bytes[0][a].empty() || bytes[0][a] != bytes[1][a])
      {
        std::printf("FAIL: sphere from the mesh: the %s's %s array is not the CPU's\n",
          Backend.c_str(),
          names[a]);
        ++vtkdf::testing::Failures;
      }
    }
  }
  return vtkdf::testing::Verdict();
}
