#include "vtkSegmentedDistanceVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "EmptySpace.h"
#include "PreIntegratedVolume_frag.h"
#include "PreIntegrationTable.h"
#include "SegmentedVolumeGL.h"
#include "SegmentedVolumeState.h"
#include "SegmentedVolume_frag.h"
#include "SegmentedVolume_vert.h"
#include "SlabCommon.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

using vtkdf::render::Apply;
using vtkdf::render::BoxTriangles;
using vtkdf::render::BrickSize;
using vtkdf::render::Create3D;
using vtkdf::render::DecodeFieldTexels;
using vtkdf::render::DefaultRegionColor;
using vtkdf::render::Dot;
using vtkdf::render::Normalized;
using vtkdf::render::NormalMatrix;
using vtkdf::render::PrepareTexture;
using vtkdf::render::ReadDepthFormat;
using vtkdf::render::SetLastBrick;
using vtkdf::render::SetPlainMatrix;
using vtkdf::render::StoredGradientVoxels;
using vtkdf::render::Sub;
using vtkdf::render::UploadClosestPoints;
using vtkdf::render::UploadLeaps;
using vtkdf::render::UploadScalars;
using vtkdf::render::UploadTable;
using vtkdf::render::Vec3;

vtkStandardNewMacro(vtkSegmentedDistanceVolumeMapper);

vtkSegmentedDistanceVolumeMapper::vtkSegmentedDistanceVolumeMapper()
  : Impl(new Internals)
{
}

// No GL calls here: the context may be gone. ReleaseGraphicsResources() frees them.
vtkSegmentedDistanceVolumeMapper::~vtkSegmentedDistanceVolumeMapper() = default;

const char* vtkSegmentedDistanceVolumeMapper::GetModeAsString()
{
  return this->Mode == Composite ? "Composite" : "Surface";
}

const char* vtkSegmentedDistanceVolumeMapper::GetInterpolationAsString()
{
  switch (this->Interpolation)
  {
    case Nearest:
      return "Nearest";
    case Linear:
      return "Linear";
    default:
      return "RegionAware";
  }
}

void vtkSegmentedDistanceVolumeMapper::SetRegionColor(int region, double r, double g, double b)
{
  if (region < 0)
  {
    vtkErrorMacro("SetRegionColor: region " << region << " is negative");
    return;
  }
  auto& rgb = this->Impl->RegionColors[region];
  rgb = { std::clamp(r, 0.0, 1.0), std::clamp(g, 0.0, 1.0), std::clamp(b, 0.0, 1.0) };
  this->Impl->ColorsModified.Modified();
  this->Modified();
}

void vtkSegmentedDistanceVolumeMapper::GetRegionColor(int region, double rgb[3])
{
  const auto found = this->Impl->RegionColors.find(region);
  if (found != this->Impl->RegionColors.end())
  {
    std::copy(found->second.begin(), found->second.end(), rgb);
    return;
  }
  DefaultRegionColor(region, rgb);
}

void vtkSegmentedDistanceVolumeMapper::RemoveAllRegionColors()
{
  this->Impl->RegionColors.clear();
  this->Impl->ColorsModified.Modified();
  this->Modified();
}

void vtkSegmentedDistanceVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->GetModeAsString() << "\n";
  os << indent << "Interpolation: " << this->GetInterpolationAsString() << "\n";
  os << indent << "PreIntegrationTableSize: " << this->PreIntegrationTableSize << "\n";
  os << indent << "TableBuilds: " << this->TableBuilds << "\n";
  os << indent << "StepTableBuilds: " << this->StepTableBuilds << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "NumberOfSlices: " << this->NumberOfSlices << "\n";
  os << indent << "SurfaceOpacity: " << this->SurfaceOpacity << "\n";
  os << indent << "UseClosestPointNormals: " << this->UseClosestPointNormals << "\n";
  os << indent << "EmptySpaceLeaping: " << this->EmptySpaceLeaping << "\n";
  os << indent << "RegionColors set: " << this->Impl->RegionColors.size() << "\n";
  os << indent << "LastNumberOfSlices: " << this->LastNumberOfSlices << "\n";
  os << indent << "LastRegionCount: " << this->LastRegionCount << "\n";
  os << indent << "LastSegmented: " << this->LastSegmented << "\n";
}

void vtkSegmentedDistanceVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& impl = *this->Impl;
  for (vtkTextureObject* texture : { impl.Field.Get(),
         impl.Colors.Get(),
         impl.SurfaceLeaps.Get(),
         impl.CompositeLeaps.Get(),
         impl.ClosestPoints.Get(),
         impl.Scalars.Get(),
         impl.Table.Get(),
         impl.StepTable.Get(),
         impl.OpaqueDepth.Get() })
  {
    texture->ReleaseGraphicsResources(window);
  }
  impl.Vertices->ReleaseGraphicsResources();
  impl.Surfaces.ReleaseGraphicsResources(window);
  impl.Composite.ReleaseGraphicsResources(window);
  impl.FieldValid = false;
  impl.ScalarsValid = false;
  impl.DepthSize[0] = impl.DepthSize[1] = 0;
  this->Superclass::ReleaseGraphicsResources(window);
}

