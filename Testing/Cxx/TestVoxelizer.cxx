// vtkPolyDataVoxelizer against exact references (VoxelReference.h):
// - Boundary, on closed, open, non-manifold and soup meshes and an anisotropic explicit
//   grid, an open sheet at two resolutions, and degenerate triangles: the set voxels are
//   exactly those whose centre lies within half the cell diagonal of a triangle (those
//   at half a diagonal, within a relative 1e-9, may go either way).
// - Solid, on closed meshes: equal to the inside test on every voxel farther than
//   sqrt(3) spacings from the surface, and on at least 99.5 % of all voxels.
// - A closed box crossed by open sheets (flat and tilted; the paper's potted plant):
//   Solid is the box's interior only.
// - Mode Both gives the same masks as Boundary and Solid alone.
// - Triangles too far from the grid to snap are counted in a warning.
//
// - On the GPU backend, every mask equals the CPU backend's, bit for bit, also on a
//   150^3 grid whose lanes span several layers (run in passes of one layer each with
//   VTKDF_MAX_SSBO_BYTES small), and for a 12-triangle box on a 300^3 grid (triangles
//   of many lane tiles).
//
// usage: TestVoxelizer DATA_DIR cpu|gpu
#include "vtkPolyDataVoxelizer.h"

#include "TestSupport.h"

#include "VoxelReference.h"

#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataReader.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
int Identical = 0; // masks compared equal between the backends
vtkSmartPointer<vtkPolyData> Load(const std::string& path)
{
  auto read = [&](auto reader) -> vtkSmartPointer<vtkPolyData>
  {
    reader->SetFileName(path.c_str());
    reader->Update();
    return reader->GetOutput();
  };
  const std::string extension = path.substr(path.size() - 4);
  if (extension == ".vtk")
  {
    return read(vtkSmartPointer<vtkPolyDataReader>::New());
  }
  if (extension == ".obj")
  {
    return read(vtkSmartPointer<vtkOBJReader>::New());
  }
  return read(vtkSmartPointer<vtkXMLPolyDataReader>::New());
}

struct Explicit
{
  double Origin[3], Spacing[3];
  int Dims[3];
};

std::string Backend = "cpu";

vtkSmartPointer<vtkImageData> Voxelize(vtkPolyData* mesh,
  int mode,
  int resolution,
  const Explicit* grid = nullptr,
  const std::string& backend = Backend)
{
  vtkNew<vtkPolyDataVoxelizer> v;
  v->SetInputData(mesh);
  v->SetMode(mode);
  v->SetResolution(resolution);
  vtkdf::testing::UseBackend(v.GetPointer(), backend);
  if (grid)
  {
    v->ExplicitGridOn();
    v->SetGridOrigin(const_cast<double*>(grid->Origin));
    v->SetGridSpacing(const_cast<double*>(grid->Spacing));
    v->SetGridDimensions(const_cast<int*>(grid->Dims));
  }
  v->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(v->GetOutput());
  if (backend == "gpu" && std::string(v->GetLastBackend()) != "gpu")
  {
    std::printf("FAIL: the GPU backend did not run\n");
    ++vtkdf::testing::Failures;
  }
  if (backend == "gpu" && Backend == "gpu")
  {
    // The same masks as the CPU backend, bit for bit.
    auto cpu = Voxelize(mesh, mode, resolution, grid, "cpu");
    for (const char* name : { "Boundary", "Solid" })
    {
      auto* a = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray(name));
      auto* b = vtkUnsignedCharArray::SafeDownCast(cpu->GetPointData()->GetArray(name));
      if (!a != !b)
      {
        std::printf("FAIL: %s present on one backend only\n", name);
        ++vtkdf::testing::Failures;
      }
      else if (a)
      {
        vtkIdType differ = 0;
        for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
        {
          differ += a->GetValue(i) != b->GetValue(i);
        }
        if (differ)
        {
          std::printf(
            "FAIL: %s: %lld voxels differ between GPU and CPU\n", name, (long long)differ);
          ++vtkdf::testing::Failures;
        }
        else
        {
          ++Identical;
        }
      }
    }
  }
  return out;
}

const unsigned char* Mask(vtkImageData* image, const char* name)
{
  auto* a = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetArray(name));
  return a ? a->GetPointer(0) : nullptr;
}

