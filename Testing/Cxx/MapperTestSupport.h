// MapperTestSupport: what the tests of vtkSegmentedDistanceVolumeMapper share (frames read
// back from a window, depth comparisons, scenes, the fields they draw) and the tests,
// one function a mode (TestSegmentedDistanceVolumeMapper.cxx runs them):
// TestSegmentedDistanceVolumeMapper.cxx the surface modes, TestMapperComposite.cxx the
// composite mode, TestMapperAccuracy.cxx the accuracy against meshes and the images.
#ifndef MapperTestSupport_h
#define MapperTestSupport_h

// usage: TestSegmentedDistanceVolumeMapper MODE DATA_DIR [-V BASELINE -T TMP]
#include "TestShapes.h"
#include "TestSupport.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkSegmentedDistanceContour.h"
#include "vtkSegmentedDistanceField.h"
#include "vtkSegmentedDistanceVolumeMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDistanceFieldBlend.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkFlyingEdges3D.h"
#include "vtkImageData.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkStaticCellLocator.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace vtkdf
{
namespace testing
{
namespace mapper
{
const int Size = 240;
const double Background[3] = { 0.1, 0.1, 0.15 };

/// A window's pixels: depth (1 = nothing) and colour, bottom row first.
struct Frame
{
  std::vector<float> Depth;
  std::vector<unsigned char> Rgb;
  int Width = 0, Height = 0;
  bool Covered(size_t p) const { return this->Depth[p] < 1.0f; }
};

inline Frame Grab(vtkRenderWindow* window)
{
  Frame frame;
  const int* size = window->GetSize();
  frame.Width = size[0];
  frame.Height = size[1];
  vtkNew<vtkFloatArray> depth;
  window->GetZbufferData(0, 0, size[0] - 1, size[1] - 1, depth);
  frame.Depth.assign(depth->GetPointer(0), depth->GetPointer(0) + size[0] * size[1]);
  vtkNew<vtkUnsignedCharArray> rgb;
  window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, rgb);
  frame.Rgb.assign(rgb->GetPointer(0), rgb->GetPointer(0) + 3 * size[0] * size[1]);
  return frame;
}

/// The distance along the view direction of a depth-buffer value.
inline double ViewDepth(float z, vtkCamera* camera)
{
  double range[2];
  camera->GetClippingRange(range);
  const double n = range[0], f = range[1];
  if (camera->GetParallelProjection())
  {
    return n + z * (f - n);
  }
  const double ndc = 2.0 * z - 1.0;
  return 2.0 * n * f / ((f + n) - ndc * (f - n));
}

/// How two pictures of one surface differ: the share of the pixels covered by only one,
/// and the depth differences where both are (world units).
struct Difference
{
  double Mismatch = 0, Median = 0, P90 = 0, Mean = 0;
  size_t Both = 0;
};

inline Difference Compare(const Frame& a, const Frame& b, vtkCamera* camera)
{
  Difference d;
  size_t either = 0, one = 0;
  std::vector<double> errors;
  for (size_t p = 0; p < a.Depth.size(); ++p)
  {
    const bool ca = a.Covered(p), cb = b.Covered(p);
    either += (ca || cb) ? 1 : 0;
    one += (ca != cb) ? 1 : 0;
    if (ca && cb)
    {
      errors.push_back(std::abs(ViewDepth(a.Depth[p], camera) - ViewDepth(b.Depth[p], camera)));
    }
  }
  d.Mismatch = either ? static_cast<double>(one) / either : 1.0;
  d.Both = errors.size();
  if (!errors.empty())
  {
    std::sort(errors.begin(), errors.end());
    d.Median = errors[errors.size() / 2];
    d.P90 = errors[errors.size() * 9 / 10];
    for (double e : errors)
    {
      d.Mean += e / errors.size();
    }
  }
  return d;
}

/// A window with one renderer and a fixed camera around `bounds`.
struct Scene
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  Scene(const double bounds[6], bool parallel, double azimuth, double elevation, int size = Size)
  {
    this->Window->SetSize(size, size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(Background[0], Background[1], Background[2]);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetParallelProjection(parallel);
    this->Renderer->ResetCamera(bounds);
    camera->Azimuth(azimuth);
    camera->Elevation(elevation);
    camera->OrthogonalizeViewUp();
    this->Renderer->ResetCamera(bounds);
    // The same clipping range for every picture of the scene.
    const double centre[3] = {
      (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2
    };
    const double radius = 0.5 *
      std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) +
        std::pow(bounds[5] - bounds[4], 2));
    double position[3];
    camera->GetPosition(position);
    const double distance = std::sqrt(std::pow(position[0] - centre[0], 2) +
      std::pow(position[1] - centre[1], 2) + std::pow(position[2] - centre[2], 2));
    camera->SetClippingRange(
      std::max(distance - 1.5 * radius, 0.05 * distance), distance + 1.5 * radius);
  }
  /// Draws `props` alone and reads the window back.
  Frame Draw(std::initializer_list<vtkProp*> props)
  {
    // Only the props that change are removed (removing one releases its graphics
    // resources) or added.
    vtkPropCollection* current = this->Renderer->GetViewProps();
    std::vector<vtkProp*> gone;
    current->InitTraversal();
    for (vtkProp* prop = current->GetNextProp(); prop; prop = current->GetNextProp())
    {
      if (std::find(props.begin(), props.end(), prop) == props.end())
      {
        gone.push_back(prop);
      }
    }
    for (vtkProp* prop : gone)
    {
      this->Renderer->RemoveViewProp(prop);
    }
    for (vtkProp* prop : props)
    {
      if (!this->Renderer->HasViewProp(prop))
      {
        this->Renderer->AddViewProp(prop);
      }
    }
    this->Window->Render();
    return Grab(this->Window);
  }
};

inline vtkSmartPointer<vtkActor> SurfaceActor(vtkPolyData* surface, const double rgb[3])
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(rgb[0], rgb[1], rgb[2]);
  actor->GetProperty()->LightingOff();
  return actor;
}

