// vtkSparseDistanceField: every piece holds the dense field's bits (vtkLinearFactorDistanceField
// on its site scan, MaximumDistance the band's half-width) at every one of its samples, every
// band sample of the dense field lies in a piece, and every sample outside the pieces has
// its brick's side (closed meshes, an open one, a non-manifold export, a soup's band; brick
// sizes from 2 to 32; default and explicit anisotropic grids); the arrays asked for, the
// ghost array, the sides' grid; bad input.
//
// Usage: TestSparseDistanceField DATA_DIR exact|errors
#include "TestSupport.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkSparseDistanceField.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace vtkdf::testing;

namespace
{
vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

struct Case
{
  const char* Mesh;
  int Resolution;
  double Band;
  int Brick;
  int Sign;
  bool FarSides; // the band's sides agree: the far samples' sides are the dense field's
  bool Explicit = false;
};

bool SameBits(vtkDataArray* a, vtkIdType i, vtkDataArray* b, vtkIdType j)
{
  const int n = a->GetNumberOfComponents();
  const int size = a->GetDataTypeSize();
  return std::memcmp(static_cast<char*>(a->GetVoidPointer(0)) + i * n * size,
           static_cast<char*>(b->GetVoidPointer(0)) + j * n * size,
           static_cast<size_t>(n * size)) == 0;
}

/// The dense field of the same grid and band.
vtkSmartPointer<vtkImageData> Dense(vtkPolyData* mesh,
  const Case& c,
  vtkSparseDistanceField* sparse)
{
  vtkNew<vtkLinearFactorDistanceField> dense;
  dense->SetInputData(mesh);
  dense->SetBackendToCPU();
  dense->SetRouteToSiteScan();
  dense->SetSignMode(c.Sign);
  dense->SetComputeClosestFeature(true);
  dense->SetComputeClosestPoint(true);
  dense->SetResolution(c.Resolution);
  dense->SetExplicitGrid(sparse->GetExplicitGrid());
  dense->SetGridOrigin(sparse->GetGridOrigin());
  dense->SetGridSpacing(sparse->GetGridSpacing());
  dense->SetGridDimensions(sparse->GetGridDimensions());
  dense->UpdateInformation();
  double spacing[3];
  dense->GetOutputInformation(0)->Get(vtkDataObject::SPACING(), spacing);
  dense->SetMaximumDistance(c.Band * std::fmin(std::fmin(spacing[0], spacing[1]), spacing[2]));
  dense->Update();
  return dense->GetOutput();
}

/// Compares one case's pieces and sides with the dense field.
void CompareCase(const std::string& data, const Case& c)
{
  vtkSmartPointer<vtkPolyData> mesh = Read(data + "/" + c.Mesh);
  vtkNew<vtkSparseDistanceField> sparse;
  sparse->SetInputData(mesh);
  sparse->SetResolution(c.Resolution);
  sparse->SetBandWidth(c.Band);
  sparse->SetBrickSize(c.Brick);
  sparse->SetSignMode(c.Sign);
  sparse->SetComputeClosestCellId(true);
  sparse->SetComputeClosestFeature(true);
  sparse->SetComputeClosestPoint(true);
  if (c.Explicit)
  {
    double b[6];
    mesh->GetBounds(b);
    sparse->SetExplicitGrid(true);
    sparse->SetGridOrigin(b[0] - 0.1, b[2] - 0.2, b[4] - 0.05);
    sparse->SetGridSpacing((b[1] - b[0]) / 30, (b[3] - b[2]) / 23, (b[5] - b[4]) / 41);
    sparse->SetGridDimensions(34, 28, 44);
  }
  sparse->Update();
  vtkSmartPointer<vtkImageData> dense = Dense(mesh, c, sparse);
  auto* pieces = vtkPartitionedDataSet::SafeDownCast(sparse->GetOutputDataObject(0));
  auto* sides = vtkImageData::SafeDownCast(sparse->GetOutputDataObject(1));
  CHECK(sparse->GetErrorCode() == 0 && pieces && sides && dense->GetNumberOfPoints() > 0);
  if (!pieces || !sides || sparse->GetErrorCode())
  {
    return;
  }
  int whole[6], dims[3];
  dense->GetExtent(whole);
  dense->GetDimensions(dims);
  std::vector<char> covered(dense->GetNumberOfPoints(), 0);
  const char* names[] = { "Distance", "ClosestCellId", "ClosestFeature", "ClosestPoint" };
  int64_t differences = 0, band = 0, hiddenWrong = 0, sidesOnly = 0;
  for (unsigned p = 0; p < pieces->GetNumberOfPartitions(); ++p)
  {
    auto* piece = vtkImageData::SafeDownCast(pieces->GetPartition(p));
    int e[6];
    piece->GetExtent(e);
    vtkDataArray* ghosts = piece->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName());
    double ghostRange[2];
    ghosts->GetRange(ghostRange);
    sidesOnly += ghostRange[0] == vtkDataSetAttributes::HIDDENPOINT; // no band sample
    for (int k = e[4]; k <= e[5]; ++k)
    {
      for (int j = e[2]; j <= e[3]; ++j)
      {
        for (int i = e[0]; i <= e[1]; ++i)
        {
          const vtkIdType at =
            (i - e[0]) + (e[1] - e[0] + 1) * ((j - e[2]) + (e[3] - e[2] + 1) * vtkIdType(k - e[4]));
          const vtkIdType d =
            (i - whole[0]) + dims[0] * ((j - whole[2]) + dims[1] * vtkIdType(k - whole[4]));
          covered[d] = 1;
          const bool inBand =
            dense->GetPointData()->GetArray("ClosestFeature")->GetTuple1(d) != 255;
          band += inBand;
          for (const char* name : names)
          {
            // Beyond a soup's band the sides may differ: the magnitudes may not.
            const bool sideOnly = !c.FarSides && !inBand && std::strcmp(name, "Distance") == 0;
            vtkDataArray* mine = piece->GetPointData()->GetArray(name);
            vtkDataArray* theirs = dense->GetPointData()->GetArray(name);
            const bool same = sideOnly
              ? std::fabs(mine->GetTuple1(at)) == std::fabs(theirs->GetTuple1(d))
              : SameBits(mine, at, theirs, d);
            differences += !same;
          }
          hiddenWrong += (ghosts->GetTuple1(at) == vtkDataSetAttributes::HIDDENPOINT) == inBand;
        }
      }
    }
  }
  // Every band sample in a piece; every other sample with its brick's side.
  int64_t uncoveredBand = 0, sideWrong = 0;
  vtkDataArray* side = sides->GetCellData()->GetArray("Side");
  int nb[3];
  sides->GetDimensions(nb);
  for (vtkIdType d = 0; d < dense->GetNumberOfPoints(); ++d)
  {
    if (covered[d])
    {
      continue;
    }
    uncoveredBand += dense->GetPointData()->GetArray("ClosestFeature")->GetTuple1(d) != 255;
    const int ijk[3] = { int(d % dims[0]), int(d / dims[0] % dims[1]), int(d / dims[0] / dims[1]) };
    int brick[3];
    for (int a = 0; a < 3; ++a)
    {
      brick[a] = std::min(ijk[a] / c.Brick, nb[a] - 2);
    }
    const double s = side->GetTuple1(brick[0] + (nb[0] - 1) * (brick[1] + (nb[1] - 1) * brick[2]));
    const double value = dense->GetPointData()->GetArray("Distance")->GetTuple1(d);
    const double expected = c.Sign == 0 ? 0 : (value < 0 ? -1 : 1);
    sideWrong += c.FarSides && s != expected;
  }
  std::printf("%s %d band %g brick %d sign %d: %u pieces (%lld beyond the band), %lld band "
              "samples (%lld in the pieces), %lld differences, %lld band samples outside "
              "them, %lld far sides wrong, %lld ghosts wrong; %lld bricks decided by sample\n",
    c.Mesh,
    c.Resolution,
    c.Band,
    c.Brick,
    c.Sign,
    pieces->GetNumberOfPartitions(),
    static_cast<long long>(sidesOnly),
    static_cast<long long>(sparse->GetLastBandSamples()),
    static_cast<long long>(band),
    static_cast<long long>(differences),
    static_cast<long long>(uncoveredBand),
    static_cast<long long>(sideWrong),
    static_cast<long long>(hiddenWrong),
    static_cast<long long>(sparse->GetLastWindingBricksDecided()));
  CHECK(pieces->GetNumberOfPartitions() > 0 && band > 0);
  CHECK(band == sparse->GetLastBandSamples());
  CHECK(differences == 0 && uncoveredBand == 0 && sideWrong == 0 && hiddenWrong == 0);
}

