// Benchmark (not a test): voxelization and chamfer distance, the shape of Martinek et al.'s
// Tables 1 and 2, next to VTK's own route to a Manhattan field
// (vtkPolyDataToImageStencil + vtkImageStencilToImage + vtkImageCityBlockDistance) on
// the same grid.
//
// usage: BenchChamfer MESH [MESH...] [--sizes 128,256,512] [--backends cpu,gpu] [--reps 3]
//                     [--metric manhattan|chessboard18|chessboard26]
// Columns: boundary and solid voxelization (both masks from one pass for "solid"), the
// chamfer field limited to one layer and the complete field (in --metric, Manhattan by
// default, from the boundary mask), the floor under the field (a float array of the
// grid's size allocated and written once, first touch included, on the same threads) and
// the field's multiple of it, voxelize + complete field, the memory of one layer, and the
// VTK route's time (a Manhattan field whatever --metric says).
#include "vtkChamferVoxelDistance.h"
#include "vtkPolyDataVoxelizer.h"

#include "vtkImageCityBlockDistance.h"
#include "vtkImageData.h"
#include "vtkImageStencilToImage.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataToImageStencil.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <sys/mman.h>

namespace
{
double Seconds(const std::chrono::steady_clock::time_point& start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<std::string> Split(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
  {
    out.push_back(item);
  }
  return out;
}

/// Best of `reps` runs of a filter's own time (GetLastTime).
template<typename Filter>
double Best(Filter* filter, int reps)
{
  double best = 1e30;
  for (int r = 0; r < reps; ++r)
  {
    filter->Modified();
    filter->Update();
    best = std::min(best, filter->GetLastTime());
  }
  return best;
}
/// Best of `reps` allocations of n floats, each written once in parallel. The pages are
/// mapped afresh each time (mmap): first touch included, as for a new output array (a
/// heap block freed and reused would hide it).
double FloorTime(vtkIdType n, int reps)
{
  double best = 1e30;
  const size_t bytes = size_t(n) * sizeof(float);
  for (int r = 0; r < reps; ++r)
  {
    const auto start = std::chrono::steady_clock::now();
    void* pages = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (pages == MAP_FAILED)
    {
      return -1;
    }
    float* out = static_cast<float*>(pages);
    vtkSMPTools::For(0,
      n,
      [out](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          out[i] = static_cast<float>(i & 63);
        }
      });
    best = std::min(best, Seconds(start));
    munmap(pages, bytes);
  }
  return best;
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> meshes, sizes = { "128", "256", "512" }, backends = { "cpu" };
  int reps = 3;
  std::string metric = "manhattan";
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if (arg == "--metric" && a + 1 < argc)
    {
      metric = argv[++a];
      if (metric != "manhattan" && metric != "chessboard18" && metric != "chessboard26")
      {
        std::fprintf(stderr,
          "BenchChamfer: --metric must be manhattan, chessboard18 or chessboard26, not %s\n",
          metric.c_str());
        return 2;
      }
    }
    else if (arg == "--sizes" && a + 1 < argc)
    {
      sizes = Split(argv[++a]);
    }
    else if (arg == "--backends" && a + 1 < argc)
    {
      backends = Split(argv[++a]);
    }
    else if (arg == "--reps" && a + 1 < argc)
    {
      reps = std::atoi(argv[++a]);
    }
    else
    {
      meshes.push_back(arg);
    }
  }
  std::printf("%-16s %8s %4s %-12s %-4s %9s %9s %9s %9s %9s %7s %10s %8s %9s %7s\n",
    "mesh",
    "tris",
    "N",
    "dims",
    "back",
    "bound_s",
    "solid_s",
    "layer1_s",
    "field_s",
    "floor_s",
    "x_floor",
    "vox+fld_s",
    "MiB/lyr",
    "vtk_s",
    "speedup");
  for (const std::string& path : meshes)
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(reader->GetOutput());
    triangles->Update();
    vtkPolyData* mesh = triangles->GetOutput();
    if (mesh->GetNumberOfPolys() == 0)
    {
      std::fprintf(
        stderr, "BenchChamfer: %s holds no triangles (not a .vtp mesh?)\n", path.c_str());
      return 1;
    }
    std::string name = path.substr(path.find_last_of('/') + 1);
    name = name.substr(0, name.find_last_of('.'));
    for (const std::string& size : sizes)
    {
      const int n = std::atoi(size.c_str());
      // VTK's route on the same grid: solid stencil, inside = 0, city-block distance.
      vtkNew<vtkPolyDataVoxelizer> grid;
      grid->SetInputData(mesh);
      grid->SetResolution(n);
      grid->UpdateInformation();
      double origin[3], spacing[3];
      int extent[6];
      vtkInformation* info = grid->GetOutputInformation(0);
      info->Get(vtkDataObject::ORIGIN(), origin);
      info->Get(vtkDataObject::SPACING(), spacing);
      info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
      double vtkTime = 1e30;
      for (int r = 0; r < std::min(reps, 2); ++r)
      {
        const auto start = std::chrono::steady_clock::now();
        vtkNew<vtkPolyDataToImageStencil> stencil;
        stencil->SetInputData(mesh);
        stencil->SetOutputOrigin(origin);
        stencil->SetOutputSpacing(spacing);
        stencil->SetOutputWholeExtent(extent);
        vtkNew<vtkImageStencilToImage> image;
        image->SetInputConnection(stencil->GetOutputPort());
        image->SetInsideValue(0);
        image->SetOutsideValue(32767);
        image->SetOutputScalarTypeToShort();
        vtkNew<vtkImageCityBlockDistance> distance;
        distance->SetInputConnection(image->GetOutputPort());
        distance->SetDimensionality(3);
        distance->Update();
        vtkTime = std::min(vtkTime, Seconds(start));
      }
      for (const std::string& backend : backends)
      {
        const int metricType = metric == "chessboard18" ? vtkChamferVoxelDistance::CHESSBOARD18
          : metric == "chessboard26"                    ? vtkChamferVoxelDistance::CHESSBOARD26
                                                        : vtkChamferVoxelDistance::MANHATTAN;
        auto configure = [&](vtkDistanceFieldAlgorithm* f)
        {
          f->SetResolution(n);
          if (backend == "gpu")
          {
            f->SetBackendToGPU();
          }
          else
          {
            f->SetBackendToCPU();
          }
        };
        vtkNew<vtkPolyDataVoxelizer> boundary, solid;
        boundary->SetInputData(mesh);
        boundary->SetModeToBoundary();
        configure(boundary);
        solid->SetInputData(mesh);
        solid->SetModeToBoth();
        configure(solid);
        const double boundaryTime = Best(boundary.GetPointer(), reps);
        const double solidTime = Best(solid.GetPointer(), reps);
        if (boundary->GetOutput()->GetNumberOfPoints() == 0)
        {
          std::printf("%-16s %4d %s: the voxelizer failed\n", name.c_str(), n, backend.c_str());
          continue;
        }
        // Chamfer from the boundary mask: one layer, the complete field.
        vtkNew<vtkChamferVoxelDistance> layer1, field, meshField;
        layer1->SetInputData(boundary->GetOutput());
        layer1->SetMetric(metricType);
        layer1->SetMaximumLayers(1);
        configure(layer1);
        field->SetInputData(boundary->GetOutput());
        field->SetMetric(metricType);
        configure(field);
        meshField->SetInputData(mesh);
        meshField->SetMetric(metricType);
        configure(meshField);
        const double layerTime = Best(layer1.GetPointer(), reps);
        const double fieldTime = Best(field.GetPointer(), reps);
        const double totalTime = Best(meshField.GetPointer(), reps);
        int dims[3];
        boundary->GetOutput()->GetDimensions(dims);
        const double layerMiB = double(dims[0]) * dims[1] * (((dims[2] + 63) / 64) * 8) / 1048576.0;
        const double floorTime = FloorTime(vtkIdType(dims[0]) * dims[1] * dims[2], reps);
        std::printf("%-16s %8lld %4d %4dx%4dx%4d %-4s %9.4f %9.4f %9.4f %9.4f %9.4f %6.1fx %10.4f "
                    "%8.2f %9.3f %6.1fx\n",
          name.c_str(),
          (long long)mesh->GetNumberOfPolys(),
          n,
          dims[0],
          dims[1],
          dims[2],
          backend.c_str(),
          boundaryTime,
          solidTime,
          layerTime,
          fieldTime,
          floorTime,
          fieldTime / floorTime,
          totalTime,
          layerMiB,
          vtkTime,
          vtkTime / totalTime);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
