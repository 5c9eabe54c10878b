// GridUniforms: the sample grid as the shaders see it. A shader that samples a grid has
// the line //DF::SampleGrid where Shaders/SampleGridUniforms.glsl's declarations go (HeadlessGL's
// BuildProgram puts them there), and SetGridUniforms gives them their values, so that no
// pass declares or sets them its own way.
#ifndef vtkdf_GridUniforms_h
#define vtkdf_GridUniforms_h

#include "Common/SampleGrid.h"
#include "GL/GLFunctions.h"

#include <string>

namespace vtkdf
{

/// Dims (the sizes of `extent`), Lo (its first sample index), Origin and Spacing (of
/// `grid`) on `program`, which must be in use.
void SetGridUniforms(const GLFunctions& gl,
  GLuint program,
  const SampleGrid& grid,
  const IndexBox& extent);

/// `source` with its //DF::SampleGrid line replaced by the declarations, and its
/// //DF::TriangleDistance line by Shaders/TriangleDistance.glsl (the exact point-to-
/// triangle distance that the voxelizer and the proximity searches share), and its
/// //DF::CorrectlyRounded line by Shaders/CorrectlyRounded.glsl (IEEE's double sqrt and
/// division, for the passes that must branch as the CPU does), and its //DF::ArcTangent2
/// line by Shaders/ArcTangent2.glsl (Common/ArcTangent.h's ArcTangent2, after
/// //DF::CorrectlyRounded).
std::string WithSharedCode(const char* source);

/// The constants of Shaders/ArcTangent2.glsl (ArcTangentConstants()) on `program`, which
/// must be in use.
void SetArcTangentUniforms(const GLFunctions& gl, GLuint program);

} // namespace vtkdf

#endif
