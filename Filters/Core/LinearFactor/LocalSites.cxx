#include "LinearFactor/LocalSites.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vtkdf
{

bool MoveToGridFrame(MeshInput& mesh,
  const LinearFactorRequest& request,
  const ParallelFor& parallelFor,
  LocalSites& local,
  std::string& error)
{
  if (!CheckGrid(request.Grid, mesh.Bounds.data(), error))
  {
    error = "Invalid input: " + error + ".";
    return false;
  }
  local.Frame = GridFrame::For(request.Grid);
  local.Request.Grid = local.Frame.Local(request.Grid);
  local.Request.Extent = request.Extent;
  if (request.MaximumDistance > 0)
  {
    local.Request.MaximumDistance = request.MaximumDistance / local.Frame.Scale;
  }
  MoveToLocalFrame(mesh, local.Frame, parallelFor);
  return true;
}

bool BuildLocalSites(MeshInput& mesh,
  const LinearFactorRequest& request,
  bool keepMesh,
  const ParallelFor& parallelFor,
  LocalSites& local,
  std::string& error)
{
  if (!MoveToGridFrame(mesh, request, parallelFor, local, error))
  {
    return false;
  }
  // The planes are used between the mesh and the samples: the diagonal of the box that
  // holds both bounds that distance.
  const SampleGrid& grid = local.Request.Grid;
  double diagonal2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double g0 = grid.Coordinate(a, grid.Whole.Lo[a]);
    const double g1 = grid.Coordinate(a, grid.Whole.Hi[a]);
    const double lo = std::min(std::min(g0, g1), local.Frame.ToLocal(a, mesh.Bounds[2 * a]));
    const double hi = std::max(std::max(g0, g1), local.Frame.ToLocal(a, mesh.Bounds[2 * a + 1]));
    diagonal2 += (hi - lo) * (hi - lo);
  }
  const double slack = MeshSites::PlaneSlack(1e-4 * grid.MinSpacing(), std::sqrt(diagonal2));
  // Only the winding number and the surface coordinates read the mesh after its sites
  // are built.
  const bool built = keepMesh || request.Sign == SignMode::WindingNumber
    ? local.Sites.Build(mesh, request.Domains, slack, error, parallelFor)
    : local.Sites.Build(std::move(mesh), request.Domains, slack, error, parallelFor);
  if (!built)
  {
    error = "Invalid input mesh: " + error + ".";
    return false;
  }
  return true;
}

} // namespace vtkdf