void CheckBoundary(const std::string& name, vtkPolyData* mesh, vtkImageData* image)
{
  const unsigned char* mask = Mask(image, "Boundary");
  CHECK(mask, "%s: no Boundary array", name.c_str());
  if (!mask)
  {
    return;
  }
  const voxelref::Grid g(image);
  const double halfDiagonal = 0.5 *
    std::sqrt(
      g.Spacing[0] * g.Spacing[0] + g.Spacing[1] * g.Spacing[1] + g.Spacing[2] * g.Spacing[2]);
  const auto d = voxelref::NearDistance(g, voxelref::Triangles(mesh), halfDiagonal);
  // Voxels at half a diagonal, within a relative 1e-9, may go either way.
  int64_t far = 0, missing = 0, set = 0, within = 0;
  for (int64_t v = 0; v < g.Count(); ++v)
  {
    set += mask[v] != 0;
    far += mask[v] && !(d[v] <= halfDiagonal * (1 + 1e-9));
    within += d[v] <= halfDiagonal * (1 - 1e-9);
    missing += !mask[v] && d[v] <= halfDiagonal * (1 - 1e-9);
  }
  std::printf("%-30s boundary %dx%dx%d: %lld set, %lld within half a diagonal, %lld of them "
              "missing, %lld set too far\n",
    name.c_str(),
    g.Dims[0],
    g.Dims[1],
    g.Dims[2],
    (long long)set,
    (long long)within,
    (long long)missing,
    (long long)far);
  CHECK(far == 0,
    "%s: %lld boundary voxels farther than half a diagonal",
    name.c_str(),
    (long long)far);
  CHECK(within > 0 && missing == 0,
    "%s: %lld of %lld voxels within half a diagonal are not set",
    name.c_str(),
    (long long)missing,
    (long long)within);
}

void CheckSolid(const std::string& name,
  const std::vector<std::array<std::array<double, 3>, 3>>& closedPart,
  vtkImageData* image)
{
  const unsigned char* mask = Mask(image, "Solid");
  CHECK(mask, "%s: no Solid array", name.c_str());
  if (!mask)
  {
    return;
  }
  const voxelref::Grid g(image);
  const double h = std::max(g.Spacing[0], std::max(g.Spacing[1], g.Spacing[2]));
  const auto d = voxelref::NearDistance(g, closedPart, std::sqrt(3.0) * h);
  const auto inside = voxelref::Inside(g, closedPart);
  int64_t wrongFar = 0, wrong = 0, solid = 0, insideCount = 0;
  for (int64_t v = 0; v < g.Count(); ++v)
  {
    const bool differs = (mask[v] != 0) != (inside[v] != 0);
    wrong += differs;
    wrongFar += differs && !(d[v] <= std::sqrt(3.0) * h);
    solid += mask[v] != 0;
    insideCount += inside[v] != 0;
  }
  const double agreement = 1.0 - double(wrong) / g.Count();
  std::printf("%-30s solid %dx%dx%d: %lld solid, %lld inside, %lld differ far from the surface, "
              "%.3f %% agree\n",
    name.c_str(),
    g.Dims[0],
    g.Dims[1],
    g.Dims[2],
    (long long)solid,
    (long long)insideCount,
    (long long)wrongFar,
    100 * agreement);
  CHECK(insideCount > 0, "%s: the reference finds no inside voxel", name.c_str());
  CHECK(wrongFar == 0,
    "%s: %lld voxels far from the surface differ from the inside test",
    name.c_str(),
    (long long)wrongFar);
  CHECK(agreement >= 0.995,
    "%s: Solid agrees on only %.3f %% of the voxels",
    name.c_str(),
    100 * agreement);
}

