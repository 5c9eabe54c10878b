// Scale invariance of every filter (issue: results must not depend on the user's unit).
// usage: TestScaleInvariance DATA_DIR linfac|linfac-queries|voxelize|chamfer|medial cpu|gpu
//
// The trefoil knot and its default grid are scaled by k. For k = 2^100 and 2^-100 every
// output must be exactly k times the unscaled one (distances, closest points, radii) or
// the same (ids, features, masks, layers, medial marks), bit for bit: the cores work in
// the grid's frame, scaled by a power of two, and such a scaling is exact in IEEE
// arithmetic. For k = 10^-30 ... 10^30 distances must equal k times the unscaled ones
// within 1e-3 of a spacing, and discrete outputs may differ only at ties, which are
// counted and checked to be ties: two cells equally near (within 1e-3 h), a voxel
// centre at half a cell diagonal from the mesh (within 1e-9 relative), a solid voxel
// next to the surface, a medial pair at the angle threshold or between equal radii.
// On the GPU, at 1 and 2^+-100, every array also equals the CPU backend's, bit for bit.
#include "vtkCell.h"
#include "vtkChamferVoxelDistance.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkMath.h"
#include "vtkMedialAxisFilter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataVoxelizer.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include "ExactDistance.h"
#include "Medial/MedialAxis.h"
#include "TestSupport.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace
{
constexpr int Resolution = 32;

vtkSmartPointer<vtkPolyData> Scaled(vtkPolyData* mesh, double k)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(mesh);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double x[3];
    mesh->GetPoint(i, x);
    points->SetPoint(i, k * x[0], k * x[1], k * x[2]);
  }
  out->SetPoints(points);
  return out;
}

/// Exact distance from x to the mesh's cell `cell` (triangles), or to the whole mesh.
double CellDistance(vtkPolyData* mesh, vtkIdType cell, const double x[3])
{
  double best = HUGE_VAL;
  const vtkIdType first = cell < 0 ? 0 : cell,
                  last = cell < 0 ? mesh->GetNumberOfCells() : cell + 1;
  for (vtkIdType c = first; c < last; ++c)
  {
    vtkCell* triangle = mesh->GetCell(c);
    double p[3][3], q[3];
    for (int v = 0; v < 3; ++v)
    {
      mesh->GetPoint(triangle->GetPointId(v), p[v]);
    }
    vtkdf::reference::ClosestOnTriangle(x, p[0], p[1], p[2], q);
    best = std::min(best, std::sqrt(vtkMath::Distance2BetweenPoints(x, q)));
  }
  return best;
}

struct Output
{
  vtkSmartPointer<vtkImageData> Image;
  vtkDataArray* Get(const char* name) const { return this->Image->GetPointData()->GetArray(name); }
};

template<typename Filter>
void Configure(Filter* filter, vtkPolyData* mesh, const std::string& backend)
{
  filter->SetInputData(mesh);
  filter->SetResolution(Resolution);
  vtkdf::testing::UseBackend(filter, backend);
}

Output LinearFactor(vtkPolyData* mesh, const std::string& backend, int route)
{
  vtkNew<vtkLinearFactorDistanceField> filter;
  Configure(filter.Get(), mesh, backend);
  filter->SetRoute(route);
  filter->SetSignModeToPseudoNormal();
  filter->ComputeClosestFeatureOn();
  filter->ComputeClosestPointOn();
  filter->Update();
  return { filter->GetOutput() };
}

Output Run(const std::string& name, vtkPolyData* mesh, const std::string& backend)
{
  if (name == "linfac" || name == "linfac-queries")
  {
    return LinearFactor(mesh,
      backend,
      name == "linfac-queries" ? vtkLinearFactorDistanceField::ROUTE_SAMPLE_QUERIES
                               : vtkLinearFactorDistanceField::ROUTE_AUTO);
  }
  if (name == "voxelize")
  {
    vtkNew<vtkPolyDataVoxelizer> filter;
    Configure(filter.Get(), mesh, backend);
    filter->Update();
    return { filter->GetOutput() };
  }
  if (name == "chamfer")
  {
    vtkNew<vtkChamferVoxelDistance> filter;
    Configure(filter.Get(), mesh, backend);
    filter->SignedOn();
    filter->OutputMasksOn();
    filter->Update();
    return { filter->GetOutput() };
  }
  vtkNew<vtkMedialAxisFilter> filter;
  Configure(filter.Get(), mesh, backend);
  filter->Update();
  return { filter->GetOutput() };
}

