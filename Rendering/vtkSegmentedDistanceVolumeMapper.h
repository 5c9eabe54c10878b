/**
 * @class   vtkSegmentedDistanceVolumeMapper
 * @brief   Pre-integrated ray casting of segmented and signed distance fields.
 *
 * The renderer of Yamazaki et al. (SMI 2003) (section 4) through VTK's OpenGL layer, ray cast:
 * one fragment a pixel (the volume box's back faces) walks its ray front to back through the
 * slabs between view-aligned sample planes (SampleDistance apart, or NumberOfSlices of them
 * across the volume's depth: the slices the publication draws). Each slab is sampled where the
 * ray enters and where it leaves it, which decides what the
 * paper's vertex generation diagram tabulated: whether an interface lies in the slab (the two
 * samples are in different regions, and eq. 7 holds: an edge of the interface point's cell joins
 * voxels of two regions whose distances add up to at most its length, as the polygonizer tests it,
 * so open boundaries stay open), where (eq. 6: at u / (u + v) of the way, refined to the
 * interpolant's zero by RegionAware sampling), and in which colour (the region on the viewer's
 * side). The decision is evaluated in the shader, exactly, rather than looked up in a quantized
 * table: a table of (front, back) pairs at 8 bits was what 2002 hardware could do, and it
 * quantizes the interface position to 1/256 of a region. The ray's loop only samples, until a
 * slab's ends lie in two regions; the decision runs then. On a signed field the march, the
 * interface's placement and its gradient read the filtered signed value (one fetch each,
 * the same interpolation). Rays leap over empty space (EmptySpaceLeaping).
 *
 * Input: vtkImageData with, as point scalars,
 * - `SegmentedDistance` and the field-data `RegionOffset` (vtkSegmentedDistanceField,
 *   vtkDistanceFieldBlend): each sample's region r and distance d are read back from
 *   f = min(d, Delta) + RegionOffset * r;
 * - or any one-component array of signed distances (vtkLinearFactorDistanceField): two
 *   regions, 0 where the value is >= 0 (outside) and 1 where it is < 0.
 * The array is `SegmentedDistance` when the input has it, else the one chosen with
 * SelectScalarArray(), else the active point scalars.
 *
 * Sampling (Interpolation):
 * - RegionAware (default): in a cell whose eight voxels are in one region, trilinear
 *   interpolation of the distance; in a cell that holds several regions, the distance
 *   relative to the nearest voxel's region (positive in it, negative elsewhere) is
 *   interpolated trilinearly, which across two regions is exactly the signed field's
 *   interpolation: so a closed surface sits where its signed field's zero level set is,
 *   not on the voxels' Voronoi faces, and no third region is invented between two;
 * - Nearest: the paper's nearest-voxel sampling (surfaces on the Voronoi faces, up to
 *   half a voxel off);
 * - Linear: trilinear interpolation of the stored value itself, for comparison (between
 *   regions i and i+2 it invents region i+1, the paper's Fig. 7).
 *
 * Surfaces are lit with normals from the gradient of the distance relative to the
 * viewer-side region (central differences), or from the input's ClosestPoint array
 * (UseClosestPointNormals), and the vtkVolumeProperty's ambient,
 * diffuse, specular and specular power when its Shade is on (a headlight); without
 * Shade they are flat. Each surface takes the colour of the region on the viewer's side
 * (SetRegionColor(), distinct defaults). With SurfaceOpacity = 1 the surfaces are opaque:
 * a ray stops at its first interface and writes gl_FragDepth there (rays without one are
 * discarded), so the depth buffer holds the surface and opaque geometry occludes it, and it
 * them, both ways. Below 1 a ray composites its interfaces front to back (premultiplied)
 * until it is opaque or meets the opaque geometry's depth.
 *
 * Composite rays (Mode) stop where they meet opaque geometry and once their alpha reaches
 * 0.998. Their samples lie SampleDistance apart along each ray, at the sample planes'
 * distances from the eye (the planes in a parallel projection, spheres around the eye in a
 * perspective one), so that every whole step has one length and takes its opacity from a
 * table made for it; the first and last slabs, cut short, from the table of averages. The
 * samples come from the texture unit's trilinear filtering, and a shaded volume
 * of up to 2^26 voxels keeps each voxel's central differences next to its value (16-bit
 * normalized, 8 bytes a voxel) so that one fetch gives a sample's value and gradient.
 *
 * Needs an OpenGL 3.2 core context (vtkOpenGLRenderWindow); Mesa's llvmpipe will do.
 * All GL state changes go through vtkOpenGLState; ReleaseGraphicsResources() frees the
 * textures, buffers and program. Cropping, clipping planes and blend modes of
 * vtkVolumeMapper are not used.
 */
