// Benchmark (not a test): the exact sparse band (vtkSparseDistanceField) next to OpenVDB's
// meshToLevelSet on the same voxels, band and thread count, and OpenVDB's error against
// the exact distances.
//
// usage: BenchSparseBand MESH N [BAND] [THREADS] [RUNS]
//
// The grid is the module's default one of resolution N (docs/grid.md); OpenVDB's transform
// maps its voxel (i, j, k) onto the same sample (voxel size the spacing, translated to the
// grid's origin), and its half-width is BAND voxels (default 3). Both run on THREADS
// threads (default 2): vtkSMPTools for ours, a tbb::global_control for OpenVDB. Each side
// is timed alone, RUNS times interleaved (default 5; every run and the medians are
// printed: the first run of each side meets fresh memory, the later ones reuse some), ours signed
// by pseudonormals and kept as its pieces, OpenVDB's as its sparse grid (no dense copy).
// Then, at every voxel active in both, OpenVDB's value is compared with ours: the largest
// and the 99th-percentile difference in spacings, and the voxels whose signs differ.
#include "vtkSparseDistanceField.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataSetAttributes.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

vtkSmartPointer<vtkPolyData> ReadTriangles(const std::string& path)
{
  vtkNew<vtkTriangleFilter> triangles;
  if (path.size() > 4 && path.substr(path.size() - 4) == ".ply")
  {
    vtkNew<vtkPLYReader> reader;
    reader->SetFileName(path.c_str());
    triangles->SetInputConnection(reader->GetOutputPort());
    triangles->Update();
  }
  else
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    triangles->SetInputConnection(reader->GetOutputPort());
    triangles->Update();
  }
  return triangles->GetOutput();
}

/// Our value at sample ijk, from the piece of its brick; false when no piece holds it in
/// the band.
bool OurValue(vtkPartitionedDataSet* pieces,
  vtkImageData* sides,
  int brickSize,
  const openvdb::Coord& ijk,
  float& value)
{
  int dims[3];
  sides->GetDimensions(dims);
  int b[3];
  for (int a = 0; a < 3; ++a)
  {
    b[a] = std::min(ijk[a] / brickSize, dims[a] - 2);
    if (ijk[a] < 0)
    {
      return false;
    }
  }
  auto* pieceOf = vtkIntArray::SafeDownCast(sides->GetCellData()->GetArray("Piece"));
  const int p = pieceOf->GetValue(b[0] + (dims[0] - 1) * (b[1] + (dims[1] - 1) * b[2]));
  if (p < 0)
  {
    return false;
  }
  auto* piece = vtkImageData::SafeDownCast(pieces->GetPartition(p));
  int e[6];
  piece->GetExtent(e);
  if (ijk[0] > e[1] || ijk[1] > e[3] || ijk[2] > e[5])
  {
    return false;
  }
  const vtkIdType at = (ijk[0] - e[0]) +
    (e[1] - e[0] + 1) * ((ijk[1] - e[2]) + vtkIdType(e[3] - e[2] + 1) * (ijk[2] - e[4]));
  auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
    piece->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  if (ghosts->GetValue(at) != 0)
  {
    return false;
  }
  value = vtkFloatArray::SafeDownCast(piece->GetPointData()->GetArray("Distance"))->GetValue(at);
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: %s MESH N [BAND] [THREADS] [RUNS]\n", argv[0]);
    return 2;
  }
  const int resolution = std::atoi(argv[2]);
  const double band = argc > 3 ? std::atof(argv[3]) : 3.0;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 2;
  const int runs = argc > 5 ? std::atoi(argv[5]) : 5;
  vtkSMPTools::Initialize(threads);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  openvdb::initialize();
  vtkSmartPointer<vtkPolyData> mesh = ReadTriangles(argv[1]);

  vtkNew<vtkSparseDistanceField> ours;
  ours->SetInputData(mesh);
  ours->SetResolution(resolution);
  ours->SetBandWidth(band);
  ours->SetSignModeToPseudoNormal();
  ours->UpdateInformation();
  double origin[3], spacing[3];
  ours->GetOutputInformation(0)->Get(vtkDataObject::ORIGIN(), origin);
  ours->GetOutputInformation(0)->Get(vtkDataObject::SPACING(), spacing);
  const double h = spacing[0];

  // OpenVDB's input: world points and triangles.
  std::vector<openvdb::Vec3s> points(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    points[p] = openvdb::Vec3s(float(x[0]), float(x[1]), float(x[2]));
  }
  std::vector<openvdb::Vec3I> triangles;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    triangles.emplace_back(ids[0], ids[1], ids[2]);
  }
  auto transform = openvdb::math::Transform::createLinearTransform(h);
  transform->postTranslate(openvdb::Vec3d(origin[0], origin[1], origin[2]));

  std::vector<double> ourTimes, vdbTimes;
  openvdb::FloatGrid::Ptr vdb;
  for (int run = 0; run < runs; ++run)
  {
    ours->Modified();
    double start = Now();
    ours->Update();
    ourTimes.push_back(Now() - start);
    vdb.reset();
    start = Now();
    vdb = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(
      *transform, points, triangles, static_cast<float>(band));
    vdbTimes.push_back(Now() - start);
    std::printf("run %d: ours %.3f s, OpenVDB %.3f s\n", run + 1, ourTimes.back(), vdbTimes.back());
    std::fflush(stdout);
  }
  auto* pieces = vtkPartitionedDataSet::SafeDownCast(ours->GetOutputDataObject(0));
  auto* sides = vtkImageData::SafeDownCast(ours->GetOutputDataObject(1));

  // OpenVDB's error at the voxels active in both.
  std::vector<float> errors;
  int64_t signs = 0, onlyVdb = 0;
  for (auto on = vdb->cbeginValueOn(); on; ++on)
  {
    float exact;
    if (!OurValue(pieces, sides, ours->GetBrickSize(), on.getCoord(), exact))
    {
      ++onlyVdb;
      continue;
    }
    errors.push_back(std::fabs(*on - exact) / float(h));
    signs += (*on < 0) != (exact < 0) && exact != 0;
  }
  std::sort(errors.begin(), errors.end());
  const double worst = errors.empty() ? 0 : errors.back();
  const double p99 = errors.empty() ? 0 : errors[errors.size() * 99 / 100];
  std::printf("%s N=%d band=%g threads=%d: ours %.3f s (%lld band samples, %lld pieces, "
              "stages %s), OpenVDB meshToLevelSet %.3f s (%llu active voxels): OpenVDB / ours "
              "%.2f; OpenVDB's error at %zu common voxels: max %.3f h, 99th percentile %.3f h, "
              "%lld signs differ; %lld voxels active in OpenVDB's band only\n",
    argv[1],
    resolution,
    band,
    threads,
    Median(ourTimes),
    static_cast<long long>(ours->GetLastBandSamples()),
    static_cast<long long>(ours->GetLastPieces()),
    ours->GetLastStageTimes(),
    Median(vdbTimes),
    static_cast<unsigned long long>(vdb->activeVoxelCount()),
    Median(vdbTimes) / Median(ourTimes),
    errors.size(),
    worst,
    p99,
    static_cast<long long>(signs),
    static_cast<long long>(onlyVdb));
  return 0;
}
