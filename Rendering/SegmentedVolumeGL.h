// SegmentedVolumeGL: the GL pieces of vtkSegmentedDistanceVolumeMapper that are not the
// mapper's state: textures made from arrays (the field's texels, tables, leaps, values
// with gradients), uniforms from matrices, the default region colours and the box's
// faces. Through VTK's OpenGL layer (vtk_glew.h), like the mapper.
#ifndef vtkdf_SegmentedVolumeGL_h
#define vtkdf_SegmentedVolumeGL_h

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

class vtkDataArray;
class vtkMatrix4x4;
class vtkShaderProgram;
class vtkTextureObject;

namespace vtkdf
{
namespace render
{
using Vec3 = std::array<double, 3>;

inline Vec3 Sub(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
inline Vec3 Normalized(const Vec3& a)
{
  const double n = std::sqrt(Dot(a, a));
  return n > 0 ? Vec3{ a[0] / n, a[1] / n, a[2] / n } : a;
}

/// The empty-space leaps' bricks: BrickSize^3 cells.
constexpr int BrickSize = 4;

/// Shaded composite volumes up to this many voxels store their gradients (8 bytes a voxel
/// instead of 4: 512 MiB at most); larger ones difference their values in the shader.
constexpr double StoredGradientVoxels = 1 << 26;

/// A point through a plain (row-major, column-vector) 4x4 matrix.
Vec3 Apply(vtkMatrix4x4* m, const Vec3& p);

/// A plain matrix as a uniform (vtkShaderProgram uploads a vtkMatrix4x4 transposed).
void SetPlainMatrix(vtkShaderProgram* program, const char* name, const vtkMatrix4x4* plain);
void SetPlainMatrix(vtkShaderProgram* program, const char* name, const double plain[3][3]);

/// A texture's sampling (clamped, `filter` both ways) and, when `internalFormat` is not 0,
/// the GL formats its data will be created with.
void PrepareTexture(vtkTextureObject* texture,
  int filter,
  unsigned int internalFormat = 0,
  unsigned int format = 0,
  unsigned int type = 0);

/// The inverse transpose of a 4x4 matrix's linear part, given the matrix's inverse.
void NormalMatrix(vtkMatrix4x4* inverse, double normal[3][3]);

/// The default colour of region r.
void DefaultRegionColor(int region, double rgb[3]);

/// A field's (distance, region) texels: a segmented one from f = min(d, Delta) +
/// RegionOffset * r, a signed one as (value, sign). `finite` false at a non-finite value;
/// `regions` the highest region + 1.
void DecodeFieldTexels(vtkDataArray* array,
  bool segmented,
  double offset,
  float* texels,
  bool& finite,
  int& regions);

/// The depth format of the framebuffer the window reads from, as vtkTextureObject names it.
int ReadDepthFormat();

/// A size x size RGBA table stored as `internalFormat` (GL_RGBA32F or GL_RGBA16F).
bool UploadTable(vtkTextureObject* texture,
  const std::vector<float>& table,
  int size,
  unsigned int internalFormat);

/// The leap texture's last brick per axis, for the shader's clamp.
void SetLastBrick(vtkShaderProgram* program, const int dims[3]);

/// Each voxel's value and its central differences as 16-bit signed normalized texels.
std::vector<short> PackedWithGradients(const std::vector<float>& values,
  const int dims[3],
  const double range[2],
  double& gradientScale);

/// The leap distances (LeapDistances) of the bricks that are `occupied`, as an R8 texture.
bool UploadLeaps(vtkTextureObject* texture,
  const std::vector<unsigned char>& occupied,
  const std::array<int, 3>& bricks);

/// A 3D texture of dims[0] x dims[1] x dims[2] texels of `components` values of VTK type
/// `type` (the formats set by PrepareTexture).
bool Create3D(vtkTextureObject* texture, const int dims[3], int components, int type, void* data);

/// The composite mode's values as a texture: R32F, or with `gradient` RGBA16_SNORM (the
/// value and its central differences, PackedWithGradients, which sets `gradientScale`).
bool UploadScalars(vtkTextureObject* texture,
  std::vector<float>& values,
  const int dims[3],
  const double range[2],
  bool gradient,
  double& gradientScale);

/// A field's closest points (3 components a point) as an RGB32F texture.
bool UploadClosestPoints(vtkTextureObject* texture, vtkDataArray* closest, const int dims[3]);

/// The box's twelve triangles (36 corners, x y z each), counter-clockwise seen from
/// outside whatever the handedness of `corners` (the box's corners, bit k of the index
/// choosing the far side along axis k), so that culling the front faces leaves the back
/// ones.
std::vector<float> BoxTriangles(const std::array<Vec3, 8>& corners, const Vec3& centre);
} // namespace render
} // namespace vtkdf

#endif
