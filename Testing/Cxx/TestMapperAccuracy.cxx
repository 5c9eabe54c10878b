// vtkSegmentedDistanceVolumeMapper against meshes (accuracy MESH) and the regression
// images (MapperTestSupport.h).
#include "MapperTestSupport.h"

namespace vtkdf
{
namespace testing
{
namespace mapper
{
/// Geometric accuracy, by depth buffers unprojected to eye-space distances (one clipping
/// range for every picture), of the mapper drawing a mesh's segmented field (48 samples
/// across):
/// - against the field's own polygonized surface (vtkSegmentedDistanceContour), i.e. the
///   renderer's fidelity: within a voxel on >= 99% of the pixels both hit (but teapot and
///   max3ds_export, see below);
/// - against the mesh drawn as opaque polygons, on >= 99% of the pixels both hit, on all
///   five meshes: within a voxel in 3D, i.e. some pixel of the mesh's picture within a
///   voxel sideways (at the pixel's depth) lies within a voxel in depth and sideways
///   together. Per pixel in depth alone (the pixel's own depths within a voxel) bunny_small,
///   plane and scad_back_to_back also reach 99%; teapot and max3ds_export do not (94.3%,
///   85.9%), nearly all of it at silhouettes, where a sideways shift of less than a voxel
///   makes one ray hit the surface behind (thin limbs, the lid's gap: the share falls with
///   the voxel, 98.0% and 95.2% at 128^3), and are held per pixel to what they reach so
///   that they cannot get worse unnoticed;
/// - no spurious surface: every pixel the mapper draws, unprojected, lies within a voxel
///   of the mesh (for >= 99.5% of them): open boundaries end within a voxel.
/// For bunny_small's signed field also VTK's GPU ray caster in ISOSURFACE mode (its
/// first-hit depth from RenderToImage, the same sample distance), side by side: the
/// mapper is the more accurate.
int TestAccuracy(const std::string& data, const std::string& name, int resolution, int size)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((data + "/" + name + ".vtp").c_str());
  reader->Update();
  vtkPolyData* mesh = reader->GetOutput();
  const double white[3] = { 1, 1, 1 };
  auto meshActor = SurfaceActor(mesh, white);
  vtkNew<vtkSegmentedDistanceField> segment;
  segment->SetInputData(mesh);
  segment->SetResolution(resolution);
  segment->SetBackendToCPU();
  segment->Update();
  vtkImageData* field = segment->GetOutput();
  const double h = field->GetSpacing()[0];
  // The paper's polygonization (vertices on the interpolated field, as the mapper draws
  // it), not the closest points' feature vertices.
  vtkNew<vtkSegmentedDistanceContour> contour;
  contour->SetInputData(field);
  contour->UseClosestPointsOff();
  contour->Update();
  auto contourActor = SurfaceActor(contour->GetOutput(), white);
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  auto volume = FieldVolume(mapper, false);
  vtkdf::testing::MessageRecorder messages(mapper);
  Scene scene(field->GetBounds(), false, 35, 20, size);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const Frame reference = scene.Draw({ meshActor });
  const Frame polygonized = scene.Draw({ contourActor });