/// Arrays whose values scale with k (distances, points) and arrays that must not change.
struct Arrays
{
  std::vector<const char*> Scaling, Discrete;
};
Arrays ArraysOf(const std::string& name)
{
  if (name == "linfac" || name == "linfac-queries")
  {
    return { { "Distance", "ClosestPoint" }, { "ClosestCellId", "ClosestFeature" } };
  }
  if (name == "voxelize")
  {
    return { {}, { "Boundary", "Solid" } };
  }
  if (name == "chamfer")
  {
    return { {}, { "ChamferDistance", "Boundary", "Solid" } };
  }
  return { { "Radius" }, { "Medial", "SeparationAngle" } };
}

/// A GPU run's every array equal to the CPU backend's, bit for bit (linfac: the CPU's
/// scan, the route the GPU takes).
void CheckSameAsCPU(const std::string& name, vtkPolyData* mesh, const Output& gpu, double k)
{
  const Output cpu = name == "linfac"
    ? LinearFactor(mesh, "cpu", vtkLinearFactorDistanceField::ROUTE_SITE_SCAN)
    : Run(name, mesh, "cpu");
  const Arrays arrays = ArraysOf(name);
  for (const auto* list : { &arrays.Scaling, &arrays.Discrete })
  {
    for (const char* array : *list)
    {
      vtkDataArray* a = gpu.Get(array);
      vtkDataArray* b = cpu.Get(array);
      const bool same = a && b && a->GetDataType() == b->GetDataType() &&
        a->GetNumberOfTuples() == b->GetNumberOfTuples() &&
        a->GetNumberOfComponents() == b->GetNumberOfComponents() &&
        std::memcmp(a->GetVoidPointer(0),
          b->GetVoidPointer(0),
          a->GetNumberOfValues() * a->GetDataTypeSize()) == 0;
      CHECK(same, "scale %g: the GPU's %s is not the CPU backend's", k, array);
    }
  }
}

