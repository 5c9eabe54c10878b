// UnionQuery: the entry point of the union family's closest-point query, after Y. J. Kim,
// K. Hoff, M. C. Lin and D. Manocha, "Closest Point Query Among the Union of Convex
// Polytopes Using Rasterization Hardware", Journal of Graphics Tools 7(4), 2002: for each
// query point, the closest point on the boundary of a union of convex pieces, without
// building the union. Exact on the CPU (UnionClosestPoint), or with a GPU pass's upper
// bounds that the exact CPU search starts from (UnionClosestPointGPU), the same answers.
// The penetration depth of two such unions is PenetrationDepth's Compute.
#ifndef vtkdf_UnionQuery_h
#define vtkdf_UnionQuery_h

#include "Common/Parallel.h"
#include "Union/UnionClosestPoint.h"
#include "Union/UnionClosestPointGPU.h"

#include <string>
#include <vector>

namespace vtkdf
{
class HeadlessGL;

struct UnionQueryOptions
{
  /// How many threads the host's loop runs: below four queries a thread, each query's
  /// faces are searched in parallel instead of the queries.
  int Threads = 1;
};

/// Answers `queries` (xyz triples) over `query`'s pieces, on the GPU when `gl` is given.
/// Progress from 0.1 to 0.9 (per twentieth of the queries on the CPU, per dispatch and
/// block of certified queries on the GPU); an abort leaves `aborted` set and the answers
/// incomplete. False and `error` when the GPU fails.
bool QueryUnion(UnionClosestPoint& query,
  const std::vector<double>& queries,
  HeadlessGL* gl,
  const UnionQueryOptions& options,
  const Execution& execution,
  std::vector<UnionGPUAnswer>& answers,
  bool& aborted,
  std::string& error);

} // namespace vtkdf

#endif