std::string vtkSegmentedDistanceVolumeMapper::ArraySelectionKey() const
{
  return std::to_string(this->ArrayAccessMode) + ":" + std::to_string(this->ArrayId) + ":" +
    (this->ArrayName ? this->ArrayName : "");
}

bool vtkSegmentedDistanceVolumeMapper::HasArraySelection() const
{
  return (this->ArrayAccessMode == VTK_GET_ARRAY_BY_NAME && this->ArrayName && *this->ArrayName) ||
    (this->ArrayAccessMode == VTK_GET_ARRAY_BY_ID && this->ArrayId >= 0);
}

vtkDataArray* vtkSegmentedDistanceVolumeMapper::SelectedArray(vtkImageData* image) const
{
  vtkPointData* pd = image->GetPointData();
  if (this->ArrayAccessMode == VTK_GET_ARRAY_BY_NAME && this->ArrayName && *this->ArrayName)
  {
    return pd->GetArray(this->ArrayName);
  }
  if (this->ArrayAccessMode == VTK_GET_ARRAY_BY_ID && this->ArrayId >= 0)
  {
    return pd->GetArray(this->ArrayId);
  }
  return nullptr;
}

bool vtkSegmentedDistanceVolumeMapper::CheckGrid(vtkImageData* image, int dims[3])
{
  image->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    vtkErrorMacro("The field is " << dims[0] << " x " << dims[1] << " x " << dims[2]
                                  << " samples: a volume needs at least 2 on every axis");
    return false;
  }
  GLint largest = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &largest);
  if (dims[0] > largest || dims[1] > largest || dims[2] > largest)
  {
    vtkErrorMacro("The field is " << dims[0] << " x " << dims[1] << " x " << dims[2]
                                  << " samples; this OpenGL takes 3D textures of at most "
                                  << largest << " a side");
    return false;
  }
  return true;
}

void vtkSegmentedDistanceVolumeMapper::SetGeometry(vtkImageData* image, const int dims[3])
{
  Internals& impl = *this->Impl;
  std::copy(dims, dims + 3, impl.Dims);
  image->GetSpacing(impl.Spacing);
  // The textures start at the extent's first point, not at index 0 (a piece of a grid, a
  // cropped image).
  const int* extent = image->GetExtent();
  double first[3];
  image->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], first);
  vtkImageData::ComputeIndexToPhysicalMatrix(
    first, image->GetSpacing(), image->GetDirectionMatrix()->GetData(), impl.IndexToPhysical);
}

bool vtkSegmentedDistanceVolumeMapper::UpdateField(vtkImageData* image)
{
  Internals& impl = *this->Impl;
  if (impl.FieldValid && impl.Field->GetHandle() && impl.FieldImage == image &&
    impl.FieldTime > image->GetMTime() && impl.FieldKey == this->ArraySelectionKey())
  {
    return true;
  }
  impl.FieldValid = false;
  int dims[3];
  if (!this->CheckGrid(image, dims))
  {
    return false;
  }
  // The array: the one selected, else SegmentedDistance, else the active scalars.
  vtkPointData* pd = image->GetPointData();
  vtkDataArray* array = this->SelectedArray(image);
  if (!array && !this->HasArraySelection())
  {
    array = pd->GetArray("SegmentedDistance");
    array = array ? array : pd->GetScalars();
  }
  if (!array)
  {
    vtkErrorMacro("The field has no point array to render: neither the selected one, nor "
                  "SegmentedDistance, nor point scalars (a signed distance field)");
    return false;
  }
  if (array->GetNumberOfComponents() != 1 ||
    array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    vtkErrorMacro("The array " << (array->GetName() ? array->GetName() : "(unnamed)")
                               << " must have one component per point");
    return false;
  }
  bool segmented = false;
  double offset = 0;
  if (array->GetName() && std::string(array->GetName()) == "SegmentedDistance")
  {
    vtkDataArray* offsetArray = image->GetFieldData()->GetArray("RegionOffset");
    offset =
      offsetArray && offsetArray->GetNumberOfTuples() > 0 ? offsetArray->GetComponent(0, 0) : 0.0;
    if (!(offset > 0) || !std::isfinite(offset))
    {
      vtkErrorMacro("SegmentedDistance needs a positive field-data RegionOffset (what "
                    "vtkSegmentedDistanceField writes) to tell the regions apart");
      return false;
    }
    segmented = true;
  }

  const vtkIdType count = image->GetNumberOfPoints();
  std::vector<float> texels(2 * static_cast<size_t>(count));
  bool finite = true;
  int regions = 0;
  DecodeFieldTexels(array, segmented, offset, texels.data(), finite, regions);
  if (!finite)
  {
    vtkErrorMacro("The field " << array->GetName() << " holds NaN or infinite values");
    return false;
  }
  if (regions > (1 << 24))
  {
    vtkErrorMacro("The field has " << regions << " regions; at most 2^24 can be rendered");
    return false;
  }
  // Surface mode draws a signed field's zero set: a field with no negative sample (an
  // unsigned distance, as vtkSegmentedDistanceField's Distance) has none, and the picture
  // would stay empty without a word.
  if (!segmented && regions < 2)
  {
    vtkWarningMacro("The field " << (array->GetName() ? array->GetName() : "(unnamed)")
                                 << " has no negative value, so Mode Surface draws nothing: it "
                                    "draws a signed field's zero set. Choose a signed field, or "
                                    "SegmentedDistance for a segmented one");
  }

  // Linear filtering for the rays' march over a signed field; the rest reads texels.
  PrepareTexture(impl.Field, vtkTextureObject::Linear, GL_RG32F, GL_RG, GL_FLOAT);
  if (!Create3D(impl.Field, dims, 2, VTK_FLOAT, texels.data()))
  {
    vtkErrorMacro("Could not make the field's 3D texture (" << dims[0] << " x " << dims[1] << " x "
                                                            << dims[2] << ")");
    return false;
  }
  // Where interfaces may lie, by bricks: the rays leap over the others.
  if (!UploadLeaps(impl.SurfaceLeaps,
        vtkdf::render::MixedBricks(texels.data(), dims, BrickSize),
        vtkdf::render::BrickCounts(dims, BrickSize)))
  {
    vtkErrorMacro("Could not make the bricks' 3D texture");
    return false;
  }
  // Closest points (vtkLinearFactorDistanceField's ComputeClosestPoint) give the normals.
  impl.HasClosestPoints = false;
  vtkDataArray* closest = pd->GetArray("ClosestPoint");
  if (closest && closest->GetNumberOfComponents() == 3 && closest->GetNumberOfTuples() == count)
  {
    impl.HasClosestPoints = UploadClosestPoints(impl.ClosestPoints, closest, dims);
  }
  this->SetGeometry(image, dims);
  impl.Segmented = segmented;
  impl.RegionOffset = offset;
  impl.RegionCount = regions;
  impl.FieldImage = image;
  impl.FieldKey = this->ArraySelectionKey();
  impl.FieldValid = true;
  impl.FieldTime.Modified();
  return true;
}