inline vtkSmartPointer<vtkVolume> FieldVolume(vtkSegmentedDistanceVolumeMapper* mapper, bool shade)
{
  vtkNew<vtkVolumeProperty> property;
  property->SetShade(shade);
  property->SetAmbient(0.25);
  property->SetDiffuse(0.75);
  property->SetSpecular(0.2);
  property->SetSpecularPower(24);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  return volume;
}

inline vtkSmartPointer<vtkImageData> SignedBunny(const std::string& data,
  double spacing[3],
  double padding = 0.1)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((data + "/bunny_small.vtp").c_str());
  vtkNew<vtkLinearFactorDistanceField> field;
  field->SetInputConnection(reader->GetOutputPort());
  field->SetResolution(40);
  field->SetPadding(padding);
  field->SetBackendToCPU();
  field->SetSignModeToPseudoNormal();
  field->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(field->GetOutput());
  image->GetSpacing(spacing);
  return image;
}

inline vtkSmartPointer<vtkPolyData> ZeroLevelSet(vtkImageData* field)
{
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(field);
  contour->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Distance");
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->Update();
  return contour->GetOutput();
}

inline bool SameColour(const unsigned char* pixel, const double rgb[3], int tolerance)
{
  for (int c = 0; c < 3; ++c)
  {
    if (std::abs(pixel[c] - 255.0 * rgb[c]) > tolerance)
    {
      return false;
    }
  }
  return true;
}

inline vtkSmartPointer<vtkImageData> WalledBoxField(int resolution, int* regions)
{
  vtkNew<vtkSegmentedDistanceField> segment;
  segment->SetInputData(vtkdf::testing::OpenWalledBox());
  segment->SetResolution(resolution);
  segment->SetBackendToCPU();
  segment->Update();
  *regions = segment->GetLastRegionCount();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(segment->GetOutput());
  return image;
}

// The tests.
int TestSigned(const std::string& data);
int TestSegmented();
int TestOcclusion(const std::string& data);
int TestTranslucent(const std::string& data);
int TestLifecycle(const std::string& data);
int TestErrors();
int TestLeaping(const std::string& data);
int TestLighting();
int TestComposite();
int TestPreIntegration();
int TestAccuracy(const std::string& data, const std::string& name, int resolution, int size);
int TestImage(const std::string& picture, int argc, char* argv[]);
} // namespace mapper
} // namespace testing
} // namespace vtkdf

#endif
