// Benchmark (not a test): frame rates of vtkSegmentedDistanceVolumeMapper next to VTK's
// GPU ray caster (vtkOpenGLGPUVolumeRayCastMapper) on the same field, window and camera:
// - the bunny's signed field (vtkLinearFactorDistanceField, pseudonormal sign) at N^3;
// - the mapper's surface (region-aware, lit) and composite (pre-integrated distance
//   shells) with P sample planes across the volume's depth;
// - VTK's ray caster in ISOSURFACE (at 0) and COMPOSITE modes with the same transfer
//   functions, its sample distance the volume's depth along the view direction over P
//   (the mapper's plane spacing);
// with shading on and off. A measure is the mean of FRAMES frames after a first one
// (uploads, tables, shader builds) with a glFinish after the last; the four renderings
// are measured in turn REPEATS times and each figure is the median of its measures.
//
// usage: BenchRender MESH_DIR [--sizes 128,256] [--planes 32,64,256] [--frames 3]
//          [--repeats 5] [--shading on|off|both] [--windows 512x512,1920x1080]
//          [--headless] [--snapshot DIR]
// Without --headless it renders in VTK's own offscreen X window (run it under xvfb-run
// on a machine without a display). With --headless it renders into the module's own EGL
// context (EGL device or surfaceless, as the filters' GPU backend) through a
// vtkGenericOpenGLRenderWindow: the route for a GPU without an X server, since Debian's
// VTK 9.1 has X render windows only. --snapshot writes the four pictures of the first
// measure as PNGs (DIR/{surface,iso,composite,vtk-composite}.png).
#include "BenchRenderContext.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkSegmentedDistanceVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace
{
/// A render window over a context that is already current (BenchRenderContext). It
/// differs from vtkGenericOpenGLRenderWindow in one place: Debian's GLEW is a GLX build,
/// and on an EGL context glewInit() loads every GL entry point and then reports that
/// there is no GLX display, which VTK takes for a failure.
class HeadlessRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static HeadlessRenderWindow* New();
  vtkTypeMacro(HeadlessRenderWindow, vtkGenericOpenGLRenderWindow);

  void OpenGLInitContext() override
  {
    this->ContextCreationTime.Modified();
    if (this->Initialized)
    {
      return;
    }
    const GLenum result = glewInit();
    if ((result != GLEW_OK && result != GLEW_ERROR_NO_GLX_DISPLAY) || !GLEW_VERSION_3_2)
    {
      vtkErrorMacro("no OpenGL 3.2 entry points on the headless context: "
        << reinterpret_cast<const char*>(glewGetErrorString(result)));
      return;
    }
    this->GlewInitValid = true;
    this->Initialized = true;
    this->MaximumHardwareLineWidth = 1.0f;
  }

protected:
  HeadlessRenderWindow()
  {
    this->SetIsCurrent(true); // the context stays current for the whole process
    this->SetReadyForRendering(true);
    this->SetOwnContext(false);
  }
};
vtkStandardNewMacro(HeadlessRenderWindow);

