#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkSegmentedDistanceVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

namespace vtkdf::cli
{

namespace
{
/// vtkdf render's options.
struct RenderOptions
{
  std::string Output, Mode = "surface", Interpolation = "region-aware";
  int Size[2] = { 512, 512 }, Slices = 0;
  double Azimuth = 30, Elevation = 20, Opacity = 1;
  bool Timing = false;

  /// Parses argv[3...]; "" or the usage error.
  std::string Parse(int argc, char* argv[])
  {
    for (int a = 3; a < argc; ++a)
    {
      const std::string option = argv[a];
      if (option == "--timing")
      {
        this->Timing = true;
        continue;
      }
      if (option == "--size" && a + 2 < argc)
      {
        this->Size[0] = ParseInt("--size", argv[++a]);
        this->Size[1] = ParseInt("--size", argv[++a]);
        continue;
      }
      if (a + 1 >= argc)
      {
        return option + " needs a value";
      }
      const char* value = argv[++a];
      if (option == "-o")
      {
        this->Output = value;
      }
      else if (option == "--mode")
      {
        this->Mode = value;
      }
      else if (option == "--interpolation")
      {
        this->Interpolation = value;
      }
      else if (option == "--azimuth")
      {
        this->Azimuth = ParseNumber("--azimuth", value);
      }
      else if (option == "--elevation")
      {
        this->Elevation = ParseNumber("--elevation", value);
      }
      else if (option == "--slices")
      {
        this->Slices = ParseInt("--slices", value);
      }
      else if (option == "--opacity")
      {
        this->Opacity = ParseNumber("--opacity", value);
      }
      else
      {
        return "unknown option " + option;
      }
    }
    return this->Check();
  }

