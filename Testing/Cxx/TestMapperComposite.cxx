// The composite mode of vtkSegmentedDistanceVolumeMapper: pre-integrated rendering
// against the emission-absorption integral, and the tables (MapperTestSupport.h).
#include "MapperTestSupport.h"

namespace vtkdf
{
namespace testing
{
namespace mapper
{
/// Composite: pre-integrated rendering of a ramp (scalar = x over the unit cube, exact
/// under trilinear interpolation) with a peaked opacity and a varying colour, half hidden
/// behind an opaque plane inside the volume; every 6th pixel against the emission-
/// absorption integral along its ray, summed on the CPU in 4000 steps.
int TestComposite()
{
  vtkNew<vtkImageData> ramp;
  const int n = 33;
  ramp->SetDimensions(n, n, n);
  ramp->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  vtkNew<vtkFloatArray> values;
  values->SetName("Ramp");
  values->SetNumberOfTuples(n * n * n);
  for (vtkIdType i = 0; i < n * n * n; ++i)
  {
    values->SetValue(i, static_cast<float>((i % n) / (n - 1.0)));
  }
  ramp->GetPointData()->SetScalars(values);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(0.0, 1.0, 0.2, 0.1);
  colour->AddRGBPoint(0.5, 0.1, 0.9, 0.2);
  colour->AddRGBPoint(1.0, 0.2, 0.3, 1.0);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.02);
  opacity->AddPoint(0.40, 0.02);
  opacity->AddPoint(0.45, 0.6);
  opacity->AddPoint(0.50, 0.02);
  opacity->AddPoint(0.85, 0.02);
  opacity->AddPoint(0.9, 0.3);
  opacity->AddPoint(1.0, 0.3);
  const double unit = 0.1;
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(ramp);
  mapper->SetModeToComposite();
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(colour);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(unit);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkdf::testing::MessageRecorder messages(mapper);
  // The plane z = 0.6 over x < 0.5, inside the volume.
  vtkNew<vtkPlaneSource> planeSource;
  planeSource->SetOrigin(-0.5, -0.5, 0.6);
  planeSource->SetPoint1(0.5, -0.5, 0.6);
  planeSource->SetPoint2(-0.5, 1.5, 0.6);
  planeSource->Update();
  const double white[3] = { 1, 1, 1 };
  auto plane = SurfaceActor(planeSource->GetOutput(), white);
  const double bounds[6] = { 0, 1, 0, 1, 0, 1 };
  // In a perspective projection the samples lie on spheres around the eye, in a parallel
  // one on planes: both against the integral along each pixel's ray. The parallel scene
  // stays for the tables' checks below.
  std::unique_ptr<Scene> perspective(new Scene(bounds, false, 30, 20));
  Scene scene(bounds, true, 30, 20);
  // One slab a voxel (the default), and three: the slab test is exact in the slab's
  // length, the rest is the colour's weighting inside a slab and 8-bit output.
  for (Scene* view : { perspective.get(), &scene })
  {
    vtkCamera* camera = view->Renderer->GetActiveCamera();
    const bool parallel = camera->GetParallelProjection() != 0;
    for (const double sampleDistance : { 0.0, 1.0 / (3 * (n - 1)) })
    {
      mapper->SetSampleDistance(sampleDistance);
      const Frame frame = view->Draw({ plane, volume });
      size_t compared = 0, off = 0, throughPlane = 0;
      double worst = 0;
      for (int y = 3; y < Size; y += 6)
      {
        for (int x = 3; x < Size; x += 6)
        {
          // The pixel's ray: from its point on the near plane along the view direction, or
          // from the eye through that point.
          double start[4], dir[3];
          view->Renderer->SetDisplayPoint(x + 0.5, y + 0.5, 0.0);
          view->Renderer->DisplayToWorld();
          view->Renderer->GetWorldPoint(start);
          for (int c = 0; c < 3; ++c)
          {
            start[c] /= start[3];
          }
          camera->GetDirectionOfProjection(dir);
          if (!parallel)
          {
            double eye[3];
            camera->GetPosition(eye);
            const double length = std::sqrt(std::pow(start[0] - eye[0], 2) +
              std::pow(start[1] - eye[1], 2) + std::pow(start[2] - eye[2], 2));
            for (int c = 0; c < 3; ++c)
            {
              dir[c] = (start[c] - eye[c]) / length;
              start[c] = eye[c];
            }
          }
          // The ray's entry into and exit from the unit cube, and where it meets the plane.
          double enter = 0, leave = std::numeric_limits<double>::max();
          for (int c = 0; c < 3; ++c)
          {
            if (std::abs(dir[c]) < 1e-12)
            {
              enter = (start[c] < 0 || start[c] > 1) ? leave : enter;
              continue;
            }
            const double t0 = (0 - start[c]) / dir[c], t1 = (1 - start[c]) / dir[c];
            enter = std::max(enter, std::min(t0, t1));
            leave = std::min(leave, std::max(t0, t1));
          }
          double stop = leave;
          bool hitsPlane = false;
          const double tPlane = (0.6 - start[2]) / dir[2];
          const double px = start[0] + tPlane * dir[0], py = start[1] + tPlane * dir[1];
          if (tPlane > 0 && px >= -0.5 && px <= 0.5 && py >= -0.5 && py <= 1.5)
          {
            hitsPlane = true;
            stop = std::min(stop, tPlane);
          }
          double expected[3] = { 0, 0, 0 }, transmitted = 1;
          if (leave > enter)
          {
            const int steps = 4000;
            const double dt = (stop - enter) / steps;
            for (int k = 0; k < steps && dt > 0; ++k)
            {
              const double t = enter + (k + 0.5) * dt;
              const double s = std::clamp(start[0] + t * dir[0], 0.0, 1.0);
              const double a = std::min(opacity->GetValue(s), 1.0 - 1e-7);
              const double tau = -std::log1p(-a) / unit;
              const double slab = 1.0 - std::exp(-tau * dt);
              double rgb[3];
              colour->GetColor(s, rgb);
              for (int c = 0; c < 3; ++c)
              {
                expected[c] += transmitted * slab * rgb[c];
              }
              transmitted *= 1.0 - slab;
            }
          }
          // Skip pixels within a pixel of the plane's or the cube's outline.
          if (leave > enter && (leave - enter) < 0.02)
          {
            continue;
          }
          for (int c = 0; c < 3; ++c)
          {
            expected[c] += transmitted * (hitsPlane ? white[c] : Background[c]);
          }
          const unsigned char* pixel = &frame.Rgb[3 * (static_cast<size_t>(y) * Size + x)];
          double error = 0;
          for (int c = 0; c < 3; ++c)
          {
            error = std::max(error, std::abs(pixel[c] - 255 * expected[c]));
          }
          ++compared;
          throughPlane += hitsPlane && leave > enter;
          off += error > 3;
          worst = std::max(worst, error);
        }
      }
      std::printf("composite, %s: %d slices, %zu pixels compared (%zu with the plane behind "
                  "volume), %zu off by more than 3/255, worst %.1f/255\n",
        parallel ? "parallel" : "perspective",
        mapper->GetLastNumberOfSlices(),
        compared,
        throughPlane,
        off,
        worst);
      CHECK(compared > 1000 && throughPlane > 100, "too few pixels compared");
      CHECK(off <= compared / 200, "%zu pixels differ from the integral", off);
      CHECK(sampleDistance == 0 || worst <= 3, "thin slabs: off by up to %.1f/255", worst);
    }
  }
  // The perspective window's end releases the mapper's resources: draw once more first.
  perspective.reset();
  scene.Draw({ plane, volume });
  vtkCamera* camera = scene.Renderer->GetActiveCamera();

