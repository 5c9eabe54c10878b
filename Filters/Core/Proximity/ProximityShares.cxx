#include "Proximity/ProximityQuery.h"

#include <algorithm>
#include <utility>

namespace vtkdf
{
void MergeProximityShares(std::vector<ProximityReport>& shares, ProximityReport& merged)
{
  merged = std::move(shares[0]);
  for (size_t k = 1; k < shares.size(); ++k)
  {
    ProximityReport& share = shares[k];
    merged.PointQueries += share.PointQueries;
    merged.InsideEvaluations += share.InsideEvaluations;
    merged.Contact.ContactTests = std::max(merged.Contact.ContactTests, share.Contact.ContactTests);
    PenetrationSide* into[2] = { &merged.AInB, &merged.BInA };
    PenetrationSide* from[2] = { &share.AInB, &share.BInA };
    for (int m = 0; m < 2; ++m)
    {
      into[m]->Samples += from[m]->Samples;
      into[m]->SamplesInside += from[m]->SamplesInside;
      // The first deepest in the order of the samples: shares are in that order.
      if (from[m]->TriangleOfOther >= 0 &&
        (from[m]->Depth > into[m]->Depth || into[m]->TriangleOfOther < 0))
      {
        into[m]->Depth = from[m]->Depth;
        into[m]->Deepest = from[m]->Deepest;
        into[m]->ClosestOnOther = from[m]->ClosestOnOther;
        into[m]->Normal = from[m]->Normal;
        into[m]->TriangleOfOther = from[m]->TriangleOfOther;
      }
      into[m]->Contacts.insert(
        into[m]->Contacts.end(), from[m]->Contacts.begin(), from[m]->Contacts.end());
    }
  }
  ProximityResult& contact = merged.Contact;
  contact.AInsideB = merged.AInB.SamplesInside > 0;
  contact.BInsideA = merged.BInA.SamplesInside > 0;
  contact.Colliding = contact.ContactA >= 0 || contact.AInsideB || contact.BInsideA;
  if (contact.Colliding)
  {
    // The first share may have searched the separation before the others' samples
    // inside were known.
    contact.Separation = 0;
    contact.ClosestTriangleA = contact.ClosestTriangleB = -1;
    contact.DistanceTests = 0;
  }
}

namespace
{
constexpr int ContactDoubles = 9; // point, normal, depth, triangle, vertex

void PackSide(const PenetrationSide& side, std::vector<double>& out)
{
  const double head[] = { side.Depth,
    side.Deepest[0],
    side.Deepest[1],
    side.Deepest[2],
    side.ClosestOnOther[0],
    side.ClosestOnOther[1],
    side.ClosestOnOther[2],
    side.Normal[0],
    side.Normal[1],
    side.Normal[2],
    double(side.TriangleOfOther),
    double(side.Samples),
    double(side.SamplesInside),
    double(side.Contacts.size()) };
  out.insert(out.end(), std::begin(head), std::end(head));
  for (const ContactSample& c : side.Contacts)
  {
    const double values[ContactDoubles] = { c.Point[0],
      c.Point[1],
      c.Point[2],
      c.Normal[0],
      c.Normal[1],
      c.Normal[2],
      c.Depth,
      double(c.Triangle),
      double(c.Vertex) };
    out.insert(out.end(), std::begin(values), std::end(values));
  }
}

bool UnpackSide(const double*& at, const double* end, PenetrationSide& side)
{
  if (end - at < 14)
  {
    return false;
  }
  side.Depth = at[0];
  std::copy(at + 1, at + 4, side.Deepest.begin());
  std::copy(at + 4, at + 7, side.ClosestOnOther.begin());
  std::copy(at + 7, at + 10, side.Normal.begin());
  side.TriangleOfOther = static_cast<int64_t>(at[10]);
  side.Samples = static_cast<int64_t>(at[11]);
  side.SamplesInside = static_cast<int64_t>(at[12]);
  const double count = at[13];
  at += 14;
  if (!(count >= 0) || count * ContactDoubles > double(end - at))
  {
    return false;
  }
  side.Contacts.resize(static_cast<size_t>(count));
  for (ContactSample& c : side.Contacts)
  {
    std::copy(at, at + 3, c.Point.begin());
    std::copy(at + 3, at + 6, c.Normal.begin());
    c.Depth = at[6];
    c.Triangle = static_cast<int64_t>(at[7]);
    c.Vertex = static_cast<int64_t>(at[8]);
    at += ContactDoubles;
  }
  return true;
}
} // namespace

std::vector<double> PackProximityShare(const ProximityReport& report)
{
  const ProximityResult& c = report.Contact;
  std::vector<double> out = { double(c.ContactA),
    double(c.ContactB),
    c.Separation,
    c.ClosestA[0],
    c.ClosestA[1],
    c.ClosestA[2],
    c.ClosestB[0],
    c.ClosestB[1],
    c.ClosestB[2],
    double(c.ClosestTriangleA),
    double(c.ClosestTriangleB),
    double(c.ContactTests),
    double(c.DistanceTests),
    double(report.PointQueries),
    double(report.InsideEvaluations) };
  PackSide(report.AInB, out);
  PackSide(report.BInA, out);
  return out;
}

bool UnpackProximityShares(const double* data,
  size_t count,
  const ProximityReport& local,
  std::vector<ProximityReport>& shares)
{
  shares.clear();
  const double* at = data;
  const double* end = data + count;
  while (at < end)
  {
    if (end - at < 15)
    {
      return false;
    }
    // What every share computes alike (the region, the step, the point distances) is
    // the local report's.
    ProximityReport share;
    share.Region = local.Region;
    share.Step = local.Step;
    ProximityResult& c = share.Contact;
    c.ContactA = static_cast<int64_t>(at[0]);
    c.ContactB = static_cast<int64_t>(at[1]);
    c.Separation = at[2];
    std::copy(at + 3, at + 6, c.ClosestA.begin());
    std::copy(at + 6, at + 9, c.ClosestB.begin());
    c.ClosestTriangleA = static_cast<int64_t>(at[9]);
    c.ClosestTriangleB = static_cast<int64_t>(at[10]);
    c.ContactTests = static_cast<int64_t>(at[11]);
    c.DistanceTests = static_cast<int64_t>(at[12]);
    share.PointQueries = static_cast<int64_t>(at[13]);
    share.InsideEvaluations = static_cast<int64_t>(at[14]);
    at += 15;
    if (!UnpackSide(at, end, share.AInB) || !UnpackSide(at, end, share.BInA))
    {
      return false;
    }
    if (shares.empty())
    {
      share.DistanceA = local.DistanceA;
      share.DistanceB = local.DistanceB;
    }
    shares.push_back(std::move(share));
  }
  return !shares.empty();
}
} // namespace vtkdf
