// The segmented field computed in pieces, as the ranks of a distributed run compute it:
// each piece computes its piece and one sample around it, and the pieces' region
// evidence is added up and handed to every piece (as the ranks' all-gather does). Every piece must
// equal the same samples of the whole grid computed in one piece, bit for bit (SegmentedDistance,
// RegionIndex, Distance, PatchId, ClosestPoint), with the same regions and sides, for:
// - slabs sharing their boundary planes (VTK's pieces), uneven;
// - 2 x 2 blocks sharing planes;
// - slabs that share nothing;
// - the whole grid on every piece (a sample belongs to the first piece that holds it);
// - an empty piece beside two slabs.
// Pieces that leave samples out, an extent without the sample around the piece, and a
// part of the grid without Combine are refused. PieceOwnership and CoveredSamples are
// checked against counting every sample; RegionEvidence::Add refuses malformed words.
// With the argument gpu, the same pieces on the GPU. The mesh: a closed cube, a fin on one of its
// edges (a junction of three sheets) and an open square beside it, so that the regions merge,
// refuse merges and meet at a junction.
#include "Common/PieceOwnership.h"
#include "GL/HeadlessGL.h"
#include "Segment/SegmentRegions.h"
#include "Segment/SegmentedField.h"

#include "CoreTest.h"
#include "GLCoreTest.h"
#include "ThreadFor.h"

#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
using vtkdf::IndexBox;
using vtkdf::coretest::Check;

vtkdf::MeshInput Scene()
{
  vtkdf::MeshInput mesh;
  const double corners[8][3] = { { 0, 0, 0 },
    { 1, 0, 0 },
    { 1, 1, 0 },
    { 0, 1, 0 },
    { 0, 0, 1 },
    { 1, 0, 1 },
    { 1, 1, 1 },
    { 0, 1, 1 } };
  for (const auto& c : corners)
  {
    mesh.Points.insert(mesh.Points.end(), c, c + 3);
  }
  // The fin on the edge (7, 6) and the open square at x = 1.5.
  const double more[6][3] = { { 1, 1.4, 1.4 },
    { 0, 1.4, 1.4 },
    { 1.5, 0.2, 0.2 },
    { 1.5, 0.8, 0.2 },
    { 1.5, 0.8, 0.8 },
    { 1.5, 0.2, 0.8 } };
  for (const auto& c : more)
  {
    mesh.Points.insert(mesh.Points.end(), c, c + 3);
  }
  const int64_t triangles[][3] = { { 0, 2, 1 },
    { 0, 3, 2 },
    { 4, 5, 6 },
    { 4, 6, 7 },
    { 0, 1, 5 },
    { 0, 5, 4 },
    { 1, 2, 6 },
    { 1, 6, 5 },
    { 2, 3, 7 },
    { 2, 7, 6 },
    { 3, 0, 4 },
    { 3, 4, 7 },
    { 7, 6, 8 },
    { 7, 8, 9 },
    { 10, 11, 12 },
    { 10, 12, 13 } };
  int64_t cell = 0;
  for (const auto& t : triangles)
  {
    mesh.Triangles.insert(mesh.Triangles.end(), t, t + 3);
    mesh.TriangleCells.push_back(cell++);
  }
  vtkdf::UsedPointBounds(mesh, mesh.Bounds);
  return mesh;
}

vtkdf::SampleGrid Grid()
{
  vtkdf::SampleGrid grid;
  grid.Origin = { -0.3, -0.31, -0.29 };
  grid.Spacing = { 0.1, 0.11, 0.09 };
  grid.Whole.Lo = { 0, 0, 0 };
  grid.Whole.Hi = { 21, 19, 21 };
  return grid;
}

IndexBox Box(int x0, int x1, int y0, int y1, int z0, int z1)
{
  IndexBox box;
  box.Lo = { x0, y0, z0 };
  box.Hi = { x1, y1, z1 };
  return box;
}

struct Fields
{
  IndexBox Extent;
  std::vector<float> Segmented, Distance, Closest;
  std::vector<int32_t> Region, Patch;
  vtkdf::SegmentedFieldReport Report;
  bool Ok = false;
  std::string Error;

  vtkdf::SegmentedFieldArrays Arrays(const IndexBox& extent)
  {
    this->Extent = extent;
    const size_t n = static_cast<size_t>(extent.Count());
    this->Segmented.assign(n, -7), this->Distance.assign(n, -7), this->Closest.assign(3 * n, -7);
    this->Region.assign(n, -7), this->Patch.assign(n, -7);
    vtkdf::SegmentedFieldArrays arrays;
    arrays.SegmentedDistance = this->Segmented.data();
    arrays.Distance = this->Distance.data();
    arrays.ClosestPoint = this->Closest.data();
    arrays.RegionIndex = this->Region.data();
    arrays.PatchId = this->Patch.data();
    return arrays;
  }
};

