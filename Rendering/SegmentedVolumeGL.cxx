#include "SegmentedVolumeGL.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkSMPTools.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "EmptySpace.h"

#include <algorithm>
#include <cmath>

namespace vtkdf
{
namespace render
{
namespace
{
/// Reads a field into (distance, region) texels: a segmented one from f = min(d, Delta)
/// + RegionOffset * r, a signed one as (value, sign): the shader takes the distance's
/// absolute value, and marches rays on the filtered signed value. Reports a non-finite
/// value.
struct DecodeField
{
  template<typename Array>
  void operator()(Array* array,
    bool segmented,
    double offset,
    float* texels,
    bool& finite,
    int& regions) const
  {
    const auto values = vtk::DataArrayValueRange<1>(array);
    vtkIdType i = 0;
    int highest = 0;
    for (const auto value : values)
    {
      const double f = static_cast<double>(value);
      if (!std::isfinite(f))
      {
        finite = false;
        return;
      }
      double distance, region;
      if (segmented)
      {
        region = std::floor(f / offset);
        distance = f - region * offset;
      }
      else
      {
        region = f < 0 ? 1 : 0;
        distance = f;
      }
      texels[2 * i] = static_cast<float>(distance);
      texels[2 * i + 1] = static_cast<float>(region);
      highest = std::max(highest, static_cast<int>(region));
      ++i;
    }
    regions = highest + 1;
  }
};
} // namespace

/// A point through a plain (row-major, column-vector) 4x4 matrix.
Vec3 Apply(vtkMatrix4x4* m, const Vec3& p)
{
  const double q[4] = { p[0], p[1], p[2], 1 };
  double r[4];
  m->MultiplyPoint(q, r);
  return { r[0] / r[3], r[1] / r[3], r[2] / r[3] };
}

/// vtkShaderProgram uploads a vtkMatrix4x4's elements row by row into a GLSL
/// (column-major) matrix, that is transposed: hand it the transpose of the plain matrix.
void SetPlainMatrix(vtkShaderProgram* program, const char* name, const vtkMatrix4x4* plain)
{
  vtkNew<vtkMatrix4x4> transposed;
  vtkMatrix4x4::Transpose(plain, transposed);
  program->SetUniformMatrix(name, transposed);
}
void SetPlainMatrix(vtkShaderProgram* program, const char* name, const double plain[3][3])
{
  vtkNew<vtkMatrix3x3> transposed;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      transposed->SetElement(j, i, plain[i][j]);
    }
  }
  program->SetUniformMatrix(name, transposed);
}

/// A texture's sampling (clamped, `filter` both ways) and, when `internalFormat` is not 0,
/// the GL formats its data will be created with.
void PrepareTexture(vtkTextureObject* texture,
  int filter,
  unsigned int internalFormat,
  unsigned int format,
  unsigned int type)
{
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
  texture->SetMinificationFilter(filter);
  texture->SetMagnificationFilter(filter);
  if (internalFormat != 0)
  {
    texture->SetInternalFormat(internalFormat);
    texture->SetFormat(format);
    texture->SetDataType(type);
  }
}

/// The inverse transpose of a 4x4 matrix's linear part, given the matrix's inverse: what
/// turns gradients (normals) on the matrix's input side into its output side.
void NormalMatrix(vtkMatrix4x4* inverse, double normal[3][3])
{
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      normal[i][j] = inverse->GetElement(j, i);
    }
  }
}

/// The default colour of region r: a palette of distinct colours, then hues spread by
/// the golden angle.
void DefaultRegionColor(int region, double rgb[3])
{
  static const double palette[8][3] = { { 0.92, 0.90, 0.84 },
    { 0.86, 0.38, 0.30 },
    { 0.32, 0.56, 0.88 },
    { 0.42, 0.76, 0.40 },
    { 0.95, 0.76, 0.28 },
    { 0.66, 0.46, 0.82 },
    { 0.30, 0.76, 0.76 },
    { 0.88, 0.56, 0.74 } };
  if (region >= 0 && region < 8)
  {
    std::copy(palette[region], palette[region] + 3, rgb);
    return;
  }
  const double hue = std::fmod(region * 0.618033988749895, 1.0) * 6.0;
  const double x = 1.0 - std::abs(std::fmod(hue, 2.0) - 1.0);
  const int sector = static_cast<int>(hue) % 6;
  const double c[6][3] = {
    { 1, x, 0 }, { x, 1, 0 }, { 0, 1, x }, { 0, x, 1 }, { x, 0, 1 }, { 1, 0, x }
  };
  for (int k = 0; k < 3; ++k)
  {
    rgb[k] = 0.25 + 0.65 * c[sector][k];
  }
}

