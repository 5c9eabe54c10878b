// The union closest-point query on the GPU (Filters/Core/Union/UnionClosestPointGPU.h)
// against the exact CPU query (checked against brute forces by Core.Union), on llvmpipe
// in CI:
// - random unions (seeded) of 5 to 70 convex pieces of 8 to 40 faces (hulls of random
//   points on ellipsoids), queries inside and outside: the certified GPU answer equals the
//   CPU answer bit for bit (distance, point, piece), and the uncertified U is never
//   below it (it is a point of the boundary); a batch of queries gives the same images
//   as one query a batch;
// - the paper's hard cases: touching cubes (the shared face is not boundary: 0.5, not
//   0.1; U too), blocks of 27 and 125 touching or overlapping cubes (one and two hops), O
//   exactly on a shared face and on an outer face, a sub-pixel slot of free space pointing
//   at O (U misses it, the certified answer does not), a piece holding O alone, nested
//   pieces;
// - the six images: every pixel's distance is a boundary point's (at least the answer).
#include "CoreTest.h"
#include "GLCoreTest.h"
#include "Union/ConvexHull.h"
#include "Union/UnionClosestPointGPU.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{

ConvexPiece HullPiece(const std::vector<double>& points)
{
  std::vector<std::vector<int64_t>> faces;
  int64_t corners = 0;
  std::string error;
  ConvexPiece piece;
  Check(ConvexHull(points, faces, corners, error) && piece.Build(points, faces, 1e-9, error),
    "%s",
    std::string("a test piece: " + error).c_str());
  return piece;
}

ConvexPiece Box(double x0, double x1, double y0, double y1, double z0, double z1)
{
  std::vector<double> points;
  for (int k = 0; k < 8; ++k)
  {
    points.insert(points.end(), { k & 1 ? x1 : x0, k & 2 ? y1 : y0, k & 4 ? z1 : z0 });
  }
  return HullPiece(points);
}