/// The framebuffer a headless window's frames are blitted to (what a window's back
/// buffer is to an X window), resized with the window.
class TargetFramebuffer
{
public:
  void Resize(int width, int height)
  {
    if (this->Id == 0)
    {
      glGenFramebuffers(1, &this->Id);
      glGenRenderbuffers(2, this->Buffers);
    }
    glBindRenderbuffer(GL_RENDERBUFFER, this->Buffers[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, this->Buffers[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, this->Id);
    glFramebufferRenderbuffer(
      GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, this->Buffers[0]);
    glFramebufferRenderbuffer(
      GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, this->Buffers[1]);
    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
  }
  bool Complete() const
  {
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  }

private:
  GLuint Id = 0, Buffers[2] = { 0, 0 };
};

std::vector<int> SplitInts(const std::string& s, char separator)
{
  std::vector<int> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, separator))
  {
    out.push_back(std::atoi(item.c_str()));
  }
  return out;
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct Options
{
  std::string Meshes, Snapshot;
  std::vector<int> Sizes{ 128, 256 }, Planes{ 32, 64, 256 };
  std::vector<std::pair<int, int>> Windows{ { 512, 512 }, { 1920, 1080 } };
  std::vector<bool> Shading{ true, false };
  int Frames = 3, Repeats = 5;
  bool Headless = false;

  bool Parse(int argc, char* argv[])
  {
    if (argc < 2)
    {
      return false;
    }
    this->Meshes = argv[1];
    for (int a = 2; a < argc; ++a)
    {
      const std::string option = argv[a];
      if (option == "--headless")
      {
        this->Headless = true;
        continue;
      }
      if (a + 1 >= argc)
      {
        return false;
      }
      const std::string value = argv[++a];
      if (option == "--sizes")
      {
        this->Sizes = SplitInts(value, ',');
      }
      else if (option == "--planes")
      {
        this->Planes = SplitInts(value, ',');
      }
      else if (option == "--frames")
      {
        this->Frames = std::atoi(value.c_str());
      }
      else if (option == "--repeats")
      {
        this->Repeats = std::atoi(value.c_str());
      }
      else if (option == "--snapshot")
      {
        this->Snapshot = value;
      }
      else if (option == "--shading")
      {
        if (value != "on" && value != "off" && value != "both")
        {
          return false;
        }
        this->Shading = value == "on" ? std::vector<bool>{ true }
          : value == "off"            ? std::vector<bool>{ false }
                                      : std::vector<bool>{ true, false };
      }
      else if (option == "--windows")
      {
        this->Windows.clear();
        std::stringstream in(value);
        std::string item;
        while (std::getline(in, item, ','))
        {
          const std::vector<int> wh = SplitInts(item, 'x');
          if (wh.size() != 2 || wh[0] < 1 || wh[1] < 1)
          {
            return false;
          }
          this->Windows.emplace_back(wh[0], wh[1]);
        }
      }
      else
      {
        return false;
      }
    }
    const auto positive = [](const std::vector<int>& values)
    { return !values.empty() && *std::min_element(values.begin(), values.end()) > 0; };
    return this->Frames > 0 && this->Repeats > 0 && positive(this->Sizes) &&
      positive(this->Planes) && !this->Windows.empty();
  }
};

/// Renders frames of one prop and measures them.
class Bench
{
public:
  Bench(vtkRenderWindow* window, vtkRenderer* renderer, TargetFramebuffer* target, int frames)
    : Window(window)
    , Renderer(renderer)
    , Target(target)
    , Frames(frames)
  {
  }

  /// Frames per second of `prop` in a width x height window, after one frame that
  /// uploads and builds what it needs.
  double FramesPerSecond(vtkProp* prop, int width, int height)
  {
    this->Show(prop, width, height);
    this->Window->Render();
    this->Window->WaitForCompletion();
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < this->Frames; ++f)
    {
      this->Window->Render();
    }
    this->Window->WaitForCompletion();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return this->Frames / seconds;
  }

  void Snapshot(vtkProp* prop, int width, int height, const std::string& file)
  {
    this->Show(prop, width, height);
    this->Window->Render();
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(this->Window);
    grab->ReadFrontBufferOff();
    grab->ShouldRerenderOff();
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputConnection(grab->GetOutputPort());
    writer->SetFileName(file.c_str());
    writer->Write();
  }

private:
  void Show(vtkProp* prop, int width, int height)
  {
    const int* size = this->Window->GetSize();
    if (size[0] != width || size[1] != height)
    {
      this->Window->SetSize(width, height);
      if (this->Target)
      {
        this->Target->Resize(width, height);
      }
    }
    this->Renderer->RemoveAllViewProps();
    this->Renderer->AddViewProp(prop);
  }

