// WindingCrossings: inside or outside at every sample of a grid for a closed mesh, from
// the surface's signed crossings along the grid's x lines, without VTK types.
//
// When the triangles make a closed chain (points merged by position, every edge used as
// often in one direction as in the other), w is an integer off the surface: the signed
// number of times the surface crosses a ray from the sample to x = -infinity. Each
// triangle is projected along x onto the (y, z) plane and counted on the lines whose
// point lies inside its projection, by exact orientation tests
// (Predicates/ExactPredicates.h) with the point moved symbolically to (y + e, z + e^2)
// (the simulation of simplicity of Edelsbrunner and Mücke, ACM Transactions on Graphics
// 9(1), 1990): a line through a projected edge or corner takes each crossing of the
// moved line exactly once, and a sample off the surface has the moved sample's w. Along
// a line, the crossing lies between the two samples on either side of the triangle's
// plane (Orient3D); a sample on that plane lies on the surface and is decided by
// WindingNumber::Inside, as WindingSigns decides it. Every other sample is |w| > 1/2
// exactly, without evaluating w: the work is one pass over the triangles' footprints on
// the lines.
//
// An open mesh S is closed by cones C over its boundary (one per closed walk along the
// boundary edges, from the mean of its corners, lifted): S + C is a closed chain, so
// w_S = N - w_C with N its crossings' count. w_C is smooth away from the cones, so that
// WindingSigns' blocks decide it up to S itself (WindingSigns.cxx).
#ifndef vtkdf_WindingCrossings_h
#define vtkdf_WindingCrossings_h

#include "Common/LargeVector.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "Winding/WindingNumber.h"
#include "Winding/WindingSigns.h"

#include <climits>
#include <cstdint>
#include <functional>
#include <vector>

namespace vtkdf
{
/// Whether triangles (3 ids each into xyz `points`) make a closed chain: with points at
/// equal coordinates merged, every edge between distinct points used as often from u to
/// v as from v to u, and no triangle repeated with the same orientation (the winding
/// number counts those once).
bool IsClosedChain(const LargeVector<double>& points, const LargeVector<int64_t>& triangles);

/// Whether the crossings' routes may decide these triangles' signs: closed, or with no
/// edge (points merged by coordinates) used more than 64 times more often in one
/// direction than in the other, so that CloseWithCones may close them.
bool CrossingsDecide(const LargeVector<double>& points, const LargeVector<int64_t>& triangles);

/// Sign of det[u - p', v - p'] in (y, z), p' = (y + e, z + e^2) for an infinitesimal e,
/// when det[u - p, v - p] is 0: its e term (u_z - v_z), else its e^2 term (v_y - u_y).
int PerturbedSide(const double u[3], const double v[3]);

/// Triangle (a, b, c)'s contribution `delta` to the signed count of crossings of the ray
/// from p to x = -infinity, by the rule of the grid's lines (p moved symbolically to
/// (y + e, z + e^2), exact orientation tests): summed over a closed chain's triangles,
/// w at p. False when p may lie on the triangle (then undecided).
bool RayCrossing(const double* a, const double* b, const double* c, const double p[3], int& delta);

/// CrossingCounts' mark of a sample whose count is not known: on the surface, or
/// |N| >= 127.
constexpr int8_t CountUnknown = INT8_MIN;

/// An open mesh closed by cones: Points (its corners, then the apexes), Triangles (its
/// own, then the cones'), Cone (the cones' alone), ids into Points.
struct ConeClosure
{
  LargeVector<double> Points;
  LargeVector<int64_t> Triangles, Cone;
};

/// Closes the triangles of `corners` (9 coordinates each, none repeated with the same
/// orientation: WindingNumber::TriangleCorners) by cones over their boundary (the edges,
/// points merged by coordinates, used more often in one direction than in the other, once
/// per surplus use), one cone a closed walk along it, from the walk's mean lifted along
/// its area vector. False when a cone triangle would repeat another, an edge's surplus
/// exceeds 64, or the points number 2^32 or more.
bool CloseWithCones(const LargeVector<double>& corners, ConeClosure& closure);

/// N at every sample of `extent` (x fastest): the signed count of the crossings of the
/// closed chain `triangles` on the ray to x = -infinity, CountUnknown on the surface.
/// Returns the samples whose count is known.
int64_t CrossingCounts(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  const SampleGrid& grid,
  const IndexBox& extent,
  int8_t* counts,
  const ParallelFor& parallelFor);

/// WindingSigns for a closed chain (IsClosedChain): inside[v] (1 or 0) for every sample
/// of `extent` (x fastest). `hierarchy` gives the triangles' WindingNumber for the
/// samples on the surface, called (once) only when there is one. Statistics: LineSamples
/// decided by the crossings, Evaluated (and Exact) on the surface.
WindingSignStatistics CrossingSigns(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const ParallelFor& parallelFor,
  const std::function<const WindingNumber&()>& hierarchy);
} // namespace vtkdf

#endif
