// ProximityQuery: the proximity of two deforming triangle meshes, frame after frame,
// without VTK types: the family's entry point (vtkDistanceFieldProximity adapts it).
// After Sud et al., "Interactive 3D distance field computation using linear
// factorization" (ACM I3D 2006), section 6.2: each model's distance field is evaluated
// where the other's surface needs it, inside the region where the two can interact.
//
// Here the fields are not sampled on a dense grid: every value the query uses is the
// exact distance of one point to the other model (its nearest triangle through the box
// hierarchy), so a value is only computed where it is read. The grid survives as the
// step h of the face samples: Resolution samples along the interaction region's longest
// side, as a grid of that resolution would have.
//
// One query gives:
// - Colliding, decided exactly (MeshProximity.h): a pair of triangles with a point in
//   common, or a point of one model inside the other;
// - when apart: the exact separation and a closest pair of points, searched with the
//   least of the vertices' distances to the other model as the starting bound;
// - each model's penetration into the other: its vertices and face samples (a
//   barycentric lattice of step h on each triangle) inside the interaction region and
//   inside the other model, each at its exact distance, the deepest with the direction
//   to its closest point (the contact normal);
// - every point's signed distance to the other model (negative inside).
// "Inside" is the winding number's |w| > 1/2 (right on open meshes and soups) or the
// sign of the angle-weighted pseudonormal at the closest feature.
#ifndef vtkdf_ProximityQuery_h
#define vtkdf_ProximityQuery_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Proximity/MeshProximity.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vtkdf
{
enum class InsideRule
{
  WindingNumber, // |w| > 1/2, the generalized winding number (Winding/WindingNumber.h)
  PseudoNormal   // (x - c) . n < 0, n the angle-weighted pseudonormal of the closest feature
};

/// One model, prepared for queries and kept between frames: its triangles, their box
/// hierarchy, and what the inside rule needs (the winding number's hierarchy, or the
/// pseudonormals and the edges they are summed over).
class ProximityModel
{
public:
  ProximityModel();
  ~ProximityModel();
  ProximityModel(const ProximityModel&) = delete;
  ProximityModel& operator=(const ProximityModel&) = delete;

  /// Takes `mesh`'s triangles. When they and the number of points are those of the
  /// previous Load with the same rule (a deforming mesh), the topology is kept (the
  /// hierarchy's order, refitted to the new coordinates; the edges) and only what
  /// depends on the coordinates is recomputed. False with `error` (naming the model by
  /// `name`) when the mesh has no triangle, a triangle uses a point that does not
  /// exist, or a point has a coordinate that is not finite.
  bool Load(const MeshInput& mesh, const char* name, InsideRule rule, std::string& error);

  /// Whether the last Load kept the previous topology.
  bool ReusedTopology() const;
  int64_t NumberOfPoints() const;
  int64_t NumberOfTriangles() const;

  struct Data;
  const Data& Get() const { return *this->D; }

private:
  std::unique_ptr<Data> D;
};

class HeadlessGL;

/// The GPU's side of the queries, kept between frames: the search program and each
/// model's buffers, the topology uploaded once and the coordinates every frame
/// (ProximityGPU.h). Made on a context that must outlive it; its GL objects are deleted
/// with it.
class ProximityDevice
{
public:
  explicit ProximityDevice(HeadlessGL& context);
  ~ProximityDevice();
  ProximityDevice(const ProximityDevice&) = delete;
  ProximityDevice& operator=(const ProximityDevice&) = delete;

  HeadlessGL& Context() const;

  struct State;
  State& Get() { return *this->S; }

private:
  std::unique_ptr<State> S;
};

struct ProximityRequest
{
  /// The nearest-triangle searches (every exact point-to-model distance) on this
  /// device's GPU, all face samples of the triangles that meet the region at once; null:
  /// on the CPU, each when it is needed. The rest (contacts, separation, inside-ness)
  /// runs on the CPU either way.
  ProximityDevice* Device = nullptr;
  InsideRule Rule = InsideRule::WindingNumber;
  /// The interaction region: the overlap of the models' bounding boxes, each grown by
  /// ContactMargin (>= 0) on every side.
  double ContactMargin = 0;
  /// The face samples' step h: Step when > 0, else the region's longest side over
  /// Resolution (the union of the boxes when the region is empty).
  double Step = 0;
  int Resolution = 64;
  /// List every sample inside the other model (ProximityReport's Contacts), not only the
  /// deepest. Without the list, a sample that cannot be deeper than the deepest so far
  /// (its distance bounded from a known point's) is counted inside without its distance.
  bool Contacts = true;
  /// A distributed query: this call takes share `Share` of `Shares` of the face samples
  /// (consecutive blocks of triangles; the vertices are the first share's). Every share
  /// computes the points' distances alike (its face samples start from them); only the
  /// first tests the triangle pairs for contact and searches the separation.
  /// MergeProximityShares puts the shares' reports together into the report of one call,
  /// bit for bit.
  int Share = 0, Shares = 1;
  /// The most face samples a query may take (a step far below the triangles' size
  /// otherwise asks for billions): more is an error, not a slow run.
  int64_t MaximumSamples = 50000000;
};

/// A point of one model inside the other.
struct ContactSample
{
  std::array<double, 3> Point, Normal; // Normal: the unit direction to the closest point
  double Depth;                        // the exact distance to the other model
  int64_t Triangle;                    // its triangle in its own model (-1 for a vertex)
  int64_t Vertex;                      // its point id when it is a vertex, else -1
};

/// One model's penetration into the other.
struct PenetrationSide
{
  double Depth = 0; // the largest distance to the other over the samples inside it
  std::array<double, 3> Deepest{ { 0, 0, 0 } }, ClosestOnOther{ { 0, 0, 0 } };
  std::array<double, 3> Normal{ { 0, 0, 0 } }; // from Deepest to ClosestOnOther, unit
  int64_t TriangleOfOther = -1;                // -1 when no sample is inside
  int64_t Samples = 0, SamplesInside = 0;      // in the region, vertices included
  std::vector<ContactSample> Contacts;         // vertices first, then by triangle
};

struct ProximityReport
{
  /// Colliding, the contact pair, and (apart) the separation with its closest points.
  ProximityResult Contact;
  std::array<double, 6> Region{ { 0, -1, 0, -1, 0, -1 } }; // empty when Min > Max
  double Step = 0;
  PenetrationSide AInB, BInA;
  /// Each point's signed distance to the other model (negative inside it).
  std::vector<double> DistanceA, DistanceB;
  /// Exact point-to-model distances evaluated (the fields' samples that were read), and
  /// winding numbers evaluated for face samples. On a closed model the side of a sample
  /// joined to a known point by a ball free of the surface (centred at either, of its
  /// distance as radius) is that point's: most samples need neither.
  int64_t PointQueries = 0, InsideEvaluations = 0;
  /// On the GPU: the bytes sent to it (a deforming model with its topology on the
  /// device sends only its coordinates) and read back (the answers).
  int64_t BytesToDevice = 0, BytesFromDevice = 0;
};

/// One frame's query between prepared models a and b. Runs its loops with
/// `execution.For` when set; the report does not depend on the number of threads. False
/// with `error` when the request is invalid (margin, step, resolution) or the samples
/// would exceed MaximumSamples, or when `execution` asks to abort.
bool ComputeProximity(const ProximityModel& a,
  const ProximityModel& b,
  const ProximityRequest& request,
  ProximityReport& report,
  const Execution& execution,
  std::string& error);

/// The report of one call from the reports of its shares, in share order (each from
/// ComputeProximity with Share = its index; the first holds the point distances).
/// Consumes `shares`.
void MergeProximityShares(std::vector<ProximityReport>& shares, ProximityReport& merged);

/// A share's report as numbers, for a transport between processes (without the point
/// distances and the region, which every share computes alike).
std::vector<double> PackProximityShare(const ProximityReport& report);

/// The shares' reports from the concatenation of PackProximityShare's numbers, in share
/// order; the region, step and (for the first) the point distances from `local`. False
/// when the numbers are not such a concatenation.
bool UnpackProximityShares(const double* data,
  size_t count,
  const ProximityReport& local,
  std::vector<ProximityReport>& shares);
} // namespace vtkdf

#endif