double Diagonal(const UnionClosestPoint& u)
{
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const ConvexPiece& p : u.Pieces)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p.Lo[a]);
      hi[a] = std::max(hi[a], p.Hi[a]);
    }
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
    (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

struct Totals
{
  int Queries = 0, Inside = 0, Passes = 0, MaxPasses = 0;
  double WorstGap = 0; // (U - exact) / diagonal
  int Beyond = 0;      // uncertified answers off by more than their ErrorBound
  long long CertifyFaces = 0, CpuFaces = 0;
} totals;

/// GPU (certified and not) against the CPU at every query; returns the certified answers.
std::vector<UnionGPUAnswer> Compare(HeadlessGL& gl,
  const UnionClosestPoint& u,
  const std::vector<double>& queries,
  const std::string& name,
  int resolution = 64,
  std::vector<float>* images = nullptr,
  std::vector<double>* frames = nullptr)
{
  const double tolerance = 1e-6 * Diagonal(u);
  UnionGPUSettings settings;
  settings.Resolution = resolution;
  std::vector<UnionGPUAnswer> certified, estimated;
  std::string error;
  Check(QueryUnionGPU(gl, u, queries, settings, certified, error, images, frames),
    "%s",
    std::string(name + ": " + error).c_str());
  settings.Certify = false;
  Check(QueryUnionGPU(gl, u, queries, settings, estimated, error),
    "%s",
    std::string(name + ": " + error).c_str());
  if (certified.size() != queries.size() / 3 || estimated.size() != certified.size())
  {
    Check(false, "%s", std::string(name + ": answers missing").c_str());
    return certified;
  }
  for (size_t q = 0; q < certified.size(); ++q)
  {
    const UnionAnswer exact = u.Query(&queries[3 * q]);
    const std::string at = name + " query " + std::to_string(q);
    const UnionGPUAnswer& c = certified[q];
    Check(c.Certified && c.ErrorBound == 0,
      "%s (%.17g)",
      std::string(at + ": certified").c_str(),
      static_cast<double>(c.ErrorBound));
    // The certified answer is the CPU's bit for bit: the seeded search's faces give the
    // bits the unseeded search's do (UnionClosestPoint's window).
    Check(c.Answer.Distance == exact.Distance,
      "%s (%.17g)",
      std::string(at + ": certified GPU = CPU (" + std::to_string(exact.Distance) + ")").c_str(),
      static_cast<double>(c.Answer.Distance));
    Check(std::equal(c.Answer.Closest, c.Answer.Closest + 3, exact.Closest) &&
        c.Answer.Piece == exact.Piece,
      "%s (piece %lld, %lld)",
      std::string(at + ": the same point and piece").c_str(),
      static_cast<long long>(c.Answer.Piece),
      static_cast<long long>(exact.Piece));
    const UnionGPUAnswer& e = estimated[q];
    Check(!e.Certified && e.Estimate >= std::fabs(exact.Distance) - tolerance,
      "%s (%.17g)",
      std::string(
        at + ": U never below the answer (" + std::to_string(std::fabs(exact.Distance)) + ")")
        .c_str(),
      static_cast<double>(e.Estimate));
    Check(e.Answer.Inside == exact.Inside,
      "%s (%.17g)",
      std::string(at + ": the same side").c_str(),
      static_cast<double>(e.Answer.Inside));
    if (e.Estimate - std::fabs(exact.Distance) > e.ErrorBound)
    {
      ++totals.Beyond;
      std::printf("beyond its ErrorBound: %s: U %.9g, exact %.9g, ErrorBound %.3g\n",
        at.c_str(),
        e.Estimate,
        std::fabs(exact.Distance),
        e.ErrorBound);
    }
    totals.WorstGap =
      std::max(totals.WorstGap, (e.Estimate - std::fabs(exact.Distance)) / Diagonal(u));
    ++totals.Queries;
    totals.Inside += exact.Inside;
    totals.Passes += c.Passes;
    totals.MaxPasses = std::max(totals.MaxPasses, c.Passes);
    totals.CertifyFaces += c.Answer.FacesVisited;
    totals.CpuFaces += exact.FacesVisited;
  }
  return certified;
}

void RandomUnions(HeadlessGL& gl)
{
  std::mt19937 random(20261124);
  std::uniform_real_distribution<double> unit(-1, 1);
  const int sizes[] = { 5, 12, 30, 45, 70 };
  int trial = 0;
  for (const int m : sizes)
  {
    for (int repeat = 0; repeat < 2; ++repeat, ++trial)
    {
      UnionClosestPoint u;
      const double spread = 0.4 * std::cbrt(double(m));
      for (int i = 0; i < m; ++i)
      {
        const int corners = 6 + static_cast<int>(random() % 17); // 8 to 40 faces
        const double c[3] = { spread * unit(random), spread * unit(random), spread * unit(random) };
        const double r[3] = { 0.3 + 0.3 * (unit(random) + 1),
          0.3 + 0.3 * (unit(random) + 1),
          0.3 + 0.3 * (unit(random) + 1) };
        std::vector<double> points;
        for (int k = 0; k < corners; ++k)
        {
          double d[3] = { unit(random), unit(random), unit(random) };
          const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-12;
          for (int a = 0; a < 3; ++a)
          {
            points.push_back(c[a] + r[a] * d[a] / length);
          }
        }
        u.Pieces.push_back(HullPiece(points));
      }
      // Queries: pieces' centres (inside), random points around, far outside.
      std::vector<double> queries;
      for (int k = 0; k < 3; ++k)
      {
        const ConvexPiece& p = u.Pieces[random() % u.Pieces.size()];
        for (int a = 0; a < 3; ++a)
        {
          queries.push_back(0.5 * (p.Lo[a] + p.Hi[a]));
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          queries.push_back(1.3 * spread * unit(random));
        }
      }
      queries.insert(queries.end(), { 3 * spread + 2, 0.1, -0.2 });
      Compare(gl,
        u,
        queries,
        "random union " + std::to_string(trial) + " (" + std::to_string(m) + " pieces)");
      if (trial == 2)
      {
        // One query a batch: the same images, so the same U.
        UnionGPUSettings settings;
        settings.Resolution = 64;
        settings.Certify = false;
        std::vector<UnionGPUAnswer> together, apart;
        std::string error;
        Check(QueryUnionGPU(gl, u, queries, settings, together, error),
          "%s",
          std::string("batched: " + error).c_str());
        settings.BatchBytes = 1;
        Check(QueryUnionGPU(gl, u, queries, settings, apart, error),
          "%s",
          std::string("one a batch: " + error).c_str());
        Check(together.size() == apart.size() && !apart.empty(), "batched and alone: answers");
        for (size_t q = 0; q < together.size() && together.size() == apart.size(); ++q)
        {
          Check(together[q].Estimate == apart[q].Estimate,
            "batched and alone: the same U (%.17g)",
            static_cast<double>(together[q].Estimate - apart[q].Estimate));
        }
      }
    }
  }
}

void HardCases(HeadlessGL& gl)
{
  {
    UnionClosestPoint u;
    u.Pieces = { Box(0, 1, 0, 1, 0, 1), Box(1, 2, 0, 1, 0, 1) };
    const auto answers =
      Compare(gl, u, { 0.9, 0.5, 0.5, 1, 0.5, 0.5, 0, 0.5, 0.5 }, "two touching cubes");
    Check(answers.size() == 3 && std::fabs(answers[0].Answer.Distance + 0.5) < 1e-9,
      "two cubes from (0.9, 0.5, 0.5): 0.5 (%.17g)",
      static_cast<double>(answers.empty() ? 0 : answers[0].Answer.Distance));
    Check(answers.size() == 3 && std::fabs(answers[1].Answer.Distance + 0.5) < 1e-9,
      "two cubes from the shared face: 0.5 (%.17g)",
      static_cast<double>(answers.size() < 2 ? 0 : answers[1].Answer.Distance));
    Check(answers.size() == 3 && std::fabs(answers[2].Answer.Distance) < 1e-9,
      "two cubes from an outer face: 0 (%.17g)",
      static_cast<double>(answers.size() < 3 ? 0 : answers[2].Answer.Distance));
  }
  for (const int k : { 3, 5 })
  {
    for (const double grow : { 0.0, 0.1 })
    {
      UnionClosestPoint u;
      for (int x = 0; x < k; ++x)
      {
        for (int y = 0; y < k; ++y)
        {
          for (int z = 0; z < k; ++z)
          {
            u.Pieces.push_back(
              Box(x - grow, x + 1 + grow, y - grow, y + 1 + grow, z - grow, z + 1 + grow));
          }
        }
      }
      const double c = 0.5 * k;
      const auto answers = Compare(gl,
        u,
        { c, c + 0.1, c - 0.05 },
        "block of " + std::to_string(k * k * k) + (grow > 0 ? " overlapping" : " touching") +
          " cubes");
      const double expected = c - 0.1 + grow;
      Check(!answers.empty() && std::fabs(answers[0].Answer.Distance + expected) < 1e-9,
        "block: the outer boundary (%.17g)",
        static_cast<double>(answers.empty() ? 0 : answers[0].Answer.Distance));
      Check(!answers.empty() && answers[0].Passes >= (k - 1) / 2 + 1,
        "block: the hops need passes (%.17g)",
        static_cast<double>(answers.empty() ? 0 : answers[0].Passes));
    }
  }
  {
    // A slot of free space, 2e-4 wide, from the outside to 0.2 of O: narrower than a
    // pixel seen from O, so U misses it; the certified answer is 0.2.
    const double w = 1e-4;
    UnionClosestPoint u;
    u.Pieces = {
      Box(-3, 3, -3, 3, -3, -w), Box(-3, 3, -3, 3, w, 3), Box(-3, 0.2, -3, 3, -2 * w, 2 * w)
    };
    const int beyond = totals.Beyond;
    const auto answers = Compare(gl, u, { 0, 0, 0 }, "sub-pixel slot");
    Check(totals.Beyond == beyond + 1,
      "slot: U misses it, beyond its ErrorBound (%.17g)",
      static_cast<double>(totals.Beyond));
    Check(!answers.empty() && std::fabs(answers[0].Answer.Distance + 0.2) < 1e-9,
      "slot: the certified answer is its tip (%.17g)",
      static_cast<double>(answers.empty() ? 0 : answers[0].Answer.Distance));
  }
  {
    UnionClosestPoint u;
    u.Pieces = { Box(0, 1, 0, 1, 0, 1), Box(5, 6, 0, 1, 0, 1), Box(5.5, 7, 0.5, 2, 0, 1) };
    Compare(gl, u, { 0.3, 0.4, 0.45 }, "a piece holding O alone");
  }
  {
    UnionClosestPoint u;
    u.Pieces = { Box(0.4, 0.6, 0.4, 0.6, 0.4, 0.6),
      Box(0, 1, 0, 1, 0, 1),
      Box(0.45, 0.55, 0.45, 0.55, 0.3, 0.7) };
    const auto answers = Compare(gl, u, { 0.5, 0.5, 0.5 }, "nested pieces");
    Check(!answers.empty() && std::fabs(answers[0].Answer.Distance + 0.5) < 1e-9,
      "nested: the outer box (%.17g)",
      static_cast<double>(answers.empty() ? 0 : answers[0].Answer.Distance));
  }
  {
    // The images: every seen pixel is a boundary point (the ray's point is in the closed
    // union, and a little farther along the ray it is out).
    UnionClosestPoint u;
    u.Pieces = { Box(0, 1, 0, 1, 0, 1), Box(0.5, 1.5, 0.2, 0.8, 0.2, 0.8) };
    std::vector<float> images;
    std::vector<double> frames;
    const double o[3] = { 0.6, 0.5, 0.5 };
    Compare(gl, u, { o[0], o[1], o[2] }, "images", 32, &images, &frames);
    int bad = 0, seen = 0;
    double worst = 0;
    for (size_t p = 0; p < images.size() && frames.size() == 54; ++p)
    {
      const int view = static_cast<int>(p / (32 * 32)), row = static_cast<int>(p / 32 % 32),
                column = static_cast<int>(p % 32);
      const double x = 2.0 * (column + 0.5) / 32 - 1, y = 2.0 * (row + 0.5) / 32 - 1;
      double d[3], length = 0;
      for (int a = 0; a < 3; ++a)
      {
        d[a] = x * frames[9 * view + a] + y * frames[9 * view + 3 + a] + frames[9 * view + 6 + a];
        length += d[a] * d[a];
      }
      length = std::sqrt(length);
      double before[3], after[3];
      for (int a = 0; a < 3; ++a)
      {
        before[a] = o[a] + d[a] / length * (images[p] - 2e-5);
        after[a] = o[a] + d[a] / length * (images[p] + 2e-5);
      }
      ++seen;
      const bool boundary = u.Contains(before) && !u.Contains(after);
      bad += !boundary;
      // Where the ray leaves each box (both hold O): the image holds the farther.
      const double lo[2][3] = { { 0, 0, 0 }, { 0.5, 0.2, 0.2 } },
                   hi[2][3] = { { 1, 1, 1 }, { 1.5, 0.8, 0.8 } };
      double exits[2];
      for (int b = 0; b < 2; ++b)
      {
        exits[b] = HUGE_VAL;
        for (int a = 0; a < 3; ++a)
        {
          if (d[a] != 0)
          {
            exits[b] =
              std::min(exits[b], ((d[a] > 0 ? hi[b][a] : lo[b][a]) - o[a]) / (d[a] / length));
          }
        }
      }
      const double exact = std::max(exits[0], exits[1]);
      worst = std::max(worst, std::fabs(images[p] - exact));
      if (!boundary && bad <= 3)
      {
        std::printf("images: view %d row %d column %d holds %.9g; the boxes are left at %.9g "
                    "and %.9g\n",
          view,
          row,
          column,
          static_cast<double>(images[p]),
          exits[0],
          exits[1]);
      }
    }
    std::printf("images: the distances within %.3g of the exact ones\n", worst);
    Check(seen == 6 * 32 * 32 && bad == 0,
      "images: every pixel a boundary point (bad pixels) (%.17g)",
      static_cast<double>(bad));
  }
}
} // namespace

int main()
{
  HeadlessGL* gl = vtkdf::coretest::GLContext();
  if (!gl)
  {
    return 1;
  }
  HardCases(*gl);
  RandomUnions(*gl);
  std::printf("%d queries (%d inside): passes %.2f on average, at most %d; U above the answer "
              "by at most %.3g of the diagonal at 64 pixels, beyond its ErrorBound in %d; faces "
              "searched: %lld certifying, %lld by the CPU alone\n",
    totals.Queries,
    totals.Inside,
    double(totals.Passes) / std::max(1, totals.Queries),
    totals.MaxPasses,
    totals.WorstGap,
    totals.Beyond,
    totals.CertifyFaces,
    totals.CpuFaces);
  if (Failures == 0)
  {
    std::printf("all GPU union checks passed\n");
  }
  return Verdict();
}