int Exact(const std::string& data)
{
  const Case cases[] = {
    { "bunny_small.vtp", 48, 3, 8, 1, true },
    { "bunny_small.vtp", 40, 1.5, 2, 1, true },
    { "bunny_small.vtp", 48, 2, 32, 0, true },
    { "trefoil_knot.vtp", 40, 2.5, 5, 1, true },
    { "max3ds_export.vtp", 40, 4, 16, 1, true },
    { "aneurysm.vtp", 40, 3, 7, 1, true },
    { "boeing_soup.vtp", 40, 2, 8, 1, false },
    { "boeing_soup.vtp", 40, 2, 8, 0, true },
    // Anisotropic: the band (2 of the smallest spacings) is thinner than the largest
    // spacing, and some far samples touch band samples of both sides (which side a flood
    // gives them depends on its order); the band's bits are compared.
    { "bunny_small.vtp", 48, 2, 6, 1, false, true },
    { "bunny_small.vtp", 48, 5, 6, 1, true, true },
    // The winding number's sign: every sample's side is the dense field's, open meshes,
    // soups and thin bands included.
    { "bunny_small.vtp", 48, 3, 8, 2, true },
    { "trefoil_knot.vtp", 40, 2.5, 5, 2, true },
    { "aneurysm.vtp", 40, 3, 7, 2, true },
    { "aneurysm.vtp", 36, 0.3, 4, 2, true },
    // Bricks beyond the band that the surface |w| = 1/2 across the vessel's cut ends
    // passes through: pieces without band samples.
    { "aneurysm.vtp", 100, 1, 2, 2, true },
    { "teapot.vtp", 40, 2, 8, 2, true },
    { "plane.vtp", 32, 1, 4, 2, true },
    { "max3ds_export.vtp", 40, 4, 16, 2, true },
    { "scad_back_to_back.vtp", 32, 2, 5, 2, true },
    { "boeing_soup.vtp", 40, 2, 8, 2, true },
    { "bunny_small.vtp", 48, 2, 6, 2, true, true },
    { "bunny_small.vtp", 40, 0.2, 3, 2, true },
  };
  for (const Case& c : cases)
  {
    CompareCase(data, c);
  }
  return Verdict();
}

