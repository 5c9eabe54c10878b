// PointDistance: the exact distance from arbitrary points (a point cloud, the nodes of
// any mesh, one point at a time) to a polygon mesh, with its sign, closest point, cell
// and feature, without VTK types.
//
// The nearest-primitive tree of the grid's query route (QueryTree.h: triangles, and the
// segments and points of degenerate and lower-dimensional cells) answers each point; the
// rules are the grid field's, so a point at a grid sample gets the grid's answer:
//   - the distance from the nearest primitive, in double precision;
//   - ClosestCellId the smallest input cell holding the closest feature (vertex, edge or
//     face interior), so that shared and duplicate cells give the same id;
//   - PseudoNormal: negative where the closest point lies ahead of the feature's
//     angle-weighted pseudonormal (Baerentzen and Aanaes, IEEE TVCG 11(3), 2005);
//     WindingNumber: negative where the generalized winding number has |w| > 1/2,
//     decided with certified bounds, exactly where they do not suffice
//     (Winding/WindingNumber.h). A point on the surface is 0 (-0 where w says inside).
//
// The work is done in the mesh's own frame, scaled by a power of two (exact), so that a
// mesh and its points scaled by 2^k give answers scaled by 2^k. A batch of points is
// queried in Morton order (neighbours in turn, each bounded by the previous one's
// closest point: less work, the same answers) and written in the input's order.
#ifndef vtkdf_PointDistance_h
#define vtkdf_PointDistance_h

#include "Common/ExactSum.h"
#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "LinearFactor/LinearFactorField.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

namespace vtkdf
{

/// One point's answer, in world units. Where the point lies beyond the search's cap,
/// Beyond is true, Distance the cap (by the winding sign in WindingNumber mode, NaN in
/// PseudoNormal mode: no closest feature signs it), Cell and SubTriangle -1, Feature 255
/// and the vectors NaN.
struct PointAnswer
{
  double Distance = 0;
  double Closest[3] = { 0, 0, 0 };
  int64_t Cell = -1;
  /// The index, within Cell's triangles (or segments, or points) as the module splits
  /// the cell, of the one whose Barycentric coordinates locate Closest.
  int64_t SubTriangle = -1;
  double Barycentric[3] = { 0, 0, 0 };
  uint8_t Feature = 255; // 0 vertex, 1 edge, 2 face interior
  /// The unit vector from Closest to the point, times the sign; on the surface, the
  /// closest feature's unit pseudonormal (0 where it has none: a point or segment cell).
  double Gradient[3] = { 0, 0, 0 };
  double Winding = 0; // w, where asked for (to about 1e-3, exact where near 1/2)
  bool Beyond = false;
  /// The winding number's side (WindingNumber mode), and a radius around the point that
  /// holds no point of the surface (the distance, or the cap beyond it): with Point, what
  /// a next query may take as its hint.
  bool Inside = false;
  double Clearance = 0;
  double Point[3] = { 0, 0, 0 }; // set by the caller that passes the answer on as a hint
};

/// Which of PointAnswer's parts a query computes (the distance always).
struct PointQueryParts
{
  bool Closest = true; // Closest, Cell, SubTriangle, Barycentric, Feature
  bool Gradient = true;
  bool Winding = false; // only where Build made the winding hierarchy
};

/// Where a batch's answers go: each array, when not null, holds one value (or three) per
/// point, in the input's order.
struct PointDistanceArrays
{
  double* Distance = nullptr;
  double* ClosestPoint = nullptr;
  int64_t* ClosestCellId = nullptr;
  int64_t* ClosestSubTriangle = nullptr;
  double* ClosestBarycentric = nullptr;
  uint8_t* ClosestFeature = nullptr;
  double* Gradient = nullptr;
  double* WindingNumber = nullptr;
  /// |distance| within the cap, NaN beyond it: what the statistics summarize.
  double* Magnitude = nullptr;
};

/// A batch's summary of |distance| over the points within the cap (its sums exact: the
/// same on any number of threads, and for any split of the points into batches that
/// Combine adds up).
struct PointDistanceStatistics
{
  int64_t Points = 0;      // the points summarized (those not excluded)
  int64_t Beyond = 0;      // points beyond the cap
  int64_t Evaluations = 0; // primitive distances computed
  double Maximum = 0, Mean = 0, RootMeanSquare = 0;
  int64_t Farthest = -1; // the first point at the maximum
  bool Aborted = false;
  ExactSum Sum, Squares; // of |d| and of its (rounded) squares, over the points within

  /// Counts one point whose |distance| is `magnitude` (NaN: beyond the cap), named
  /// `key` (its index, or its global id) if it becomes the farthest.
  void Count(double magnitude, int64_t key)
  {
    ++this->Points;
    if (std::isnan(magnitude))
    {
      ++this->Beyond;
      return;
    }
    this->Sum.Add(magnitude);
    this->Squares.Add(magnitude * magnitude);
    if (magnitude > this->Maximum || this->Farthest < 0)
    {
      this->Maximum = magnitude;
      this->Farthest = key;
    }
  }

  /// Mean and RootMeanSquare from the sums.
  void Finish()
  {
    const double within = static_cast<double>(this->Points - this->Beyond);
    this->Mean = within > 0 ? this->Sum.Value() / within : 0;
    this->RootMeanSquare = within > 0 ? std::sqrt(this->Squares.Value() / within) : 0;
  }
};

class PointDistanceQueries
{
public:
  PointDistanceQueries();
  ~PointDistanceQueries();

  /// The tree of `mesh` (and the winding hierarchy of its triangles, for WindingNumber or
  /// `windingValues`). False and `error` when the mesh has no cell, a cell refers to a
  /// point that does not exist or a used point is not finite.
  bool Build(MeshInput mesh,
    SignMode sign,
    bool windingValues,
    const ParallelFor& parallelFor,
    std::string& error);

  /// The answer at x (world units), searching up to `cap` (HUGE_VAL: everywhere).
  /// Thread-safe. `seed`, when given, is a point of the mesh (a previous answer's
  /// Closest) whose distance bounds the search; `hint`, a previous answer (with its
  /// Point), whose winding side x shares where the mesh's triangles form a closed chain
  /// and the two points' surface-free balls overlap. Both save work, never change the
  /// answer. Returns the primitive distances computed.
  int64_t Query(const double x[3],
    double cap,
    const double* seed,
    const PointQueryParts& parts,
    PointAnswer& answer,
    const PointAnswer* hint = nullptr) const;

  /// The answers at `count` points (xyz, world units) into `arrays`. False and `error`
  /// when a point has a NaN or infinite coordinate (naming it); progress and abort
  /// between batches of points. Points i with `excluded[i]` non-zero (when given: a
  /// distributed run's copies of points another rank owns) get their answers but are
  /// left out of the statistics.
  bool QueryPoints(const double* points,
    int64_t count,
    double cap,
    const PointDistanceArrays& arrays,
    const Execution& execution,
    PointDistanceStatistics& stats,
    std::string& error,
    const uint8_t* excluded = nullptr) const;

  SignMode Sign() const;
  /// The mesh's triangles, segments and points in the tree.
  int64_t Primitives() const;

private:
  /// Whether `hint` decides x's winding side (see Query), into `inside`.
  bool SideFromHint(const double x[3],
    double clearance,
    const PointQueryParts& parts,
    const PointAnswer* hint,
    bool& inside) const;

  struct Internal;
  std::unique_ptr<Internal> Impl;
};

} // namespace vtkdf

#endif