/// The depth format of the framebuffer the window reads from, as vtkTextureObject names
/// it: the opaque depth's copy in the same format is a plain copy (into a float texture
/// from a 32-bit fixed-point buffer, llvmpipe converted for 5 ms a 1920x1080 frame) and
/// exact. Float32 where the buffer's format is not one of those.
int ReadDepthFormat()
{
  GLint framebuffer = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &framebuffer);
  const GLenum attachment = framebuffer != 0 ? GL_DEPTH_ATTACHMENT : GL_DEPTH;
  GLint object = GL_NONE, type = GL_NONE, bits = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &object);
  if (object == GL_NONE)
  {
    return vtkTextureObject::Float32;
  }
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  if (type == GL_UNSIGNED_NORMALIZED)
  {
    switch (bits)
    {
      case 16:
        return vtkTextureObject::Fixed16;
      case 24:
        return vtkTextureObject::Fixed24;
      case 32:
        return vtkTextureObject::Fixed32;
      default:
        break;
    }
  }
  return vtkTextureObject::Float32;
}

/// A size x size RGBA table (pre-integration: averages or a step's), filtered, stored as
/// `internalFormat` (GL_RGBA32F or GL_RGBA16F) from floats.
bool UploadTable(vtkTextureObject* texture,
  const std::vector<float>& table,
  int size,
  unsigned int internalFormat)
{
  PrepareTexture(texture, vtkTextureObject::Linear, internalFormat, GL_RGBA, GL_FLOAT);
  return texture->Create2DFromRaw(static_cast<unsigned int>(size),
    static_cast<unsigned int>(size),
    4,
    VTK_FLOAT,
    const_cast<float*>(table.data()));
}

/// The leap texture's last brick per axis, for the shader's clamp.
void SetLastBrick(vtkShaderProgram* program, const int dims[3])
{
  const std::array<int, 3> counts = vtkdf::render::BrickCounts(dims, BrickSize);
  const float last[3] = { counts[0] - 1.0f, counts[1] - 1.0f, counts[2] - 1.0f };
  program->SetUniform3f("lastBrick", last);
}

/// Each voxel's value and its central differences along x, y and z (one-sided at the
/// grid's faces, as the shader's clamped interpolation gives them there), as 16-bit signed
/// normalized texels: the value over `range` mapped to [-1, 1] (65,535 steps, finer than
/// the largest pre-integration table), the differences divided by `gradientScale`, the
/// largest of them. Half the bytes of floats (at 128^3 on llvmpipe, 8% more frames).
std::vector<short> PackedWithGradients(const std::vector<float>& values,
  const int dims[3],
  const double range[2],
  double& gradientScale)
{
  const vtkIdType nx = dims[0], ny = dims[1], nz = dims[2];
  std::vector<float> differences(3 * values.size());
  vtkSMPTools::For(0,
    nz,
    [&](vtkIdType zBegin, vtkIdType zEnd)
    {
      const auto at = [&](vtkIdType x, vtkIdType y, vtkIdType z)
      { return values[x + nx * (y + ny * z)]; };
      for (vtkIdType z = zBegin; z < zEnd; ++z)
      {
        for (vtkIdType y = 0; y < ny; ++y)
        {
          for (vtkIdType x = 0; x < nx; ++x)
          {
            float* d = &differences[3 * (x + nx * (y + ny * z))];
            d[0] = at(std::min(x + 1, nx - 1), y, z) - at(std::max<vtkIdType>(x - 1, 0), y, z);
            d[1] = at(x, std::min(y + 1, ny - 1), z) - at(x, std::max<vtkIdType>(y - 1, 0), z);
            d[2] = at(x, y, std::min(z + 1, nz - 1)) - at(x, y, std::max<vtkIdType>(z - 1, 0));
          }
        }
      }
    });
  float largest = 0;
  for (const float d : differences)
  {
    largest = std::max(largest, std::abs(d));
  }
  gradientScale = largest > 0 ? largest : 1.0;
  const double toValue = 2.0 / (range[1] - range[0]);
  const auto snorm = [](double f)
  { return static_cast<short>(std::lround(std::clamp(f, -1.0, 1.0) * 32767.0)); };
  std::vector<short> texels(4 * values.size());
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(values.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        texels[4 * i] = snorm((values[i] - range[0]) * toValue - 1.0);
        for (int c = 0; c < 3; ++c)
        {
          texels[4 * i + 1 + c] = snorm(differences[3 * i + c] / gradientScale);
        }
      }
    });
  return texels;
}

