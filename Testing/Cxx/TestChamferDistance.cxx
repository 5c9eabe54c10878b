// vtkChamferVoxelDistance against a breadth-first search with the same neighbourhood
// from the same zero set, on every voxel, for each metric, with and without
// MaximumLayers, signed and unsigned:
// - mesh inputs (bunny_small, teapot, scad_back_to_back, boeing_soup), whose zero set
//   and solid come back in the output (OutputMasks);
// - mask images made here (uint8 and float masks): one voxel, a plane, the grid's
//   corners and faces, with nz = 1, 129 and 300.
//
// On the GPU backend the field also equals the CPU backend's, voxel for voxel.
//
// usage: TestChamferDistance DATA_DIR cpu|gpu (VTKDF_MAX_SSBO_BYTES: hand-made grids only)
#include "vtkChamferVoxelDistance.h"

#include "TestSupport.h"

#include "VoxelReference.h"

#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

namespace
{
std::string Backend = "cpu";

vtkSmartPointer<vtkImageData> Run(vtkDataObject* input,
  int metric,
  int layers,
  bool signedField,
  const std::string& backend)
{
  vtkNew<vtkChamferVoxelDistance> f;
  f->SetInputData(input);
  f->SetMetric(metric);
  f->SetMaximumLayers(layers);
  f->SetSigned(signedField);
  f->OutputMasksOn();
  f->SetResolution(40);
  vtkdf::testing::UseBackend(f.GetPointer(), backend);
  f->Update();
  if (std::string(f->GetLastBackend()) != backend)
  {
    std::printf("FAIL: asked for %s, ran on %s\n", backend.c_str(), f->GetLastBackend());
    ++vtkdf::testing::Failures;
  }
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(f->GetOutput());
  return out;
}

/// Runs the filter on the backend under test and compares with the search (and, on the
/// GPU, with the CPU backend).
void Compare(const std::string& name,
  vtkDataObject* input,
  int metric,
  int layers,
  bool signedField)
{
  vtkSmartPointer<vtkImageData> out = Run(input, metric, layers, signedField, Backend);
  auto* distance = vtkIntArray::SafeDownCast(out->GetPointData()->GetArray("ChamferDistance"));
  auto* boundary = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("Boundary"));
  auto* solid = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("Solid"));
  auto* unreachedArray = vtkIntArray::SafeDownCast(out->GetFieldData()->GetArray("UnreachedValue"));
  if (!distance || !boundary || !unreachedArray || (signedField && !solid))
  {
    std::printf("FAIL: %s: missing output arrays\n", name.c_str());
    ++vtkdf::testing::Failures;
    return;
  }
  const int unreached = unreachedArray->GetValue(0);
  if (layers > 0 && unreached != layers + 1)
  {
    std::printf("FAIL: %s: UnreachedValue %d, expected %d\n", name.c_str(), unreached, layers + 1);
    ++vtkdf::testing::Failures;
  }
  const voxelref::Grid g(out);
  int layersRun = 0;
  for (vtkIdType v = 0; v < distance->GetNumberOfTuples(); ++v)
  {
    const int value = std::abs(distance->GetValue(v));
    layersRun = value != unreached ? std::max(layersRun, value) : layersRun;
  }
  if (Backend == "gpu")
  {
    auto cpu = Run(input, metric, layers, signedField, "cpu");
    auto* other = vtkIntArray::SafeDownCast(cpu->GetPointData()->GetArray("ChamferDistance"));
    vtkIdType differ = 0;
    for (vtkIdType v = 0; other && v < distance->GetNumberOfTuples(); ++v)
    {
      differ += distance->GetValue(v) != other->GetValue(v);
    }
    if (!other || differ)
    {
      std::printf("FAIL: %s: GPU and CPU differ on %lld voxels\n", name.c_str(), (long long)differ);
      ++vtkdf::testing::Failures;
    }
  }
  std::vector<char> zero(g.Count());
  for (int64_t v = 0; v < g.Count(); ++v)
  {
    zero[v] = boundary->GetValue(v) != 0;
  }
  auto expected = voxelref::Layers(g, zero, metric, layers, unreached);
  int64_t wrong = 0, first = -1, negative = 0;
  for (int64_t v = 0; v < g.Count(); ++v)
  {
    int e = expected[v];
    if (signedField && solid->GetValue(v))
    {
      e = -e;
    }
    if (distance->GetValue(v) != e)
    {
      first = first < 0 ? v : first;
      ++wrong;
    }
    negative += distance->GetValue(v) < 0;
  }
  const char* metrics[] = { "manhattan", "chessboard18", "chessboard26" };
  std::printf("%-40s %-13s M=%d %-8s %dx%dx%d: %lld voxels differ, %d layers, %lld negative\n",
    name.c_str(),
    metrics[metric],
    layers,
    signedField ? "signed" : "unsigned",
    g.Dims[0],
    g.Dims[1],
    g.Dims[2],
    (long long)wrong,
    layersRun,
    (long long)negative);
  if (wrong)
  {
    std::printf("FAIL: %s: %lld voxels differ from the search (first %lld: %d, expected %d)\n",
      name.c_str(),
      (long long)wrong,
      (long long)first,
      distance->GetValue(first),
      expected[first]);
    ++vtkdf::testing::Failures;
  }
  if (signedField && negative == 0)
  {
    std::printf("FAIL: %s: a signed field with no negative value\n", name.c_str());
    ++vtkdf::testing::Failures;
  }
}