#ifndef vtkSegmentedDistanceVolumeMapper_h
#define vtkSegmentedDistanceVolumeMapper_h

#include "vtkDistanceFieldsRenderingModule.h" // For export macro
#include "vtkVolumeMapper.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkDataArray;
class vtkImageData;
class vtkMatrix4x4;
class vtkOpenGLHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkVolumeProperty;
class vtkRenderer;
class vtkVolume;
class vtkWindow;

class VTKDISTANCEFIELDSRENDERING_EXPORT vtkSegmentedDistanceVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkSegmentedDistanceVolumeMapper* New();
  vtkTypeMacro(vtkSegmentedDistanceVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    Surface = 0,
    Composite = 1
  };
  ///@{
  /// Surface (default): the (segmented or signed) field's surfaces. Composite:
  /// pre-integrated rendering of any one-component scalar volume with the volume
  /// property's colour (RGB or gray) and scalar opacity transfer functions over the
  /// array's range, slabs cut by opaque geometry.
  vtkSetClampMacro(Mode, int, Surface, Composite);
  vtkGetMacro(Mode, int);
  void SetModeToSurface() { this->SetMode(Surface); }
  void SetModeToComposite() { this->SetMode(Composite); }
  const char* GetModeAsString();
  ///@}

  ///@{
  /// Composite: the pre-integration table's entries a side (default 256), over the
  /// array's range; rebuilt only when the transfer functions, the range, the unit
  /// distance or this change. TableBuilds counts the builds. From it, a second table holds
  /// each entry's premultiplied colour and opacity for a ray's whole step (so the ray's
  /// loop has no exponential): made again when the step's length changes
  /// (NumberOfSlices with a view that changes the volume's depth; never with a fixed
  /// SampleDistance), size^2 exponentials. StepTableBuilds counts those.
  vtkSetClampMacro(PreIntegrationTableSize, int, 2, 4096);
  vtkGetMacro(PreIntegrationTableSize, int);
  vtkGetMacro(TableBuilds, int);
  vtkGetMacro(StepTableBuilds, int);
  ///@}

  enum InterpolationModes
  {
    RegionAware = 0,
    Nearest = 1,
    Linear = 2
  };
  ///@{
  /// How the field is sampled between voxels (see the class description).
  vtkSetClampMacro(Interpolation, int, RegionAware, Linear);
  vtkGetMacro(Interpolation, int);
  void SetInterpolationToRegionAware() { this->SetInterpolation(RegionAware); }
  void SetInterpolationToNearest() { this->SetInterpolation(Nearest); }
  void SetInterpolationToLinear() { this->SetInterpolation(Linear); }
  const char* GetInterpolationAsString();
  ///@}

  ///@{
  /// The distance between the sample planes (slices), in world units; 0 (default): the
  /// smallest voxel spacing (one slab a voxel: interfaces between planes are found by the
  /// slab test).
  vtkSetClampMacro(SampleDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SampleDistance, double);
  ///@}

  ///@{
  /// The number of sample planes (slices) across the volume's depth; 0 (default): from
  /// SampleDistance.
  vtkSetClampMacro(NumberOfSlices, int, 0, 1 << 20);
  vtkGetMacro(NumberOfSlices, int);
  ///@}

  ///@{
  /// The surfaces' opacity: 1 (default) opaque, written to the depth buffer; below 1
  /// blended back to front.
  vtkSetClampMacro(SurfaceOpacity, double, 0.0, 1.0);
  vtkGetMacro(SurfaceOpacity, double);
  ///@}

  ///@{
  /// Surface normals from the input's `ClosestPoint` array (what
  /// vtkLinearFactorDistanceField writes with ComputeClosestPoint) when it has one and
  /// this is on: the directions from the cell's voxels' closest points, blended; else
  /// (default) from the gradient of the interpolated distance. Both are within 0.5% in
  /// diffuse brightness on a sphere 20 voxels across (Render.Mapper.lighting); the
  /// gradient was the closer there and on the bunny, so it is the default.
  vtkSetMacro(UseClosestPointNormals, bool);
  vtkGetMacro(UseClosestPointNormals, bool);
  vtkBooleanMacro(UseClosestPointNormals, bool);
  ///@}

  ///@{
  /// The colour of a region's surfaces (seen from that region). Regions without one take
  /// a default from a palette of distinct colours.
  void SetRegionColor(int region, double r, double g, double b);
  void GetRegionColor(int region, double rgb[3]);
  void RemoveAllRegionColors();
  ///@}

  ///@{
  /// Empty-space leaping (default on): a ray leaps over the bricks of 4^3 cells around it
  /// that hold no interface (Surface) or whose values the transfer function makes
  /// transparent (Composite: at the ray's two ends only), to the last sample before it
  /// leaves them. The picture is the same either way (those slabs add nothing); off
  /// samples every slab, for comparison.
  vtkSetMacro(EmptySpaceLeaping, bool);
  vtkGetMacro(EmptySpaceLeaping, bool);
  vtkBooleanMacro(EmptySpaceLeaping, bool);
  ///@}

  ///@{
  /// What the last Render() drew: the number of sample planes, the number of regions of the
  /// field, and whether it was read as a segmented field (else a signed one).
  vtkGetMacro(LastNumberOfSlices, int);
  vtkGetMacro(LastRegionCount, int);
  vtkGetMacro(LastSegmented, bool);
  ///@}

  void Render(vtkRenderer* renderer, vtkVolume* volume) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSegmentedDistanceVolumeMapper();
  ~vtkSegmentedDistanceVolumeMapper() override;

  int Mode = Surface;
  bool UseClosestPointNormals = false;
  bool EmptySpaceLeaping = true;
  int PreIntegrationTableSize = 256;
  int TableBuilds = 0;
  int StepTableBuilds = 0;
  int Interpolation = RegionAware;
  double SampleDistance = 0.0;
  int NumberOfSlices = 0;
  double SurfaceOpacity = 1.0;
  int LastNumberOfSlices = 0;
  int LastRegionCount = 0;
  bool LastSegmented = false;