bool vtkSegmentedDistanceVolumeMapper::UpdateScalars(vtkImageData* image, bool shade)
{
  Internals& impl = *this->Impl;
  // A shaded volume keeps each voxel's central differences next to its value: the
  // gradient a ray step needs is then the trilinear interpolation of eight texels, the
  // same numbers as central differences of the interpolated values a voxel each way
  // (interpolation is linear in the voxels), for a quarter of the fetches.
  const bool gradient =
    shade && static_cast<double>(image->GetNumberOfPoints()) <= StoredGradientVoxels;
  if (impl.ScalarsValid && impl.Scalars->GetHandle() && impl.ScalarsImage == image &&
    impl.ScalarsTime > image->GetMTime() && impl.ScalarsKey == this->ArraySelectionKey() &&
    impl.ScalarsGradient == gradient)
  {
    return true;
  }
  impl.ScalarsValid = false;
  int dims[3];
  if (!this->CheckGrid(image, dims))
  {
    return false;
  }
  // The array: the one selected, else the active scalars, else SegmentedDistance.
  vtkPointData* pd = image->GetPointData();
  vtkDataArray* array = this->SelectedArray(image);
  array = array ? array : pd->GetScalars();
  array = array ? array : pd->GetArray("SegmentedDistance");
  if (!array || array->GetNumberOfComponents() != 1 ||
    array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    vtkErrorMacro("Composite needs a point array of one component (the selected one, else the "
                  "active scalars)");
    return false;
  }
  const vtkIdType count = image->GetNumberOfPoints();
  std::vector<float> values(static_cast<size_t>(count));
  double range[2] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double v = array->GetComponent(i, 0);
    if (!std::isfinite(v))
    {
      vtkErrorMacro("The array " << (array->GetName() ? array->GetName() : "(unnamed)")
                                 << " holds NaN or infinite values");
      return false;
    }
    values[i] = static_cast<float>(v);
    range[0] = std::min(range[0], v);
    range[1] = std::max(range[1], v);
  }
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0;
  }
  impl.BrickRanges = vtkdf::render::BrickValueRanges(values.data(), dims, BrickSize);
  const bool made = UploadScalars(impl.Scalars, values, dims, range, gradient, impl.GradientScale);
  if (!made)
  {
    vtkErrorMacro("Could not make the scalars' 3D texture");
    return false;
  }
  std::copy(range, range + 2, impl.ScalarRange);
  this->SetGeometry(image, dims);
  impl.ScalarsImage = image;
  impl.ScalarsKey = this->ArraySelectionKey();
  impl.ScalarsGradient = gradient;
  impl.ScalarsValid = true;
  impl.ScalarsTime.Modified();
  return true;
}