vtkdf::Execution Threads()
{
  vtkdf::Execution execution;
  execution.For = ThreadFor;
  return execution;
}

/// Runs the pieces as the ranks of a distributed run would, one after the other: each
/// computes its piece grown by one sample (within the grid) unless `extents` says
/// otherwise, and shares its region evidence; a first pass collects every piece's (its
/// Combine refuses to go on), a second gives each piece the sum, as the ranks'
/// all-gather does. A piece that fails before it shares its evidence keeps that error.
std::vector<Fields> RunPieces(vtkdf::HeadlessGL* gl,
  const std::vector<IndexBox>& pieces,
  std::vector<IndexBox> extents = {})
{
  const vtkdf::SampleGrid grid = Grid();
  std::vector<Fields> results(pieces.size());
  vtkdf::RegionEvidence sum;
  bool valid = true;
  for (int pass = 0; pass < 2; ++pass)
  {
    for (size_t p = 0; p < pieces.size(); ++p)
    {
      vtkdf::SegmentedFieldRequest request;
      request.Grid = grid;
      request.Pieces.Piece = pieces[p];
      request.Pieces.Before.assign(pieces.begin(), pieces.begin() + p);
      bool shared = false;
      request.Combine = [&](vtkdf::RegionEvidence& evidence, std::string& error)
      {
        shared = true;
        if (pass == 0)
        {
          const std::vector<int64_t> words = evidence.Pack();
          valid = sum.Add(words.data(), static_cast<int64_t>(words.size())) && valid;
          error = "collected";
          return false;
        }
        evidence = sum;
        return valid;
      };
      Fields& out = results[p];
      if (pieces[p].Empty())
      {
        vtkdf::RegionEvidence none; // a piece with no samples adds no evidence
        out.Ok = request.Combine(none, out.Error);
        continue;
      }
      if (pass == 1 && !out.Ok && out.Error.find("collected") == std::string::npos)
      {
        continue; // it failed before sharing its evidence
      }
      request.Extent = extents.empty() ? pieces[p].Grown(1, grid.Whole) : extents[p];
      const vtkdf::SegmentedFieldArrays arrays = out.Arrays(request.Extent);
      out.Ok = vtkdf::ComputeSegmentedField(
        Scene(), request, gl, arrays, Threads(), out.Report, out.Error);
      Check(shared || !out.Ok, "a piece succeeded without sharing its evidence");
    }
  }
  return results;
}

template<typename T>
bool SameSamples(const std::vector<T>& whole,
  const IndexBox& wholeBox,
  const std::vector<T>& part,
  const IndexBox& partBox,
  const IndexBox& piece,
  int components)
{
  for (int k = piece.Lo[2]; k <= piece.Hi[2]; ++k)
  {
    for (int j = piece.Lo[1]; j <= piece.Hi[1]; ++j)
    {
      for (int i = piece.Lo[0]; i <= piece.Hi[0]; ++i)
      {
        auto index = [&](const IndexBox& b)
        {
          return ((int64_t(k - b.Lo[2]) * b.Size(1) + (j - b.Lo[1])) * b.Size(0) + (i - b.Lo[0])) *
            components;
        };
        if (std::memcmp(&whole[index(wholeBox)], &part[index(partBox)], sizeof(T) * components))
        {
          return false;
        }
      }
    }
  }
  return true;
}

