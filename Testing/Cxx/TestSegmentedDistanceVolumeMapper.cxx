// vtkSegmentedDistanceVolumeMapper, tested by numbers read back from the window (depth
// buffer and colours) against polygonal references drawn by VTK's own mapper with the
// same camera:
// - signed: bunny_small's signed field. The mapper's depth against the zero level set
//   (vtkFlyingEdges3D) of the same field, perspective and parallel; RegionAware within a
//   small fraction of a voxel, closer than the paper's Nearest sampling; against the mesh
//   itself within a voxel.
// - segmented: the open walled box (junction lines, an open chamber) against its
//   polygonized surface (vtkSegmentedDistanceContour): depth, and every region's colour
//   on screen where the reference shows that region's side.
// - occlusion: a sphere actor half inside the bunny's field: the combined depth buffer is
//   the nearer of the two drawn alone, and the colours follow, both ways.
// - translucent: SurfaceOpacity 0.5 blends over the background and writes no depth.
// - composite: pre-integrated rendering of a ramp against the emission-absorption
//   integral per pixel, in perspective and parallel projections, slabs cut by an opaque
//   plane inside the volume; the table is rebuilt only when a transfer function changes,
//   the step table also when the step's length does.
// - accuracy MESH: a mesh's segmented field drawn by the mapper against its polygonized
//   surface, against the mesh's own depth, and every drawn point against the mesh in 3D
//   (for bunny_small also its signed field, next to VTK's ray caster in ISOSURFACE mode).
// - lighting: diffuse brightness on a sphere against |n . v| with the radial normal at
//   each pixel's surface point, normals from ClosestPoint and from the gradient.
// - lifecycle: window resizes, property changes, new input data and
//   ReleaseGraphicsResources between frames; the same pictures, no GL error.
// - errors: bad input is reported (no scalars, NaN, a flat grid, SegmentedDistance without
//   RegionOffset) and nothing is drawn; a field with no negative value (an unsigned
//   distance) draws nothing in Mode Surface, with a warning.
// - image walledbox|ct|blend: regression images (a non-manifold mesh's surfaces by
//   region, a translucent composite of a CT-like phantom, the middle frame of a blend),
//   each with numbers checked too; -V BASELINE -T TMP.
//
#include "MapperTestSupport.h"

