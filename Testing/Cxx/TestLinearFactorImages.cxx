// Regression images of vtkLinearFactorDistanceField on one slice through bunny_small:
//   distance: the signed distance in a diverging colour map, isolines every 4 h, the
//             surface's cross-section;
//   voronoi:  the discrete Voronoi diagram of the slice, ClosestCellId in distinct
//             colours, with the surface's cross-section.
// The image is compared with Testing/Data/Baseline/<name>.png (vtkRegressionTester).
//
// usage: TestLinearFactorImages DATA_DIR distance|voronoi cpu|gpu -V BASELINE.png -T TMPDIR
#include "ImageTestSupport.h"
#include "TestSupport.h"
#include "vtkLinearFactorDistanceField.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkContourFilter.h"
#include "vtkCutter.h"
#include "vtkIdTypeArray.h"
#include "vtkImageActor.h"
#include "vtkImageData.h"
#include "vtkImageMapToColors.h"
#include "vtkImageMapper3D.h"
#include "vtkImageProperty.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace
{
/// A colour per cell id that neighbours rarely share (a hash, bright enough to read).
void CellColour(vtkIdType id, unsigned char rgb[3])
{
  uint64_t x = static_cast<uint64_t>(id) * 0x9E3779B97F4A7C15ull;
  x ^= x >> 29;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 32;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = static_cast<unsigned char>(60 + (x >> (8 * c)) % 196);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(
        argc, argv, 3, "DATA_DIR distance|voronoi cpu|gpu -V BASELINE -T TMP"))
  {
    return 2;
  }
  const std::string dataDir = argv[1], mode = argv[2], backend = argv[3];

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dataDir + "/bunny_small.vtp").c_str());
  reader->Update();
  vtkPolyData* mesh = reader->GetOutput();
  double bounds[6];
  mesh->GetBounds(bounds);

  // One slice (nz = 1) through the middle of the bunny, 1 h = 1/120 of the padded box.
  const int n = 120;
  double longest = 0;
  for (int a = 0; a < 3; ++a)
  {
    longest = std::fmax(longest, bounds[2 * a + 1] - bounds[2 * a]);
  }
  const double pad = 0.1 * longest, h = (longest + 2 * pad) / (n - 1);
  const double zSlice = 0.5 * (bounds[4] + bounds[5]);
  const int nx = static_cast<int>(std::ceil((bounds[1] - bounds[0] + 2 * pad) / h)) + 1;
  const int ny = static_cast<int>(std::ceil((bounds[3] - bounds[2] + 2 * pad) / h)) + 1;

  vtkNew<vtkLinearFactorDistanceField> field;
  field->SetInputConnection(reader->GetOutputPort());
  field->SetExplicitGrid(true);
  field->SetGridOrigin(bounds[0] - pad, bounds[2] - pad, zSlice);
  field->SetGridSpacing(h, h, h);
  field->SetGridDimensions(nx, ny, 1);
  field->SetSignModeToPseudoNormal();
  field->SetComputeClosestPoint(false);
  field->SetComputeClosestFeature(false);
  vtkdf::testing::UseBackend(field.GetPointer(), backend);
  field->Update();
  vtkImageData* slice = field->GetOutput();
  if (slice->GetNumberOfPoints() != vtkIdType(nx) * ny)
  {
    std::printf("FAIL: the slice has %lld samples, expected %d\n",
      static_cast<long long>(slice->GetNumberOfPoints()),
      nx * ny);
    return 1;
  }
  std::printf(
    "%s backend: %s (%s)\n", mode.c_str(), field->GetLastBackend(), field->GetLastRenderer());

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  vtkNew<vtkImageActor> image;
  image->GetProperty()->SetInterpolationTypeToNearest();
  vtkNew<vtkImageMapToColors> colours;
  vtkNew<vtkImageData> rgbSlice;
  if (mode == "distance")
  {
    // Blue inside, red outside, white on the surface; symmetric range.
    double range[2];
    slice->GetPointData()->GetArray("Distance")->GetRange(range);
    const double extreme = std::fmax(std::fabs(range[0]), std::fabs(range[1]));
    vtkNew<vtkLookupTable> lut;
    lut->SetNumberOfTableValues(256);
    lut->SetTableRange(-extreme, extreme);
    for (int i = 0; i < 256; ++i)
    {
      const double t = i / 255.0;
      const double r = t < 0.5 ? 2 * t : 1.0;
      const double b = t < 0.5 ? 1.0 : 2 * (1 - t);
      const double g = 1.0 - std::fabs(2 * t - 1);
      lut->SetTableValue(i, 0.3 + 0.7 * r, 0.3 + 0.7 * g, 0.3 + 0.7 * b, 1.0);
    }
    slice->GetPointData()->SetActiveScalars("Distance");
    colours->SetInputData(slice);
    colours->SetLookupTable(lut);
    colours->SetOutputFormatToRGB();
    image->GetMapper()->SetInputConnection(colours->GetOutputPort());

    vtkNew<vtkContourFilter> isolines;
    isolines->SetInputData(slice);
    isolines->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Distance");
    const int count = static_cast<int>(std::floor(extreme / (4 * h)));
    int value = 0;
    for (int i = -count; i <= count; ++i)
    {
      if (i != 0)
      {
        isolines->SetValue(value++, 4 * h * i);
      }
    }
    vtkNew<vtkPolyDataMapper> isoMapper;
    isoMapper->SetInputConnection(isolines->GetOutputPort());
    isoMapper->ScalarVisibilityOff();
    vtkNew<vtkActor> isoActor;
    isoActor->SetMapper(isoMapper);
    isoActor->GetProperty()->SetColor(0.15, 0.15, 0.15);
    isoActor->SetPosition(0, 0, 0.01 * h);
    renderer->AddActor(isoActor);
  }
  else
  {
    vtkIdTypeArray* ids =
      vtkIdTypeArray::SafeDownCast(slice->GetPointData()->GetArray("ClosestCellId"));
    if (!ids)
    {
      std::printf("FAIL: no ClosestCellId array\n");
      return 1;
    }
    rgbSlice->ShallowCopy(slice);
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetName("Voronoi");
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(ids->GetNumberOfTuples());
    for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
    {
      unsigned char c[3];
      CellColour(ids->GetValue(i), c);
      rgb->SetTypedTuple(i, c);
    }
    rgbSlice->GetPointData()->SetScalars(rgb);
    image->GetMapper()->SetInputData(rgbSlice);
  }
  renderer->AddActor(image);

  // The surface's cross-section on the slice.
  const double cutColour[3] = { 0, 0, mode == "distance" ? 0.6 : 0.0 };
  auto cutActor = vtkdf::testing::SurfaceCut(reader->GetOutputPort(), zSlice, cutColour, 0.02 * h);
  renderer->AddActor(cutActor);

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->ParallelProjectionOn();
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.15);
  window->Render();

  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::PASSED ? 0 : 1;
}