  vtkRenderWindow* Window;
  vtkRenderer* Renderer;
  TargetFramebuffer* Target;
  int Frames;
};
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!options.Parse(argc, argv))
  {
    std::fprintf(stderr,
      "usage: BenchRender MESH_DIR [--sizes 128,256] [--planes 32,64,256] [--frames 3] "
      "[--repeats 5] [--shading on|off|both] [--windows 512x512,1920x1080] [--headless] "
      "[--snapshot DIR]\n");
    return 2;
  }

  vtkSmartPointer<vtkRenderWindow> window;
  TargetFramebuffer target;
  if (options.Headless)
  {
    std::string renderer, error;
    if (!MakeHeadlessContextCurrent(renderer, error))
    {
      std::fprintf(stderr, "BenchRender: no headless context: %s\n", error.c_str());
      return 1;
    }
    // The entry points, before VTK's first frame, for the target framebuffer.
    const GLenum result = glewInit();
    if (result != GLEW_OK && result != GLEW_ERROR_NO_GLX_DISPLAY)
    {
      std::fprintf(stderr, "BenchRender: GLEW: %s\n", glewGetErrorString(result));
      return 1;
    }
    const auto first = options.Windows.front();
    target.Resize(first.first, first.second);
    if (!target.Complete())
    {
      std::fprintf(stderr, "BenchRender: the target framebuffer is incomplete\n");
      return 1;
    }
    window = vtkSmartPointer<HeadlessRenderWindow>::New();
    window->SetSize(first.first, first.second);
  }
  else
  {
    window = vtkSmartPointer<vtkRenderWindow>::New();
    window->OffScreenRenderingOn();
  }
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer);
  Bench bench(window, renderer, options.Headless ? &target : nullptr, options.Frames);

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((options.Meshes + "/bunny_75k.vtp").c_str());
  reader->Update();
  if (reader->GetOutput()->GetNumberOfCells() == 0)
  {
    std::fprintf(stderr, "BenchRender: no cells in %s/bunny_75k.vtp\n", options.Meshes.c_str());
    return 1;
  }

  bool printedRenderer = false, snapshotTaken = options.Snapshot.empty();
  if (!snapshotTaken)
  {
    std::error_code error;
    std::filesystem::create_directories(options.Snapshot, error);
  }
  std::printf("| N | window | planes | shading | mapper surface fps | VTK isosurface fps | "
              "ratio | mapper composite fps | VTK composite fps | ratio |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int n : options.Sizes)
  {
    vtkNew<vtkLinearFactorDistanceField> field;
    field->SetInputConnection(reader->GetOutputPort());
    field->SetResolution(n);
    field->SetSignModeToPseudoNormal();
    field->SetBackendToCPU();
    field->Update();
    vtkImageData* image = field->GetOutput();
    image->GetPointData()->SetActiveScalars("Distance");
    const double* spacing = image->GetSpacing();
    const double h = std::min({ spacing[0], spacing[1], spacing[2] });
    double range[2];
    image->GetPointData()->GetArray("Distance")->GetRange(range);

    vtkNew<vtkColorTransferFunction> colour;
    colour->AddRGBPoint(range[0], 0.25, 0.45, 0.95);
    colour->AddRGBPoint(0, 0.95, 0.85, 0.6);
    colour->AddRGBPoint(range[1], 0.95, 0.4, 0.2);
    vtkNew<vtkPiecewiseFunction> opacity;
    const double shellPoints[][2] = { { range[0], 0.02 },
      { -h, 0.02 },
      { 0, 1.0 },
      { h, 0.0 },
      { 3 * h, 0.0 },
      { 4 * h, 0.25 },
      { 5 * h, 0.0 },
      { range[1], 0.0 } };
    for (const auto& point : shellPoints)
    {
      opacity->AddPoint(point[0], point[1]);
    }
    vtkNew<vtkVolumeProperty> shells, surface, iso;
    shells->SetColor(colour);
    shells->SetScalarOpacity(opacity);
    shells->SetScalarOpacityUnitDistance(h);
    iso->GetIsoSurfaceValues()->SetValue(0, 0.0);
    vtkNew<vtkColorTransferFunction> grey; // the mapper's surface colour
    grey->AddRGBPoint(range[0], 0.9, 0.9, 0.9);
    grey->AddRGBPoint(range[1], 0.9, 0.9, 0.9);
    iso->SetColor(grey);
    vtkNew<vtkPiecewiseFunction> solid;
    solid->AddPoint(range[0], 1.0);
    solid->AddPoint(range[1], 1.0);
    iso->SetScalarOpacity(solid);

    vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
    mapper->SetInputData(image);
    vtkNew<vtkVolume> ours;
    ours->SetMapper(mapper);
    vtkNew<vtkOpenGLGPUVolumeRayCastMapper> caster;
    caster->SetInputData(image);
    caster->AutoAdjustSampleDistancesOff();
    vtkNew<vtkVolume> theirs;
    theirs->SetMapper(caster);

    renderer->ResetCamera(image->GetBounds());
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->Azimuth(30);
    camera->Elevation(20);
    camera->OrthogonalizeViewUp();
    renderer->ResetCamera(image->GetBounds());
    // The volume's depth along the view direction: what the mapper divides into planes.
    const double* b = image->GetBounds();
    const double* direction = camera->GetDirectionOfProjection();
    double nearest = 1e300, farthest = -1e300;
    for (int corner = 0; corner < 8; ++corner)
    {
      const double p[3] = { b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + (corner >> 2)] };
      const double d = p[0] * direction[0] + p[1] * direction[1] + p[2] * direction[2];
      nearest = std::min(nearest, d);
      farthest = std::max(farthest, d);
    }
    const double depth = farthest - nearest;

    // The four renderings, in the order they are measured: the mapper's surface, VTK's
    // isosurface, the mapper's composite, VTK's composite.
    const char* names[4] = { "surface", "iso", "composite", "vtk-composite" };
    const auto select = [&](int which) -> vtkProp*
    {
      switch (which)
      {
        case 0:
          ours->SetProperty(surface);
          mapper->SetModeToSurface();
          return ours;
        case 1:
          theirs->SetProperty(iso);
          caster->SetBlendModeToIsoSurface();
          return theirs;
        case 2:
          ours->SetProperty(shells);
          mapper->SetModeToComposite();
          return ours;
        default:
          theirs->SetProperty(shells);
          caster->SetBlendModeToComposite();
          return theirs;
      }
    };
    for (const auto& size : options.Windows)
    {
      for (const int planes : options.Planes)
      {
        for (const bool shade : options.Shading)
        {
          shells->SetShade(shade);
          surface->SetShade(shade);
          iso->SetShade(shade);
          mapper->SetNumberOfSlices(planes);
          caster->SetSampleDistance(depth / planes);
          const int w = size.first, hgt = size.second;
          if (!snapshotTaken)
          {
            snapshotTaken = true;
            for (int which = 0; which < 4; ++which)
            {
              bench.Snapshot(select(which), w, hgt, options.Snapshot + "/" + names[which] + ".png");
            }
          }
          std::vector<double> measures[4];
          for (int r = 0; r < options.Repeats; ++r)
          {
            for (int which = 0; which < 4; ++which)
            {
              measures[which].push_back(bench.FramesPerSecond(select(which), w, hgt));
            }
          }
          if (!printedRenderer)
          {
            printedRenderer = true;
            std::fprintf(stderr,
              "renderer: %s, OpenGL %s\n",
              reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
              reinterpret_cast<const char*>(glGetString(GL_VERSION)));
          }
          const double s = Median(measures[0]), i = Median(measures[1]);
          const double c = Median(measures[2]), v = Median(measures[3]);
          std::printf("| %d | %dx%d | %d | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
            n,
            w,
            hgt,
            planes,
            shade ? "on" : "off",
            s,
            i,
            s / i,
            c,
            v,
            c / v);
          std::fflush(stdout);
        }
      }
    }
  }
  return 0;
}