namespace vtkdf
{
namespace testing
{
namespace mapper
{
int TestSigned(const std::string& data)
{
  double spacing[3];
  auto field = SignedBunny(data, spacing);
  const double h = spacing[0];
  auto levelSet = ZeroLevelSet(field);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((data + "/bunny_small.vtp").c_str());
  reader->Update();
  const double white[3] = { 1, 1, 1 };
  auto levelSetActor = SurfaceActor(levelSet, white);
  auto meshActor = SurfaceActor(reader->GetOutput(), white);
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  auto volume = FieldVolume(mapper, false);
  vtkdf::testing::MessageRecorder messages(mapper);
  for (const bool parallel : { false, true })
  {
    Scene scene(field->GetBounds(), parallel, 35, 20);
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    const Frame reference = scene.Draw({ levelSetActor });
    const Frame mesh = scene.Draw({ meshActor });
    std::map<int, Difference> byMode;
    for (const int mode :
      { vtkSegmentedDistanceVolumeMapper::RegionAware, vtkSegmentedDistanceVolumeMapper::Nearest })
    {
      mapper->SetInterpolation(mode);
      const Frame drawn = scene.Draw({ volume });
      const Difference d = Compare(drawn, reference, camera);
      const Difference m = Compare(drawn, mesh, camera);
      byMode[mode] = d;
      std::printf("%s %s: %d slices; against the level set: %.2f%% pixels differ, depth "
                  "median %.3f p90 %.3f mean %.3f voxels; against the mesh: %.2f%%, median "
                  "%.3f p90 %.3f voxels\n",
        parallel ? "parallel" : "perspective",
        mapper->GetInterpolationAsString(),
        mapper->GetLastNumberOfSlices(),
        100 * d.Mismatch,
        d.Median / h,
        d.P90 / h,
        d.Mean / h,
        100 * m.Mismatch,
        m.Median / h,
        m.P90 / h);
      CHECK(d.Both > 5000, "too few pixels covered (%zu)", d.Both);
      CHECK(mapper->GetLastRegionCount() == 2 && !mapper->GetLastSegmented(),
        "a signed field is two regions (%d)",
        mapper->GetLastRegionCount());
      if (mode == vtkSegmentedDistanceVolumeMapper::RegionAware)
      {
        CHECK(
          d.Mismatch < 0.02, "coverage differs from the level set's on %.2f%%", 100 * d.Mismatch);
        CHECK(d.Median < 0.05 * h && d.P90 < 0.15 * h,
          "depth off the level set: median %.3f p90 %.3f voxels",
          d.Median / h,
          d.P90 / h);
        CHECK(m.Mismatch < 0.04 && m.P90 < 0.5 * h,
          "depth off the mesh: %.2f%% pixels, p90 %.3f voxels",
          100 * m.Mismatch,
          m.P90 / h);
      }
    }
    CHECK(byMode[vtkSegmentedDistanceVolumeMapper::RegionAware].Mean <
        0.5 * byMode[vtkSegmentedDistanceVolumeMapper::Nearest].Mean,
      "region-aware sampling is not closer than nearest sampling");
  }
  // A cube whose grid ends 0.6 voxel outside its faces: rays enter the volume through its
  // sides between two slices, and the face lies in that stretch before their first slice
  // (searched too, else the faces would show holes onto the cube's inside).
  {
    vtkNew<vtkCubeSource> cubeSource;
    cubeSource->SetXLength(2);
    cubeSource->SetYLength(2);
    cubeSource->SetZLength(2);
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(cubeSource->GetOutputPort());
    vtkNew<vtkLinearFactorDistanceField> cubeField;
    cubeField->SetInputConnection(triangles->GetOutputPort());
    cubeField->SetResolution(40);
    cubeField->SetPadding(0.3 / 39);
    cubeField->SetBackendToCPU();
    cubeField->SetSignModeToPseudoNormal();
    cubeField->Update();
    vtkImageData* cube = cubeField->GetOutput();
    auto cubeActor = SurfaceActor(ZeroLevelSet(cube), white);
    mapper->SetInputData(cube);
    mapper->SetInterpolationToRegionAware();
    Scene scene(cube->GetBounds(), false, 35, 20);
    const Frame reference = scene.Draw({ cubeActor });
    const Frame drawn = scene.Draw({ volume });
    const double hc = cube->GetSpacing()[0];
    const Difference d = Compare(drawn, reference, scene.Renderer->GetActiveCamera());
    std::printf("cube at the volume's sides: %.2f%% pixels differ from the level set, depth "
                "median %.3f p90 %.3f voxels\n",
      100 * d.Mismatch,
      d.Median / hc,
      d.P90 / hc);
    CHECK(d.Mismatch < 0.02 && d.P90 < 0.1 * hc, "the surface at the volume's sides is off");
  }
  // The eye inside the volume's box (outside the bunny, near a corner of its box): the rays
  // start at the near plane, and the box's faces in front of the eye are behind it.
  {
    mapper->SetInputData(field);
    const double* b = field->GetBounds();
    Scene scene(b, false, 0, 0);
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    const double eye[3] = {
      b[0] + 0.05 * (b[1] - b[0]), b[2] + 0.05 * (b[3] - b[2]), b[4] + 0.95 * (b[5] - b[4])
    };
    camera->SetPosition(eye);
    camera->SetFocalPoint((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2);
    camera->SetViewUp(0, 1, 0);
    camera->OrthogonalizeViewUp();
    camera->SetViewAngle(60);
    camera->SetClippingRange(0.01 * (b[1] - b[0]), 4 * (b[1] - b[0]));
    const Frame reference = scene.Draw({ levelSetActor });
    const Frame drawn = scene.Draw({ volume });
    const Difference d = Compare(drawn, reference, camera);
    std::printf("eye inside the volume's box: %zu pixels covered by both, %.2f%% differ from the "
                "level set, depth median %.3f p90 %.3f voxels\n",
      d.Both,
      100 * d.Mismatch,
      d.Median / h,
      d.P90 / h);
    CHECK(d.Both > 5000 && d.Mismatch < 0.02 && d.Median < 0.05 * h && d.P90 < 0.15 * h,
      "the surface seen from inside the volume's box is off");
  }
  CHECK(messages.Errors.empty(), "errors: %s", messages.Errors.c_str());
  return 0;
}

int TestSegmented()
{
  int regions = 0;
  auto field = WalledBoxField(40, &regions);
  const double h = field->GetSpacing()[0];
  vtkNew<vtkSegmentedDistanceContour> contour;
  contour->SetInputData(field);
  contour->UseClosestPointsOff(); // the paper's vertices, as the mapper draws them
  contour->Update();
  vtkPolyData* surface = contour->GetOutput();
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  auto volume = FieldVolume(mapper, false);
  vtkdf::testing::MessageRecorder messages(mapper);
  // Seen from above the open chamber: the outside, the closed chamber's lid and the open
  // chamber's floor and walls all show.
  Scene scene(field->GetBounds(), false, 30, 55);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const double white[3] = { 1, 1, 1 };
  auto surfaceActor = SurfaceActor(surface, white);
  const Frame reference = scene.Draw({ surfaceActor });
  const Frame drawn = scene.Draw({ volume });
  const Difference d = Compare(drawn, reference, camera);
  std::printf("walled box: %d regions, %d drawn, %d slices; %.2f%% pixels differ, depth median "
              "%.3f p90 %.3f voxels\n",
    regions,
    mapper->GetLastRegionCount(),
    mapper->GetLastNumberOfSlices(),
    100 * d.Mismatch,
    d.Median / h,
    d.P90 / h);
  CHECK(mapper->GetLastSegmented() && mapper->GetLastRegionCount() == regions,
    "read %d regions of %d",
    mapper->GetLastRegionCount(),
    regions);
  CHECK(d.Mismatch < 0.03,
    "coverage differs from the polygonized surface's on %.2f%%",
    100 * d.Mismatch);
  CHECK(d.Median < 0.1 * h && d.P90 < 0.5 * h, "depth off the polygonized surface");

  // Colours: the reference draws each triangle in the colour of the region on the side
  // the viewer sees (a triangle faces the higher of the two regions it separates; its
  // back shows the lower one). Where both pictures show the same depth, the colours agree.
  vtkDataArray* pairs = surface->GetCellData()->GetArray("Regions");
  std::map<std::pair<int, int>, vtkSmartPointer<vtkPolyData>> byPair;
  for (vtkIdType t = 0; t < surface->GetNumberOfCells(); ++t)
  {
    const auto key = std::make_pair(
      static_cast<int>(pairs->GetComponent(t, 0)), static_cast<int>(pairs->GetComponent(t, 1)));
    auto& part = byPair[key];
    if (!part)
    {
      part = vtkSmartPointer<vtkPolyData>::New();
      part->SetPoints(surface->GetPoints());
      part->AllocateExact(16, 16);
    }
    part->InsertNextCell(VTK_TRIANGLE, surface->GetCell(t)->GetPointIds());
  }
  std::vector<vtkSmartPointer<vtkActor>> parts;
  for (const auto& p : byPair)
  {
    double low[3], high[3];
    mapper->GetRegionColor(p.first.first, low);
    mapper->GetRegionColor(p.first.second, high);
    auto actor = SurfaceActor(p.second, high);
    vtkNew<vtkProperty> backface;
    backface->SetColor(low);
    backface->LightingOff();
    actor->SetBackfaceProperty(backface);
    parts.push_back(actor);
  }
  scene.Renderer->RemoveAllViewProps();
  for (const auto& actor : parts)
  {
    scene.Renderer->AddActor(actor);
  }
  scene.Window->Render();
  const Frame coloured = Grab(scene.Window);
  std::map<int, size_t> shown;
  size_t compared = 0, differ = 0;
  for (size_t p = 0; p < drawn.Depth.size(); ++p)
  {
    if (!drawn.Covered(p) || !coloured.Covered(p) ||
      std::abs(ViewDepth(drawn.Depth[p], camera) - ViewDepth(coloured.Depth[p], camera)) > 0.25 * h)
    {
      continue;
    }
    ++compared;
    int which = -1;
    for (int r = 0; r < regions; ++r)
    {
      double rgb[3];
      mapper->GetRegionColor(r, rgb);
      which = SameColour(&drawn.Rgb[3 * p], rgb, 3) ? r : which;
    }
    ++shown[which];
    differ += (memcmp(&drawn.Rgb[3 * p], &coloured.Rgb[3 * p], 3) != 0);
  }
  for (const auto& r : shown)
  {
    std::printf("region %d: %.1f%% of the surface pixels\n", r.first, 100.0 * r.second / compared);
  }
  std::printf("colours differ from the reference's on %.2f%% of %zu pixels\n",
    100.0 * differ / compared,
    compared);
  CHECK(shown.count(-1) == 0, "%zu pixels in no region's colour", shown[-1]);
  CHECK(shown.size() >= 2, "fewer than two regions show");
  CHECK(differ < 0.01 * compared, "colours differ on %zu pixels", differ);

  // The paper's Fig. 7: linear interpolation between region 0 (outside) and region 2 (the
  // open chamber) passes through values of region 1 (the closed chamber), which then shows
  // where no surface of region 1 is in view. Region-aware sampling shows it only where the
  // three regions meet (the wall's top edge, a pixel or so).
  auto middleRegionPixels = [&](const Frame& f)
  {
    double rgb1[3];
    mapper->GetRegionColor(1, rgb1);
    size_t count = 0;
    for (size_t p = 0; p < f.Depth.size(); ++p)
    {
      count += f.Covered(p) && SameColour(&f.Rgb[3 * p], rgb1, 3);
    }
    return count;
  };
  mapper->SetInterpolationToLinear();
  const Frame linear = scene.Draw({ volume });
  mapper->SetInterpolationToNearest();
  const Frame nearest = scene.Draw({ volume });
  mapper->SetInterpolationToRegionAware();
  std::printf("region 1's colour on %zu pixels with linear sampling, %zu nearest, %zu "
              "region-aware\n",
    middleRegionPixels(linear),
    middleRegionPixels(nearest),
    middleRegionPixels(drawn));
  CHECK(middleRegionPixels(drawn) <= 5, "region 1 shows with region-aware sampling");
  CHECK(middleRegionPixels(nearest) <= 5, "region 1 shows with nearest sampling");
  CHECK(middleRegionPixels(linear) > 100, "linear sampling does not invent region 1");

  // SetRegionColor recolours; the depth stays.
  double rgb0[3];
  mapper->GetRegionColor(0, rgb0);
  mapper->SetRegionColor(0, 1.0, 0.0, 1.0);
  const Frame recoloured = scene.Draw({ volume });
  const double magenta[3] = { 1, 0, 1 };
  size_t magentaPixels = 0, region0Pixels = 0;
  for (size_t p = 0; p < recoloured.Depth.size(); ++p)
  {
    magentaPixels += recoloured.Covered(p) && SameColour(&recoloured.Rgb[3 * p], magenta, 3);
    region0Pixels += drawn.Covered(p) && SameColour(&drawn.Rgb[3 * p], rgb0, 3);
  }
  CHECK(magentaPixels == region0Pixels && magentaPixels > 0,
    "region 0 recoloured on %zu pixels, not %zu",
    magentaPixels,
    region0Pixels);
  CHECK(recoloured.Depth == drawn.Depth, "recolouring changed the depth");
  CHECK(messages.Errors.empty(), "errors: %s", messages.Errors.c_str());
  return 0;
}

int TestOcclusion(const std::string& data)
{
  double spacing[3];
  auto field = SignedBunny(data, spacing);
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  auto volume = FieldVolume(mapper, false);
  // A sphere centred on the bunny's surface at its widest: half inside, half outside.
  const double* b = field->GetBounds();
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2);
  sphere->SetRadius(0.3 * (b[1] - b[0]));
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  sphere->Update();
  const double red[3] = { 0.9, 0.1, 0.1 };
  auto sphereActor = SurfaceActor(sphere->GetOutput(), red);
  Scene scene(b, false, 20, 10);
  const Frame sphereAlone = scene.Draw({ sphereActor });
  const Frame volumeAlone = scene.Draw({ volume });
  const Frame both = scene.Draw({ sphereActor, volume });
  double rgb0[3];
  mapper->GetRegionColor(0, rgb0);
  size_t sphereFront = 0, volumeFront = 0, wrongDepth = 0, wrongColour = 0;
  for (size_t p = 0; p < both.Depth.size(); ++p)
  {
    const float expected = std::min(sphereAlone.Depth[p], volumeAlone.Depth[p]);
    wrongDepth += std::abs(both.Depth[p] - expected) > 1e-6f;
    if (!sphereAlone.Covered(p) || !volumeAlone.Covered(p) ||
      std::abs(sphereAlone.Depth[p] - volumeAlone.Depth[p]) < 1e-3f)
    {
      continue;
    }
    const bool sphereNearer = sphereAlone.Depth[p] < volumeAlone.Depth[p];
    (sphereNearer ? sphereFront : volumeFront) += 1;
    wrongColour += !SameColour(&both.Rgb[3 * p], sphereNearer ? red : rgb0, 3);
  }
  std::printf("occlusion: sphere in front on %zu pixels, the surface on %zu; %zu depths and "
              "%zu colours differ from the nearer one's\n",
    sphereFront,
    volumeFront,
    wrongDepth,
    wrongColour);
  CHECK(sphereFront > 1000 && volumeFront > 1000, "the scene does not test both ways");
  CHECK(wrongDepth == 0 && wrongColour == 0, "occlusion is wrong");
  return 0;
}

int TestTranslucent(const std::string& data)
{
  double spacing[3];
  auto field = SignedBunny(data, spacing);
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  auto volume = FieldVolume(mapper, false);
  Scene scene(field->GetBounds(), false, 35, 20);
  const Frame opaque = scene.Draw({ volume });
  mapper->SetSurfaceOpacity(0.5);
  const Frame translucent = scene.Draw({ volume });
  double rgb0[3], rgb1[3];
  mapper->GetRegionColor(0, rgb0);
  mapper->GetRegionColor(1, rgb1);
  // A ray through the bunny crosses the surface twice: outside -> inside (region 0's
  // side) and inside -> outside (region 1's), blended back to front over the background.
  size_t through = 0, wrong = 0, depthWritten = 0;
  for (size_t p = 0; p < opaque.Depth.size(); ++p)
  {
    depthWritten += translucent.Covered(p);
    if (!opaque.Covered(p))
    {
      continue;
    }
    double expected[3];
    for (int c = 0; c < 3; ++c)
    {
      const double back = 0.5 * rgb1[c] + 0.5 * Background[c];
      expected[c] = 0.5 * rgb0[c] + 0.5 * back;
    }
    ++through;
    wrong += !SameColour(&translucent.Rgb[3 * p], expected, 4);
  }
  std::printf("translucent: %zu pixels, %zu not the two-layer blend, %zu depths written\n",
    through,
    wrong,
    depthWritten);
  // Silhouette pixels may cross the surface once or more than twice.
  CHECK(through > 5000 && wrong < 0.05 * through, "the blend is wrong on %zu pixels", wrong);
  CHECK(depthWritten == 0, "a translucent surface wrote depth");
  return 0;
}

int TestLifecycle(const std::string& data)
{
  double spacing[3];
  auto field = SignedBunny(data, spacing);
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  auto volume = FieldVolume(mapper, true);
  vtkdf::testing::MessageRecorder messages(mapper);
  Scene scene(field->GetBounds(), false, 35, 20);
  const Frame first = scene.Draw({ volume });
  auto coverage = [](const Frame& f)
  {
    size_t n = 0;
    for (size_t p = 0; p < f.Depth.size(); ++p)
    {
      n += f.Covered(p);
    }
    return static_cast<double>(n) / f.Depth.size();
  };
  // Resize and back.
  scene.Window->SetSize(Size + 60, Size + 20);
  const Frame resized = scene.Draw({ volume });
  scene.Window->SetSize(Size, Size);
  const Frame back = scene.Draw({ volume });
  CHECK(resized.Width == Size + 60 && coverage(resized) > 0.5 * coverage(first),
    "nothing after a resize");
  CHECK(back.Depth == first.Depth, "resizing back changed the picture");
  // Release everything, draw again.
  mapper->ReleaseGraphicsResources(scene.Window);
  const Frame released = scene.Draw({ volume });
  CHECK(released.Depth == first.Depth && released.Rgb == first.Rgb,
    "the picture after ReleaseGraphicsResources differs");
  // Shade off then on: colours change, depth does not.
  volume->GetProperty()->ShadeOff();
  const Frame flat = scene.Draw({ volume });
  CHECK(flat.Depth == first.Depth && flat.Rgb != first.Rgb, "Shade is not picked up");
  volume->GetProperty()->ShadeOn();
  // New input data: a shifted copy of the field moves the picture.
  vtkNew<vtkImageData> shifted;
  shifted->DeepCopy(field);
  double origin[3];
  field->GetOrigin(origin);
  shifted->SetOrigin(origin[0] + 5 * spacing[0], origin[1], origin[2]);
  mapper->SetInputData(shifted);
  const Frame moved = scene.Draw({ volume });
  CHECK(moved.Depth != first.Depth, "new input data is not picked up");
  mapper->SetInputData(field);
  const Frame restored = scene.Draw({ volume });
  CHECK(restored.Depth == first.Depth, "the first input does not come back");
  // Modified values in place.
  vtkDataArray* values = field->GetPointData()->GetArray("Distance");
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    values->SetTuple1(i, values->GetTuple1(i) - 0.5 * spacing[0]);
  }
  values->Modified();
  field->Modified();
  const Frame grown = scene.Draw({ volume });
  CHECK(coverage(grown) > coverage(first), "a modified array is not picked up");
  std::printf("lifecycle: coverage %.3f, resized %.3f, grown %.3f\n",
    coverage(first),
    coverage(resized),
    coverage(grown));
  CHECK(messages.Errors.empty(), "errors: %s", messages.Errors.c_str());
  return 0;
}

int TestErrors()
{
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  auto volume = FieldVolume(mapper, false);
  const double bounds[6] = { 0, 1, 0, 1, 0, 1 };
  Scene scene(bounds, false, 0, 0);
  struct Case
  {
    const char* Name;
    vtkSmartPointer<vtkImageData> Image;
    const char* Expected;
  };
  std::vector<Case> cases;
  auto grid = [](int nz)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(8, 8, nz);
    image->SetSpacing(1.0 / 7, 1.0 / 7, 1.0 / 7);
    return image;
  };
  cases.push_back({ "no scalars", grid(8), "no point array" });
  {
    auto image = grid(8);
    vtkNew<vtkFloatArray> values;
    values->SetName("Distance");
    values->SetNumberOfTuples(image->GetNumberOfPoints());
    values->Fill(0.5);
    values->SetValue(100, std::numeric_limits<float>::quiet_NaN());
    image->GetPointData()->SetScalars(values);
    cases.push_back({ "NaN", image, "NaN" });
  }
  {
    auto image = grid(1);
    vtkNew<vtkFloatArray> values;
    values->SetNumberOfTuples(image->GetNumberOfPoints());
    values->Fill(0.5);
    image->GetPointData()->SetScalars(values);
    cases.push_back({ "flat grid", image, "at least 2 on every axis" });
  }
  {
    auto image = grid(8);
    vtkNew<vtkFloatArray> values;
    values->SetName("SegmentedDistance");
    values->SetNumberOfTuples(image->GetNumberOfPoints());
    values->Fill(0.5);
    image->GetPointData()->AddArray(values);
    cases.push_back({ "no RegionOffset", image, "RegionOffset" });
  }
  for (const auto& c : cases)
  {
    vtkdf::testing::MessageRecorder messages(mapper);
    mapper->SetInputData(c.Image);
    const Frame frame = scene.Draw({ volume });
    const bool drawn =
      std::any_of(frame.Depth.begin(), frame.Depth.end(), [](float z) { return z < 1.0f; });
    std::printf("%s: %s", c.Name, messages.Errors.c_str());
    CHECK(messages.Errors.find(c.Expected) != std::string::npos,
      "%s: no error naming '%s'",
      c.Name,
      c.Expected);
    CHECK(!drawn, "%s: something was drawn", c.Name);
  }
  // A field without a negative sample (an unsigned distance) has no zero set to draw in
  // Mode Surface: nothing drawn, and a warning that says why.
  {
    auto image = grid(8);
    vtkNew<vtkFloatArray> values;
    values->SetName("Distance");
    values->SetNumberOfTuples(image->GetNumberOfPoints());
    values->Fill(0.5);
    image->GetPointData()->SetScalars(values);
    vtkdf::testing::MessageRecorder messages(mapper);
    mapper->SetInputData(image);
    const Frame frame = scene.Draw({ volume });
    const bool drawn =
      std::any_of(frame.Depth.begin(), frame.Depth.end(), [](float z) { return z < 1.0f; });
    std::printf("unsigned: %s", messages.Warnings.c_str());
    CHECK(
      messages.Errors.empty() && messages.Warnings.find("no negative value") != std::string::npos,
      "unsigned: no warning that the field has no zero set");
    CHECK(!drawn, "unsigned: something was drawn");
  }
  return 0;
}

/// Empty-space leaping changes no pixel: the signed bunny with a wide padding (surfaces,
/// opaque and translucent, region-aware and nearest), the segmented walled box, and
/// pre-integrated shells around the bunny (transparent far from it, shaded), each drawn
/// with leaping on and off.
int TestLeaping(const std::string& data)
{
  double spacing[3];
  auto bunny = SignedBunny(data, spacing, 0.3);
  int regions = 0;
  auto box = WalledBoxField(48, &regions);
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  auto volume = FieldVolume(mapper, true);
  vtkdf::testing::MessageRecorder messages(mapper);
  const auto compare = [&](const char* what, vtkImageData* field)
  {
    Scene scene(field->GetBounds(), false, 35, 20);
    mapper->SetInputData(field);
    mapper->EmptySpaceLeapingOff();
    const Frame all = scene.Draw({ volume });
    mapper->EmptySpaceLeapingOn();
    const Frame leaping = scene.Draw({ volume });
    size_t drawn = 0, differ = 0;
    for (size_t p = 0; p < all.Depth.size(); ++p)
    {
      drawn += all.Covered(p) || !SameColour(&all.Rgb[3 * p], Background, 1) ? 1 : 0;
      differ += all.Depth[p] != leaping.Depth[p] ||
          !std::equal(&all.Rgb[3 * p], &all.Rgb[3 * p] + 3, &leaping.Rgb[3 * p])
        ? 1
        : 0;
    }
    std::printf("%s: %zu pixels drawn, %zu differ with leaping\n", what, drawn, differ);
    CHECK(drawn > 2000, "%s: %zu pixels drawn only", what, drawn);
    CHECK(differ == 0, "%s: leaping changed %zu pixels", what, differ);
  };
  compare("signed bunny, region-aware", bunny);
  mapper->SetInterpolationToNearest();
  compare("signed bunny, nearest", bunny);
  mapper->SetInterpolationToRegionAware();
  mapper->SetSurfaceOpacity(0.5);
  compare("signed bunny, translucent", bunny);
  mapper->SetSurfaceOpacity(1);
  compare("walled box, segmented", box);
  // Shells: opaque at the surface, a faint one three voxels out, nothing further.
  const double h = spacing[0];
  double range[2];
  bunny->GetPointData()->GetScalars()->GetRange(range);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(range[0], 0.25, 0.45, 0.95);
  colour->AddRGBPoint(0, 0.95, 0.85, 0.6);
  colour->AddRGBPoint(range[1], 0.95, 0.4, 0.2);
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& point : { std::array<double, 2>{ range[0], 0.02 },
         { -h, 0.02 },
         { 0, 1.0 },
         { h, 0.0 },
         { 3 * h, 0.0 },
         { 4 * h, 0.25 },
         { 5 * h, 0.0 },
         { range[1], 0.0 } })
  {
    opacity->AddPoint(point[0], point[1]);
  }
  volume->GetProperty()->SetColor(colour);
  volume->GetProperty()->SetScalarOpacity(opacity);
  volume->GetProperty()->SetScalarOpacityUnitDistance(h);
  mapper->SetModeToComposite();
  compare("shells, composite", bunny);
  CHECK(messages.Errors.empty(), "errors: %s", messages.Errors.c_str());
  return 0;
}

