// libFuzzer target: bytes -> a small mesh, a grid and filter properties (valid or not)
// -> vtkLinearFactorDistanceField, vtkPolyDataVoxelizer, vtkChamferVoxelDistance,
// vtkMedialAxisFilter and vtkSegmentedDistanceField (and its vtkSegmentedDistanceContour)
// on the CPU backend. Built with clang,
// -fsanitize=fuzzer,address, undefined (Testing/run-fuzz.sh). A crash, a sanitizer report, a leak
// or a broken invariant of a successful output (below) is a finding; an error reported by a filter
// is the expected answer to bad input.
#include "vtkChamferVoxelDistance.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkMedialAxisFilter.h"
#include "vtkPolyDataVoxelizer.h"
#include "vtkSegmentedDistanceContour.h"
#include "vtkSegmentedDistanceField.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace
{
/// Reads the fuzzer's bytes; zeros once they run out.
class Bytes
{
public:
  Bytes(const uint8_t* data, size_t size)
    : Data(data)
    , Size(size)
  {
  }
  uint8_t U8() { return this->At < this->Size ? this->Data[this->At++] : 0; }
  int8_t S8() { return static_cast<int8_t>(this->U8()); }
  double Raw()
  {
    uint64_t bits = 0;
    for (int i = 0; i < 8; ++i)
    {
      bits |= uint64_t(this->U8()) << (8 * i);
    }
    double value;
    std::memcpy(&value, &bits, sizeof(value));
    return value;
  }
  /// One of `values`, or (index past them) a raw double.
  template<size_t N>
  double Pick(const double (&values)[N])
  {
    const uint8_t index = this->U8() % (N + 1);
    return index < N ? values[index] : this->Raw();
  }
  /// A coordinate: mostly a small multiple of 1/8, sometimes NaN, infinite, huge or raw.
  double Coordinate()
  {
    const uint8_t kind = this->U8() % 16;
    switch (kind)
    {
      case 12:
        return std::numeric_limits<double>::quiet_NaN();
      case 13:
        return std::numeric_limits<double>::infinity();
      case 14:
        return 1e30 * this->S8();
      case 15:
        return this->Raw();
      default:
        return 0.125 * this->S8();
    }
  }

private:
  const uint8_t* Data;
  size_t Size;
  size_t At = 0;
};

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
constexpr double Inf = std::numeric_limits<double>::infinity();

void Trap(bool holds)
{
  if (!holds)
  {
    __builtin_trap(); // a broken invariant: a finding
  }
}

void Configure(vtkDistanceFieldAlgorithm* filter, vtkPolyData* mesh, Bytes& in)
{
  filter->SetInputData(mesh);
  filter->SetBackendToCPU();
  filter->SetResolution(in.S8() % 16);
  const double paddings[] = { 0.1, 0, 0.5, 1e-9, -1, NaN, Inf, 1e308 };
  filter->SetPadding(in.Pick(paddings));
  if (in.U8() & 1)
  {
    const double spacings[] = { 0.25, 1, 0.01, 3, 0, -1, NaN, Inf, 1e-40, 1e30 };
    filter->ExplicitGridOn();
    filter->SetGridOrigin(in.Coordinate(), in.Coordinate(), in.Coordinate());
    filter->SetGridSpacing(in.Pick(spacings), in.Pick(spacings), in.Pick(spacings));
    filter->SetGridDimensions(in.S8() % 12, in.S8() % 12, in.S8() % 12);
  }
  // Small limits too: the memory check must refuse, not crash.
  const double limits[] = { 0, 0, 1e9, 100, -1, NaN };
  filter->SetMemoryLimit(in.Pick(limits));
}

/// Whether the filter succeeded with an output (its invariants are then checked).
bool Succeeded(vtkDistanceFieldAlgorithm* filter)
{
  filter->Update();
  vtkImageData* output = filter->GetOutput();
  if (filter->GetErrorCode() != 0)
  {
    Trap(output->GetNumberOfPoints() == 0); // a failed run leaves no output
    return false;
  }
  return output->GetNumberOfPoints() > 0;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const bool quiet = []()
  {
    vtkObject::GlobalWarningDisplayOff();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    return true;
  }();
  (void)quiet;
  Bytes in(data, size);

  // The mesh: up to 16 points, up to 8 cells of any kind with any ids.
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const int numPoints = in.U8() % 17;
  for (int i = 0; i < numPoints; ++i)
  {
    points->InsertNextPoint(in.Coordinate(), in.Coordinate(), in.Coordinate());
  }
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  vtkCellArray* kinds[4] = { verts, lines, polys, strips };
  const int numCells = in.U8() % 9;
  for (int c = 0; c < numCells; ++c)
  {
    const uint8_t kind = in.U8() % 4;
    const int count = in.U8() % 7;
    vtkIdType ids[6];
    for (int k = 0; k < count; ++k)
    {
      // Mostly valid ids; sometimes negative or past the end.
      const int8_t raw = in.S8();
      ids[k] = raw >= 0 && numPoints > 0 ? raw % numPoints : raw;
    }
    kinds[kind]->InsertNextCell(count, ids);
  }
  mesh->SetPoints(points);
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  mesh->SetPolys(polys);
  mesh->SetStrips(strips);
  // ClosestCellId names a cell, or a point of a mesh without cells (a point cloud, whose
  // points are the sites).
  const vtkIdType cells = mesh->GetNumberOfCells();
  const vtkIdType sites = cells > 0 ? cells : mesh->GetNumberOfPoints();

  {
    vtkNew<vtkLinearFactorDistanceField> filter;
    Configure(filter, mesh, in);
    const double caps[] = { 0, 0, 0.5, 3, 1e-300, -1, NaN, Inf };
    filter->SetMaximumDistance(in.Pick(caps));
    filter->SetSignMode(in.U8() % 3);
    filter->SetDomainShape(in.U8() % 4);
    filter->SetRoute(in.U8() % 4); // Auto, SiteScan, SampleQueries, or invalid
    filter->ComputeClosestFeatureOn();
    filter->ComputeClosestPointOn();
    if (Succeeded(filter))
    {
      vtkPointData* pd = filter->GetOutput()->GetPointData();
      vtkDataArray* distance = pd->GetArray("Distance");
      vtkDataArray* ids = pd->GetArray("ClosestCellId");
      for (vtkIdType v = 0; v < distance->GetNumberOfTuples(); ++v)
      {
        Trap(std::isfinite(distance->GetTuple1(v)));
        const double id = ids->GetTuple1(v);
        Trap(id >= -1 && id < sites);
      }
    }
  }
  {
    vtkNew<vtkPolyDataVoxelizer> filter;
    Configure(filter, mesh, in);
    filter->SetMode(in.U8() % 4);
    if (Succeeded(filter))
    {
      vtkPointData* pd = filter->GetOutput()->GetPointData();
      for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
      {
        const double* range = pd->GetArray(a)->GetRange();
        Trap(range[0] >= 0 && range[1] <= 1);
      }
    }
  }
  {
    vtkNew<vtkChamferVoxelDistance> filter;
    Configure(filter, mesh, in);
    filter->SetMetric(in.U8() % 4);
    filter->SetMaximumLayers(in.S8());
    filter->SetSigned(in.U8() & 1);
    if (Succeeded(filter))
    {
      vtkImageData* output = filter->GetOutput();
      const double unreached = output->GetFieldData()->GetArray("UnreachedValue")->GetTuple1(0);
      const double* range = output->GetPointData()->GetArray("ChamferDistance")->GetRange();
      Trap(range[0] >= -unreached && range[1] <= unreached);
    }
  }
  {
    vtkNew<vtkMedialAxisFilter> filter;
    Configure(filter, mesh, in);
    const double angles[] = { 90, 120, 45, 170, 0, 180, NaN };
    filter->SetSeparationAngle(in.Pick(angles));
    filter->SetRegion(in.U8() % 4);
    if (Succeeded(filter))
    {
      const double* range = filter->GetOutput()->GetPointData()->GetArray("Medial")->GetRange();
      Trap(range[0] >= 0 && range[1] <= 1);
      Trap(filter->GetMedialPoints()->GetNumberOfPoints() == filter->GetLastMedialCount());
    }
  }
  {
    vtkNew<vtkSegmentedDistanceField> filter;
    Configure(filter, mesh, in);
    const double lengths[] = { 0, 1, 0.5, 4, -1, Inf, NaN };
    filter->SetDelta(in.Pick(lengths));
    filter->SetRegionOffset(in.Pick(lengths));
    if (Succeeded(filter))
    {
      // Every sample in a region, and f = min(d, Delta) + RegionOffset * r to float's
      // precision.
      vtkImageData* output = filter->GetOutput();
      vtkPointData* pd = output->GetPointData();
      vtkDataArray* f = pd->GetArray("SegmentedDistance");
      vtkDataArray* r = pd->GetArray("RegionIndex");
      vtkDataArray* d = pd->GetArray("Distance");
      const double delta = output->GetFieldData()->GetArray("Delta")->GetTuple1(0);
      const double offset = output->GetFieldData()->GetArray("RegionOffset")->GetTuple1(0);
      for (vtkIdType v = 0; v < f->GetNumberOfTuples(); ++v)
      {
        const double region = r->GetTuple1(v);
        Trap(region >= 0 && region < filter->GetLastRegionCount());
        const double expected = std::min(d->GetTuple1(v), delta) + offset * region;
        Trap(std::fabs(f->GetTuple1(v) - expected) <=
          1e-6 * std::fabs(expected) + std::numeric_limits<float>::denorm_min());
      }
      // Its surface, vertices from the closest points: finite points within the grid
      // grown by two spacings (a feature point may lie past its cell), valid ids.
      vtkNew<vtkSegmentedDistanceContour> contour;
      contour->SetInputData(output);
      const double featureAngles[] = { 30, 1, 180, 90 };
      contour->SetFeatureAngle(in.Pick(featureAngles));
      contour->Update();
      vtkPolyData* surface = contour->GetOutput();
      double bounds[6];
      output->GetBounds(bounds);
      const double* h = output->GetSpacing();
      for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
      {
        double x[3];
        surface->GetPoint(p, x);
        for (int a = 0; a < 3; ++a)
        {
          Trap(x[a] >= bounds[2 * a] - 2 * h[a] && x[a] <= bounds[2 * a + 1] + 2 * h[a]);
        }
      }
      vtkIdType count = 0;
      const vtkIdType* ids = nullptr;
      vtkCellArray* polys = surface->GetPolys();
      for (polys->InitTraversal(); polys->GetNextCell(count, ids);)
      {
        Trap(count == 3);
        for (vtkIdType k = 0; k < count; ++k)
        {
          Trap(ids[k] >= 0 && ids[k] < surface->GetNumberOfPoints());
        }
      }
    }
  }
  return 0;
}