  // The share of the pixels both hit whose depths agree within a voxel, and their median
  // difference in voxels.
  auto agree = [&](const std::vector<float>& depth, const Frame& against, size_t& both)
  {
    std::vector<double> errors;
    for (size_t p = 0; p < depth.size(); ++p)
    {
      if (depth[p] < 1.0f && against.Covered(p))
      {
        errors.push_back(
          std::abs(ViewDepth(depth[p], camera) - ViewDepth(against.Depth[p], camera)) / h);
      }
    }
    both = errors.size();
    if (errors.empty())
    {
      return std::make_pair(0.0, 0.0);
    }
    const double within = static_cast<double>(std::count_if(
                            errors.begin(), errors.end(), [](double e) { return e <= 1.0; })) /
      errors.size();
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    return std::make_pair(within, errors[errors.size() / 2]);
  };
  // The same pixels, with the voxel of tolerance in every direction: a pixel agrees when
  // a pixel of `against` within a voxel of it sideways (at its depth) lies within a voxel
  // in 3D. At a silhouette a sideways shift of less than a voxel makes a ray hit the
  // surface behind instead, a depth difference the per-pixel test counts as an error;
  // a hole or a misplaced surface still fails this test.
  auto agree3D = [&](const std::vector<float>& depth, const Frame& against)
  {
    const double tangent = std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2);
    size_t both = 0, within = 0;
    for (int y = 0; y < against.Height; ++y)
    {
      for (int x = 0; x < against.Width; ++x)
      {
        const size_t p = static_cast<size_t>(y) * against.Width + x;
        if (!(depth[p] < 1.0f && against.Covered(p)))
        {
          continue;
        }
        ++both;
        const double d = ViewDepth(depth[p], camera);
        const double pixel = camera->GetParallelProjection()
          ? 2 * camera->GetParallelScale() / against.Height
          : 2 * d * tangent / against.Height;
        const int reach = static_cast<int>(std::ceil(h / pixel));
        bool found = false;
        for (int dy = -reach; dy <= reach && !found; ++dy)
        {
          for (int dx = -reach; dx <= reach && !found; ++dx)
          {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= against.Width || qy >= against.Height)
            {
              continue;
            }
            const size_t q = static_cast<size_t>(qy) * against.Width + qx;
            if (!against.Covered(q))
            {
              continue;
            }
            const double sideways = std::hypot(dx, dy) * pixel;
            const double along = d - ViewDepth(against.Depth[q], camera);
            found = sideways * sideways + along * along <= h * h;
          }
        }
        within += found;
      }
    }
    return both ? static_cast<double>(within) / both : 0.0;
  };
  // Per pixel again, over the pixels away from the mesh picture's silhouettes: those
  // whose every neighbour within a voxel (on screen, at their depth) is covered, with no
  // step of more than a voxel in depth between two adjacent ones. There a sideways shift
  // of less than a voxel cannot make a ray hit another surface.
  auto agreeInside = [&](const std::vector<float>& depth, const Frame& against, size_t& inside)
  {
    const double tangent = std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2);
    size_t within = 0;
    inside = 0;
    for (int y = 0; y < against.Height; ++y)
    {
      for (int x = 0; x < against.Width; ++x)
      {
        const size_t p = static_cast<size_t>(y) * against.Width + x;
        if (!(depth[p] < 1.0f && against.Covered(p)))
        {
          continue;
        }
        const double d = ViewDepth(against.Depth[p], camera);
        const double pixel = camera->GetParallelProjection()
          ? 2 * camera->GetParallelScale() / against.Height
          : 2 * d * tangent / against.Height;
        const int reach = static_cast<int>(std::ceil(h / pixel));
        bool smooth = true;
        for (int dy = -reach; dy <= reach && smooth; ++dy)
        {
          for (int dx = -reach; dx <= reach && smooth; ++dx)
          {
            const int qx = x + dx, qy = y + dy;
            const size_t q = static_cast<size_t>(qy) * against.Width + qx;
            smooth = qx >= 0 && qy >= 0 && qx + 1 < against.Width && qy + 1 < against.Height &&
              against.Covered(q) && against.Covered(q + 1) && against.Covered(q + against.Width);
            const double dq = smooth ? ViewDepth(against.Depth[q], camera) : 0;
            smooth = smooth && std::abs(ViewDepth(against.Depth[q + 1], camera) - dq) <= h &&
              std::abs(ViewDepth(against.Depth[q + against.Width], camera) - dq) <= h;
          }
        }
        if (smooth)
        {
          ++inside;
          within += std::abs(ViewDepth(depth[p], camera) - d) <= h;
        }
      }
    }
    return inside ? static_cast<double>(within) / inside : 0.0;
  };
  const Frame drawn = scene.Draw({ volume });
  size_t bothPolygonized = 0, bothMesh = 0;
  const auto fidelity = agree(drawn.Depth, polygonized, bothPolygonized);
  const auto onMesh = agree(drawn.Depth, reference, bothMesh);
  size_t bothContourMesh = 0;
  const auto contourOnMesh = agree(polygonized.Depth, reference, bothContourMesh);
  // Every drawn pixel's surface point against the mesh, in 3D.
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();
  size_t drawnPixels = 0, nearMesh = 0;
  for (int y = 0; y < drawn.Height; ++y)
  {
    for (int x = 0; x < drawn.Width; ++x)
    {
      const size_t p = static_cast<size_t>(y) * drawn.Width + x;
      if (!drawn.Covered(p))
      {
        continue;
      }
      double world[4], closest[3], d2;
      scene.Renderer->SetDisplayPoint(x + 0.5, y + 0.5, drawn.Depth[p]);
      scene.Renderer->DisplayToWorld();
      scene.Renderer->GetWorldPoint(world);
      for (int c = 0; c < 3; ++c)
      {
        world[c] /= world[3];
      }
      vtkIdType cell;
      int sub;
      locator->FindClosestPoint(world, closest, cell, sub, d2);
      ++drawnPixels;
      nearMesh += std::sqrt(d2) <= h;
    }
  }
  const double near = drawnPixels ? static_cast<double>(nearMesh) / drawnPixels : 0.0;
  const double onMesh3D = agree3D(drawn.Depth, reference);
  size_t insidePixels = 0;
  const double onMeshInside = agreeInside(drawn.Depth, reference, insidePixels);
  std::printf("%s, %d^3: the mapper against the mesh within a voxel per pixel %.2f%%, with "
              "the voxel sideways too %.2f%%; per pixel away from silhouettes %.2f%% (%zu of "
              "the %zu pixels)\n",
    name.c_str(),
    resolution,
    100 * onMesh.first,
    100 * onMesh3D,
    100 * onMeshInside,
    insidePixels,
    bothMesh);
  std::printf("%s, segmented field (%d regions), %zu pixels drawn: against its polygonized "
              "surface %.2f%% within a voxel (median %.3f); against the mesh %.2f%% within a "
              "voxel (median %.3f, %zu pixels; the polygonized surface: %.2f%%); %.2f%% of the "
              "drawn points within a voxel of the mesh\n",
    name.c_str(),
    mapper->GetLastRegionCount(),
    drawnPixels,
    100 * fidelity.first,
    fidelity.second,
    100 * onMesh.first,
    onMesh.second,
    bothMesh,
    100 * contourOnMesh.first,
    100 * near);
  CHECK(bothPolygonized > 500 && bothMesh > 500, "too few pixels compared");
  // Where the field cannot separate sub-voxel gaps, the mapper and the polygonizer make
  // different choices (the mapper sees into a gap the polygonizer closes with a fan):
  // teapot and max3ds_export are held to what they reach.
  const bool limited = name == "teapot" || name == "max3ds_export";
  const double fidelityFloor = !limited || resolution >= 192 ? 0.99
    : name == "teapot"                                       ? 0.95
                                                             : 0.965;
  const double meshFloor = !limited || resolution >= 192 ? 0.99 : name == "teapot" ? 0.95 : 0.865;
  CHECK(fidelity.first >= fidelityFloor,
    "the mapper is off the field's polygonized surface (%.2f%% within a voxel, < %.1f%%)",
    100 * fidelity.first,
    100 * fidelityFloor);
  CHECK(onMesh.first >= meshFloor,
    "the surface is off the mesh (%.2f%% within a voxel, < %.1f%%)",
    100 * onMesh.first,
    100 * meshFloor);
  CHECK(onMesh3D >= 0.99,
    "the surface is off the mesh (%.2f%% within a voxel, sideways included, < 99%%)",
    100 * onMesh3D);
  CHECK(near >= 0.995,
    "%.2f%% of the drawn points are farther than a voxel from the mesh",
    100 * (1 - near));
  CHECK(insidePixels > 0 && onMeshInside >= 0.99,
    "the surface is off the mesh away from silhouettes (%.2f%% within a voxel per pixel)",
    100 * onMeshInside);

  if (name == "bunny_small")
  {
    vtkNew<vtkLinearFactorDistanceField> signedField;
    signedField->SetInputData(mesh);
    signedField->SetResolution(resolution);
    signedField->SetBackendToCPU();
    signedField->SetSignModeToPseudoNormal();
    signedField->Update();
    vtkImageData* sdf = signedField->GetOutput();
    sdf->GetPointData()->SetActiveScalars("Distance");
    mapper->SetInputData(sdf);
    size_t both = 0;
    const std::vector<float> mapperDepth = scene.Draw({ volume }).Depth;
    const auto m = agree(mapperDepth, reference, both);
    // VTK's ray caster, ISOSURFACE at 0, sampling at the mapper's slice spacing.
    vtkNew<vtkOpenGLGPUVolumeRayCastMapper> caster;
    caster->SetInputData(sdf);
    caster->SetBlendModeToIsoSurface();
    caster->AutoAdjustSampleDistancesOff();
    caster->SetSampleDistance(static_cast<float>(h));
    caster->SetRenderToImage(1);
    vtkNew<vtkVolumeProperty> isoProperty;
    isoProperty->GetIsoSurfaceValues()->SetValue(0, 0.0);
    vtkNew<vtkPiecewiseFunction> opaque;
    opaque->AddPoint(-1e6, 1.0);
    opaque->AddPoint(1e6, 1.0);
    isoProperty->SetScalarOpacity(opaque);
    vtkNew<vtkVolume> isoVolume;
    isoVolume->SetMapper(caster);
    isoVolume->SetProperty(isoProperty);
    scene.Draw({ isoVolume });
    vtkNew<vtkImageData> depthImage;
    caster->GetDepthImage(depthImage);
    std::vector<float> casterDepth(reference.Depth.size(), 1.0f);
    vtkDataArray* values = depthImage->GetPointData()->GetScalars();
    if (values && values->GetNumberOfTuples() == static_cast<vtkIdType>(casterDepth.size()))
    {
      for (size_t p = 0; p < casterDepth.size(); ++p)
      {
        casterDepth[p] = static_cast<float>(values->GetComponent(static_cast<vtkIdType>(p), 0));
      }
    }
    size_t casterBoth = 0;
    const auto c = agree(casterDepth, reference, casterBoth);
    const double m3 = agree3D(mapperDepth, reference), c3 = agree3D(casterDepth, reference);
    size_t mInsidePixels = 0, cInsidePixels = 0;
    const double mInside = agreeInside(mapperDepth, reference, mInsidePixels);
    const double cInside = agreeInside(casterDepth, reference, cInsidePixels);
    std::printf("%s, signed field against the mesh: mapper %.2f%% within a voxel (%.2f%% "
                "sideways included, %.2f%% away from silhouettes), median %.3f voxel; VTK's "
                "ray caster (ISOSURFACE, same sample distance) %.2f%% within a voxel (%.2f%% "
                "sideways included, %.2f%% away from silhouettes), median %.3f voxel (%zu "
                "pixels)\n",
      name.c_str(),
      100 * m.first,
      100 * m3,
      100 * mInside,
      m.second,
      100 * c.first,
      100 * c3,
      100 * cInside,
      c.second,
      casterBoth);
    CHECK(m.first >= 0.99 && m3 >= 0.99, "the signed field's surface is off the mesh");
    CHECK(casterBoth > 2000, "the ray caster's depth image was not read");
    CHECK(m.second < c.second && m.first > c.first && m3 > c3,
      "the mapper is not more accurate than the ray caster");
  }
  CHECK(messages.Errors.empty(), "errors: %s", messages.Errors.c_str());
  return 0;
}

