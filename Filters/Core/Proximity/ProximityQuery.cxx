#include "Proximity/ProximityQuery.h"

#include "Common/Vector3.h"
#include "Proximity/ProximityGPU.h"
#include "Proximity/ProximityParts.h"
#include "Segment/TriangleCrossings.h"
#include "Winding/WindingCrossings.h"

#include <algorithm>
#include <cmath>

namespace vtkdf
{
namespace
{
using proximity::CountFaceSamples;
using proximity::OnDevice;
using proximity::Penetrate;
using proximity::PointDistances;
using proximity::PointQuery;
} // namespace

namespace
{
/// Whether the request can be answered for these models; false with `error`.
bool CheckRequest(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  const ProximityRequest& request,
  std::string& error)
{
  if (!a.Loaded || !b.Loaded)
  {
    error = "both models must be loaded before a query";
    return false;
  }
  if (a.Rule != request.Rule || b.Rule != request.Rule)
  {
    error = "the models were loaded for another inside rule than the request's";
    return false;
  }
  if (!(request.ContactMargin >= 0) || !std::isfinite(request.ContactMargin))
  {
    error = "the contact margin must be finite and at least 0; it is " +
      std::to_string(request.ContactMargin);
    return false;
  }
  if (!(request.Step >= 0) || !std::isfinite(request.Step))
  {
    error = "the step must be finite and at least 0 (0: from the resolution); it is " +
      std::to_string(request.Step);
    return false;
  }
  if (request.Shares < 1 || request.Share < 0 || request.Share >= request.Shares)
  {
    error = "share " + std::to_string(request.Share) + " of " + std::to_string(request.Shares) +
      " does not exist";
    return false;
  }
  if (request.Step == 0 && (request.Resolution < 1 || request.Resolution > 65536))
  {
    error = "the resolution must be 1 to 65536; it is " + std::to_string(request.Resolution);
    return false;
  }
  return true;
}

/// The interaction region (the boxes' overlap grown by the margin; empty: `empty`) and
/// the step from it, into the report; false with `error` when the face samples would
/// exceed the request's limit.
bool InteractionRegion(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  const ProximityRequest& request,
  ProximityReport& report,
  bool& empty,
  std::string& error)
{
  std::array<double, 6> hull;
  double longest = 0, regionLongest = 0;
  empty = false;
  for (int k = 0; k < 3; ++k)
  {
    const double m = request.ContactMargin;
    report.Region[2 * k] = std::max(a.Bounds[2 * k], b.Bounds[2 * k]) - m;
    report.Region[2 * k + 1] = std::min(a.Bounds[2 * k + 1], b.Bounds[2 * k + 1]) + m;
    hull[2 * k] = std::min(a.Bounds[2 * k], b.Bounds[2 * k]);
    hull[2 * k + 1] = std::max(a.Bounds[2 * k + 1], b.Bounds[2 * k + 1]);
    empty = empty || report.Region[2 * k] > report.Region[2 * k + 1];
    longest = std::max(longest, hull[2 * k + 1] - hull[2 * k]);
    regionLongest = std::max(regionLongest, report.Region[2 * k + 1] - report.Region[2 * k]);
  }
  if (empty)
  {
    report.Region = { { 0, -1, 0, -1, 0, -1 } };
  }
  report.Step = request.Step > 0
    ? request.Step
    : (empty || regionLongest <= 0 ? longest : regionLongest) / request.Resolution;
  if (!(report.Step > 0))
  {
    // Both models are one point: any positive step samples them.
    report.Step = 1;
  }
  if (!empty)
  {
    const double samples = CountFaceSamples(a, report.Region, report.Step) +
      CountFaceSamples(b, report.Region, report.Step);
    if (samples > static_cast<double>(request.MaximumSamples))
    {
      error = "the face samples at step " + std::to_string(report.Step) + " would number " +
        std::to_string(static_cast<long long>(samples)) + ", over the limit of " +
        std::to_string(request.MaximumSamples) + ": take a coarser step (a lower resolution)";
      return false;
    }
  }
  return true;
}

/// Contact: the first pair of triangles, one of each model, with a point in common.
void FindContactPair(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  ProximityResult& contact)
{
  a.Tree->ForEachOverlappingPair(*b.Tree,
    [&](size_t s, size_t t)
    {
      Point3 p[3], q[3];
      a.Model.Corners(s, p);
      b.Model.Corners(t, q);
      ++contact.ContactTests;
      if (ClosedTrianglesIntersect(p, q))
      {
        contact.ContactA = static_cast<int64_t>(s);
        contact.ContactB = static_cast<int64_t>(t);
        return false;
      }
      return true;
    });
}

/// Apart: the separation and its pair, from the least of the points' distances as the
/// bound (searched again without one should rounding leave the bound short).
void FindSeparation(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  ProximityReport& report)
{
  double bound = HUGE_VAL;
  for (const auto* distances : { &report.DistanceA, &report.DistanceB })
  {
    for (const double d : *distances)
    {
      bound = std::isnan(d) ? bound : std::min(bound, std::fabs(d));
    }
  }
  if (!NearestPair(a.Model, *a.Tree, b.Model, *b.Tree, bound * bound, report.Contact))
  {
    NearestPair(a.Model, *a.Tree, b.Model, *b.Tree, HUGE_VAL, report.Contact);
  }
}
} // namespace

bool ComputeProximity(const ProximityModel& modelA,
  const ProximityModel& modelB,
  const ProximityRequest& request,
  ProximityReport& report,
  const Execution& execution,
  std::string& error)
{
  report = ProximityReport();
  const ProximityModel::Data& a = modelA.Get();
  const ProximityModel::Data& b = modelB.Get();
  bool empty = false;
  if (!CheckRequest(a, b, request, error) ||
    !InteractionRegion(a, b, request, report, empty, error))
  {
    return false;
  }
  auto aborted = [&](double fraction)
  {
    if (execution.Report(fraction))
    {
      return false;
    }
    error = "aborted";
    return true;
  };

  // On the GPU: both models there (their coordinates; their topology when it is new).
  ProximityDevice* device = request.Device;
  if (device)
  {
    DeviceResetTraffic(*device);
    if (!DeviceLoadModel(*device, 0, a.Model, *a.Tree, a.Topology, error) ||
      !DeviceLoadModel(*device, 1, b.Model, *b.Tree, b.Topology, error))
    {
      return false;
    }
    execution.EndStage("upload");
  }
  const OnDevice gpuAB{ device, 0, 1 }, gpuBA{ device, 1, 0 };

  // The merged report takes the contact pair and the separation from the first share:
  // the others skip both.
  ProximityResult& contact = report.Contact;
  const bool first = request.Share == 0;
  if (first)
  {
    FindContactPair(a, b, contact);
  }
  if (aborted(0.1))
  {
    return false;
  }

  // Every point's distance to the other model: the fields where the points need them.
  std::vector<PointQuery> queriesA, queriesB;
  if (!PointDistances(a, b, gpuAB, execution, report.DistanceA, queriesA, error) ||
    !PointDistances(b, a, gpuBA, execution, report.DistanceB, queriesB, error))
  {
    return false;
  }
  if (request.Share == 0)
  {
    report.PointQueries += static_cast<int64_t>(std::count(a.Used.begin(), a.Used.end(), true) +
      std::count(b.Used.begin(), b.Used.end(), true));
  }
  execution.EndStage("point distances");
  if (aborted(0.3))
  {
    return false;
  }

  // Penetration, both ways, over the region's samples.
  auto penetrate = [&](const ProximityModel::Data& self,
                     const ProximityModel::Data& other,
                     const OnDevice& gpu,
                     const std::vector<PointQuery>& queries,
                     PenetrationSide& side)
  {
    return Penetrate(self,
      other,
      gpu,
      queries,
      report.Region,
      report.Step,
      request.Contacts,
      request.Share,
      request.Shares,
      execution,
      side,
      report.PointQueries,
      report.InsideEvaluations,
      error);
  };
  if (!empty &&
    (!penetrate(a, b, gpuAB, queriesA, report.AInB) || aborted(0.6) ||
      !penetrate(b, a, gpuBA, queriesB, report.BInA)))
  {
    return false;
  }
  execution.EndStage("penetration");
  if (device)
  {
    DeviceTraffic(*device, report.BytesToDevice, report.BytesFromDevice);
  }
  contact.AInsideB = report.AInB.SamplesInside > 0;
  contact.BInsideA = report.BInA.SamplesInside > 0;
  contact.Colliding = contact.ContactA >= 0 || contact.AInsideB || contact.BInsideA;
  if (contact.Colliding || !first)
  {
    contact.Separation = 0;
  }
  else
  {
    FindSeparation(a, b, report);
    execution.EndStage("separation");
  }
  return !aborted(1.0);
}

} // namespace vtkdf
