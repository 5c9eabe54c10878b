// MedialAxisField: the entry points of the medial axis family: the theta-simplified medial
// axis (M. Foskey, M. C. Lin and D. Manocha, "Efficient Computation of a Simplified
// Medial Axis", ACM Symposium on Solid Modeling and Applications, 2003) of a distance
// field with closest points, as section 6.3 of A. Sud, N. Govindaraju, R. Gayle and
// D. Manocha, "Interactive 3D Distance Field Computation using Linear Factorization"
// (I3D 2006) estimates it (MedialAxis.h), on the CPU or the GPU with the same voxels.
#ifndef vtkdf_MedialAxisField_h
#define vtkdf_MedialAxisField_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "LinearFactor/LinearFactorField.h"
#include "Medial/MedialAxis.h"

#include <cstdint>
#include <string>

namespace vtkdf
{
class HeadlessGL;

/// What the medial axis writes per voxel of the grid (x fastest).
struct MedialArrays
{
  uint8_t* Medial = nullptr;        // 1 on the medial axis, else 0
  float* SeparationAngle = nullptr; // degrees: the largest aperture that marked the voxel, else 0
  float* Radius = nullptr;          // |distance|, world units
  int64_t Count = 0;                // the medial voxels
  bool Aborted = false;             // the host asked to abort: the arrays are incomplete
};

/// The medial axis of a field (`field`: world grid, Distance and ClosestPoint), on the GPU
/// when `gl` is given. False and `error` when the GPU fails.
bool ComputeMedialAxis(const MedialInput& field,
  HeadlessGL* gl,
  MedialArrays& arrays,
  const Execution& execution,
  std::string& error);

/// The medial axis of a mesh (world coordinates, Bounds filled) on the voxels `extent`
/// of `parameters.Grid` (world; `arrays` hold extent's voxels): its signed field there by
/// `sign`, then the pass (parameters' Distance and ClosestPoint are not read). Each
/// voxel's field, hence each cell inside `extent`, is that of the whole grid bit for
/// bit, so a voxel's answer is the whole grid's when `extent` holds its neighbours (a
/// piece of the grid grown by one voxel). On the GPU with the pseudonormal sign, the
/// field stays there and one pass reads it (stage field+medial); otherwise the stages
/// are field and medial. Progress (and abort) during the field, from 0 to 0.9, but in
/// the fused GPU pass. False and `error` on invalid input or when the GPU fails.
/// `signContext` (with no `gl`): the winding sign there, the rest on the CPU
/// (LinearFactorRequest::SignContext).
bool ComputeMedialAxis(MeshInput mesh,
  SignMode sign,
  const MedialInput& parameters,
  const IndexBox& extent,
  HeadlessGL* gl,
  MedialArrays& arrays,
  const Execution& execution,
  std::string& error,
  HeadlessGL* signContext = nullptr);

} // namespace vtkdf

#endif