/// The unit box [0,1]^3 (outward triangles) and, optionally, an open sheet through it.
vtkSmartPointer<vtkPolyData> PottedPlant(int sheet)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> polys;
  for (int k = 0; k < 8; ++k)
  {
    pts->InsertNextPoint(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  }
  const vtkIdType quads[6][4] = {
    { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 }
  };
  for (const auto& q : quads)
  {
    const vtkIdType a[3] = { q[0], q[1], q[2] }, b[3] = { q[0], q[2], q[3] };
    polys->InsertNextCell(3, a);
    polys->InsertNextCell(3, b);
  }
  if (sheet > 0)
  {
    // A quad well beyond the box on every side: flat at z = 0.53, or tilted.
    const double tilt = sheet == 2 ? 0.3 : 0.0;
    const vtkIdType first = pts->GetNumberOfPoints();
    pts->InsertNextPoint(-0.7, -0.6, 0.53 - tilt);
    pts->InsertNextPoint(1.6, -0.6, 0.53 - tilt);
    pts->InsertNextPoint(1.6, 1.7, 0.53 + tilt);
    pts->InsertNextPoint(-0.7, 1.7, 0.53 + tilt);
    const vtkIdType a[3] = { first, first + 1, first + 2 }, b[3] = { first, first + 2, first + 3 };
    polys->InsertNextCell(3, a);
    polys->InsertNextCell(3, b);
  }
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  return mesh;
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR cpu|gpu"))
  {
    return 2;
  }
  const std::string data = argv[1];
  Backend = argv[2];
  const int resolution = 48;

  for (const char* name :
    { "bunny_small", "teapot", "scad_back_to_back", "boeing_soup", "plane", "scad_zero_area" })
  {
    auto mesh = Load(data + "/" + name + ".vtp");
    auto boundary = Voxelize(mesh, vtkPolyDataVoxelizer::BOUNDARY, resolution);
    CheckBoundary(name, mesh, boundary);
    if (std::string(name) == "plane")
    {
      // The sheet's borders fall between lanes differently at another resolution.
      CheckBoundary("plane 33", mesh, Voxelize(mesh, vtkPolyDataVoxelizer::BOUNDARY, 33));
    }
    auto both = Voxelize(mesh, vtkPolyDataVoxelizer::BOTH, resolution);
    const unsigned char* a = Mask(boundary, "Boundary");
    const unsigned char* b = Mask(both, "Boundary");
    CHECK(a && b && std::equal(a, a + boundary->GetNumberOfPoints(), b),
      "%s: Mode Both gives another Boundary",
      name);
  }
  // Zero-area triangles (a repeated index, collinear corners, a point) next to valid ones,
  // and concave polygons, from the bad-input corpus.
  for (const char* name : { "degenerate.vtk", "concave.obj" })
  {
    auto mesh = Load(data + "/../BadInput/" + name);
    CheckBoundary(name, mesh, Voxelize(mesh, vtkPolyDataVoxelizer::BOUNDARY, 24));
  }
  {
    // Anisotropic explicit grid cutting the bunny.
    auto mesh = Load(data + "/bunny_small.vtp");
    double bounds[6];
    mesh->GetBounds(bounds);
    Explicit grid;
    for (int a = 0; a < 3; ++a)
    {
      grid.Origin[a] = bounds[2 * a] + 0.1 * (bounds[2 * a + 1] - bounds[2 * a]);
      grid.Spacing[a] = (bounds[2 * a + 1] - bounds[2 * a]) / (31 + 7 * a);
      grid.Dims[a] = 30 + 6 * a;
    }
    CheckBoundary("bunny_small anisotropic",
      mesh,
      Voxelize(mesh, vtkPolyDataVoxelizer::BOUNDARY, resolution, &grid));
  }

  {
    // Streaming: a sub-extent computed alone equals those voxels of the whole.
    auto mesh = Load(data + "/bunny_small.vtp");
    auto whole = Voxelize(mesh, vtkPolyDataVoxelizer::BOTH, resolution);
    vtkNew<vtkPolyDataVoxelizer> v;
    v->SetInputData(mesh);
    v->SetResolution(resolution);
    if (Backend == "gpu")
    {
      v->SetBackendToGPU();
    }
    else
    {
      v->SetBackendToCPU();
    }
    v->UpdateInformation();
    const int extent[6] = { 3, 40, 5, 29, 7, 33 };
    v->UpdateExtent(extent);
    vtkImageData* piece = v->GetOutput();
    int got[6];
    piece->GetExtent(got);
    CHECK(std::equal(extent, extent + 6, got), "streaming: the piece has another extent");
    int64_t differ = 0, compared = 0;
    int wholeExtent[6];
    whole->GetExtent(wholeExtent);
    for (const char* name : { "Boundary", "Solid" })
    {
      auto* a = vtkUnsignedCharArray::SafeDownCast(piece->GetPointData()->GetArray(name));
      auto* b = vtkUnsignedCharArray::SafeDownCast(whole->GetPointData()->GetArray(name));
      CHECK(a && b, "streaming: no %s array", name);
      if (!a || !b)
      {
        continue;
      }
      const int pnx = got[1] - got[0] + 1, pny = got[3] - got[2] + 1;
      const int wnx = wholeExtent[1] + 1, wny = wholeExtent[3] + 1;
      for (int k = got[4]; k <= got[5]; ++k)
      {
        for (int j = got[2]; j <= got[3]; ++j)
        {
          for (int i = got[0]; i <= got[1]; ++i)
          {
            const vtkIdType inPiece =
              (i - got[0]) + pnx * ((j - got[2]) + vtkIdType(pny) * (k - got[4]));
            const vtkIdType inWhole = i + wnx * (j + vtkIdType(wny) * k);
            differ += a->GetValue(inPiece) != b->GetValue(inWhole);
            ++compared;
          }
        }
      }
    }
    CHECK(compared > 0, "streaming: nothing compared");
    std::printf("streaming (bunny_small, extent 3-40 x 5-29 x 7-33): %lld voxels differ\n",
      (long long)differ);
    CHECK(differ == 0, "streaming: %lld voxels differ from the whole", (long long)differ);
  }

  for (const char* name : { "bunny_small", "cow", "trefoil_knot" })
  {
    auto mesh = Load(data + "/" + name + ".vtp");
    auto solid = Voxelize(mesh, vtkPolyDataVoxelizer::SOLID, resolution);
    CheckSolid(name, voxelref::Triangles(mesh), solid);
    auto both = Voxelize(mesh, vtkPolyDataVoxelizer::BOTH, resolution);
    const unsigned char* a = Mask(solid, "Solid");
    const unsigned char* b = Mask(both, "Solid");
    CHECK(a && b && std::equal(a, a + solid->GetNumberOfPoints(), b),
      "%s: Mode Both gives another Solid",
      name);
  }

  // The potted plant: the box's interior only, whatever the sheet.
  {
    const auto box = voxelref::Triangles(PottedPlant(0));
    Explicit grid;
    for (int a = 0; a < 3; ++a)
    {
      grid.Origin[a] = -0.8 + 0.013 * a;
      grid.Spacing[a] = 0.05;
      grid.Dims[a] = 55;
    }
    for (int sheet : { 0, 1, 2 })
    {
      const char* names[] = { "box", "box + flat sheet", "box + tilted sheet" };
      CheckSolid(names[sheet],
        box,
        Voxelize(PottedPlant(sheet), vtkPolyDataVoxelizer::SOLID, resolution, &grid));
    }
  }
  {
    // Triangles with a vertex beyond the snapping range (2^22 cells from the grid along
    // every axis) are left out of the solid with a warning that counts them, on either
    // backend (Voxelize compares the GPU's masks with the CPU's).
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    mesh->DeepCopy(Load(data + "/bunny_small.vtp"));
    double bounds[6];
    mesh->GetBounds(bounds);
    Explicit grid;
    for (int a = 0; a < 3; ++a)
    {
      grid.Spacing[a] = (bounds[2 * a + 1] - bounds[2 * a]) / 39;
      grid.Origin[a] = bounds[2 * a];
      grid.Dims[a] = 40;
    }
    const vtkIdType far = mesh->GetPoints()->InsertNextPoint(bounds[1] + 1e7 * grid.Spacing[0],
      bounds[3] + 1e7 * grid.Spacing[1],
      bounds[5] + 1e7 * grid.Spacing[2]);
    for (vtkIdType first : { 0, 2 })
    {
      const vtkIdType ids[3] = { first, first + 1, far };
      mesh->GetPolys()->InsertNextCell(3, ids);
    }
    vtkNew<vtkPolyDataVoxelizer> v;
    v->SetInputData(mesh);
    v->SetMode(vtkPolyDataVoxelizer::SOLID);
    vtkdf::testing::UseBackend(v.GetPointer(), Backend);
    v->ExplicitGridOn();
    v->SetGridOrigin(grid.Origin);
    v->SetGridSpacing(grid.Spacing);
    v->SetGridDimensions(grid.Dims);
    vtkdf::testing::MessageRecorder messages(v);
    v->Update();
    std::printf("far triangles: %s\n", messages.Warnings.c_str());
    CHECK(
      messages.Warnings.find("2 triangles with a vertex more than 2^22 cells") != std::string::npos,
      "the two far triangles are not reported");
    Voxelize(mesh, vtkPolyDataVoxelizer::SOLID, resolution, &grid);
  }
  if (Backend == "gpu")
  {
    // Lanes of more than one layer of 128 bits (the solid's 303 bins), which the
    // Voxelizer.Masks.gpu.slabs run sets in passes of one layer at a time: the GPU's
    // masks against the CPU's (Voxelize compares them).
    Voxelize(Load(data + "/bunny_small.vtp"), vtkPolyDataVoxelizer::BOTH, 150);
    // A box of 12 triangles on a 300^3 grid: a face spans up to 300 x 280 lanes, which
    // many invocations walk in tiles (llvmpipe ends a shader's loops after 65535
    // iterations of a SIMD vector: one invocation a triangle lost half the boundary).
    vtkNew<vtkPoints> corners;
    for (int k = 0; k < 8; ++k)
    {
      corners->InsertNextPoint(k & 1 ? 0.9 : 0.1, k & 2 ? 0.87 : 0.13, k & 4 ? 0.8 : 0.2);
    }
    vtkNew<vtkCellArray> triangles;
    const vtkIdType quads[6][4] = {
      { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 }
    };
    for (const auto& q : quads)
    {
      const vtkIdType first[3] = { q[0], q[1], q[2] }, second[3] = { q[0], q[2], q[3] };
      triangles->InsertNextCell(3, first);
      triangles->InsertNextCell(3, second);
    }
    vtkNew<vtkPolyData> box;
    box->SetPoints(corners);
    box->SetPolys(triangles);
    if (!std::getenv("VTKDF_MAX_SSBO_BYTES")) // a layer of 300 x 280 lanes needs 1.3 MB
    {
      Voxelize(box, vtkPolyDataVoxelizer::BOTH, 300);
    }
    std::printf("%d masks identical on the GPU and the CPU\n", Identical);
  }
  return vtkdf::testing::Verdict();
}
