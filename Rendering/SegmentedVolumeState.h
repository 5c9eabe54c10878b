// SegmentedVolumeState: what the mapper keeps between frames (its
// textures, the programs and the keys that say when to remake them). Private to the
// mapper's source.
#ifndef vtkdf_SegmentedVolumeState_h
#define vtkdf_SegmentedVolumeState_h

#include "vtkSegmentedDistanceVolumeMapper.h"

#include "vtkNew.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkTextureObject.h"
#include "vtkTimeStamp.h"

#include <array>
#include <map>
#include <string>
#include <vector>

struct vtkSegmentedDistanceVolumeMapper::Internals
{
  // Surface mode.
  vtkNew<vtkTextureObject> Field;        // RG32F: distance (signed value of a signed field), region
  vtkNew<vtkTextureObject> Colors;       // RGB32F, one texel a region
  vtkNew<vtkTextureObject> SurfaceLeaps; // R8: per brick, bricks to the nearest interface
  vtkNew<vtkTextureObject> ClosestPoints; // RGB32F, when the input has ClosestPoint
  bool HasClosestPoints = false;
  vtkOpenGLHelper Surfaces; // program and VAO of the box's faces, surface mode
  // Composite mode.
  // R32F, or RGBA16_SNORM (value, central differences) for shaded volumes up to
  // StoredGradientVoxels.
  vtkNew<vtkTextureObject> Scalars;
  bool ScalarsGradient = false;
  double GradientScale = 1;
  vtkNew<vtkTextureObject> Table;     // RGBA32F pre-integration table: averages
  std::vector<float> Averages;        // the same on the CPU, for the step table
  vtkNew<vtkTextureObject> StepTable; // RGBA16F: premultiplied colour, opacity of a step
  double StepLength = -1;             // the world length StepTable is for
  vtkTimeStamp StepTableTime;
  vtkOpenGLHelper Composite;
  vtkNew<vtkTextureObject> CompositeLeaps;       // R8: per brick, bricks to the nearest opaque one
  std::vector<std::array<float, 2>> BrickRanges; // per brick, its values' range
  std::vector<double> Extinction;                // the table's transfer samples
  vtkTimeStamp CompositeLeapsTime;
  vtkTimeStamp ScalarsTime;
  vtkTimeStamp TableTime;
  vtkImageData* ScalarsImage = nullptr;
  std::string ScalarsKey;
  bool ScalarsValid = false;
  double ScalarRange[2] = { 0, 1 };
  std::array<double, 5> TableKey = { 0, 0, 0, 0, 0 };
  int DepthSize[2] = { 0, 0 };
  int DepthFormat = -1; // vtkTextureObject's depth format of OpaqueDepth
  // Both.
  vtkNew<vtkTextureObject> OpaqueDepth; // the depth buffer before the volume
  vtkNew<vtkOpenGLVertexBufferObject> Vertices;
  vtkTimeStamp FieldTime;
  vtkTimeStamp ColorsTime;
  vtkTimeStamp ColorsModified;
  vtkImageData* FieldImage = nullptr; // which input the texture holds (not owned)
  std::string FieldKey;               // and which array selection
  bool FieldValid = false;
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double IndexToPhysical[16];
  bool Segmented = false;
  double RegionOffset = 0;
  int RegionCount = 0;
  std::map<int, std::array<double, 3>> RegionColors;
};

#endif
