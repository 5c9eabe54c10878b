// Regression image of vtkChamferVoxelDistance (like the paper's Figure 1): a slice
// through bunny_small of the signed chessboard layers, each layer its own colour, with
// the surface's cross-section. Compared with Testing/Data/Baseline/TestChamferImage.png.
//
// usage: TestChamferImage DATA_DIR cpu|gpu -V BASELINE.png -T TMPDIR
#include "ImageTestSupport.h"
#include "TestSupport.h"
#include "vtkChamferVoxelDistance.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCutter.h"
#include "vtkExtractVOI.h"
#include "vtkImageActor.h"
#include "vtkImageData.h"
#include "vtkImageMapToColors.h"
#include "vtkImageMapper3D.h"
#include "vtkImageProperty.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdio>
#include <string>

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR cpu|gpu -V BASELINE -T TMP"))
  {
    return 2;
  }
  const std::string dataDir = argv[1], backend = argv[2];
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dataDir + "/bunny_small.vtp").c_str());

  vtkNew<vtkChamferVoxelDistance> chamfer;
  chamfer->SetInputConnection(reader->GetOutputPort());
  chamfer->SetResolution(120);
  chamfer->SetPadding(0.3);
  chamfer->SetMetricToChessboard18();
  chamfer->SetMaximumLayers(30);
  chamfer->SignedOn();
  vtkdf::testing::UseBackend(chamfer.GetPointer(), backend);
  chamfer->Update();
  vtkImageData* field = chamfer->GetOutput();
  int dims[3];
  field->GetDimensions(dims);
  if (field->GetNumberOfPoints() == 0)
  {
    std::printf("FAIL: no field\n");
    return 1;
  }
  std::printf("%dx%dx%d, %d layers (%s)\n",
    dims[0],
    dims[1],
    dims[2],
    chamfer->GetLastLayers(),
    chamfer->GetLastBackend());

  const int k = dims[2] / 2;
  vtkNew<vtkExtractVOI> slice;
  slice->SetInputData(field);
  slice->SetVOI(0, dims[0] - 1, 0, dims[1] - 1, k, k);
  slice->Update();
  const double z = field->GetOrigin()[2] + k * field->GetSpacing()[2];

  // One colour per layer: warm outside, cool inside, alternating light and dark shells;
  // unreached voxels (31) white.
  vtkNew<vtkLookupTable> lut;
  lut->SetNumberOfTableValues(63);
  lut->SetTableRange(-31, 31);
  for (int i = 0; i < 63; ++i)
  {
    const int layer = i - 31;
    const double t = std::fabs(layer) / 30.0, shade = (std::abs(layer) % 2) ? 0.75 : 1.0;
    if (std::abs(layer) == 31)
    {
      lut->SetTableValue(i, 1, 1, 1, 1);
    }
    else if (layer > 0)
    {
      lut->SetTableValue(i, shade, shade * (0.85 - 0.6 * t), shade * (0.3 + 0.1 * t), 1);
    }
    else if (layer < 0)
    {
      lut->SetTableValue(i, shade * 0.3, shade * (0.5 + 0.4 * t), shade, 1);
    }
    else
    {
      lut->SetTableValue(i, 0.1, 0.1, 0.1, 1);
    }
  }
  vtkNew<vtkImageMapToColors> colours;
  colours->SetInputConnection(slice->GetOutputPort());
  colours->SetLookupTable(lut);
  colours->SetOutputFormatToRGB();
  vtkNew<vtkImageActor> image;
  image->GetMapper()->SetInputConnection(colours->GetOutputPort());
  image->GetProperty()->SetInterpolationTypeToNearest();

  const double white[3] = { 1, 1, 1 };
  auto cutActor =
    vtkdf::testing::SurfaceCut(reader->GetOutputPort(), z, white, 0.5 * field->GetSpacing()[2]);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->AddActor(image);
  renderer->AddActor(cutActor);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->ParallelProjectionOn();
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.15);
  window->Render();
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::PASSED ? 0 : 1;
}
