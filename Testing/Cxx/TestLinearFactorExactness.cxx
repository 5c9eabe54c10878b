// vtkLinearFactorDistanceField against an exact double-precision brute force over the
// input's cells, on every sample: distance, ClosestCellId, ClosestPoint, sign; every
// culling mode, anisotropic and explicit grids, streaming, GPU vs CPU.
//
// usage: TestLinearFactorExactness DATA_DIR cpu|gpu
#include "vtkLinearFactorDistanceField.h"

#include "TestSupport.h"

#include "ExactDistance.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace
{

/// Per cell: its primitives (triangles by fan, segments, points) in input coordinates.
struct Reference
{
  struct Primitive
  {
    int Kind; // 0 point, 1 segment, 2 triangle
    double P[3][3];
    vtkIdType Cell;
  };
  std::vector<Primitive> Primitives;
  vtkIdType NumCells = 0;

  explicit Reference(vtkPolyData* mesh)
  {
    vtkIdType cell = 0, n;
    const vtkIdType* ids;
    auto add = [&](int kind, std::initializer_list<vtkIdType> pts)
    {
      Primitive p{ kind, {}, cell };
      int k = 0;
      for (vtkIdType id : pts)
      {
        mesh->GetPoint(id, p.P[k++]);
      }
      this->Primitives.push_back(p);
    };
    for (mesh->GetVerts()->InitTraversal(); mesh->GetVerts()->GetNextCell(n, ids); ++cell)
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        add(0, { ids[i] });
      }
    }
    for (mesh->GetLines()->InitTraversal(); mesh->GetLines()->GetNextCell(n, ids); ++cell)
    {
      for (vtkIdType i = 0; i + 1 < n; ++i)
      {
        add(1, { ids[i], ids[i + 1] });
      }
    }
    for (mesh->GetPolys()->InitTraversal(); mesh->GetPolys()->GetNextCell(n, ids); ++cell)
    {
      for (vtkIdType i = 1; i + 1 < n; ++i)
      {
        add(2, { ids[0], ids[i], ids[i + 1] });
      }
    }
    for (mesh->GetStrips()->InitTraversal(); mesh->GetStrips()->GetNextCell(n, ids); ++cell)
    {
      for (vtkIdType i = 0; i + 2 < n; ++i)
      {
        add(2, { ids[i], ids[i + 1], ids[i + 2] });
      }
    }
    this->NumCells = cell;
  }

  /// The brute force at a grid's samples, kept for the next field on the same grid (the
  /// runs of one mesh share it: the test's cost is the brute force, not the filter).
  struct Samples
  {
    double Origin[3] = { 0, 0, 0 }, Spacing[3] = { 0, 0, 0 };
    int Extent[6] = { 0, -1, 0, -1, 0, -1 };
    std::vector<double> Best, Second;
    std::vector<vtkIdType> Cell;
    std::vector<signed char> Inside; // -1: not computed yet
    // The last closest point asked about at each sample, and its distance to the mesh.
    std::vector<float> Point;
    std::vector<double> OnMesh;
  };
  mutable Samples Cache;

  /// Cache ready for `field`'s grid: Best, Second and Cell filled at every sample.
  const Samples& AtSamples(vtkImageData* field) const
  {
    Samples& s = this->Cache;
    double origin[3], spacing[3];
    int extent[6];
    field->GetOrigin(origin);
    field->GetSpacing(spacing);
    field->GetExtent(extent);
    if (std::equal(origin, origin + 3, s.Origin) && std::equal(spacing, spacing + 3, s.Spacing) &&
      std::equal(extent, extent + 6, s.Extent) && !s.Best.empty())
    {
      return s;
    }
    std::copy(origin, origin + 3, s.Origin);
    std::copy(spacing, spacing + 3, s.Spacing);
    std::copy(extent, extent + 6, s.Extent);
    const vtkIdType n = field->GetNumberOfPoints();
    s.Best.assign(n, 0);
    s.Second.assign(n, 0);
    s.Cell.assign(n, -1);
    s.Inside.assign(n, -1);
    s.Point.assign(3 * n, NAN);
    s.OnMesh.assign(n, 0);
    vtkSMPTools::For(0,
      n,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          double x[3], closest[3];
          field->GetPoint(i, x);
          this->Query(x, s.Best[i], closest, s.Cell[i], s.Second[i]);
        }
      });
    return s;
  }

  /// Nearest distance and point, its cell, and the nearest distance of any other cell.
  void Query(const double x[3],
    double& best,
    double closest[3],
    vtkIdType& cell,
    double& secondBest) const
  {
    std::vector<double> perCell(this->NumCells, HUGE_VAL);
    best = HUGE_VAL;
    for (const Primitive& p : this->Primitives)
    {
      double c[3];
      if (p.Kind == 0)
      {
        std::copy(p.P[0], p.P[0] + 3, c);
      }
      else if (p.Kind == 1)
      {
        vtkdf::reference::ClosestOnSegment(x, p.P[0], p.P[1], c);
      }
      else
      {
        vtkdf::reference::ClosestOnTriangle(x, p.P[0], p.P[1], p.P[2], c);
      }
      const double d = std::sqrt((c[0] - x[0]) * (c[0] - x[0]) + (c[1] - x[1]) * (c[1] - x[1]) +
        (c[2] - x[2]) * (c[2] - x[2]));
      perCell[p.Cell] = std::min(perCell[p.Cell], d);
      if (d < best)
      {
        best = d;
        std::copy(c, c + 3, closest);
        cell = p.Cell;
      }
    }
    secondBest = HUGE_VAL;
    for (vtkIdType c = 0; c < this->NumCells; ++c)
    {
      if (c != cell)
      {
        secondBest = std::min(secondBest, perCell[c]);
      }
    }
  }

  /// Generalized winding number (sum of signed solid angles / 4 pi): exactly +-1 or 0
  /// away from the surface of a closed mesh.
  double Winding(const double x[3]) const
  {
    double total = 0;
    for (const Primitive& p : this->Primitives)
    {
      if (p.Kind != 2)
      {
        continue;
      }
      double a[3], b[3], c[3];
      for (int k = 0; k < 3; ++k)
      {
        a[k] = p.P[0][k] - x[k];
        b[k] = p.P[1][k] - x[k];
        c[k] = p.P[2][k] - x[k];
      }
      const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
      const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
      const double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
        a[2] * (b[0] * c[1] - b[1] * c[0]);
      const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      const double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
      const double ca = c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
      total += 2 * std::atan2(det, la * lb * lc + ab * lc + bc * la + ca * lb);
    }
    return total / (4 * M_PI);
  }
};