  // The table is built once, and again only when a transfer function changes; the step
  // table with it, and when the step's length changes: never under a fixed SampleDistance,
  // with the volume's depth under NumberOfSlices.
  const int builds = mapper->GetTableBuilds();
  const int stepBuilds = mapper->GetStepTableBuilds();
  camera->Azimuth(10);
  scene.Draw({ plane, volume });
  CHECK(mapper->GetTableBuilds() == builds, "a camera move rebuilt the table");
  CHECK(mapper->GetStepTableBuilds() == stepBuilds,
    "a camera move rebuilt the step table under a fixed SampleDistance");
  opacity->AddPoint(0.2, 0.5);
  scene.Draw({ plane, volume });
  CHECK(mapper->GetTableBuilds() == builds + 1, "a transfer function change did not rebuild");
  CHECK(mapper->GetStepTableBuilds() == stepBuilds + 1,
    "a transfer function change did not rebuild the step table");
  mapper->SetNumberOfSlices(40);
  scene.Draw({ plane, volume });
  scene.Draw({ plane, volume });
  CHECK(mapper->GetStepTableBuilds() == stepBuilds + 2,
    "a new step length made %d step tables",
    mapper->GetStepTableBuilds() - stepBuilds - 1);
  camera->Elevation(25);
  camera->OrthogonalizeViewUp();
  scene.Draw({ plane, volume });
  CHECK(mapper->GetStepTableBuilds() == stepBuilds + 3,
    "a view with another depth kept the step table under NumberOfSlices");
  CHECK(mapper->GetTableBuilds() == builds + 1, "a new step length rebuilt the table");
  std::printf(
    "table builds: %d, step tables: %d\n", mapper->GetTableBuilds(), mapper->GetStepTableBuilds());
  CHECK(messages.Errors.empty(), "errors: %s", messages.Errors.c_str());
  return 0;
}

/// Pre-integration against post-classification: a thin shell of high opacity (the radial
/// distance r from the centre of a 48^3 grid, opacity peaked over r in 0.5 +- 0.006, far
/// thinner than a voxel) at one sample a voxel. Reference: VTK's GPU ray caster at a
/// twentieth of a voxel. The mapper at one slab a voxel is closer to it than the ray caster
/// at one sample a voxel (whose shell breaks into rings), and converges to it.
int TestPreIntegration()
{
  const int n = 48;
  vtkNew<vtkImageData> radial;
  radial->SetDimensions(n, n, n);
  const double h = 1.0 / (n - 1);
  radial->SetSpacing(h, h, h);
  radial->SetOrigin(-0.5, -0.5, -0.5);
  vtkNew<vtkFloatArray> values;
  values->SetName("Radius");
  values->SetNumberOfTuples(n * n * n);
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double x = -0.5 + i * h, y = -0.5 + j * h, z = -0.5 + k * h;
        values->SetValue(i + n * (j + n * k), static_cast<float>(std::sqrt(x * x + y * y + z * z)));
      }
    }
  }
  radial->GetPointData()->SetScalars(values);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(0.0, 1.0, 0.9, 0.7);
  colour->AddRGBPoint(0.9, 1.0, 0.9, 0.7);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.494, 0.0);
  opacity->AddPoint(0.5, 0.9);
  opacity->AddPoint(0.506, 0.0);
  opacity->AddPoint(0.9, 0.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(colour);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(0.01);
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(radial);
  mapper->SetModeToComposite();
  mapper->SetPreIntegrationTableSize(1024);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkOpenGLGPUVolumeRayCastMapper> caster;
  caster->SetInputData(radial);
  caster->AutoAdjustSampleDistancesOff();
  vtkNew<vtkVolume> casterVolume;
  casterVolume->SetMapper(caster);
  casterVolume->SetProperty(property);
  const double bounds[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  Scene scene(bounds, true, 25, 15);
  scene.Renderer->SetBackground(0, 0, 0);
  auto grab = [&](vtkVolume* v, double sampleDistance)
  {
    caster->SetSampleDistance(static_cast<float>(sampleDistance));
    mapper->SetSampleDistance(sampleDistance);
    return scene.Draw({ v });
  };
  const Frame reference = grab(casterVolume, h / 20);
  auto error = [&](const Frame& f)
  {
    double sum = 0;
    for (size_t i = 0; i < f.Rgb.size(); ++i)
    {
      sum += std::abs(f.Rgb[i] - reference.Rgb[i]);
    }
    return sum / f.Rgb.size();
  };
  const double casterCoarse = error(grab(casterVolume, h));
  const double mapperCoarse = error(grab(volume, h));
  const double mapperFine = error(grab(volume, h / 8));
  std::printf("thin shell, mean |pixel - reference| (of 255): ray caster at a voxel %.2f, "
              "mapper at a voxel %.2f, mapper at 1/8 voxel %.2f\n",
    casterCoarse,
    mapperCoarse,
    mapperFine);
  CHECK(
    mapperCoarse < 0.5 * casterCoarse, "pre-integration is not better than post-classification");
  CHECK(mapperFine < 2.0, "the mapper does not converge to the reference");
  return 0;
}
} // namespace mapper
} // namespace testing
} // namespace vtkdf