/// Passes the window to vtkRegressionTestImage, refusing a missing baseline (it would
/// write one and pass).
void CheckAgainstBaseline(vtkRenderWindow* window, int argc, char* argv[])
{
  std::string baseline;
  for (int i = 1; i + 1 < argc; ++i)
  {
    baseline = std::string(argv[i]) == "-V" ? argv[i + 1] : baseline;
  }
  CHECK(!baseline.empty() && vtksys::SystemTools::FileExists(baseline),
    "the baseline %s is missing",
    baseline.c_str());
  const int result = vtkRegressionTestImage(window);
  CHECK(result == vtkRegressionTester::PASSED, "the image differs from the baseline");
}

/// A CT-like phantom: a head of soft tissue (300) in a skull shell (1200), two ventricles
/// (50) and a dense rod, smooth-edged, on 64^3.
vtkSmartPointer<vtkImageData> Phantom()
{
  const int n = 64;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  const double h = 2.0 / (n - 1);
  image->SetSpacing(h, h, h);
  image->SetOrigin(-1, -1, -1);
  vtkNew<vtkFloatArray> values;
  values->SetName("Density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  auto inside = [](double q)
  {
    const double x = std::clamp((1 - q) / 0.08 + 0.5, 0.0, 1.0);
    return x * x * (3 - 2 * x);
  };
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double x = -1 + i * h, y = -1 + j * h, z = -1 + k * h;
        const double head =
          std::sqrt(std::pow(x / 0.75, 2) + std::pow(y / 0.9, 2) + std::pow(z / 0.8, 2));
        const double ventricle = std::min(
          std::sqrt(std::pow((x - 0.2) / 0.12, 2) + std::pow(y / 0.35, 2) + std::pow(z / 0.15, 2)),
          std::sqrt(std::pow((x + 0.2) / 0.12, 2) + std::pow(y / 0.35, 2) + std::pow(z / 0.15, 2)));
        const double rod = std::sqrt(std::pow(x / 0.06, 2) + std::pow((z + 0.45) / 0.06, 2));
        const double value = 300 * inside(head) + 900 * (inside(head) - inside(head / 0.9)) -
          250 * inside(ventricle) + 900 * inside(rod) * inside(head);
        values->SetValue(i + n * (j + static_cast<vtkIdType>(n) * k), static_cast<float>(value));
      }
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

/// Regression images: `walledbox`, the segmented surfaces of a non-manifold mesh lit and
/// coloured by region; `ct`, a translucent pre-integrated composite of a CT-like phantom
/// (with a check that its skin, skull and the dark background all show); `blend`, the
/// middle frame of a blend between two closed walled boxes (walls at x = -0.3 and 0.35)
/// drawn translucent, after checking the opaque picture of that frame against the
/// blended field's polygonized surface (within a voxel on >= 99% of the pixels).
int TestImage(const std::string& picture, int argc, char* argv[])
{
  if (picture == "walledbox")
  {
    int regions = 0;
    auto field = WalledBoxField(40, &regions);
    vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
    mapper->SetInputData(field);
    auto volume = FieldVolume(mapper, true);
    Scene scene(field->GetBounds(), false, 30, 55);
    scene.Draw({ volume });
    CheckAgainstBaseline(scene.Window, argc, argv);
  }
  else if (picture == "ct")
  {
    auto phantom = Phantom();
    vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
    mapper->SetInputData(phantom);
    mapper->SetModeToComposite();
    vtkNew<vtkColorTransferFunction> colour;
    colour->AddRGBPoint(0, 0.1, 0.05, 0.05);
    colour->AddRGBPoint(300, 0.95, 0.6, 0.45);
    colour->AddRGBPoint(1200, 1.0, 1.0, 0.92);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0, 0.0);
    opacity->AddPoint(150, 0.0);
    opacity->AddPoint(300, 0.04);
    opacity->AddPoint(700, 0.04);
    opacity->AddPoint(1000, 0.12);
    opacity->AddPoint(1300, 0.12);
    auto volume = FieldVolume(mapper, true);
    vtkdf::testing::MessageRecorder messages(mapper);
    volume->GetProperty()->SetColor(colour);
    volume->GetProperty()->SetScalarOpacity(opacity);
    volume->GetProperty()->SetScalarOpacityUnitDistance(phantom->GetSpacing()[0]);
    Scene scene(phantom->GetBounds(), false, 40, 25);
    const Frame frame = scene.Draw({ volume });
    size_t bright = 0, tinted = 0, background = 0;
    for (size_t p = 0; p < frame.Depth.size(); ++p)
    {
      const unsigned char* c = &frame.Rgb[3 * p];
      const bool isBackground = std::abs(c[0] - 255 * Background[0]) <= 2 &&
        std::abs(c[1] - 255 * Background[1]) <= 2 && std::abs(c[2] - 255 * Background[2]) <= 2;
      background += isBackground;
      bright += c[0] > 200 && c[1] > 180;
      tinted += !isBackground && c[0] > c[2] + 20;
    }
    std::printf("ct: %d slices; %zu bright (skull), %zu skin-tinted, %zu background pixels\n",
      mapper->GetLastNumberOfSlices(),
      bright,
      tinted,
      background);
    CHECK(bright > 500 && tinted > 5000 && background > 5000, "the phantom does not show");
    CHECK(messages.Errors.empty(), "errors: %s", messages.Errors.c_str());
    CheckAgainstBaseline(scene.Window, argc, argv);
  }
  else if (picture == "blend")
  {
    std::vector<vtkSmartPointer<vtkImageData>> fields;
    for (const double wall : { -0.3, 0.35 })
    {
      vtkNew<vtkSegmentedDistanceField> segment;
      segment->SetInputData(vtkdf::testing::WalledBox(wall, false, 1.0));
      segment->ExplicitGridOn();
      segment->SetGridOrigin(-1.2, -1.2, -1.2);
      segment->SetGridSpacing(0.06, 0.06, 0.06);
      segment->SetGridDimensions(41, 41, 41);
      segment->SetBackendToCPU();
      segment->Update();
      fields.push_back(segment->GetOutput());
    }
    vtkNew<vtkDistanceFieldBlend> blend;
    blend->SetInputData(0, fields[0]);
    blend->SetInputData(1, fields[1]);
    blend->SetT(0.5);
    blend->Update();
    vtkImageData* middle = blend->GetOutput();
    vtkNew<vtkSegmentedDistanceContour> contour;
    contour->SetInputData(middle);
    contour->Update();
    const double white[3] = { 1, 1, 1 };
    auto contourActor = SurfaceActor(contour->GetOutput(), white);
    vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
    mapper->SetInputData(middle);
    auto volume = FieldVolume(mapper, true);
    Scene scene(middle->GetBounds(), false, 30, 35);
    const Frame polygonized = scene.Draw({ contourActor });
    const Frame opaque = scene.Draw({ volume });
    const Difference d = Compare(opaque, polygonized, scene.Renderer->GetActiveCamera());
    std::printf("blend at t = 0.5: %d regions; against the polygonized surface %.2f%% pixels "
                "differ, depth median %.3f p90 %.3f voxels\n",
      mapper->GetLastRegionCount(),
      100 * d.Mismatch,
      d.Median / 0.06,
      d.P90 / 0.06);
    CHECK(mapper->GetLastRegionCount() == 3,
      "the blend has %d regions, not 3",
      mapper->GetLastRegionCount());
    CHECK(d.Mismatch < 0.01 && d.P90 < 0.06, "the blended frame is off its surface");
    mapper->SetSurfaceOpacity(0.5);
    scene.Draw({ volume });
    CheckAgainstBaseline(scene.Window, argc, argv);
  }
  else
  {
    CHECK(false, "unknown picture %s", picture.c_str());
  }
  return 0;
}
} // namespace mapper
} // namespace testing
} // namespace vtkdf
