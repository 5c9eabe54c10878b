// UnionClosestPointGPU: the closest point on a union of convex pieces with the GPU's help,
// certified on the CPU. Without VTK types.
//
// A compute pass (Shaders/UnionBound.comp.glsl) gives each query O an upper bound U of
// its answer: the distance to the nearest point of the pieces' faces that is certainly a
// boundary point (on a face of its piece and outside every other piece by more than the
// tolerance), all the queries in one dispatch, one invocation a query and block of faces.
// From outside the union U is the answer itself (up to rounding); from inside, the
// nearest such face point. The exact CPU query (UnionClosestPoint) then searches only the
// faces nearer than U, and gives the CPU backend's answer bit for bit: the search's
// answer does not depend on its bound. Where U is not above the answer (the face points
// nearest O all touch other pieces, or rounding), the bounded search finds nothing and
// the full search runs.
//
// Y. J. Kim, K. Hoff, M. C. Lin and D. Manocha, "Closest Point Query Among the Union of
// Convex Polytopes Using Rasterization Hardware", Journal of Graphics Tools 7(4), 2002,
// find U in six rendered cube-face views around each query instead; that path ran on the
// small graphics part of a data-centre GPU and gave an image-space estimate unless
// certified, so the compute pass replaced it.
#ifndef vtkdf_UnionClosestPointGPU_h
#define vtkdf_UnionClosestPointGPU_h

#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "Union/UnionClosestPoint.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

struct UnionGPUAnswer
{
  UnionAnswer Answer; // exact: the CPU backend's answer
  /// U, the GPU's upper bound (HUGE_VAL when it found no face point certainly on the
  /// boundary).
  double Estimate = HUGE_VAL;
  /// Whether U was not above the answer, so that the full search ran after the bounded one.
  bool Reseeded = false;
  /// Whether an invocation of the pass ran out of loop iterations (UnionGPUSettings::
  /// IterationBudget) before it had tested all its faces: U may then be larger.
  bool Stopped = false;
};

struct UnionGPUSettings
{
  /// The most face tests a dispatch makes (queries times faces; at least one query a
  /// dispatch): progress is told and an abort heard between dispatches.
  int64_t DispatchTests = int64_t(1) << 24;
  /// Faces an invocation tests (a query's faces are split among its invocations).
  int BlockFaces = 16;
  /// The loop iterations an invocation may run; one that runs out keeps the points it
  /// finished testing (a larger U, the same answers). 0: as the context allows (half of
  /// HeadlessGL::InvocationLoopBudget, as the pass counts iterations and not the loop
  /// entries, no more than those).
  int IterationBudget = 0;
  /// A parallel loop for the certification, over the queries (serial when empty).
  ParallelFor For;
  /// Told the fraction done after each dispatch and each block of certified queries;
  /// returning false stops the run (QueryUnionGPU then returns false, with `error`
  /// "aborted").
  ProgressCallback Progress;
};

/// Answers `queries` (xyz triples) over the pieces of `u`.
bool QueryUnionGPU(HeadlessGL& context,
  const UnionClosestPoint& u,
  const std::vector<double>& queries,
  const UnionGPUSettings& settings,
  std::vector<UnionGPUAnswer>& answers,
  std::string& error);

} // namespace vtkdf

#endif