/// A mask image; `set` says which voxels are in the zero set.
template<typename ArrayT>
vtkSmartPointer<vtkImageData> MaskImage(int nx,
  int ny,
  int nz,
  const std::function<bool(int, int, int)>& set)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetOrigin(-1, 2, 0.5);
  image->SetSpacing(0.5, 0.25, 1);
  vtkNew<ArrayT> mask;
  mask->SetName("Boundary");
  mask->SetNumberOfTuples(int64_t(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        mask->SetValue(i + int64_t(nx) * (j + int64_t(ny) * k), set(i, j, k) ? 3 : 0);
      }
    }
  }
  image->GetPointData()->AddArray(mask);
  return image;
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
  // With VTKDF_MAX_SSBO_BYTES set small (the ".slabs" test), the GPU binds the distance
  // array a slab of 128 slices at a time: only the tall hand-made grids have several.
  const bool slabs = std::getenv("VTKDF_MAX_SSBO_BYTES") != nullptr;
  const std::vector<const char*> meshes = {
    "bunny_small", "teapot", "scad_back_to_back", "boeing_soup"
  };
  for (const char* name : slabs ? std::vector<const char*>() : meshes)
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName((data + "/" + name + ".vtp").c_str());
    reader->Update();
    const bool closed = std::string(name) == "bunny_small";
    for (int metric = 0; metric < 3; ++metric)
    {
      for (int layers : { 0, 4 })
      {
        Compare(name, reader->GetOutput(), metric, layers, false);
        if (closed)
        {
          Compare(name, reader->GetOutput(), metric, layers, true);
        }
      }
    }
  }

  struct Shape
  {
    int Nx, Ny, Nz;
  };
  for (const Shape s : { Shape{ 9, 8, 1 }, Shape{ 5, 4, 129 }, Shape{ 3, 5, 300 } })
  {
    const std::string size =
      std::to_string(s.Nx) + "x" + std::to_string(s.Ny) + "x" + std::to_string(s.Nz);
    const std::vector<std::pair<std::string, std::function<bool(int, int, int)>>> sets = {
      { "one voxel",
        [&](int i, int j, int k) { return i == s.Nx / 2 && j == s.Ny / 3 && k == s.Nz / 2; } },
      { "plane", [&](int i, int, int) { return i == s.Nx / 3; } },
      { "corners",
        [&](int i, int j, int k) {
          return (i == 0 || i == s.Nx - 1) && (j == 0 || j == s.Ny - 1) &&
            (k == 0 || k == s.Nz - 1);
        } },
      { "face k=0", [&](int, int, int k) { return k == 0; } },
      { "face i=max", [&](int i, int, int) { return i == s.Nx - 1; } },
    };
    for (const auto& set : sets)
    {
      auto u8 = MaskImage<vtkUnsignedCharArray>(s.Nx, s.Ny, s.Nz, set.second);
      auto f32 = MaskImage<vtkFloatArray>(s.Nx, s.Ny, s.Nz, set.second);
      for (int metric = 0; metric < 3; ++metric)
      {
        for (int layers : { 0, 2 })
        {
          Compare(set.first + " " + size + " uint8", u8, metric, layers, false);
        }
      }
      Compare(set.first + " " + size + " float", f32, 1, 0, false);
    }
  }
  return vtkdf::testing::Verdict();
}
