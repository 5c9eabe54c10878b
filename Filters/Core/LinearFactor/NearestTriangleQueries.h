// NearestTriangleQueries: the exact field by one nearest-primitive query per sample, the
// route for a mesh whose triangles outnumber the grid's samples (a fine mesh on a coarse
// grid), where building every site's domain costs more than the samples need.
//
// A bounding-volume hierarchy over the mesh's triangles, segments and points (Morton
// order of their boxes' centres, split at the highest differing bit of the codes, leaves
// of at most 8; four children's boxes a node; each leaf also boxed in the frame of its
// mean normal, thin on a fine surface), and per sample a depth-first search, nearest
// child first, bounded from the start by the distance to the previous sample's closest
// point. On the dragon (871k triangles) at 64^3 a sample evaluates 86 triangles. The
// arrays are
// those of the site scan (LinearFactorScan.h, Finalize):
//   - the distance and closest point from the nearest primitive, in double precision;
//   - the closest feature (vertex, edge or face interior) where that point lies;
//   - ClosestCellId the smallest input cell holding that feature (the site scan's rule
//     for edge and vertex sites), so that duplicate and shared cells give the same id;
//   - the pseudonormal sign from the feature's angle-weighted normal, with the faces,
//     degenerate ones and the mesh's orientation (signed volume) as MeshSites has them
//     (the orientation from another reference point: equal on closed meshes).
// Both routes are exact; where a sample lies within rounding of two features, they may
// name different ones (the tests check that they differ only there).
#ifndef vtkdf_NearestTriangleQueries_h
#define vtkdf_NearestTriangleQueries_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "LinearFactor/LinearFactorScan.h"

#include <string>

namespace vtkdf
{

/// Auto's threshold: the queries where the mesh's primitives (triangles, segments,
/// points) number at least this many times the samples that need a full query. The
/// measured crossovers (docs/benchmarks.md) lie between 1.5 (armadillo_52k) and 2.6
/// (dragon_871k).
constexpr double SampleQueriesCellsPerSample = 2.5;

/// The samples that need a full query: the whole grid's; with a cap on the distances
/// (world units), those within the band (twice the cap times the triangles' area over a
/// grid cell's volume, at most the grid's), and at least a 64th of the grid's for the
/// queries beyond it that stop at the tree's first levels.
double QueriedSamples(const MeshInput& mesh, const SampleGrid& wholeGrid, double maximumDistance);

/// Whether Auto takes the query route where the site scan could run: the primitives at
/// least SampleQueriesCellsPerSample times the queried samples. From the whole mesh and
/// grid (world units), so that every piece of a distributed grid takes the same route.
bool PreferSampleQueries(const MeshInput& mesh,
  const SampleGrid& wholeGrid,
  double maximumDistance);

/// The arrays of `request` (local frame) from `mesh` (moved into the same frame); with a
/// MaximumDistance, those of the scan's narrow band (Finalize). Evaluations counts primitive
/// distances computed. False and `error` when the mesh is invalid (a cell's point id out of range,
/// a non-finite coordinate).
bool QueryNearestTriangles(const MeshInput& mesh,
  const LocalFieldRequest& request,
  const LocalFieldArrays& arrays,
  const Execution& execution,
  ScanStatistics& stats,
  std::string& error);

} // namespace vtkdf

#endif