/// The world position of sample v of `image`.
void Position(vtkImageData* image, vtkIdType v, double x[3])
{
  image->GetPoint(v, x);
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(
        argc, argv, 3, "DATA_DIR linfac|linfac-queries|voxelize|chamfer|medial cpu|gpu"))
  {
    return 2;
  }
  const std::string name = argv[2], backend = argv[3];
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((std::string(argv[1]) + "/trefoil_knot.vtp").c_str());
  reader->Update();
  vtkPolyData* mesh = reader->GetOutput();

  const Output base = Run(name, mesh, backend);
  CHECK(base.Image->GetNumberOfPoints() > 0, "the unscaled run produced no output");
  if (vtkdf::testing::Failures)
  {
    return vtkdf::testing::Verdict();
  }
  if (backend == "gpu")
  {
    CheckSameAsCPU(name, mesh, base, 1);
  }
  const double h = base.Image->GetSpacing()[0];
  const vtkIdType n = base.Image->GetNumberOfPoints();
  const Arrays arrays = ArraysOf(name);
  // For the medial ties: the field the medial filter computes, at scale 1.
  Output baseField;
  if (name == "medial")
  {
    baseField = LinearFactor(mesh, backend, vtkLinearFactorDistanceField::ROUTE_AUTO);
  }

  const double scales[] = {
    std::ldexp(1.0, 100), std::ldexp(1.0, -100), 1e-30, 1e-20, 1e-10, 1e10, 1e20, 1e30
  };
  for (const double k : scales)
  {
    int exponent;
    const bool exact = std::frexp(k, &exponent) == 0.5; // a power of two
    vtkSmartPointer<vtkPolyData> scaled = Scaled(mesh, k);
    const Output out = Run(name, scaled, backend);
    if (backend == "gpu" && exact)
    {
      CheckSameAsCPU(name, scaled, out, k);
    }
    CHECK(out.Image->GetNumberOfPoints() == n,
      "scale %g: %lld samples instead of %lld",
      k,
      static_cast<long long>(out.Image->GetNumberOfPoints()),
      static_cast<long long>(n));
    if (out.Image->GetNumberOfPoints() != n)
    {
      continue;
    }
    CHECK(std::fabs(out.Image->GetSpacing()[0] / k - h) <= 1e-12 * h,
      "scale %g: spacing %g",
      k,
      out.Image->GetSpacing()[0]);

    // Distances and points: k times, exactly or within 1e-3 h; a point may also move at a tie.
    double largest = 0;
    vtkIdType pointTies = 0;
    for (const char* array : arrays.Scaling)
    {
      vtkDataArray* a0 = base.Get(array);
      vtkDataArray* a1 = out.Get(array);
      const int components = a0->GetNumberOfComponents();
      vtkIdType inexact = 0;
      double arrayLargest = 0;
      for (vtkIdType v = 0; v < n; ++v)
      {
        for (int c = 0; c < components; ++c)
        {
          const double x0 = a0->GetComponent(v, c), x1 = a1->GetComponent(v, c);
          // float(x0) * float(k) is exact for a power of two within float's range.
          inexact +=
            exact && static_cast<float>(x1) != static_cast<float>(x0) * static_cast<float>(k);
          const double error = std::fabs(x1 / k - x0) / h;
          if (components == 3 && error > 1e-3)
          {
            // A closest point may jump between two equally near cells.
            double x[3];
            Position(base.Image, v, x);
            vtkDataArray* ids0 = base.Get("ClosestCellId");
            vtkDataArray* ids1 = out.Get("ClosestCellId");
            const double d0 = CellDistance(mesh, static_cast<vtkIdType>(ids0->GetTuple1(v)), x);
            const double d1 = CellDistance(mesh, static_cast<vtkIdType>(ids1->GetTuple1(v)), x);
            CHECK(std::fabs(d0 - d1) <= 1e-3 * h,
              "scale %g: %s of sample %lld moved %g h without a tie",
              k,
              array,
              static_cast<long long>(v),
              error);
            pointTies += c == 0;
            continue;
          }
          arrayLargest = std::max(arrayLargest, error);
        }
      }
      CHECK(inexact == 0,
        "scale %g: %lld values of %s are not exactly k times the unscaled ones",
        k,
        static_cast<long long>(inexact),
        array);
      if (components == 1) // distances; a closest point away from a tie is checked above
      {
        largest = std::max(largest, arrayLargest);
      }
    }
    CHECK(largest <= 1e-3, "scale %g: largest distance error %g h (at most 1e-3)", k, largest);

    // Discrete outputs: equal, or (not for a power of two) different at ties only.
    vtkIdType ties = 0;
    bool masksEqual = true;
    if (name == "chamfer")
    {
      for (vtkIdType u = 0; u < n && masksEqual; ++u)
      {
        masksEqual = base.Get("Boundary")->GetTuple1(u) == out.Get("Boundary")->GetTuple1(u) &&
          base.Get("Solid")->GetTuple1(u) == out.Get("Solid")->GetTuple1(u);
      }
    }
    for (const char* array : arrays.Discrete)
    {
      vtkDataArray* a0 = base.Get(array);
      vtkDataArray* a1 = out.Get(array);
      for (vtkIdType v = 0; v < n; ++v)
      {
        if (a0->GetTuple1(v) == a1->GetTuple1(v))
        {
          continue;
        }
        // A cell's aperture comes from float closest points through a cap of up to three
        // of them: where both scales mark the voxel, it may move by rounding (near 180
        // degrees, acos turns 1e-7 in the cosine into 0.03 degrees).
        if (std::string(array) == "SeparationAngle" && a0->GetTuple1(v) > 0 &&
          a1->GetTuple1(v) > 0 && std::fabs(a0->GetTuple1(v) - a1->GetTuple1(v)) <= 0.05)
        {
          continue;
        }
        CHECK(!exact, "scale %g: %s differs at sample %lld", k, array, static_cast<long long>(v));
        if (exact)
        {
          break;
        }
        double x[3];
        Position(base.Image, v, x);
        const std::string a = array;
        bool tie = false;
        if (a == "ClosestCellId" || a == "ClosestFeature")
        {
          const double d0 =
            CellDistance(mesh, static_cast<vtkIdType>(base.Get("ClosestCellId")->GetTuple1(v)), x);
          const double d1 =
            CellDistance(mesh, static_cast<vtkIdType>(out.Get("ClosestCellId")->GetTuple1(v)), x);
          // Also a feature flip at the same point (a face site against its own edge).
          tie = std::fabs(d0 - d1) <= 1e-3 * h;
        }
        else if (a == "Boundary")
        {
          const double limit = 0.5 * std::sqrt(3.0) * h;
          tie = std::fabs(CellDistance(mesh, -1, x) - limit) <= 1e-9 * limit;
        }
        else if (a == "Solid")
        {
          tie = CellDistance(mesh, -1, x) <= 0.5 * h;
        }
        else if (a == "ChamferDistance")
        {
          // Layers follow the masks: with equal masks they must be equal.
          tie = !masksEqual;
        }
        else // Medial, SeparationAngle: a cell of v at the threshold, at the fan bound, or
             // with two largest |distance| equal
        {
          const Output& f0 = baseField;
          int dims[3];
          base.Image->GetDimensions(dims);
          const vtkIdType stride[3] = { 1, dims[0], vtkIdType(dims[0]) * dims[1] };
          const int ijk[3] = { static_cast<int>(v % dims[0]),
            static_cast<int>((v / dims[0]) % dims[1]),
            static_cast<int>(v / stride[2]) };
          auto* cp = vtkFloatArray::SafeDownCast(f0.Get("ClosestPoint"));
          auto* dist = f0.Get("Distance");
          const double threshold = std::cos(90.0 * M_PI / 180.0);
          for (int o = 0; o < 8 && !tie; ++o)
          {
            const int lo[3] = { ijk[0] - (o & 1), ijk[1] - ((o >> 1) & 1), ijk[2] - (o >> 2) };
            if (lo[0] < 0 || lo[1] < 0 || lo[2] < 0 || lo[0] + 1 >= dims[0] ||
              lo[1] + 1 >= dims[1] || lo[2] + 1 >= dims[2])
            {
              continue;
            }
            float d[8];
            const float* closest[8];
            double corner[8][3];
            for (int k = 0; k < 8; ++k)
            {
              const vtkIdType id = (lo[0] + (k & 1)) + (lo[1] + ((k >> 1) & 1)) * stride[1] +
                (lo[2] + (k >> 2)) * stride[2];
              d[k] = static_cast<float>(dist->GetTuple1(id));
              closest[k] = cp->GetPointer(3 * id);
              Position(base.Image, id, corner[k]);
            }
            const int marked = vtkdf::MarkedCorner(d, vtkdf::MedialRegion::Inside);
            for (int k = 0; k < 8 && marked >= 0; ++k)
            {
              tie = tie ||
                (k != marked && std::fabs(std::fabs(d[k]) - std::fabs(d[marked])) <= 1e-3 * h);
            }
            const double* spacing = base.Image->GetSpacing();
            const vtkdf::MedialCellMeasure cell = vtkdf::MeasureMedialCell(d,
              closest,
              corner,
              0.5 *
                std::sqrt(
                  spacing[0] * spacing[0] + spacing[1] * spacing[1] + spacing[2] * spacing[2]));
            tie = tie || std::fabs(cell.Cosine - threshold) <= 1e-3 ||
              std::fabs(cell.Reach - vtkdf::MedialFanMargin) <= 1e-3;
          }
        }
        CHECK(tie,
          "scale %g: %s differs at sample %lld, which is not a tie",
          k,
          array,
          static_cast<long long>(v));
        ties += tie;
      }
    }
    std::printf("scale %-8g: largest distance error %.3g h, %lld discrete values and %lld closest "
                "points differ at ties%s\n",
      k,
      largest,
      static_cast<long long>(ties),
      static_cast<long long>(pointTies),
      exact ? " (power of two: bit for bit)" : "");
  }
  return vtkdf::testing::Verdict();
}