/// Uploads per-brick leap distances (vtkdf::render::LeapDistances) as an R8 texture.
bool UploadLeaps(vtkTextureObject* texture,
  const std::vector<unsigned char>& occupied,
  const std::array<int, 3>& bricks)
{
  const std::vector<unsigned char> leaps = vtkdf::render::LeapDistances(occupied, bricks);
  PrepareTexture(texture, vtkTextureObject::Nearest, GL_R8, GL_RED, GL_UNSIGNED_BYTE);
  return texture->Create3DFromRaw(static_cast<unsigned int>(bricks[0]),
    static_cast<unsigned int>(bricks[1]),
    static_cast<unsigned int>(bricks[2]),
    1,
    VTK_UNSIGNED_CHAR,
    const_cast<unsigned char*>(leaps.data()));
}

void DecodeFieldTexels(vtkDataArray* array,
  bool segmented,
  double offset,
  float* texels,
  bool& finite,
  int& regions)
{
  if (!vtkArrayDispatch::Dispatch::Execute(
        array, DecodeField{}, segmented, offset, texels, finite, regions))
  {
    DecodeField{}(array, segmented, offset, texels, finite, regions);
  }
}

std::vector<float> BoxTriangles(const std::array<Vec3, 8>& corners, const Vec3& centre)
{
  // The box's twelve triangles, each counter-clockwise seen from outside (whatever the
  // handedness of index-to-world), so that culling the front faces leaves the back ones.
  static const int faces[6][4] = {
    { 0, 2, 6, 4 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 }, { 2, 3, 7, 6 }, { 0, 1, 3, 2 }, { 4, 5, 7, 6 }
  };
  std::vector<float> triangles;
  triangles.reserve(6 * 2 * 3 * 3);
  for (const auto& face : faces)
  {
    Vec3 middle = { 0, 0, 0 };
    for (const int c : face)
    {
      for (int k = 0; k < 3; ++k)
      {
        middle[k] += corners[c][k] / 4;
      }
    }
    const Vec3 outward = Sub(middle, centre);
    for (const std::array<int, 3>& corner : { std::array<int, 3>{ face[0], face[1], face[2] },
           std::array<int, 3>{ face[0], face[2], face[3] } })
    {
      const Vec3 normal = Cross(
        Sub(corners[corner[1]], corners[corner[0]]), Sub(corners[corner[2]], corners[corner[0]]));
      const bool flip = Dot(normal, outward) < 0;
      for (const int c : { corner[0], flip ? corner[2] : corner[1], flip ? corner[1] : corner[2] })
      {
        triangles.insert(triangles.end(),
          { static_cast<float>(corners[c][0]),
            static_cast<float>(corners[c][1]),
            static_cast<float>(corners[c][2]) });
      }
    }
  }
  return triangles;
}

bool Create3D(vtkTextureObject* texture, const int dims[3], int components, int type, void* data)
{
  return texture->Create3DFromRaw(static_cast<unsigned int>(dims[0]),
    static_cast<unsigned int>(dims[1]),
    static_cast<unsigned int>(dims[2]),
    components,
    type,
    data);
}

bool UploadScalars(vtkTextureObject* texture,
  std::vector<float>& values,
  const int dims[3],
  const double range[2],
  bool gradient,
  double& gradientScale)
{
  if (gradient)
  {
    std::vector<short> texels = PackedWithGradients(values, dims, range, gradientScale);
    PrepareTexture(texture, vtkTextureObject::Linear, GL_RGBA16_SNORM, GL_RGBA, GL_SHORT);
    return Create3D(texture, dims, 4, VTK_SHORT, texels.data());
  }
  PrepareTexture(texture, vtkTextureObject::Linear, GL_R32F, GL_RED, GL_FLOAT);
  return Create3D(texture, dims, 1, VTK_FLOAT, values.data());
}

bool UploadClosestPoints(vtkTextureObject* texture, vtkDataArray* closest, const int dims[3])
{
  const vtkIdType count = closest->GetNumberOfTuples();
  std::vector<float> points(3 * static_cast<size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      points[3 * i + c] = static_cast<float>(closest->GetComponent(i, c));
    }
  }
  PrepareTexture(texture, vtkTextureObject::Nearest, GL_RGB32F, GL_RGB, GL_FLOAT);
  return Create3D(texture, dims, 3, VTK_FLOAT, points.data());
}
} // namespace render
} // namespace vtkdf
