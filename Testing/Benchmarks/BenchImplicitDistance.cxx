// BenchImplicitDistance: the implicit functions of a mesh's signed distance, one point at
// a time on one thread (what vtkClipDataSet and vtkExtractGeometry call) and in a batch
// (FunctionValue on an array, what vtkCutter's grid path calls): vtkMeshDistanceFunction
// (winding-number sign) next to VTK's vtkImplicitPolyDataDistance on the same points.
// Each function is built before its clock starts (SetInput; the first evaluation builds
// ours), the batch timed with the threads vtkSMPTools has (VTK_SMP_MAX_THREADS).
// Usage: BenchImplicitDistance MESH.vtp POINTS.npy [SINGLE_POINTS]
//   POINTS: an (N, 3) float64 .npy in C order (Testing/Benchmarks/points.py makes them);
//   SINGLE_POINTS (default 100000): how many of them the one-at-a-time loops take.
// Prints one line per measurement. Not a test.
#include "vtkMeshDistanceFunction.h"

#include "vtkDoubleArray.h"
#include "vtkImplicitPolyDataDistance.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// An (N, 3) float64 array from a .npy file in C order; empty when it is not one.
std::vector<double> ReadPoints(const char* path)
{
  std::ifstream in(path, std::ios::binary);
  char magic[10];
  if (!in.read(magic, 10) || std::memcmp(magic, "\x93NUMPY", 6) != 0)
  {
    return {};
  }
  const size_t length =
    static_cast<unsigned char>(magic[8]) | (static_cast<unsigned char>(magic[9]) << 8);
  std::string header(length, ' ');
  in.read(&header[0], static_cast<std::streamsize>(length));
  const size_t shape = header.find("'shape': (");
  long long n = 0;
  if (header.find("'<f8'") == std::string::npos || shape == std::string::npos ||
    std::sscanf(header.c_str() + shape + 10, "%lld", &n) != 1)
  {
    return {};
  }
  std::vector<double> xyz(3 * static_cast<size_t>(n));
  in.read(reinterpret_cast<char*>(xyz.data()), static_cast<std::streamsize>(8 * xyz.size()));
  return in ? xyz : std::vector<double>();
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: BenchImplicitDistance MESH.vtp POINTS.npy [SINGLE_POINTS]\n");
    return 2;
  }
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(argv[1]);
  vtkNew<vtkTriangleFilter> triangles; // vtkImplicitPolyDataDistance takes triangles only
  triangles->SetInputConnection(reader->GetOutputPort());
  triangles->Update();
  vtkPolyData* mesh = triangles->GetOutput();
  std::vector<double> xyz = ReadPoints(argv[2]);
  const long long n = static_cast<long long>(xyz.size() / 3);
  const long long single = std::min(n, argc > 3 ? std::atoll(argv[3]) : 100000LL);
  if (n == 0 || mesh->GetNumberOfCells() == 0)
  {
    std::fprintf(stderr, "BenchImplicitDistance: no points or no mesh\n");
    return 1;
  }
  vtkNew<vtkMeshDistanceFunction> ours;
  ours->SetInput(mesh);
  double t = Now();
  ours->Prepare();
  std::printf("ours build_s %.4f\n", Now() - t);
  vtkNew<vtkImplicitPolyDataDistance> vtk;
  t = Now();
  vtk->SetInput(mesh);
  std::printf("vtkImplicitPolyDataDistance build_s %.4f\n", Now() - t);

  // One point at a time, one thread: the points in the file's order, then the samples
  // of a grid over the same box in x-fastest order (as vtkSampleFunction or a clip of an
  // image visits them: neighbours in turn).
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (long long i = 0; i < single; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], xyz[3 * i + a]);
      hi[a] = std::max(hi[a], xyz[3 * i + a]);
    }
  }
  const int side = std::max(2, static_cast<int>(std::cbrt(static_cast<double>(single))));
  std::vector<double> grid;
  for (int k = 0; k < side; ++k)
  {
    for (int j = 0; j < side; ++j)
    {
      for (int i = 0; i < side; ++i)
      {
        const int index[3] = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          grid.push_back(lo[a] + (hi[a] - lo[a]) * index[a] / (side - 1));
        }
      }
    }
  }
  vtkImplicitFunction* functions[2] = { ours, vtk };
  double sum = 0, seconds[2]; // the values summed, so that no call can be left out
  for (const bool onGrid : { false, true })
  {
    const double* at = onGrid ? grid.data() : xyz.data();
    const long long count = onGrid ? static_cast<long long>(grid.size() / 3) : single;
    for (int f = 0; f < 2; ++f)
    {
      t = Now();
      for (long long i = 0; i < count; ++i)
      {
        sum += functions[f]->FunctionValue(at + 3 * i);
      }
      seconds[f] = Now() - t;
    }
    static_cast<void>(sum);
    std::printf("single points %lld (%s): ours %.4f s (%.3f us a point), "
                "vtkImplicitPolyDataDistance %.4f s (%.3f us): %.1fx\n",
      count,
      onGrid ? "a grid, x fastest" : "the file's order",
      seconds[0],
      1e6 * seconds[0] / count,
      seconds[1],
      1e6 * seconds[1] / count,
      seconds[1] / seconds[0]);
  }

  // A batch: FunctionValue on an array.
  vtkNew<vtkDoubleArray> points, values[2];
  points->SetNumberOfComponents(3);
  points->SetArray(xyz.data(), 3 * n, 1);
  for (int f = 0; f < 2; ++f)
  {
    t = Now();
    functions[f]->FunctionValue(points, values[f]);
    seconds[f] = Now() - t;
  }
  long long signs = 0;
  double largest = 0;
  for (long long i = 0; i < n; ++i)
  {
    const double a = values[0]->GetValue(i), b = values[1]->GetValue(i);
    largest = std::max(largest, std::fabs(std::fabs(a) - std::fabs(b)));
    signs += (a < 0) != (b < 0);
  }
  std::printf("batch %lld points: ours %.4f s, vtkImplicitPolyDataDistance %.4f s: %.1fx; "
              "largest |difference| of the magnitudes %.3g, signs that differ %lld\n",
    n,
    seconds[0],
    seconds[1],
    seconds[1] / seconds[0],
    largest,
    signs);
  return 0;
}