void TestPieces(vtkdf::HeadlessGL* gl, const Fields& whole)
{
  const IndexBox all = Grid().Whole;
  struct Case
  {
    const char* Name;
    std::vector<IndexBox> Pieces;
  };
  const std::vector<Case> cases = {
    { "3 slabs sharing planes",
      { Box(0, 21, 0, 19, 0, 5), Box(0, 21, 0, 19, 5, 12), Box(0, 21, 0, 19, 12, 21) } },
    { "2 x 2 blocks sharing planes",
      { Box(0, 10, 0, 9, 0, 21),
        Box(10, 21, 0, 9, 0, 21),
        Box(0, 10, 9, 19, 0, 21),
        Box(10, 21, 9, 19, 0, 21) } },
    { "2 slabs sharing nothing", { Box(0, 21, 0, 19, 0, 8), Box(0, 21, 0, 19, 9, 21) } },
    { "the whole grid twice", { all, all } },
    { "an empty piece and 2 slabs",
      { Box(0, 21, 0, 19, 0, 10), IndexBox(), Box(0, 21, 0, 19, 10, 21) } },
  };
  for (const Case& c : cases)
  {
    const std::vector<Fields> parts = RunPieces(gl, c.Pieces);
    for (size_t p = 0; p < parts.size(); ++p)
    {
      const Fields& part = parts[p];
      Check(part.Ok, "%s, piece %zu: %s", c.Name, p, part.Error.c_str());
      if (!part.Ok || c.Pieces[p].Empty())
      {
        continue;
      }
      const IndexBox& piece = c.Pieces[p];
      const bool same[5] = {
        SameSamples(whole.Segmented, whole.Extent, part.Segmented, part.Extent, piece, 1),
        SameSamples(whole.Distance, whole.Extent, part.Distance, part.Extent, piece, 1),
        SameSamples(whole.Closest, whole.Extent, part.Closest, part.Extent, piece, 3),
        SameSamples(whole.Region, whole.Extent, part.Region, part.Extent, piece, 1),
        SameSamples(whole.Patch, whole.Extent, part.Patch, part.Extent, piece, 1)
      };
      Check(same[0] && same[1] && same[2] && same[3] && same[4],
        "%s, piece %zu: differs from the whole grid (SegmentedDistance, Distance, ClosestPoint, "
        "RegionIndex, PatchId equal: %d %d %d %d %d)",
        c.Name,
        p,
        same[0],
        same[1],
        same[2],
        same[3],
        same[4]);
      Check(part.Report.RegionCount == whole.Report.RegionCount &&
          part.Report.Sides == whole.Report.Sides &&
          part.Report.RefusedMerges == whole.Report.RefusedMerges,
        "%s, piece %zu: %d regions (%lld refused merges), the whole grid %d (%lld)",
        c.Name,
        p,
        part.Report.RegionCount,
        static_cast<long long>(part.Report.RefusedMerges),
        whole.Report.RegionCount,
        static_cast<long long>(whole.Report.RefusedMerges));
    }
    std::printf("%s (%s): %zu pieces\n", c.Name, gl ? "GPU" : "CPU", parts.size());
  }
}

void TestRefusals()
{
  // Two of three slabs: the evidence covers part of the grid.
  const std::vector<Fields> gap =
    RunPieces(nullptr, { Box(0, 21, 0, 19, 0, 5), Box(0, 21, 0, 19, 12, 21) });
  for (const Fields& part : gap)
  {
    Check(!part.Ok && part.Error.find("covers") != std::string::npos,
      "pieces leaving samples out: %s",
      part.Ok ? "accepted" : part.Error.c_str());
  }
  // An extent that is the piece alone (not one sample around it).
  const std::vector<IndexBox> slabs = { Box(0, 21, 0, 19, 0, 10), Box(0, 21, 0, 19, 10, 21) };
  const std::vector<Fields> bare = RunPieces(nullptr, slabs, slabs);
  Check(!bare[0].Ok && bare[0].Error.find("one sample around") != std::string::npos,
    "an extent without the samples around its piece: %s",
    bare[0].Ok ? "accepted" : bare[0].Error.c_str());
  // A part of the grid without Combine.
  vtkdf::SegmentedFieldRequest request;
  request.Grid = Grid();
  request.Extent = slabs[0];
  Fields out;
  std::string error;
  const bool ok = vtkdf::ComputeSegmentedField(
    Scene(), request, nullptr, out.Arrays(slabs[0]), Threads(), out.Report, error);
  Check(!ok && error.find("Combine") != std::string::npos,
    "a part without Combine: %s",
    ok ? "accepted" : error.c_str());
  // Malformed evidence words.
  vtkdf::RegionEvidence evidence;
  const std::vector<std::vector<int64_t>> bad = { {},
    { 5 },
    { 1, 1, 3 },
    { 1, 2, 4, 3, 0 },
    { 1, 0, 1, 2, 1, 5 },
    { 1, 0, 1, 1, 2, 0 },
    { 1, 0, 2, 1, 2, 5 } };
  for (const auto& words : bad)
  {
    Check(!evidence.Add(words.data(), static_cast<int64_t>(words.size())),
      "malformed evidence of %zu words accepted",
      words.size());
  }
  Check(evidence.Samples == 0 && evidence.Labels.empty() && evidence.Support.empty(),
    "a refused evidence changed the sum");
  const std::vector<int64_t> good = { 4, 2, 1, 3, 1, 1, 3, 2 };
  Check(evidence.Add(good.data(), 8) && evidence.Add(good.data(), 8) && evidence.Samples == 8 &&
      evidence.Labels == std::vector<int64_t>({ 1, 3 }) && evidence.Support.at({ 1, 3 }) == 4,
    "a well-formed evidence was not added up");
}

