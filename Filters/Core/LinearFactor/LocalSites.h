// LocalSites: a request of the linear factorization moved into its grid's local frame
// (GridFrame, SampleGrid.h), with the mesh's sites built there. The dense field
// (LinearFactorField) and the sparse band (SparseBand) start from the same sites, so that
// they give the same bits at the same samples.
#ifndef vtkdf_LocalSites_h
#define vtkdf_LocalSites_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "LinearFactor/LinearFactorField.h"
#include "LinearFactor/LinearFactorScan.h"
#include "LinearFactor/MeshSites.h"

#include <string>

namespace vtkdf
{

/// The request in the grid's local frame, and the sites of the mesh moved there.
struct LocalSites
{
  GridFrame Frame;
  LocalFieldRequest Request;
  MeshSites Sites;
};

/// Moves `mesh` into the local frame of the request's grid (its Extent and
/// MaximumDistance go to local.Request). False and `error` on a grid that cannot carry
/// the mesh's float32 distances.
bool MoveToGridFrame(MeshInput& mesh,
  const LinearFactorRequest& request,
  const ParallelFor& parallelFor,
  LocalSites& local,
  std::string& error);

/// Moves `mesh` into the local frame of the request's grid and builds its sites there.
/// The domains' slack is 1e-4 of the smallest spacing plus what the float planes need
/// over the box that holds the mesh and the whole grid (MeshSites::PlaneSlack). The mesh
/// is released once read unless a later pass needs it (a winding sign, or `keepMesh`).
bool BuildLocalSites(MeshInput& mesh,
  const LinearFactorRequest& request,
  bool keepMesh,
  const ParallelFor& parallelFor,
  LocalSites& local,
  std::string& error);

} // namespace vtkdf

#endif
