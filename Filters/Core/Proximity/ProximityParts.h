// ProximityParts: what the sources of the proximity query share: the model's data
// (ProximityModel.cxx loads it), the point queries and the penetration
// (ProximityPenetration.cxx), which ComputeProximity (ProximityQuery.cxx) drives. Private
// to the proximity family.
#ifndef vtkdf_ProximityParts_h
#define vtkdf_ProximityParts_h

#include "Proximity/ProximityQuery.h"

#include "Common/Vector3.h"
#include "Proximity/ProximityGPU.h"
#include "Proximity/ProximitySearch.h"
#include "Winding/WindingNumber.h"
#include <algorithm>
#include <atomic>

#include <cmath>
#include <map>
#include <utility>

#include <cmath>

namespace vtkdf
{
struct ProximityModel::Data
{
  InsideRule Rule = InsideRule::WindingNumber;
  bool Loaded = false, Reused = false;
  uint64_t Topology = 0; // a new number for each new topology (the GPU's copy follows it)
  LargeVector<int64_t> TriangleIds;
  TriangleModel Model;
  std::vector<bool> Used; // points that a triangle uses
  std::array<double, 6> Bounds{ { 0, -1, 0, -1, 0, -1 } };
  std::unique_ptr<TriangleBoxTree> Tree;
  WindingNumber Winding; // InsideRule::WindingNumber
  // InsideRule::PseudoNormal: each triangle's three sides' edge ids (side c from corner c
  // to corner c + 1), and the normals of the faces, vertices and edges.
  // Points at identical coordinates are one vertex (Canonical: the least such id), as
  // the linear factorization's sites merge them; Outward is -1 for a mesh whose signed
  // volume is negative (oriented inward), so that its pseudonormals point out.
  std::vector<std::array<int64_t, 3>> Sides;
  std::vector<size_t> Canonical;
  std::vector<Point3> FaceNormals, VertexNormals, EdgeNormals;
  double Outward = 1;
  // Whether the triangles, on the merged points, make a closed chain: every edge used as
  // often in one direction as in the other, and no triangle repeated with the same
  // orientation (the winding number counts those once). Then w is an integer off the
  // surface and constant on any ball that the surface does not meet.
  bool Closed = false;

  bool MergePoints();
  void BuildEdges();
  void ComputeNormals();
  bool Inside(const double x[3], const double closest[3], int64_t triangle, double d2) const;
};

namespace proximity
{
/// The unit vector along v, or 0 for a zero vector.
inline Point3 Unit(const Point3& v)
{
  const double length = std::sqrt(Dot(v.data(), v.data()));
  return length > 0 ? Point3{ { v[0] / length, v[1] / length, v[2] / length } }
                    : Point3{ { 0, 0, 0 } };
}

/// The squared distance from x to model m, its closest point and triangle, and whether x
/// is inside m.
struct PointQuery
{
  double D2 = HUGE_VAL;
  double Closest[3] = { 0, 0, 0 };
  int64_t Triangle = -1;
  bool Inside = false;

  PointQuery() = default;
  /// The nearest triangle, from `hint`'s distance when it is a triangle's index.
  PointQuery(const ProximityModel::Data& m, const double x[3], int64_t hint)
    : Triangle(hint)
  {
    this->D2 = NearestTriangle(m.Model, *m.Tree, x, this->Closest, this->Triangle);
  }
  /// The nearest triangle as the GPU found it (answers' point k).
  PointQuery(const NearestAnswers& answers, size_t k)
    : D2(answers.Values[4 * k + 3])
    , Triangle(answers.Triangles[k])
  {
    std::copy(&answers.Values[4 * k], &answers.Values[4 * k] + 3, this->Closest);
  }
  /// With whether x is inside m by m's rule.
  PointQuery(const ProximityModel::Data& m, const double x[3])
    : PointQuery(m, x, -1)
  {
    this->Inside = m.Inside(x, this->Closest, this->Triangle, this->D2);
  }
};

/// A query's device and the slots of its two models there (null: the CPU).
struct OnDevice
{
  ProximityDevice* Device;
  int Self, Other;
};

/// The signed distances of `self`'s points to `other` (NaN for the points no triangle
/// uses), with each point's query kept for the penetration. False with `error` when the
/// GPU fails.
bool PointDistances(const ProximityModel::Data& self,
  const ProximityModel::Data& other,
  const OnDevice& gpu,
  const Execution& execution,
  std::vector<double>& distances,
  std::vector<PointQuery>& queries,
  std::string& error);

/// The penetration of `self` into `other`: its vertices (from their queries) and face
/// samples in `region` inside `other`. False with `error` when the GPU fails.
bool Penetrate(const ProximityModel::Data& self,
  const ProximityModel::Data& other,
  const OnDevice& gpu,
  const std::vector<PointQuery>& vertexQueries,
  const std::array<double, 6>& region,
  double step,
  bool keepContacts,
  int share,
  int shares,
  const Execution& execution,
  PenetrationSide& side,
  int64_t& queries,
  int64_t& windings,
  std::string& error);

/// Face samples (corners excluded) that `self`'s triangles meeting `region` would take.
double CountFaceSamples(const ProximityModel::Data& self,
  const std::array<double, 6>& region,
  double step);
} // namespace proximity
} // namespace vtkdf

#endif