/// Lighting: with only diffuse light (a headlight, parallel projection) a pixel's
/// brightness is |n . v|. On a finely tessellated sphere, at the surface point each pixel's
/// depth gives, against the radial normal there: normals from ClosestPoint and from the
/// gradient are both within 0.5% on a coarse grid (20 samples across).
int TestLighting()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.8);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(256);
  vtkNew<vtkLinearFactorDistanceField> field;
  field->SetInputConnection(sphere->GetOutputPort());
  field->SetResolution(20);
  field->SetBackendToCPU();
  field->SetSignModeToPseudoNormal();
  field->ComputeClosestPointOn();
  field->Update();
  vtkImageData* image = field->GetOutput();
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetRegionColor(0, 1, 1, 1);
  auto volume = FieldVolume(mapper, true);
  volume->GetProperty()->SetAmbient(0);
  volume->GetProperty()->SetDiffuse(1);
  volume->GetProperty()->SetSpecular(0);
  Scene scene(image->GetBounds(), true, 35, 20);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  double view[3];
  camera->GetDirectionOfProjection(view);
  double mean[2] = { 0, 0 };
  for (const bool closest : { true, false })
  {
    mapper->SetUseClosestPointNormals(closest);
    const Frame drawn = scene.Draw({ volume });
    size_t compared = 0;
    double sum = 0;
    for (int y = 0; y < drawn.Height; ++y)
    {
      for (int x = 0; x < drawn.Width; ++x)
      {
        const size_t p = static_cast<size_t>(y) * drawn.Width + x;
        if (!drawn.Covered(p))
        {
          continue;
        }
        double world[4];
        scene.Renderer->SetDisplayPoint(x + 0.5, y + 0.5, drawn.Depth[p]);
        scene.Renderer->DisplayToWorld();
        scene.Renderer->GetWorldPoint(world);
        const double norm =
          std::sqrt(world[0] * world[0] + world[1] * world[1] + world[2] * world[2]);
        // Leave the silhouette, where a pixel's depth mixes the sphere and beyond.
        const double facing =
          std::abs(world[0] * view[0] + world[1] * view[1] + world[2] * view[2]) / norm;
        if (facing < 0.2)
        {
          continue;
        }
        ++compared;
        sum += std::abs(drawn.Rgb[3 * p] / 255.0 - facing);
      }
    }
    mean[closest ? 0 : 1] = sum / std::max<size_t>(compared, 1);
    std::printf("lighting, normals from %s: %zu pixels, mean |brightness - |n.v|| %.4f\n",
      closest ? "ClosestPoint" : "the gradient",
      compared,
      mean[closest ? 0 : 1]);
    CHECK(compared > 5000, "too few pixels compared");
  }
  CHECK(mean[0] < 0.005, "ClosestPoint normals are off (%.4f)", mean[0]);
  CHECK(mean[1] < 0.005, "gradient normals are off (%.4f)", mean[1]);
  return 0;
}
} // namespace mapper
} // namespace testing
} // namespace vtkdf

