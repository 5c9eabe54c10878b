// Regression images of the segmented field of a non-manifold, open surface built here: a
// box with an inner wall (junction lines where the wall meets the box) whose right
// chamber has no lid (a boundary).
// - slice: the mid-height slice of RegionIndex, each region in its colour, with the
//   polygonized surface's cut drawn on it;
// - surface: the polygonized surface (vtkSegmentedDistanceContour), each triangle
//   coloured by the pair of regions it separates, seen from above the open chamber.
// Besides the baseline comparison, the picture is checked by numbers: every region (slice)
// or every region pair (surface) of the data shows in the image, each on at least 0.5% of
// the pixels.
//
// usage: TestSegmentImages slice|surface -V BASELINE -T TMP
#include "ImageTestSupport.h"
#include "TestShapes.h"
#include "TestSupport.h"
#include "vtkSegmentedDistanceContour.h"
#include "vtkSegmentedDistanceField.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageActor.h"
#include "vtkImageData.h"
#include "vtkImageMapToColors.h"
#include "vtkImageMapper3D.h"
#include "vtkIntArray.h"
#include "vtkLookupTable.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>

namespace
{
/// A categorical colour for index i.
void Colour(int i, double rgb[3])
{
  static const double palette[8][3] = { { 0.90, 0.45, 0.35 },
    { 0.35, 0.55, 0.90 },
    { 0.40, 0.75, 0.40 },
    { 0.95, 0.80, 0.30 },
    { 0.65, 0.45, 0.80 },
    { 0.30, 0.75, 0.75 },
    { 0.85, 0.55, 0.75 },
    { 0.60, 0.60, 0.60 } };
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = palette[i % 8][c];
  }
}

/// How many pixels of the window show each colour of `colours` (within 12 of 255 per
/// channel, before shading: so used on unlit images only).
std::map<int, double> Coverage(vtkRenderWindow* window,
  const std::map<int, std::array<double, 3>>& colours)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  vtkImageData* image = grab->GetOutput();
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  std::map<int, double> share;
  const vtkIdType n = rgb->GetNumberOfTuples();
  const int components = rgb->GetNumberOfComponents();
  for (vtkIdType p = 0; p < n; ++p)
  {
    for (const auto& c : colours)
    {
      bool same = true;
      for (int ch = 0; ch < 3; ++ch)
      {
        same = same && std::abs(rgb->GetValue(components * p + ch) - 255 * c.second[ch]) <= 12;
      }
      share[c.first] += same ? 1.0 / n : 0.0;
    }
  }
  return share;
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 1, "slice|surface -V BASELINE -T TMP"))
  {
    return 2;
  }
  const std::string mode = argv[1];
  auto mesh = vtkdf::testing::OpenWalledBox();
  vtkNew<vtkSegmentedDistanceField> segment;
  segment->SetInputData(mesh);
  segment->SetResolution(48);
  segment->SetBackendToCPU();
  vtkNew<vtkSegmentedDistanceContour> contour;
  contour->SetInputConnection(segment->GetOutputPort());
  contour->Update();
  const int regions = segment->GetLastRegionCount();
  std::printf("%d regions, %lld triangles\n",
    regions,
    static_cast<long long>(contour->GetOutput()->GetNumberOfCells()));

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  std::map<int, std::array<double, 3>> colours;
  if (mode == "slice")
  {
    // RegionIndex on the mid-height slice through both chambers (z = 0.2), and the cut.
    vtkImageData* field = segment->GetOutput();
    int dims[3];
    field->GetDimensions(dims);
    const double z = 0.2;
    const int k =
      static_cast<int>(std::lround((z - field->GetOrigin()[2]) / field->GetSpacing()[2]));
    vtkNew<vtkLookupTable> table;
    table->SetNumberOfTableValues(regions);
    table->SetRange(0, regions - 1);
    for (int r = 0; r < regions; ++r)
    {
      double rgb[3];
      Colour(r, rgb);
      table->SetTableValue(r, rgb[0], rgb[1], rgb[2]);
      colours[r] = { rgb[0], rgb[1], rgb[2] };
    }
    field->GetPointData()->SetActiveScalars("RegionIndex");
    vtkNew<vtkImageMapToColors> map;
    map->SetInputData(field);
    map->SetLookupTable(table);
    map->SetOutputFormatToRGB();
    vtkNew<vtkImageActor> slice;
    slice->GetMapper()->SetInputConnection(map->GetOutputPort());
    slice->SetDisplayExtent(0, dims[0] - 1, 0, dims[1] - 1, k, k);
    slice->InterpolateOff();
    renderer->AddActor(slice);
    const double black[3] = { 0, 0, 0 };
    renderer->AddActor(vtkdf::testing::SurfaceCut(
      contour->GetOutputPort(), field->GetOrigin()[2] + k * field->GetSpacing()[2], black, 0.01));
    renderer->ResetCamera();
  }
  else
  {
    // The surface, a colour per region pair (flat, unlit: the colours are the numbers).
    vtkPolyData* surface = contour->GetOutput();
    vtkDataArray* pairs = surface->GetCellData()->GetArray("Regions");
    std::map<std::pair<int, int>, int> index;
    vtkNew<vtkIntArray> pairIndex;
    pairIndex->SetName("Pair");
    for (vtkIdType t = 0; t < pairs->GetNumberOfTuples(); ++t)
    {
      const auto key = std::make_pair(
        static_cast<int>(pairs->GetComponent(t, 0)), static_cast<int>(pairs->GetComponent(t, 1)));
      const int i = index.emplace(key, static_cast<int>(index.size())).first->second;
      pairIndex->InsertNextValue(i);
    }
    surface->GetCellData()->SetScalars(pairIndex);
    vtkNew<vtkLookupTable> table;
    const int count = static_cast<int>(index.size());
    table->SetNumberOfTableValues(count);
    table->SetRange(0, count - 1);
    for (int i = 0; i < count; ++i)
    {
      double rgb[3];
      Colour(i, rgb);
      table->SetTableValue(i, rgb[0], rgb[1], rgb[2]);
      colours[i] = { rgb[0], rgb[1], rgb[2] };
    }
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(surface);
    mapper->SetLookupTable(table);
    mapper->SetScalarRange(0, count - 1);
    mapper->SetScalarModeToUseCellData();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->LightingOff();
    renderer->AddActor(actor);
    std::printf("%d region pairs\n", count);
    renderer->ResetCamera();
    renderer->GetActiveCamera()->Elevation(55);
    renderer->GetActiveCamera()->Azimuth(30);
    renderer->ResetCamera();
  }
  window->Render();
  const auto share = Coverage(window, colours);
  for (const auto& s : share)
  {
    std::printf("%s %d: %.1f%% of the pixels\n",
      mode == "slice" ? "region" : "pair",
      s.first,
      100 * s.second);
    CHECK(s.second >= 0.005, "%s %d does not show", mode.c_str(), s.first);
  }
  CHECK(!share.empty(), "nothing drawn");
  const int result = vtkRegressionTestImage(window);
  CHECK(result == vtkRegressionTester::PASSED, "the image differs from the baseline");
  return vtkdf::testing::Verdict();
}