bool vtkSegmentedDistanceVolumeMapper::UpdateTable(vtkVolumeProperty* property)
{
  Internals& impl = *this->Impl;
  const int size = this->PreIntegrationTableSize;
  const bool gray = property->GetColorChannels(0) == 1;
  vtkObject* colour = gray ? static_cast<vtkObject*>(property->GetGrayTransferFunction(0))
                           : static_cast<vtkObject*>(property->GetRGBTransferFunction(0));
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  const double unit = property->GetScalarOpacityUnitDistance(0);
  const std::array<double, 5> key = {
    impl.ScalarRange[0], impl.ScalarRange[1], unit, static_cast<double>(size), gray ? 1.0 : 3.0
  };
  if (impl.Table->GetHandle() && impl.TableKey == key && impl.TableTime > colour->GetMTime() &&
    impl.TableTime > opacity->GetMTime())
  {
    return true;
  }
  if (!(unit > 0))
  {
    vtkErrorMacro("The volume property's ScalarOpacityUnitDistance must be positive");
    return false;
  }
  // Sample the transfer functions; opacity per unit distance becomes extinction.
  const int count = vtkdf::render::PreIntegrationSamples(size);
  vtkdf::render::TransferSamples samples;
  samples.Low = impl.ScalarRange[0];
  samples.High = impl.ScalarRange[1];
  std::vector<double> alpha(count), rgb(3 * static_cast<size_t>(count));
  opacity->GetTable(samples.Low, samples.High, count, alpha.data());
  if (gray)
  {
    std::vector<double> g(count);
    property->GetGrayTransferFunction(0)->GetTable(samples.Low, samples.High, count, g.data());
    for (int m = 0; m < count; ++m)
    {
      rgb[3 * m] = rgb[3 * m + 1] = rgb[3 * m + 2] = g[m];
    }
  }
  else
  {
    property->GetRGBTransferFunction(0)->GetTable(samples.Low, samples.High, count, rgb.data());
  }
  samples.Extinction.resize(count);
  samples.Colour.resize(count);
  for (int m = 0; m < count; ++m)
  {
    // An opacity of 1 would be an infinite extinction: keep it finite and opaque.
    const double a = std::clamp(alpha[m], 0.0, 1.0 - 1e-7);
    samples.Extinction[m] = -std::log1p(-a) / unit;
    samples.Colour[m] = { rgb[3 * m], rgb[3 * m + 1], rgb[3 * m + 2] };
  }
  std::vector<float> table = vtkdf::render::BuildPreIntegrationTable(samples, size);
  // Full floats: the averages are extinctions per world unit, of any scale.
  if (!UploadTable(impl.Table, table, size, GL_RGBA32F))
  {
    vtkErrorMacro("Could not make the pre-integration table's texture");
    return false;
  }
  impl.Extinction = std::move(samples.Extinction);
  impl.Averages = std::move(table);
  impl.TableKey = key;
  impl.TableTime.Modified();
  ++this->TableBuilds;
  return true;
}

bool vtkSegmentedDistanceVolumeMapper::UpdateStepTable(double length)
{
  Internals& impl = *this->Impl;
  if (impl.StepTable->GetHandle() && impl.StepTableTime > impl.TableTime &&
    impl.StepLength == length)
  {
    return true;
  }
  // Half floats: a step's entries lie in [0, 1] whatever the scale, where half floats keep
  // 11 significant bits (8-bit output needs 8); and a GPU filters the 64-bit texels faster
  // than 128-bit ones, once a step (an H100, 1920x1080, 256 planes: 132 -> 214 fps).
  if (!UploadTable(impl.StepTable,
        vtkdf::render::StepTable(impl.Averages, length),
        this->PreIntegrationTableSize,
        GL_RGBA16F))
  {
    vtkErrorMacro("Could not make the step table's texture");
    return false;
  }
  impl.StepLength = length;
  impl.StepTableTime.Modified();
  ++this->StepTableBuilds;
  return true;
}

bool vtkSegmentedDistanceVolumeMapper::UpdateCompositeLeaps()
{
  Internals& impl = *this->Impl;
  if (impl.CompositeLeaps->GetHandle() && impl.CompositeLeapsTime > impl.ScalarsTime &&
    impl.CompositeLeapsTime > impl.TableTime)
  {
    return true;
  }
  // A brick is transparent when every table entry a slab in it reads is zero: its values
  // widened by a table step.
  const double step =
    (impl.ScalarRange[1] - impl.ScalarRange[0]) / (this->PreIntegrationTableSize - 1);
  const std::vector<unsigned char> occupied = vtkdf::render::OpaqueBricks(
    impl.BrickRanges, impl.Extinction, impl.ScalarRange[0], impl.ScalarRange[1], step);
  if (!UploadLeaps(impl.CompositeLeaps, occupied, vtkdf::render::BrickCounts(impl.Dims, BrickSize)))
  {
    vtkErrorMacro("Could not make the bricks' 3D texture");
    return false;
  }
  impl.CompositeLeapsTime.Modified();
  return true;
}

void vtkSegmentedDistanceVolumeMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  vtkOpenGLClearErrorMacro();
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    vtkErrorMacro("vtkSegmentedDistanceVolumeMapper needs an OpenGL render window");
    return;
  }
  if (this->GetInputAlgorithm())
  {
    this->GetInputAlgorithm()->UpdateWholeExtent();
  }
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  if (!image || image->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("The input must be a non-empty vtkImageData");
    return;
  }
  Internals& impl = *this->Impl;
  vtkVolumeProperty* property = volume->GetProperty();
  const bool surface = this->Mode == Surface;
  for (vtkTextureObject* texture : { impl.Field.Get(),
         impl.Scalars.Get(),
         impl.Table.Get(),
         impl.StepTable.Get(),
         impl.Colors.Get(),
         impl.SurfaceLeaps.Get(),
         impl.CompositeLeaps.Get(),
         impl.ClosestPoints.Get(),
         impl.OpaqueDepth.Get() })
  {
    texture->SetContext(window);
  }
  if (surface ? !this->UpdateField(image)
              : !(this->UpdateScalars(image, property->GetShade(0) != 0) &&
                  this->UpdateTable(property) && this->UpdateCompositeLeaps()))
  {
    return;
  }
  const int colorCount = surface ? this->UpdateRegionColors() : 1;

  // Index space -> world: the image's index-to-physical matrix, then the volume's.
  vtkNew<vtkMatrix4x4> indexToWorld;
  vtkMatrix4x4::Multiply4x4(
    volume->GetMatrix()->GetData(), impl.IndexToPhysical, indexToWorld->GetData());
  vtkCamera* camera = renderer->GetActiveCamera();
  Vec3 eye, viewDir;
  camera->GetPosition(eye.data());
  camera->GetDirectionOfProjection(viewDir.data());
  viewDir = Normalized(viewDir);
  SamplePlanes planes;
  const std::vector<float> triangles =
    this->BoxFaces(indexToWorld, eye.data(), viewDir.data(), planes);
  if (triangles.empty() || window->CheckAbortStatus() ||
    (!surface && !this->UpdateStepTable(planes.Spacing)))
  {
    return;
  }
  vtkOpenGLHelper& helper = surface ? impl.Surfaces : impl.Composite;
  vtkShaderProgram* program = this->ReadyProgram(window,
    triangles,
    helper,
    property->GetShade(0) != 0,
    renderer->GetActiveCamera()->GetParallelProjection() != 0);
  if (!program)
  {
    return;
  }
  this->SetViewUniforms(program, renderer, indexToWorld, eye.data(), viewDir.data(), planes);
  this->SetShadingUniforms(program, property);
  std::vector<vtkTextureObject*> active = surface
    ? this->BindSurfaceTextures(program, volume, colorCount)
    : this->BindCompositeTextures(program);
  // Rays blended over the window (composite, translucent surfaces) stop at the opaque
  // geometry's depth, read from a copy; opaque surfaces meet the depth test instead.
  const bool blended = !surface || this->SurfaceOpacity < 1.0;
  if (blended)
  {
    active.push_back(this->BindOpaqueDepth(program, renderer, window));
  }
  this->DrawBox(window, blended, static_cast<GLsizei>(triangles.size() / 3));
  for (vtkTextureObject* texture : active)
  {
    texture->Deactivate();
  }
  helper.VAO->Release();
  vtkOpenGLCheckErrorMacro("failed after casting the rays");
}

int vtkSegmentedDistanceVolumeMapper::UpdateRegionColors()
{
  Internals& impl = *this->Impl;
  this->LastRegionCount = impl.RegionCount;
  this->LastSegmented = impl.Segmented;
  // Region colours: one texel per region (cycling beyond the texture's width).
  const int colorCount = std::max(1, std::min(impl.RegionCount, 4096));
  if (!impl.Colors->GetHandle() || impl.ColorsTime < impl.ColorsModified ||
    impl.ColorsTime < impl.FieldTime)
  {
    std::vector<float> rgb(3 * static_cast<size_t>(colorCount));
    for (int r = 0; r < colorCount; ++r)
    {
      double c[3];
      this->GetRegionColor(r, c);
      std::copy(c, c + 3, rgb.begin() + 3 * r);
    }
    PrepareTexture(impl.Colors, vtkTextureObject::Nearest, GL_RGB32F, GL_RGB, GL_FLOAT);
    impl.Colors->Create2DFromRaw(
      static_cast<unsigned int>(colorCount), 1, 3, VTK_FLOAT, rgb.data());
    impl.ColorsTime.Modified();
  }
  return colorCount;
}