private:
  vtkSegmentedDistanceVolumeMapper(const vtkSegmentedDistanceVolumeMapper&) = delete;
  void operator=(const vtkSegmentedDistanceVolumeMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;

  bool UpdateField(vtkImageData* image);
  bool UpdateScalars(vtkImageData* image, bool shade);
  bool UpdateTable(vtkVolumeProperty* property);
  bool UpdateStepTable(double length);
  bool UpdateCompositeLeaps();
  bool CheckGrid(vtkImageData* image, int dims[3]);
  void SetGeometry(vtkImageData* image, const int dims[3]);
  bool HasArraySelection() const;
  vtkDataArray* SelectedArray(vtkImageData* image) const;
  // The planes the rays are sampled on: Count of them, Spacing apart along the view
  // direction, the first at depth First from the eye.
  struct SamplePlanes
  {
    double First = 0;
    double Spacing = 1;
    int Count = 0;
  };
  std::vector<float> BoxFaces(vtkMatrix4x4* indexToWorld,
    const double eye[3],
    const double viewDir[3],
    SamplePlanes& planes);
  std::string ArraySelectionKey() const;
  // Render's steps: the regions' colours (their count), the program with the box's
  // vertices, the uniforms, the textures each mode reads, and the drawing.
  int UpdateRegionColors();
  vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* window,
    const std::vector<float>& triangles,
    vtkOpenGLHelper& helper,
    bool shade,
    bool parallel);
  void SetViewUniforms(vtkShaderProgram* program,
    vtkRenderer* renderer,
    vtkMatrix4x4* indexToWorld,
    const double eye[3],
    const double viewDir[3],
    const SamplePlanes& planes);
  static void SetShadingUniforms(vtkShaderProgram* program, vtkVolumeProperty* property);
  std::vector<vtkTextureObject*> BindSurfaceTextures(vtkShaderProgram* program,
    vtkVolume* volume,
    int colorCount);
  std::vector<vtkTextureObject*> BindCompositeTextures(vtkShaderProgram* program);
  vtkTextureObject* BindOpaqueDepth(vtkShaderProgram* program,
    vtkRenderer* renderer,
    vtkOpenGLRenderWindow* window);
  void DrawBox(vtkOpenGLRenderWindow* window, bool blended, int vertexCount);
};

#endif