/// A run that must fail with `expected` in its error, and leave empty outputs.
template<typename Setup>
void Refused(const char* what, const char* expected, const Setup& setup)
{
  vtkNew<vtkSparseDistanceField> sparse;
  sparse->SetInputData(Triangle());
  sparse->SetResolution(16);
  setup(sparse.Get());
  MessageRecorder recorder(sparse);
  sparse->Update();
  auto* pieces = vtkPartitionedDataSet::SafeDownCast(sparse->GetOutputDataObject(0));
  const bool ok = sparse->GetErrorCode() != 0 &&
    recorder.Errors.find(expected) != std::string::npos && pieces &&
    pieces->GetNumberOfPartitions() == 0;
  std::printf("%s: %s\n", what, ok ? "refused" : recorder.Errors.c_str());
  CHECK(ok);
}

int Errors()
{
  Refused("band nan",
    "BandWidth must be finite",
    [](vtkSparseDistanceField* s) { s->SetBandWidth(NAN); });
  Refused(
    "band 0", "BandWidth must be finite", [](vtkSparseDistanceField* s) { s->SetBandWidth(0); });
  Refused(
    "brick 1", "BrickSize must be between", [](vtkSparseDistanceField* s) { s->SetBrickSize(1); });
  Refused("sign 3", "SignMode must be", [](vtkSparseDistanceField* s) { s->SetSignMode(3); });
  Refused(
    "domains", "DomainShape must be", [](vtkSparseDistanceField* s) { s->SetDomainShape(5); });
  Refused("gpu", "CPU only", [](vtkSparseDistanceField* s) { s->SetBackendToGPU(); });
  Refused("memory",
    "above the memory limit",
    [](vtkSparseDistanceField* s)
    {
      s->SetResolution(512);
      s->SetMemoryLimit(1 << 20);
    });
  Refused("nan mesh",
    "Invalid input mesh",
    [](vtkSparseDistanceField* s) { s->SetInputData(Triangle(NAN)); });
  Refused("too many bricks",
    "larger BrickSize",
    [](vtkSparseDistanceField* s)
    {
      s->SetExplicitGrid(true);
      s->SetGridDimensions(40000, 40000, 40000);
      s->SetBrickSize(2);
      s->SetMemoryLimit(1e18);
    });
  // An empty mesh: a warning and empty outputs, no error.
  vtkNew<vtkSparseDistanceField> sparse;
  vtkNew<vtkPolyData> empty;
  sparse->SetInputData(empty);
  MessageRecorder recorder(sparse);
  sparse->Update();
  auto* pieces = vtkPartitionedDataSet::SafeDownCast(sparse->GetOutputDataObject(0));
  CHECK(sparse->GetErrorCode() == 0 && pieces && pieces->GetNumberOfPartitions() == 0);
  CHECK(recorder.Warnings.find("empty") != std::string::npos);
  // A second run after a failed one computes again.
  sparse->SetInputData(Triangle());
  sparse->SetResolution(16);
  sparse->Update();
  CHECK(sparse->GetErrorCode() == 0 && sparse->GetLastPieces() > 0);
  return Verdict();
}
} // namespace

int main(int argc, char* argv[])
{
  if (!HasArguments(argc, argv, 2, "DATA_DIR exact|errors"))
  {
    return 2;
  }
  const std::string mode = argv[2];
  return mode == "exact" ? Exact(argv[1]) : Errors();
}