vtkSmartPointer<vtkPolyData> Load(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

vtkSmartPointer<vtkPolyData> Procedural(const std::string& name)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> verts, lines, polys;
  auto add = [&](double x, double y, double z) { return pts->InsertNextPoint(x, y, z); };
  if (name == "triangle")
  {
    const vtkIdType t[3] = { add(0, 0, 0), add(1, 0.2, 0.1), add(0.3, 0.9, -0.2) };
    polys->InsertNextCell(3, t);
  }
  else if (name == "segment")
  {
    const vtkIdType s[2] = { add(0, 0, 0), add(1, 0.7, 0.3) };
    lines->InsertNextCell(2, s);
  }
  else if (name == "point")
  {
    const vtkIdType v = add(0.2, 0.3, 0.4);
    verts->InsertNextCell(1, &v);
  }
  else if (name == "cube")
  {
    for (int k = 0; k < 8; ++k)
    {
      add(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    }
    const vtkIdType quads[6][4] = {
      { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 }
    };
    for (const auto& q : quads)
    {
      polys->InsertNextCell(4, q);
    }
  }
  else // "mixed": points, a polyline and a triangle strip and a quad
  {
    const vtkIdType v[2] = { add(0.9, 0.9, 0.9), add(0.1, 0.8, 0.2) };
    verts->InsertNextCell(2, v);
    const vtkIdType l[3] = { add(0, 0, 1), add(0.5, 0.2, 0.8), add(1, 0, 0.6) };
    lines->InsertNextCell(3, l);
    const vtkIdType q[4] = { add(0, 0, 0), add(1, 0, 0.1), add(1, 1, 0), add(0, 1, 0.2) };
    polys->InsertNextCell(4, q);
    vtkNew<vtkCellArray> strips;
    const vtkIdType s[5] = { add(0, 0.5, 0.5),
      add(0.2, 0.6, 0.4),
      add(0.1, 0.6, 0.7),
      add(0.3, 0.7, 0.6),
      add(0.2, 0.8, 0.9) };
    strips->InsertNextCell(5, s);
    mesh->SetStrips(strips);
  }
  mesh->SetPoints(pts);
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  mesh->SetPolys(polys);
  return mesh;
}

struct Options
{
  std::string Backend;
  int DomainShape = vtkLinearFactorDistanceField::DOMAIN_SHAPE_AUTO;
  int Route = vtkLinearFactorDistanceField::ROUTE_AUTO;
  bool Signed = false;
  int Resolution = 20;
  bool Explicit = false;
  double Origin[3], Spacing[3];
  int Dims[3];
  double MaximumDistance = 0;
};

vtkSmartPointer<vtkImageData> Run(vtkPolyData* mesh, const Options& o, const int* extent = nullptr)
{
  vtkNew<vtkLinearFactorDistanceField> f;
  f->SetInputData(mesh);
  if (o.Backend == "gpu")
  {
    f->SetBackendToGPU();
  }
  else
  {
    f->SetBackendToCPU();
  }
  f->SetDomainShape(o.DomainShape);
  f->SetRoute(o.Route);
  f->SetSignMode(o.Signed ? vtkLinearFactorDistanceField::PSEUDO_NORMAL
                          : vtkLinearFactorDistanceField::UNSIGNED);
  f->SetResolution(o.Resolution);
  if (o.Explicit)
  {
    f->ExplicitGridOn();
    f->SetGridOrigin(const_cast<double*>(o.Origin));
    f->SetGridSpacing(const_cast<double*>(o.Spacing));
    f->SetGridDimensions(const_cast<int*>(o.Dims));
  }
  f->SetMaximumDistance(o.MaximumDistance);
  f->ComputeClosestPointOn();
  f->ComputeClosestFeatureOn();
  if (extent)
  {
    f->UpdateInformation();
    f->UpdateExtent(extent);
  }
  else
  {
    f->Update();
  }
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(f->GetOutput());
  return out;
}

/// Compares a field with the brute force on every sample; returns the max error / h.
double Compare(const std::string& label, vtkImageData* field, const Reference& ref, bool checkSign)
{
  auto* distance = vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("Distance"));
  auto* cells = vtkIdTypeArray::SafeDownCast(field->GetPointData()->GetArray("ClosestCellId"));
  auto* points = vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("ClosestPoint"));
  CHECK(distance && cells && points, "%s: missing arrays", label.c_str());
  if (!distance || !cells || !points || field->GetNumberOfPoints() == 0)
  {
    return HUGE_VAL;
  }
  double spacing[3];
  field->GetSpacing(spacing);
  const double h = std::min(spacing[0], std::min(spacing[1], spacing[2]));
  const double tol = 1e-3 * h;
  // Per sample, in parallel (the brute force is the test's cost): the distance error, the
  // closest point's error where the nearest cell is unique (else -1), whether the cell id
  // is wrong there, and the sign (-1 not checked, 0 right, 1 wrong).
  const vtkIdType n = field->GetNumberOfPoints();
  std::vector<double> error(n), pointError(n, -1);
  std::vector<signed char> wrongCell(n, 0), wrongSign(n, -1);
  Reference::Samples& cache = ref.Cache;
  ref.AtSamples(field);
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        double x[3];
        field->GetPoint(i, x);
        const double best = cache.Best[i];
        const double value = distance->GetValue(i);
        error[i] = std::fabs(std::fabs(value) - best);
        // The closest point may be any of several at the same distance: check that it is
        // at the right distance from x and lies on the mesh (the brute force again, but
        // for the same point as the last field's).
        double cp[3];
        float* last = &cache.Point[3 * i];
        bool same = true;
        for (int a = 0; a < 3; ++a)
        {
          cp[a] = points->GetComponent(i, a);
          same = same && static_cast<float>(cp[a]) == last[a];
          last[a] = static_cast<float>(cp[a]);
        }
        if (!same)
        {
          double unused[3], unusedSecond;
          vtkIdType unusedCell;
          ref.Query(cp, cache.OnMesh[i], unused, unusedCell, unusedSecond);
        }
        if (cache.Second[i] - best > tol)
        {
          wrongCell[i] = cells->GetValue(i) != cache.Cell[i];
          pointError[i] = std::max(
            cache.OnMesh[i], std::fabs(std::sqrt(vtkMath::Distance2BetweenPoints(cp, x)) - best));
        }
        if (checkSign && best > tol)
        {
          if (cache.Inside[i] < 0)
          {
            cache.Inside[i] = std::fabs(ref.Winding(x)) > 0.5;
          }
          wrongSign[i] = (cache.Inside[i] == 1) != (value < 0);
        }
      }
    });
  double worst = 0, worstPoint = 0;
  vtkIdType wrongCells = 0, wrongSigns = 0, signChecked = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    worst = std::max(worst, error[i]);
    worstPoint = std::max(worstPoint, pointError[i]);
    wrongCells += wrongCell[i];
    wrongSigns += wrongSign[i] == 1;
    signChecked += wrongSign[i] >= 0;
  }
  std::printf("%-44s max|err| %.2e h, closest point %.2e h, wrong cell ids %lld%s\n",
    label.c_str(),
    worst / h,
    worstPoint / h,
    (long long)wrongCells,
    checkSign
      ? (", wrong signs " + std::to_string(wrongSigns) + "/" + std::to_string(signChecked)).c_str()
      : "");
  CHECK(worst <= tol, "%s: distance error %g h", label.c_str(), worst / h);
  CHECK(worstPoint <= tol, "%s: closest point error %g h", label.c_str(), worstPoint / h);
  CHECK(wrongCells == 0, "%s: %lld wrong ClosestCellId", label.c_str(), (long long)wrongCells);
  CHECK(wrongSigns == 0, "%s: %lld wrong signs", label.c_str(), (long long)wrongSigns);
  return worst / h;
}
/// A narrow band (MaximumDistance = cap): within the band the exact field; beyond it
/// exactly cap (-cap inside a closed mesh) and no closest cell.
void CompareBanded(const std::string& label,
  vtkImageData* field,
  const Reference& ref,
  double cap,
  bool checkSign)
{
  auto* distance = vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("Distance"));
  auto* cells = vtkIdTypeArray::SafeDownCast(field->GetPointData()->GetArray("ClosestCellId"));
  CHECK(distance && cells && field->GetNumberOfPoints() > 0, "%s: missing arrays", label.c_str());
  if (!distance || !cells)
  {
    return;
  }
  const double h = field->GetSpacing()[0];
  const double tol = 1e-3 * h;
  double worst = 0;
  vtkIdType beyond = 0, wrongCap = 0, wrongSigns = 0, wrongCells = 0;
  Reference::Samples& cache = ref.Cache;
  ref.AtSamples(field);
  for (vtkIdType i = 0; i < field->GetNumberOfPoints(); ++i)
  {
    double x[3];
    field->GetPoint(i, x);
    const double best = cache.Best[i];
    const float value = distance->GetValue(i);
    worst = std::max(worst, std::fabs(std::fabs(value) - std::min(best, cap)));
    if (best > cap + tol)
    {
      ++beyond;
      wrongCap += std::fabs(value) != static_cast<float>(cap);
      wrongCells += cells->GetValue(i) != -1;
    }
    if (checkSign && best > tol)
    {
      if (cache.Inside[i] < 0)
      {
        cache.Inside[i] = std::fabs(ref.Winding(x)) > 0.5;
      }
      wrongSigns += (cache.Inside[i] == 1) != (value < 0);
    }
  }
  std::printf("%-44s max|err| %.2e h, %lld samples beyond the band, %lld not at the cap, "
              "%lld with a cell, %lld wrong signs\n",
    label.c_str(),
    worst / h,
    (long long)beyond,
    (long long)wrongCap,
    (long long)wrongCells,
    (long long)wrongSigns);
  CHECK(worst <= tol, "%s: distance error %g h", label.c_str(), worst / h);
  CHECK(beyond > 0, "%s: the band covers the whole grid, the test proves nothing", label.c_str());
  CHECK(wrongCap == 0,
    "%s: %lld samples beyond the band differ from the cap",
    label.c_str(),
    (long long)wrongCap);
  CHECK(wrongCells == 0,
    "%s: %lld samples beyond the band have a cell",
    label.c_str(),
    (long long)wrongCells);
  CHECK(wrongSigns == 0, "%s: %lld wrong signs", label.c_str(), (long long)wrongSigns);
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR cpu|gpu"))
  {
    return 2;
  }
  const std::string data = argv[1];
  Options base;
  base.Backend = argv[2];
  if (base.Backend == "gpu")
  {
    // Every check below needs the GPU's field; without a context there is none to check.
    vtkNew<vtkLinearFactorDistanceField> probe;
    probe->SetInputData(vtkdf::testing::Triangle());
    probe->SetBackendToGPU();
    probe->SetResolution(4);
    probe->Update();
    if (std::string(probe->GetLastBackend()) != "gpu")
    {
      std::printf("FAIL: the field could not run on the GPU (see the error above)\n");
      return 1;
    }
  }
  struct Case
  {
    std::string Name;
    vtkSmartPointer<vtkPolyData> Mesh;
    bool Closed;
  };
  std::vector<Case> cases;
  for (const char* name :
    { "bunny_small", "teapot", "scad_back_to_back", "boeing_soup", "scad_zero_area" })
  {
    cases.push_back({ name,
      Load(data + "/" + name + ".vtp"),
      std::string(name) == "bunny_small" || std::string(name) == "scad_zero_area" });
  }
  for (const char* name : { "triangle", "segment", "point", "cube", "mixed" })
  {
    cases.push_back({ name, Procedural(name), std::string(name) == "cube" });
  }
  const char* cullingNames[] = { "auto", "nonmanifold", "manifold" };
  std::vector<std::unique_ptr<Reference>> references;
  for (const Case& c : cases)
  {
    CHECK(c.Mesh && c.Mesh->GetNumberOfCells() > 0, "%s: could not load", c.Name.c_str());
    references.push_back(std::make_unique<Reference>(c.Mesh));
    const Reference& ref = *references.back();
    for (int culling = 0; culling < 3; ++culling)
    {
      Options o = base;
      o.DomainShape = culling;
      o.Signed = c.Closed;
      Compare(
        c.Name + " " + base.Backend + " " + cullingNames[culling], Run(c.Mesh, o), ref, c.Closed);
    }
    if (base.Backend == "cpu")
    {
      // The per-sample queries instead of the scan (what Auto takes for a fine mesh on a
      // coarse grid).
      Options o = base;
      o.Route = vtkLinearFactorDistanceField::ROUTE_SAMPLE_QUERIES;
      o.Signed = c.Closed;
      Compare(c.Name + " cpu sample queries", Run(c.Mesh, o), ref, c.Closed);
    }
  }

  // Anisotropic explicit grid that does not contain the whole mesh.
  {
    const Case& c = cases[0];
    Options o = base;
    o.Explicit = true;
    const double origin[3] = { -6, -1, -3 }, spacing[3] = { 0.61, 0.47, 0.83 };
    const int dims[3] = { 17, 19, 9 };
    std::copy(origin, origin + 3, o.Origin);
    std::copy(spacing, spacing + 3, o.Spacing);
    std::copy(dims, dims + 3, o.Dims);
    o.Signed = true;
    Compare("bunny_small anisotropic explicit grid", Run(c.Mesh, o), Reference(c.Mesh), true);
  }

  // Narrow band: signed on a closed mesh (the sign beyond the band comes from the flood
  // fill), unsigned on an open one.
  for (int index : { 0, 1 })
  {
    const Case& c = cases[index];
    double b[6];
    c.Mesh->GetBounds(b);
    Options o = base;
    o.Signed = c.Closed;
    o.MaximumDistance = 0.08 *
      std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
        (b[5] - b[4]) * (b[5] - b[4]));
    CompareBanded(c.Name + " " + base.Backend + " MaximumDistance",
      Run(c.Mesh, o),
      *references[index],
      o.MaximumDistance,
      c.Closed);
    if (base.Backend == "cpu")
    {
      o.Route = vtkLinearFactorDistanceField::ROUTE_SAMPLE_QUERIES;
      CompareBanded(c.Name + " cpu sample queries MaximumDistance",
        Run(c.Mesh, o),
        *references[index],
        o.MaximumDistance,
        c.Closed);
    }
  }

  // Streaming: three sub-extents computed alone equal the whole.
  {
    const Case& c = cases[1];
    Options o = base;
    auto whole = Run(c.Mesh, o);
    int w[6];
    whole->GetExtent(w);
    const int cuts[4] = { w[4], w[5] / 3, 2 * w[5] / 3, w[5] };
    vtkIdType mismatches = 0;
    for (int part = 0; part < 3; ++part)
    {
      int e[6] = { w[0] + part,
        w[1] - 1,
        w[2],
        w[3] - part,
        part == 0 ? cuts[0] : cuts[part] + 1,
        cuts[part + 1] };
      auto piece = Run(c.Mesh, o, e);
      int got[6];
      piece->GetExtent(got);
      CHECK(std::equal(e, e + 6, got), "streaming piece %d has the wrong extent", part);
      for (int k = got[4]; k <= got[5]; ++k)
      {
        for (int j = got[2]; j <= got[3]; ++j)
        {
          for (int i = got[0]; i <= got[1]; ++i)
          {
            const float a = piece->GetScalarComponentAsFloat(i, j, k, 0);
            const float b = whole->GetScalarComponentAsFloat(i, j, k, 0);
            // Ties go to the lower site on both backends: the same bits.
            mismatches += !(a == b);
          }
        }
      }
    }
    std::printf("streaming (teapot, 3 sub-extents): %lld samples differ from the whole\n",
      (long long)mismatches);
    CHECK(mismatches == 0, "streaming: %lld samples differ", (long long)mismatches);
  }

  // The GPU's arrays are the CPU's, bit for bit (run only from the GPU test, which has
  // both): every case, domain shape and sign, a narrow band, an explicit grid and
  // sub-extents.
  if (base.Backend == "gpu")
  {
    auto same = [](const std::string& label, const Options& o, const int* extent = nullptr)
    {
      Options cpu = o;
      cpu.Backend = "cpu";
      // The CPU's scan: its per-sample queries (which Auto may take for a band) break
      // ties between a face and its edge at equal distance their own way.
      cpu.Route = vtkLinearFactorDistanceField::ROUTE_SITE_SCAN;
      return [label, o, cpu, extent](vtkPolyData* mesh)
      {
        auto a = Run(mesh, o, extent);
        auto b = Run(mesh, cpu, extent);
        const int arrays = a->GetPointData()->GetNumberOfArrays();
        CHECK(arrays == b->GetPointData()->GetNumberOfArrays() && arrays >= 4,
          "%s: %d arrays on the GPU",
          label.c_str(),
          arrays);
        vtkIdType differ = 0;
        for (int n = 0; n < arrays; ++n)
        {
          vtkDataArray* x = a->GetPointData()->GetArray(n);
          vtkDataArray* y = b->GetPointData()->GetArray(x->GetName());
          CHECK(y && y->GetDataType() == x->GetDataType() &&
              y->GetNumberOfValues() == x->GetNumberOfValues(),
            "%s: array %s differs in shape",
            label.c_str(),
            x->GetName());
          if (!y || y->GetNumberOfValues() != x->GetNumberOfValues())
          {
            continue;
          }
          const int size = x->GetDataTypeSize() * x->GetNumberOfComponents();
          for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t)
          {
            if (std::memcmp(x->GetVoidPointer(t * x->GetNumberOfComponents()),
                  y->GetVoidPointer(t * x->GetNumberOfComponents()),
                  size) != 0 &&
              ++differ <= 3)
            {
              std::printf("  %s, tuple %lld: GPU %.9g, CPU %.9g\n",
                x->GetName(),
                (long long)t,
                x->GetComponent(t, 0),
                y->GetComponent(t, 0));
            }
          }
        }
        std::printf("%-44s GPU vs CPU: %lld tuples differ\n", label.c_str(), (long long)differ);
        CHECK(differ == 0,
          "%s: %lld tuples differ between GPU and CPU",
          label.c_str(),
          (long long)differ);
      };
    };
    for (const Case& c : cases)
    {
      for (int culling = 0; culling < 3; ++culling)
      {
        for (bool sign : { false, true })
        {
          Options o = base;
          o.Resolution = 28;
          o.DomainShape = culling;
          o.Signed = sign;
          same(c.Name + " " + cullingNames[culling] + (sign ? " signed" : " unsigned"), o)(c.Mesh);
        }
      }
    }
    Options banded = base;
    banded.Signed = true;
    double b[6];
    cases[0].Mesh->GetBounds(b);
    banded.MaximumDistance = 0.05 * (b[1] - b[0]);
    same("bunny_small signed MaximumDistance", banded)(cases[0].Mesh);
    Options explicitGrid = base;
    explicitGrid.Explicit = true;
    const double origin[3] = { -6, -1, -3 }, spacing[3] = { 0.61, 0.47, 0.83 };
    const int dims[3] = { 17, 19, 9 };
    std::copy(origin, origin + 3, explicitGrid.Origin);
    std::copy(spacing, spacing + 3, explicitGrid.Spacing);
    std::copy(dims, dims + 3, explicitGrid.Dims);
    explicitGrid.Signed = true;
    same("bunny_small explicit grid", explicitGrid)(cases[0].Mesh);
    int w[6];
    Run(cases[1].Mesh, base)->GetExtent(w);
    const int piece[6] = { w[0] + 1, w[1] - 2, w[2] + 2, w[3] - 1, w[4] + 1, (w[4] + w[5]) / 2 };
    same("teapot sub-extent", base, piece)(cases[1].Mesh);
  }
  return vtkdf::testing::Verdict();
}