vtkShaderProgram* vtkSegmentedDistanceVolumeMapper::ReadyProgram(vtkOpenGLRenderWindow* window,
  const std::vector<float>& triangles,
  vtkOpenGLHelper& helper,
  bool shade,
  bool parallel)
{
  Internals& impl = *this->Impl;
  // Through VTK's shader cache. Both fragment shaders take the ray code they share in
  // place of //DF::SlabCommon. What varies between frames only rarely is compiled in
  // rather than branched on: a software rasterizer runs a branch's texture fetches for
  // every pixel whichever way it goes.
  std::string fragment = this->Mode == Surface ? SegmentedVolume_frag : PreIntegratedVolume_frag;
  const bool differenced = this->Mode == Composite && shade && !impl.ScalarsGradient;
  const bool storedGradient = this->Mode == Composite && shade && impl.ScalarsGradient;
  const bool filteredMarch =
    this->Mode == Surface && !impl.Segmented && this->Interpolation != Nearest;
  // Rays blended over the window stop at the opaque geometry's depth, read from a copy.
  const bool opaqueDepth = this->Mode == Composite || this->SurfaceOpacity < 1.0;
  const bool closestNormals = impl.HasClosestPoints && this->UseClosestPointNormals;
  std::string defines;
  for (const auto& define : { std::make_pair("DIFFERENCED_GRADIENT", int(differenced)),
         std::make_pair("STORED_GRADIENT", int(storedGradient)),
         std::make_pair("FILTERED_MARCH", int(filteredMarch)),
         std::make_pair("LEAP", int(this->EmptySpaceLeaping)),
         std::make_pair("SHADE", int(shade)),
         std::make_pair("OPAQUE_DEPTH", int(opaqueDepth)),
         std::make_pair("PARALLEL", int(parallel)),
         std::make_pair("SEGMENTED", int(impl.Segmented)),
         std::make_pair("INTERPOLATION", this->Interpolation),
         std::make_pair("CLOSEST_POINT_NORMALS", int(closestNormals)),
         std::make_pair("BRICK_SIZE", BrickSize) })
  {
    defines += std::string("#define ") + define.first + " " + std::to_string(define.second) + "\n";
  }
  vtkShaderProgram::Substitute(fragment, "//DF::SlabCommon", defines + SlabCommon);
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(SegmentedVolume_vert, fragment.c_str(), "");
  if (!program)
  {
    vtkErrorMacro("Could not build the ray-casting shader program");
    return nullptr;
  }
  if (program != helper.Program)
  {
    helper.Program = program;
    helper.VAO->ShaderProgramChanged();
  }
  helper.VAO->Bind();
  impl.Vertices->Upload(triangles, vtkOpenGLBufferObject::ArrayBuffer);
  if (!helper.VAO->AddAttributeArray(
        program, impl.Vertices, "vertexWC", 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
  {
    vtkErrorMacro("Could not bind the box's vertices");
    helper.VAO->Release();
    return nullptr;
  }
  return program;
}

void vtkSegmentedDistanceVolumeMapper::SetViewUniforms(vtkShaderProgram* program,
  vtkRenderer* renderer,
  vtkMatrix4x4* indexToWorld,
  const double eye[3],
  const double viewDir[3],
  const SamplePlanes& planes)
{
  Internals& impl = *this->Impl;
  vtkNew<vtkMatrix4x4> worldToIndex;
  vtkMatrix4x4::Invert(indexToWorld, worldToIndex);
  // Gradients in index space (per index step) -> world normals: the inverse transpose of
  // index-to-world's linear part.
  double normalMatrix[3][3];
  NormalMatrix(worldToIndex, normalMatrix);
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkMatrix4x4 *worldToView, *viewToClip, *worldToClipT;
  vtkMatrix3x3* normals;
  static_cast<vtkOpenGLCamera*>(camera)->GetKeyMatrices(
    renderer, worldToView, normals, viewToClip, worldToClipT);
  // GetKeyMatrices hands out transposed matrices, which is what the upload wants.
  program->SetUniformMatrix("worldToClip", worldToClipT);
  SetPlainMatrix(program, "worldToIndex", worldToIndex);
  SetPlainMatrix(program, "indexToWorldNormal", normalMatrix);
  const float eyeF[3] = {
    static_cast<float>(eye[0]), static_cast<float>(eye[1]), static_cast<float>(eye[2])
  };
  const float dirF[3] = {
    static_cast<float>(viewDir[0]), static_cast<float>(viewDir[1]), static_cast<float>(viewDir[2])
  };
  // The eye and the view direction in index space too: the rays' set-up then needs no
  // matrix per pixel.
  const Vec3 eyeIndex = Apply(worldToIndex, { eye[0], eye[1], eye[2] });
  const Vec3 viewDirIndex = Sub(Apply(worldToIndex, { viewDir[0], viewDir[1], viewDir[2] }),
    Apply(worldToIndex, { 0.0, 0.0, 0.0 }));
  const float eyeIndexF[3] = { static_cast<float>(eyeIndex[0]),
    static_cast<float>(eyeIndex[1]),
    static_cast<float>(eyeIndex[2]) };
  const float dirIndexF[3] = { static_cast<float>(viewDirIndex[0]),
    static_cast<float>(viewDirIndex[1]),
    static_cast<float>(viewDirIndex[2]) };
  program->SetUniform3f("eyeWC", eyeF);
  program->SetUniform3f("viewDirWC", dirF);
  program->SetUniform3f("eyeI", eyeIndexF);
  program->SetUniform3f("viewDirI", dirIndexF);
  program->SetUniformf("sliceSpacing", static_cast<float>(planes.Spacing));
  program->SetUniformf("inverseSliceSpacing", static_cast<float>(1.0 / planes.Spacing));
  program->SetUniformf("firstSliceDepth", static_cast<float>(planes.First));
  program->SetUniformi("sliceCount", planes.Count);
  program->SetUniformf("nearDepth", static_cast<float>(camera->GetClippingRange()[0]));
  const float dimsF[3] = { static_cast<float>(impl.Dims[0]),
    static_cast<float>(impl.Dims[1]),
    static_cast<float>(impl.Dims[2]) };
  program->SetUniform3f("gridSize", dimsF);
}

void vtkSegmentedDistanceVolumeMapper::SetShadingUniforms(vtkShaderProgram* program,
  vtkVolumeProperty* property)
{
  program->SetUniformf("ambient", static_cast<float>(property->GetAmbient(0)));
  program->SetUniformf("diffuse", static_cast<float>(property->GetDiffuse(0)));
  program->SetUniformf("specular", static_cast<float>(property->GetSpecular(0)));
  program->SetUniformf("specularPower", static_cast<float>(property->GetSpecularPower(0)));
}

std::vector<vtkTextureObject*> vtkSegmentedDistanceVolumeMapper::BindSurfaceTextures(
  vtkShaderProgram* program,
  vtkVolume* volume,
  int colorCount)
{
  Internals& impl = *this->Impl;
  const float spacingF[3] = { static_cast<float>(std::abs(impl.Spacing[0])),
    static_cast<float>(std::abs(impl.Spacing[1])),
    static_cast<float>(std::abs(impl.Spacing[2])) };
  program->SetUniform3f("spacing", spacingF);
  program->SetUniformf("regionOffset", static_cast<float>(impl.RegionOffset));
  program->SetUniformi("regionColorCount", colorCount);
  program->SetUniformf("opacity", static_cast<float>(this->SurfaceOpacity));
  std::vector<vtkTextureObject*> active = { impl.Field, impl.Colors, impl.SurfaceLeaps };
  const bool closestNormals = impl.HasClosestPoints && this->UseClosestPointNormals;
  if (closestNormals)
  {
    active.push_back(impl.ClosestPoints);
  }
  for (vtkTextureObject* texture : active)
  {
    texture->Activate();
  }
  program->SetUniformi("field", impl.Field->GetTextureUnit());
  program->SetUniformi("regionColors", impl.Colors->GetTextureUnit());
  program->SetUniformi("leaps", impl.SurfaceLeaps->GetTextureUnit());
  SetLastBrick(program, impl.Dims);
  // Unused, the closest-point sampler names the field's unit (a 3D texture too; never
  // read), so that no sampler is left on a unit of another texture type.
  program->SetUniformi("closestPoints",
    closestNormals ? impl.ClosestPoints->GetTextureUnit() : impl.Field->GetTextureUnit());
  vtkNew<vtkMatrix4x4> indexToPhysical;
  indexToPhysical->DeepCopy(impl.IndexToPhysical);
  SetPlainMatrix(program, "indexToPhysical", indexToPhysical);
  // Physical -> world normals: the inverse transpose of the volume matrix's linear part.
  vtkNew<vtkMatrix4x4> worldToPhysical;
  vtkMatrix4x4::Invert(volume->GetMatrix(), worldToPhysical);
  double physicalNormal[3][3];
  NormalMatrix(worldToPhysical, physicalNormal);
  SetPlainMatrix(program, "physicalToWorldNormal", physicalNormal);
  return active;
}

std::vector<vtkTextureObject*> vtkSegmentedDistanceVolumeMapper::BindCompositeTextures(
  vtkShaderProgram* program)
{
  Internals& impl = *this->Impl;
  const float range[2] = { static_cast<float>(impl.ScalarRange[0]),
    static_cast<float>(impl.ScalarRange[1]) };
  program->SetUniform2f("scalarRange", range);
  // Entry i of the table's n is for the value low + i (high - low) / (n - 1), at the
  // coordinate (i + 0.5) / n. A stored gradient's texels are normalized: value =
  // low + half + half * texel.
  const double n = this->PreIntegrationTableSize;
  const double perValue = (n - 1) / (n * (impl.ScalarRange[1] - impl.ScalarRange[0]));
  double map[2] = { perValue, 0.5 / n - impl.ScalarRange[0] * perValue };
  if (impl.ScalarsGradient)
  {
    const double half = 0.5 * (impl.ScalarRange[1] - impl.ScalarRange[0]);
    map[1] += (impl.ScalarRange[0] + half) * map[0];
    map[0] *= half;
  }
  const float tableMap[2] = { static_cast<float>(map[0]), static_cast<float>(map[1]) };
  program->SetUniform2f("tableMap", tableMap);
  program->SetUniformf("packedGradientScale", static_cast<float>(impl.GradientScale));
  std::vector<vtkTextureObject*> active = {
    impl.Scalars, impl.Table, impl.StepTable, impl.CompositeLeaps
  };
  for (vtkTextureObject* texture : active)
  {
    texture->Activate();
  }
  program->SetUniformi("leaps", impl.CompositeLeaps->GetTextureUnit());
  SetLastBrick(program, impl.Dims);
  program->SetUniformi("scalars", impl.Scalars->GetTextureUnit());
  program->SetUniformi("preIntegrated", impl.Table->GetTextureUnit());
  program->SetUniformi("preIntegratedStep", impl.StepTable->GetTextureUnit());
  return active;
}

vtkTextureObject* vtkSegmentedDistanceVolumeMapper::BindOpaqueDepth(vtkShaderProgram* program,
  vtkRenderer* renderer,
  vtkOpenGLRenderWindow* window)
{
  Internals& impl = *this->Impl;
  int width, height, x0, y0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  const int format = ReadDepthFormat();
  if (!impl.OpaqueDepth->GetHandle() || impl.DepthSize[0] != width || impl.DepthSize[1] != height ||
    impl.DepthFormat != format)
  {
    impl.OpaqueDepth->ReleaseGraphicsResources(window);
    impl.OpaqueDepth->SetContext(window);
    PrepareTexture(impl.OpaqueDepth, vtkTextureObject::Nearest);
    impl.OpaqueDepth->AllocateDepth(
      static_cast<unsigned int>(width), static_cast<unsigned int>(height), format);
    impl.DepthSize[0] = width;
    impl.DepthSize[1] = height;
    impl.DepthFormat = format;
  }
  impl.OpaqueDepth->CopyFromFrameBuffer(x0, y0, 0, 0, width, height);
  impl.OpaqueDepth->Activate();
  const int origin[2] = { x0, y0 };
  program->SetUniform2i("viewportOrigin", origin);
  program->SetUniformi("opaqueDepth", impl.OpaqueDepth->GetTextureUnit());
  return impl.OpaqueDepth;
}

void vtkSegmentedDistanceVolumeMapper::DrawBox(vtkOpenGLRenderWindow* window,
  bool blended,
  GLsizei vertexCount)
{
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  // One ray a pixel, from the box's back faces (an eye inside the box has them): the
  // front faces are culled.
  GLint cullMode = GL_BACK;
  glGetIntegerv(GL_CULL_FACE_MODE, &cullMode);
  state->vtkglEnable(GL_CULL_FACE);
  state->vtkglCullFace(GL_FRONT);
  if (blended)
  {
    // Premultiplied colours over the window; the shaders stop at the opaque depth.
    state->vtkglDisable(GL_DEPTH_TEST);
    state->vtkglDepthMask(GL_FALSE);
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  else
  {
    // Opaque surfaces write their depth, tested against the opaque geometry's.
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthFunc(GL_LEQUAL);
    state->vtkglDepthMask(GL_TRUE);
    state->vtkglDisable(GL_BLEND);
  }
  glDrawArrays(GL_TRIANGLES, 0, vertexCount);
  state->vtkglCullFace(static_cast<unsigned int>(cullMode));
}

std::vector<float> vtkSegmentedDistanceVolumeMapper::BoxFaces(vtkMatrix4x4* indexToWorld,
  const double eyeIn[3],
  const double viewDirIn[3],
  SamplePlanes& planes)
{
  const Internals& impl = *this->Impl;
  const Vec3 eye = { eyeIn[0], eyeIn[1], eyeIn[2] };
  const Vec3 viewDir = { viewDirIn[0], viewDirIn[1], viewDirIn[2] };
  // The box's corners in world space, and their depths along the view direction.
  std::array<Vec3, 8> corners;
  double nearest = VTK_DOUBLE_MAX, farthest = -VTK_DOUBLE_MAX;
  Vec3 centre = { 0, 0, 0 };
  for (int c = 0; c < 8; ++c)
  {
    const Vec3 index = { (c & 1) ? impl.Dims[0] - 1.0 : 0.0,
      (c & 2) ? impl.Dims[1] - 1.0 : 0.0,
      (c & 4) ? impl.Dims[2] - 1.0 : 0.0 };
    corners[c] = Apply(indexToWorld, index);
    const double depth = Dot(Sub(corners[c], eye), viewDir);
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
    for (int k = 0; k < 3; ++k)
    {
      centre[k] += corners[c][k] / 8;
    }
  }
  double smallestSpacing = VTK_DOUBLE_MAX;
  for (int a = 0; a < 3; ++a)
  {
    const Vec3 axis = {
      indexToWorld->GetElement(0, a), indexToWorld->GetElement(1, a), indexToWorld->GetElement(2, a)
    };
    smallestSpacing = std::min(smallestSpacing, std::sqrt(Dot(axis, axis)));
  }
  const double depth = farthest - nearest;
  double spacing = this->SampleDistance > 0 ? this->SampleDistance : smallestSpacing;
  if (this->NumberOfSlices > 0)
  {
    spacing = depth / this->NumberOfSlices;
  }
  this->LastNumberOfSlices = 0;
  if (!(spacing > 0) || !std::isfinite(spacing) || !(depth > 0))
  {
    vtkErrorMacro("The volume has no extent along the view direction");
    return {};
  }
  const double sliceCount = std::ceil(depth / spacing);
  if (sliceCount > (1 << 20))
  {
    vtkErrorMacro("SampleDistance " << spacing << " makes " << sliceCount
                                    << " sample planes across the volume; at most 2^20 are used");
    return {};
  }
  planes.Count = std::max(1, static_cast<int>(sliceCount));
  planes.First = nearest;
  planes.Spacing = spacing;

  std::vector<float> triangles = vtkdf::render::BoxTriangles(corners, centre);
  this->LastNumberOfSlices = planes.Count;
  return triangles;
}
