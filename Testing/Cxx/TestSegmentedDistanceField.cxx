// vtkSegmentedDistanceField on shapes built here, each at several generic offsets of the
// grid:
// - a closed sphere: 2 regions, inside and outside;
// - two disjoint spheres: 3 (one outside, two insides);
// - an open disk: 2 (front and back meet only across the boundary);
// - a T-junction of three half-planes (a "Y" of unequal angles, one sector reflex): 3,
//   each sector one region;
// - two strips crossing without sharing an edge (CutSelfIntersections cuts them along
//   the crossing): 4, one per sector (uncut: fewer, printed); and a plane across a
//   T-junction's line, which CGAL refuses to cut: a warning, and the uncut field;
// - a closed box with an inner wall (non-manifold junction lines): 3, the outside leaking
//   into neither chamber;
// and, for every sample clear of the sheets, that it lies in the region of its part of
// space as the geometry says (the layout, not only the count).
// The result does not depend on the thread count (sequential and threaded runs equal)
// nor on the order of the triangles (shuffled: the same partition of the samples). The
// GPU run (argument gpu) must give the CPU's regions (none tied here) and SegmentedDistance
// within 1e-3 spacings; on bundled meshes (bunny_small, teapot, plane, scad_back_to_back,
// max3ds_export at 40 samples across), where the GPU computes the side labels where its
// field lies (SegmentFieldGPU) and the CPU from its arrays, every array the same bytes.
//
// usage: TestSegmentedDistanceField cpu|gpu [DATA_DIR]
#include "TestSupport.h"
#include "vtkSegmentedDistanceField.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace
{
std::string Backend = "cpu";

/// A mesh from quads (split into two triangles each) and triangles.
struct Builder
{
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Polys;
  vtkIdType Point(double x, double y, double z) { return this->Points->InsertNextPoint(x, y, z); }
  void Quad(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType d)
  {
    const vtkIdType t0[3] = { a, b, c }, t1[3] = { a, c, d };
    this->Polys->InsertNextCell(3, t0);
    this->Polys->InsertNextCell(3, t1);
  }
  vtkSmartPointer<vtkPolyData> Mesh()
  {
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    mesh->SetPoints(this->Points);
    mesh->SetPolys(this->Polys);
    return mesh;
  }
};

vtkSmartPointer<vtkPolyData> Sphere(double cx, double radius)
{
  vtkNew<vtkSphereSource> source;
  source->SetCenter(cx, 0.1, -0.05);
  source->SetRadius(radius);
  source->SetThetaResolution(24);
  source->SetPhiResolution(16);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

/// A flat disk of radius 1 in the plane z = 0.03, as a fan of quads and triangles.
vtkSmartPointer<vtkPolyData> Disk()
{
  Builder b;
  const int n = 24;
  const vtkIdType centre = b.Point(0, 0, 0.03);
  std::vector<vtkIdType> inner, outer;
  for (int k = 0; k < n; ++k)
  {
    const double a = 2 * M_PI * k / n;
    inner.push_back(b.Point(0.5 * std::cos(a), 0.5 * std::sin(a), 0.03));
    outer.push_back(b.Point(std::cos(a), std::sin(a), 0.03));
  }
  for (int k = 0; k < n; ++k)
  {
    const vtkIdType t[3] = { centre, inner[k], inner[(k + 1) % n] };
    b.Polys->InsertNextCell(3, t);
    b.Quad(inner[k], outer[k], outer[(k + 1) % n], inner[(k + 1) % n]);
  }
  return b.Mesh();
}

/// Three half-planes meeting along the z axis at the angles below (sectors of 70, 70 and
/// a reflex 220 degrees), each a strip of quads of radial length 1 and height 2. The shared
/// points are separate ids: they merge by position.
const double Angles[3] = { 0.1, 0.1 + 70 * M_PI / 180, 0.1 + 140 * M_PI / 180 };
vtkSmartPointer<vtkPolyData> Junction()
{
  Builder b;
  for (const double a : Angles)
  {
    const double c = std::cos(a), s = std::sin(a);
    for (int i = 0; i < 4; ++i)
    {
      const double r0 = i / 4.0, r1 = (i + 1) / 4.0;
      b.Quad(b.Point(r0 * c, r0 * s, -1),
        b.Point(r1 * c, r1 * s, -1),
        b.Point(r1 * c, r1 * s, 1),
        b.Point(r0 * c, r0 * s, 1));
    }
  }
  return b.Mesh();
}

/// Two strips that cross along the z axis without sharing an edge or a point there (the
/// teapot's spout through its body): planes at angles CrossAngles[0] and [1] through the
/// z axis, |along| <= 1, |z| <= 1, five quads along each, so the crossing runs through
/// the middle quads' interiors. Cut along the crossing (CutSelfIntersections), they are
/// four half-planes meeting at a junction line.
const double CrossAngles[2] = { 0.1, 0.1 + 75 * M_PI / 180 };
vtkSmartPointer<vtkPolyData> CrossedStrips()
{
  Builder b;
  for (const double a : CrossAngles)
  {
    const double c = std::cos(a), s = std::sin(a);
    for (int i = 0; i < 5; ++i)
    {
      const double r0 = -1 + 0.4 * i, r1 = r0 + 0.4;
      b.Quad(b.Point(r0 * c, r0 * s, -1),
        b.Point(r1 * c, r1 * s, -1),
        b.Point(r1 * c, r1 * s, 1),
        b.Point(r0 * c, r0 * s, 1));
    }
  }
  return b.Mesh();
}

/// The sector (0, 1, ...) of half-planes at `angles` (ascending, through the z axis, out
/// to radius 1, |z| <= 1) that holds (x, y, z), or -1 within `clear` of a half-plane or
/// outside their extent.
int Sector(double x, double y, double z, const std::vector<double>& angles, double clear)
{
  const double r = std::sqrt(x * x + y * y);
  if (r > 1 - clear || std::fabs(z) > 1 - clear)
  {
    return -1;
  }
  const size_t n = angles.size();
  for (const double angle : angles)
  {
    // Distance to the half-plane: to its line when in front of it, else to the axis.
    const double c = std::cos(angle), s = std::sin(angle);
    const double along = x * c + y * s;
    const double distance = along > 0 ? std::fabs(-x * s + y * c) : r;
    if (distance < clear)
    {
      return -1;
    }
  }
  const double a = std::atan2(y, x);
  for (size_t k = 0; k < n; ++k)
  {
    double a0 = angles[k], a1 = angles[(k + 1) % n], t = a;
    if (a1 < a0)
    {
      a1 += 2 * M_PI;
    }
    while (t < a0)
    {
      t += 2 * M_PI;
    }
    if (t < a1)
    {
      return static_cast<int>(k);
    }
  }
  return -1;
}

/// The box [-1, 1]^3 (outward) with a wall at x = Wall across it: the faces y = +-1 and
/// z = +-1 are split at x = Wall, so that the wall's edges are junction lines.
constexpr double Wall = 0.13;
vtkSmartPointer<vtkPolyData> WalledBox()
{
  Builder b;
  const double xs[3] = { -1, Wall, 1 };
  // y = -1 and y = +1, z = -1 and z = +1: two quads each, outward.
  for (int i = 0; i < 2; ++i)
  {
    const double x0 = xs[i], x1 = xs[i + 1];
    b.Quad(b.Point(x0, -1, -1), b.Point(x1, -1, -1), b.Point(x1, -1, 1), b.Point(x0, -1, 1));
    b.Quad(b.Point(x0, 1, -1), b.Point(x0, 1, 1), b.Point(x1, 1, 1), b.Point(x1, 1, -1));
    b.Quad(b.Point(x0, -1, -1), b.Point(x0, 1, -1), b.Point(x1, 1, -1), b.Point(x1, -1, -1));
    b.Quad(b.Point(x0, -1, 1), b.Point(x1, -1, 1), b.Point(x1, 1, 1), b.Point(x0, 1, 1));
  }
  b.Quad(b.Point(-1, -1, -1), b.Point(-1, -1, 1), b.Point(-1, 1, 1), b.Point(-1, 1, -1));
  b.Quad(b.Point(1, -1, -1), b.Point(1, 1, -1), b.Point(1, 1, 1), b.Point(1, -1, 1));
  b.Quad(b.Point(Wall, -1, -1), b.Point(Wall, 1, -1), b.Point(Wall, 1, 1), b.Point(Wall, -1, 1));
  return b.Mesh();
}

struct Run
{
  vtkSmartPointer<vtkImageData> Image;
  std::vector<int> Region;
  int Count = 0;
};

Run Segment(vtkPolyData* mesh, double offset, const std::string& backend, bool cut = true)
{
  vtkNew<vtkSegmentedDistanceField> f;
  f->SetInputData(mesh);
  f->SetCutSelfIntersections(cut);
  vtkdf::testing::UseBackend(f.GetPointer(), backend);
  // A generic grid: spacing 0.1 (0.11 along y), shifted by `offset` spacings.
  f->ExplicitGridOn();
  f->SetGridOrigin(-1.52 + 0.1 * offset, -1.49 + 0.11 * offset * 0.7, -1.47 + 0.1 * offset * 0.4);
  f->SetGridSpacing(0.1, 0.11, 0.1);
  f->SetGridDimensions(31, 28, 30);
  f->Update();
  Run r;
  r.Image = f->GetOutput();
  vtkDataArray* region = r.Image->GetPointData()->GetArray("RegionIndex");
  CHECK(region && f->GetErrorCode() == 0, "no RegionIndex");
  for (vtkIdType v = 0; region && v < region->GetNumberOfTuples(); ++v)
  {
    r.Region.push_back(static_cast<int>(region->GetTuple1(v)));
  }
  r.Count = f->GetLastRegionCount();
  vtkDataArray* count = r.Image->GetFieldData()->GetArray("RegionCount");
  CHECK(count && count->GetTuple1(0) == r.Count, "RegionCount differs from the filter's");
  return r;
}

/// Whether two labellings are the same partition of the samples.
bool SamePartition(const std::vector<int>& a, const std::vector<int>& b)
{
  if (a.size() != b.size())
  {
    return false;
  }
  std::map<int, int> ab, ba;
  for (size_t v = 0; v < a.size(); ++v)
  {
    if (ab.emplace(a[v], b[v]).first->second != b[v] ||
      ba.emplace(b[v], a[v]).first->second != a[v])
    {
      return false;
    }
  }
  return true;
}

/// The same mesh with its triangles in a shuffled order.
vtkSmartPointer<vtkPolyData> Shuffled(vtkPolyData* mesh)
{
  std::vector<vtkIdType> order(mesh->GetNumberOfCells());
  for (size_t c = 0; c < order.size(); ++c)
  {
    order[c] = static_cast<vtkIdType>(c);
  }
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIdList> ids;
  for (const vtkIdType c : order)
  {
    mesh->GetCellPoints(c, ids);
    polys->InsertNextCell(ids);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(mesh->GetPoints());
  out->SetPolys(polys);
  return out;
}

/// The part of space a point must be in, by the shape's geometry (-1: no claim, near a
/// sheet, a boundary or a junction).
using Layout = std::function<int(double x, double y, double z)>;

/// Segments `mesh` at three grid offsets: `regions` regions, and every sample that
/// `layout` places in a part of space is in that part's region, one region per part.
void CheckShape(const std::string& name, vtkPolyData* mesh, int regions, const Layout& layout)
{
  for (const double offset : { 0.0, 0.37, 0.61 })
  {
    const Run r = Segment(mesh, offset, Backend);
    std::map<int, int> regionOfPart, partOfRegion;
    int64_t placed = 0, misplaced = 0;
    for (vtkIdType v = 0; v < static_cast<vtkIdType>(r.Region.size()); ++v)
    {
      double p[3];
      r.Image->GetPoint(v, p);
      const int part = layout(p[0], p[1], p[2]);
      if (part < 0)
      {
        continue;
      }
      ++placed;
      const bool agrees = regionOfPart.emplace(part, r.Region[v]).first->second == r.Region[v] &&
        partOfRegion.emplace(r.Region[v], part).first->second == part;
      misplaced += !agrees;
    }
    std::printf("%-18s offset %.2f: %d regions; %lld samples placed by the geometry, %lld "
                "misplaced\n",
      name.c_str(),
      offset,
      r.Count,
      static_cast<long long>(placed),
      static_cast<long long>(misplaced));
    CHECK(r.Count == regions, "%s: %d regions, expected %d", name.c_str(), r.Count, regions);
    CHECK(misplaced == 0 && placed > 0,
      "%s: %lld samples in the wrong region",
      name.c_str(),
      static_cast<long long>(misplaced));
    if (offset == 0.37)
    {
      const Run shuffled = Segment(Shuffled(mesh), offset, Backend);
      CHECK(SamePartition(r.Region, shuffled.Region),
        "%s: shuffling the triangles changed the regions",
        name.c_str());
      vtkSMPTools::SetBackend("Sequential");
      const Run sequential = Segment(mesh, offset, Backend);
      vtkSMPTools::SetBackend("STDThread");
      CHECK(r.Region == sequential.Region, "%s: one thread gives other regions", name.c_str());
      if (Backend == "gpu")
      {
        const Run cpu = Segment(mesh, offset, "cpu");
        int64_t differ = 0;
        double worst = 0;
        vtkDataArray* fg = r.Image->GetPointData()->GetArray("SegmentedDistance");
        vtkDataArray* fc = cpu.Image->GetPointData()->GetArray("SegmentedDistance");
        for (size_t v = 0; v < cpu.Region.size() && v < r.Region.size(); ++v)
        {
          differ += cpu.Region[v] != r.Region[v];
          if (cpu.Region[v] == r.Region[v])
          {
            worst = std::max(worst, std::fabs(fg->GetTuple1(v) - fc->GetTuple1(v)));
          }
        }
        const double h = r.Image->GetSpacing()[0];
        std::printf("%-18s GPU against CPU: %lld samples differ in region; SegmentedDistance "
                    "within %.2g spacings\n",
          name.c_str(),
          static_cast<long long>(differ),
          worst / h);
        CHECK(differ == 0, "%s: the GPU's regions differ from the CPU's", name.c_str());
        CHECK(worst <= 1e-3 * h, "%s: SegmentedDistance differs by %g", name.c_str(), worst);
      }
    }
  }
}
/// Two runs of the same backend on a bundled mesh with crossings, in one process: the
/// same RegionIndex and PatchId at every sample. CGAL's refinement orders its faces by
/// what it meets first, which varies from run to run; the cut's output is put in a
/// canonical order, or the patches' and regions' numbers would vary with it.
void CheckRepeatable(const std::string& data, const std::string& name)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((data + "/" + name + ".vtp").c_str());
  reader->Update();
  std::vector<double> arrays[2];
  int64_t crossed = 0;
  for (int run = 0; run < 2; ++run)
  {
    vtkNew<vtkSegmentedDistanceField> f;
    f->SetInputData(reader->GetOutput());
    f->SetResolution(40);
    vtkdf::testing::UseBackend(f.GetPointer(), Backend);
    f->Update();
    crossed = f->GetLastCrossedTriangles();
    for (const char* array : { "RegionIndex", "PatchId" })
    {
      vtkDataArray* values = f->GetOutput()->GetPointData()->GetArray(array);
      for (vtkIdType v = 0; values && v < values->GetNumberOfTuples(); ++v)
      {
        arrays[run].push_back(values->GetTuple1(v));
      }
    }
  }
  std::printf("%-18s two runs, %lld triangles cut: %s\n",
    name.c_str(),
    static_cast<long long>(crossed),
    arrays[0] == arrays[1] ? "the same regions and patches" : "different");
  // A build without CGAL finds the crossings but cuts none.
  const bool cuts = vtkSegmentedDistanceField::IsSelfIntersectionCutAvailable();
  CHECK(!arrays[0].empty() && arrays[0] == arrays[1] && (crossed > 0) == cuts,
    "%s: two runs gave different regions or patches, or %lld triangles cut",
    name.c_str(),
    static_cast<long long>(crossed));
}

/// The GPU's field (side labels computed where the field lies) against the CPU's on a
/// bundled mesh at 40 samples across: every array the same bytes.
void CompareBackends(const std::string& data, const std::string& name)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((data + "/" + name + ".vtp").c_str());
  reader->Update();
  vtkSmartPointer<vtkImageData> image[2];
  int regions[2] = { 0, 0 };
  for (int b = 0; b < 2; ++b)
  {
    vtkNew<vtkSegmentedDistanceField> f;
    f->SetInputData(reader->GetOutput());
    f->SetResolution(40);
    vtkdf::testing::UseBackend(f.GetPointer(), b == 0 ? "cpu" : "gpu");
    f->Update();
    image[b] = f->GetOutput();
    regions[b] = f->GetLastRegionCount();
  }
  vtkDataArray* r0 = image[0]->GetPointData()->GetArray("RegionIndex");
  vtkDataArray* r1 = image[1]->GetPointData()->GetArray("RegionIndex");
  vtkDataArray* f0 = image[0]->GetPointData()->GetArray("SegmentedDistance");
  vtkDataArray* f1 = image[1]->GetPointData()->GetArray("SegmentedDistance");
  if (!r0 || !r1 || !f0 || !f1 || r0->GetNumberOfTuples() != r1->GetNumberOfTuples())
  {
    CHECK(false, "%s: a backend gave no field", name.c_str());
    return;
  }
  int64_t differ = 0;
  for (vtkIdType v = 0; v < r0->GetNumberOfTuples(); ++v)
  {
    differ += r0->GetTuple1(v) != r1->GetTuple1(v);
  }
  // Every array: the same bytes (the GPU's field is the CPU scan's, its labels the CPU's).
  std::string arraysDiffer;
  vtkPointData* p0 = image[0]->GetPointData();
  for (int a = 0; a < p0->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* x = p0->GetArray(a);
    vtkDataArray* y = image[1]->GetPointData()->GetArray(p0->GetArrayName(a));
    if (!x || !y || x->GetDataType() != y->GetDataType() ||
      x->GetNumberOfValues() != y->GetNumberOfValues() ||
      std::memcmp(x->GetVoidPointer(0),
        y->GetVoidPointer(0),
        x->GetNumberOfValues() * x->GetDataTypeSize()) != 0)
    {
      arraysDiffer += std::string(" ") + p0->GetArrayName(a);
    }
  }
  std::printf("%-18s 40 across, GPU against CPU: %d and %d regions, %lld of %lld samples "
              "differ in region; arrays not the same bytes:%s\n",
    name.c_str(),
    regions[1],
    regions[0],
    static_cast<long long>(differ),
    static_cast<long long>(r0->GetNumberOfTuples()),
    arraysDiffer.empty() ? " none" : arraysDiffer.c_str());
  CHECK(regions[0] == regions[1] && differ == 0 && arraysDiffer.empty(),
    "%s: the GPU's field differs from the CPU's",
    name.c_str());
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 1, "cpu|gpu [DATA_DIR]"))
  {
    return 2;
  }
  Backend = argv[1];
  if (argc > 2)
  {
    for (const char* name : { "teapot", "max3ds_export" })
    {
      CheckRepeatable(argv[2], name);
    }
  }
  if (Backend == "gpu" && argc > 2)
  {
    for (const char* name :
      { "bunny_small", "teapot", "plane", "scad_back_to_back", "max3ds_export" })
    {
      CompareBackends(argv[2], name);
    }
  }
  // Parts: away from every sheet by more than a spacing and a half.
  constexpr double Clear = 0.16;
  CheckShape("closed sphere",
    Sphere(0, 0.9),
    2,
    [](double x, double y, double z)
    {
      const double r = std::sqrt(x * x + (y - 0.1) * (y - 0.1) + (z + 0.05) * (z + 0.05));
      return r < 0.9 - Clear ? 0 : (r > 0.9 + Clear ? 1 : -1);
    });
  {
    vtkNew<vtkAppendPolyData> both;
    both->AddInputData(Sphere(-0.7, 0.5));
    both->AddInputData(Sphere(0.7, 0.5));
    both->Update();
    CheckShape("two spheres",
      both->GetOutput(),
      3,
      [](double x, double y, double z)
      {
        const double a =
          std::sqrt((x + 0.7) * (x + 0.7) + (y - 0.1) * (y - 0.1) + (z + 0.05) * (z + 0.05));
        const double b =
          std::sqrt((x - 0.7) * (x - 0.7) + (y - 0.1) * (y - 0.1) + (z + 0.05) * (z + 0.05));
        return a < 0.5 - Clear
          ? 0
          : (b < 0.5 - Clear ? 1 : (a > 0.5 + Clear && b > 0.5 + Clear ? 2 : -1));
      });
  }
  CheckShape("open disk",
    Disk(),
    2,
    [](double x, double y, double z)
    {
      // Above or below the disk, within its rim.
      const bool within = std::sqrt(x * x + y * y) < 0.95 - Clear;
      return !within || std::fabs(z - 0.03) < Clear ? -1 : (z > 0.03 ? 0 : 1);
    });
  CheckShape("T-junction",
    Junction(),
    3,
    [](double x, double y, double z) {
      return Sector(x, y, z, { Angles[0], Angles[1], Angles[2] }, Clear);
    });
  {
    // Two strips crossing without a shared edge: cut along the crossing, four sectors.
    const std::vector<double> quarters = {
      CrossAngles[0], CrossAngles[1], CrossAngles[0] + M_PI, CrossAngles[1] + M_PI
    };
    // Uncut, the two strips are two patches; their four sides cannot make four regions
    // without merging a patch's two sides, so a sector leaks into its neighbour.
    const Run uncut = Segment(CrossedStrips(), 0.37, Backend, false);
    std::printf("crossed strips, uncut: %d regions (4 when cut)\n", uncut.Count);
    CHECK(uncut.Count != 4, "the uncut strips made four regions: the cut is not what counts");
    if (vtkSegmentedDistanceField::IsSelfIntersectionCutAvailable())
    {
      CheckShape("crossed strips",
        CrossedStrips(),
        4,
        [&](double x, double y, double z) { return Sector(x, y, z, quarters, Clear); });
    }
    else
    {
      // Without CGAL the cut asked for is the uncut field, and a warning names the option.
      const Run asked = Segment(CrossedStrips(), 0.37, Backend, true);
      vtkNew<vtkSegmentedDistanceField> f;
      vtkdf::testing::MessageRecorder messages(f);
      f->SetInputData(CrossedStrips());
      f->SetResolution(24);
      vtkdf::testing::UseBackend(f.GetPointer(), Backend);
      f->Update();
      std::printf("crossed strips, cut asked for without CGAL: %d regions, warning: %s\n",
        asked.Count,
        messages.Warnings.c_str());
      CHECK(asked.Region == uncut.Region && f->GetLastCrossedTriangles() == 0 &&
          messages.Warnings.find("1 of 1 groups of crossing triangles (4 triangles) could not be "
                                 "cut") != std::string::npos &&
          messages.Warnings.find("-DDF_USE_CGAL=OFF") != std::string::npos,
        "without CGAL: not the uncut field (%d regions, uncut %d), or no warning naming "
        "DF_USE_CGAL",
        asked.Count,
        uncut.Count);
    }
  }
  {
    // A known limit: a plane across the T-junction's line. CGAL's halfedge mesh holds the
    // junction edge once per half-plane, and its refinement refuses the three copies
    // crossing the plane at one point; the group stays uncut, a warning says so, and the
    // field is the uncut mesh's.
    vtkNew<vtkAppendPolyData> both;
    both->AddInputData(Junction());
    Builder b;
    b.Quad(b.Point(-1.3, -1.2, 0.13),
      b.Point(1.2, -1.3, 0.13),
      b.Point(1.3, 1.2, 0.13),
      b.Point(-1.2, 1.3, 0.13));
    both->AddInputData(b.Mesh());
    both->Update();
    vtkNew<vtkSegmentedDistanceField> f;
    vtkdf::testing::MessageRecorder messages(f);
    f->SetInputData(both->GetOutput());
    f->SetResolution(24);
    f->SetBackendToCPU();
    f->Update();
    std::printf("T-junction across a plane: %lld triangles cut, %d regions\n",
      static_cast<long long>(f->GetLastCrossedTriangles()),
      f->GetLastRegionCount());
    CHECK(messages.Warnings.find("could not be cut along their crossings") != std::string::npos &&
        f->GetErrorCode() == 0 && f->GetOutput()->GetNumberOfPoints() > 0 &&
        f->GetLastCrossedTriangles() == 0,
      "a group CGAL refuses: no warning, or no field");
  }
  CheckShape("walled box",
    WalledBox(),
    3,
    [](double x, double y, double z)
    {
      const double m = std::max({ std::fabs(x), std::fabs(y), std::fabs(z) });
      if (m > 1 + Clear)
      {
        return 2; // outside
      }
      if (m > 1 - Clear || std::fabs(x - Wall) < Clear)
      {
        return -1;
      }
      return x < Wall ? 0 : 1;
    });
  return vtkdf::testing::Verdict();
}