int main(int argc, char* argv[])
{
  using namespace vtkdf::testing::mapper;
  if (!vtkdf::testing::HasArguments(argc,
        argv,
        2,
        "signed|segmented|occlusion|translucent|composite|leaping|lighting|lifecycle|errors|"
        "image "
        "DATA_DIR "
        "[-V BASELINE -T TMP]"))
  {
    return 2;
  }
  const std::string mode = argv[1], data = argv[2];
  // An X server resets when its last client disconnects and refuses connections
  // meanwhile; this window, open for the whole test, keeps Xvfb up between the scenes'.
  vtkNew<vtkRenderWindow> keeper;
  keeper->SetSize(8, 8);
  keeper->OffScreenRenderingOn();
  keeper->Render();
  if (mode == "signed")
  {
    TestSigned(data);
  }
  else if (mode == "segmented")
  {
    TestSegmented();
  }
  else if (mode == "occlusion")
  {
    TestOcclusion(data);
  }
  else if (mode == "translucent")
  {
    TestTranslucent(data);
  }
  else if (mode == "lifecycle")
  {
    TestLifecycle(data);
  }
  else if (mode == "errors")
  {
    TestErrors();
  }
  else if (mode == "composite")
  {
    TestComposite();
  }
  else if (mode == "leaping")
  {
    TestLeaping(data);
  }
  else if (mode == "lighting")
  {
    TestLighting();
  }
  else if (mode == "accuracy" && argc > 3)
  {
    // accuracy DATA MESH [N [SIZE]]: a field N samples across (48) in a SIZE^2 window
    // (240: about 5 pixels a voxel at 48; keep SIZE/N near 5 for other N, so that the
    // mesh's picture samples its surface finer than the voxel of tolerance).
    TestAccuracy(
      data, argv[3], argc > 4 ? std::atoi(argv[4]) : 48, argc > 5 ? std::atoi(argv[5]) : Size);
  }
  else if (mode == "preintegration")
  {
    TestPreIntegration();
  }
  else if (mode == "image" && argc > 3)
  {
    TestImage(argv[3], argc, argv);
  }
  else
  {
    std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
    return 2;
  }
  return vtkdf::testing::Verdict();
}