void TestOwnership()
{
  std::mt19937 random(7);
  const IndexBox whole = Box(0, 9, 0, 7, 0, 6);
  for (int round = 0; round < 200; ++round)
  {
    std::vector<IndexBox> pieces(1 + random() % 5);
    for (IndexBox& box : pieces)
    {
      for (int a = 0; a < 3; ++a)
      {
        const int n = whole.Size(a) + 2;
        int x = static_cast<int>(random() % n) - 1, y = static_cast<int>(random() % n) - 1;
        box.Lo[a] = std::min(x, y), box.Hi[a] = std::max(x, y) + (round % 7 == 0 ? -3 : 0);
      }
    }
    // Every sample of the grid: how many pieces own it, whether one holds it.
    int64_t covered = 0;
    bool once = true;
    for (int k = whole.Lo[2]; k <= whole.Hi[2]; ++k)
    {
      for (int j = whole.Lo[1]; j <= whole.Hi[1]; ++j)
      {
        std::vector<int> owners(whole.Size(0), 0);
        bool anywhere[64] = {};
        for (size_t p = 0; p < pieces.size(); ++p)
        {
          vtkdf::PieceOwnership ownership;
          ownership.Piece = pieces[p];
          ownership.Before.assign(pieces.begin(), pieces.begin() + p);
          std::vector<std::pair<int, int>> runs;
          ownership.Runs(j, k, runs);
          int last = -1000;
          for (const auto& run : runs)
          {
            once = once && run.first > last && run.first <= run.second;
            last = run.second;
            for (int i = run.first; i <= run.second; ++i)
            {
              once = once && i >= pieces[p].Lo[0] && i <= pieces[p].Hi[0];
              if (i >= whole.Lo[0] && i <= whole.Hi[0])
              {
                ++owners[i - whole.Lo[0]];
              }
            }
          }
          for (int i = whole.Lo[0]; i <= whole.Hi[0]; ++i)
          {
            const IndexBox& b = pieces[p];
            anywhere[i] = anywhere[i] ||
              (i >= b.Lo[0] && i <= b.Hi[0] && j >= b.Lo[1] && j <= b.Hi[1] && k >= b.Lo[2] &&
                k <= b.Hi[2]);
          }
        }
        for (int i = whole.Lo[0]; i <= whole.Hi[0]; ++i)
        {
          once = once && owners[i - whole.Lo[0]] == (anywhere[i] ? 1 : 0);
          covered += anywhere[i];
        }
      }
    }
    Check(once, "round %d: a sample is owned by no piece that holds it, or by two", round);
    Check(vtkdf::CoveredSamples(pieces, whole) == covered,
      "round %d: CoveredSamples %lld, counted %lld",
      round,
      static_cast<long long>(vtkdf::CoveredSamples(pieces, whole)),
      static_cast<long long>(covered));
  }
}
} // namespace

int main(int argc, char* argv[])
{
  // With the argument gpu: the field and side labels on the GPU (the whole grid and the
  // pieces alike).
  vtkdf::HeadlessGL* gl = nullptr;
  if (argc > 1 && std::string(argv[1]) == "gpu")
  {
    gl = vtkdf::coretest::GLContext();
    if (!gl)
    {
      return 1;
    }
  }
  // The whole grid in one piece (no Combine): the reference.
  vtkdf::SegmentedFieldRequest request;
  request.Grid = Grid();
  Fields whole;
  whole.Ok = vtkdf::ComputeSegmentedField(
    Scene(), request, gl, whole.Arrays(request.Grid.Whole), Threads(), whole.Report, whole.Error);
  Check(whole.Ok, "the whole grid: %s", whole.Error.c_str());
  Check(whole.Report.RegionCount >= 3 && whole.Report.RefusedMerges > 0,
    "the scene should have several regions and a refused merge: %d regions, %lld refused",
    whole.Report.RegionCount,
    static_cast<long long>(whole.Report.RefusedMerges));
  std::printf("whole grid: %d regions, %lld patches, %lld refused merges\n",
    whole.Report.RegionCount,
    static_cast<long long>(whole.Report.PatchCount),
    static_cast<long long>(whole.Report.RefusedMerges));
  if (whole.Ok)
  {
    TestPieces(gl, whole);
  }
  if (!gl)
  {
    TestRefusals();
    TestOwnership();
  }
  return vtkdf::coretest::Verdict();
}