  /// "" when the options make sense together, or the usage error.
  std::string Check() const
  {
    if (this->Output.empty() || !EndsWith(this->Output, ".png"))
    {
      return "render needs -o IMAGE.png";
    }
    if (this->Mode != "surface" && this->Mode != "composite")
    {
      return "--mode is surface or composite";
    }
    if (this->Interpolation != "region-aware" && this->Interpolation != "nearest" &&
      this->Interpolation != "linear")
    {
      return "--interpolation is region-aware, nearest or linear";
    }
    if (this->Size[0] < 1 || this->Size[1] < 1 || this->Size[0] > 16384 || this->Size[1] > 16384 ||
      this->Slices < 0 || !(this->Opacity >= 0 && this->Opacity <= 1) ||
      !std::isfinite(this->Azimuth) || !std::isfinite(this->Elevation))
    {
      return "--size takes 1 to 16384 pixels, --slices N >= 0, --opacity 0 to 1, and the "
             "angles finite numbers";
    }
    return std::string();
  }
};

/// Distance shells for --mode composite: the surface (value 0) opaque, a halo a few voxels
/// out, cool inside and warm outside; over the scalars' range for any other data. False
/// when the field has no point scalars.
bool DistanceShells(vtkImageData* field, vtkVolumeProperty* property)
{
  vtkDataArray* scalars = field->GetPointData()->GetScalars();
  if (!scalars)
  {
    return false;
  }
  double range[2];
  scalars->GetRange(range);
  const double h =
    std::min({ field->GetSpacing()[0], field->GetSpacing()[1], field->GetSpacing()[2] });
  vtkNew<vtkColorTransferFunction> colour;
  vtkNew<vtkPiecewiseFunction> alpha;
  if (range[0] < 0 && range[1] > 0)
  {
    colour->AddRGBPoint(range[0], 0.25, 0.45, 0.95);
    colour->AddRGBPoint(0, 0.95, 0.85, 0.6);
    colour->AddRGBPoint(range[1], 0.95, 0.4, 0.2);
    alpha->AddPoint(range[0], 0.02);
    alpha->AddPoint(-h, 0.02);
    alpha->AddPoint(0, 1.0);
    alpha->AddPoint(h, 0.0);
    alpha->AddPoint(3 * h, 0.0);
    alpha->AddPoint(4 * h, 0.25);
    alpha->AddPoint(5 * h, 0.0);
    alpha->AddPoint(std::max(range[1], 6 * h), 0.0);
  }
  else
  {
    colour->AddRGBPoint(range[0], 0.25, 0.45, 0.95);
    colour->AddRGBPoint(range[1], 0.95, 0.4, 0.2);
    alpha->AddPoint(range[0], 0.0);
    alpha->AddPoint(range[1], 0.5);
  }
  property->SetColor(colour);
  property->SetScalarOpacity(alpha);
  property->SetScalarOpacityUnitDistance(h);
  return true;
}

/// The GL renderer's name, from VTK's report of the window's context.
std::string RendererName(vtkRenderWindow* window)
{
  const std::string report = window->ReportCapabilities();
  const std::string key = "OpenGL renderer string:";
  const size_t at = report.find(key);
  if (at == std::string::npos)
  {
    return "unknown";
  }
  const size_t begin = report.find_first_not_of(' ', at + key.size());
  return report.substr(begin, report.find('\n', begin) - begin);
}

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
} // namespace

/// vtkdf render FIELD.vti -o IMAGE.png [--mode surface|composite] [--size W H]
///   [--azimuth A] [--elevation E] [--slices N] [--interpolation region-aware|nearest|linear]
///   [--opacity O] [--timing]
int Render(int argc, char* argv[])
{
  RenderOptions options;
  const std::string refused = options.Parse(argc, argv);
  if (!refused.empty())
  {
    return Usage(refused.c_str());
  }
  if (!EndsWith(argv[2], ".vti"))
  {
    return Usage("render takes a .vti field");
  }
  // Debian's VTK renders through X11 only.
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    std::fprintf(stderr,
      "vtkdf: render needs an X server and DISPLAY is not set; run it "
      "under one, e.g. xvfb-run -a vtkdf render ...\n");
    return 1;
  }
  vtkSmartPointer<vtkDataObject> data = ReadMeshOrImageOrExit(argv[2]);
  vtkImageData* field = vtkImageData::SafeDownCast(data);
  if (!field || field->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: %s holds no image data\n", argv[2]);
    return 1;
  }
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  mapper->SetNumberOfSlices(options.Slices);
  mapper->SetSurfaceOpacity(options.Opacity);
  mapper->SetInterpolation(options.Interpolation == "nearest"
      ? vtkSegmentedDistanceVolumeMapper::Nearest
      : options.Interpolation == "linear" ? vtkSegmentedDistanceVolumeMapper::Linear
                                          : vtkSegmentedDistanceVolumeMapper::RegionAware);
  vtkNew<vtkVolumeProperty> property;
  property->ShadeOn();
  property->SetAmbient(0.2);
  property->SetDiffuse(0.75);
  property->SetSpecular(0.25);
  property->SetSpecularPower(24);
  if (options.Mode == "composite")
  {
    mapper->SetModeToComposite();
    if (!DistanceShells(field, property))
    {
      std::fprintf(stderr, "vtkdf: %s has no point scalars to composite\n", argv[2]);
      return 1;
    }
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(options.Size[0], options.Size[1]);
  window->SetMultiSamples(0);
  window->OffScreenRenderingOn();
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(options.Azimuth);
  renderer->GetActiveCamera()->Elevation(options.Elevation);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCamera();
  // The first frame uploads the field (and builds the table); the next ones only draw.
  auto start = std::chrono::steady_clock::now();
  window->Render();
  window->WaitForCompletion();
  const double first = SecondsSince(start);
  if (mapper->GetLastNumberOfSlices() == 0)
  {
    std::fprintf(stderr, "vtkdf: nothing was rendered\n");
    return 1;
  }
  const int frames = 3;
  start = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f)
  {
    window->Render();
  }
  window->WaitForCompletion();
  const double frame = SecondsSince(start) / frames;
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  if (!WritePNG(grab->GetOutput(), options.Output))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", options.Output.c_str());
    return 1;
  }
  if (options.Timing)
  {
    int dims[3];
    field->GetDimensions(dims);
    std::printf("vtkdf: render dims=%dx%dx%d mode=%s size=%dx%d slices=%d regions=%d "
                "first_frame_s=%.4f frame_s=%.4f renderer=\"%s\"\n",
      dims[0],
      dims[1],
      dims[2],
      options.Mode.c_str(),
      options.Size[0],
      options.Size[1],
      mapper->GetLastNumberOfSlices(),
      mapper->GetLastRegionCount(),
      first,
      frame,
      RendererName(window).c_str());
  }
  return 0;
}

} // namespace vtkdf::cli
