// The union closest-point query with the GPU's bounds (Filters/Core/Union/
// UnionClosestPointGPU.h) against the exact CPU query (checked against brute forces by
// Core.Union), on llvmpipe in CI:
// - random unions (seeded) of 5 to 70 convex pieces of 8 to 40 faces (hulls of random
//   points on ellipsoids), queries inside and outside: the GPU backend's answer equals the
//   CPU's bit for bit (distance, point, piece, side); its bound U is never below the
//   answer (it is a boundary point's distance), equals it from outside, and never made
//   the full search run again; other splits of the faces into blocks and of the queries
//   into dispatches give the same U, bit for bit; a pass cut short by its loop budget
//   says so and changes no answer;
// - the publication's hard cases: touching cubes (the shared face is not boundary: 0.5,
//   not 0.1), blocks of 27 and 125 touching or overlapping cubes, O exactly on a shared
//   face and on an outer face, a slot of free space too narrow for a rendered view to see
//   (U finds its tip), a piece holding O alone, nested pieces, a bound that misses (every
//   face point nearest O touches another piece: the full search runs, the same answer).
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
  int Queries = 0, Inside = 0, Reseeded = 0;
  double WorstGap = 0; // (U - exact) / diagonal
  long long GpuFaces = 0, CpuFaces = 0;
} totals;

/// The GPU backend against the CPU at every query; returns the GPU's answers. With
/// `settings` that let the pass test every face (the default), U is complete.
std::vector<UnionGPUAnswer> Compare(HeadlessGL& gl,
  const UnionClosestPoint& u,
  const std::vector<double>& queries,
  const std::string& name,
  const UnionGPUSettings& settings = UnionGPUSettings())
{
  const double tolerance = 1e-12 * Diagonal(u);
  std::vector<UnionGPUAnswer> answers;
  std::string error;
  const bool ok = QueryUnionGPU(gl, u, queries, settings, answers, error);
  Check(ok, "%s", std::string(name + ": " + error).c_str());
  if (answers.size() != queries.size() / 3)
  {
    Check(false, "%s", std::string(name + ": answers missing").c_str());
    return answers;
  }
  for (size_t q = 0; q < answers.size(); ++q)
  {
    const UnionAnswer exact = u.Query(&queries[3 * q]);
    const std::string at = name + " query " + std::to_string(q);
    const UnionGPUAnswer& g = answers[q];
    // The CPU's answer bit for bit: the bounded search's faces give the bits the full
    // search's do (UnionClosestPoint's window).
    Check(g.Answer.Distance == exact.Distance,
      "%s (%.17g)",
      std::string(at + ": GPU = CPU (" + std::to_string(exact.Distance) + ")").c_str(),
      static_cast<double>(g.Answer.Distance));
    Check(std::equal(g.Answer.Closest, g.Answer.Closest + 3, exact.Closest) &&
        g.Answer.Piece == exact.Piece && g.Answer.Inside == exact.Inside,
      "%s (piece %lld, %lld)",
      std::string(at + ": the same point, piece and side").c_str(),
      static_cast<long long>(g.Answer.Piece),
      static_cast<long long>(exact.Piece));
    const double d = std::fabs(exact.Distance);
    const bool complete = !g.Stopped;
    Check(complete == (settings.IterationBudget == 0),
      "%s (%d)",
      std::string(at + ": the pass ran out of iterations only when its budget was cut").c_str(),
      g.Stopped ? 1 : 0);
    Check(g.Estimate >= d - tolerance && (exact.Inside || !complete || g.Estimate <= d + tolerance),
      "%s (%.17g)",
      std::string(
        at + ": U above the answer, and equal to it from outside (" + std::to_string(d) + ")")
        .c_str(),
      static_cast<double>(g.Estimate));
    // U is a boundary point's distance, so the search bounded by it finds the answer.
    Check(!g.Reseeded, "%s", std::string(at + ": U sufficed").c_str());
    if (g.Estimate < HUGE_VAL)
    {
      totals.WorstGap = std::max(totals.WorstGap, (g.Estimate - d) / Diagonal(u));
    }
    ++totals.Queries;
    totals.Inside += exact.Inside;
    totals.Reseeded += g.Reseeded;
    totals.GpuFaces += g.Answer.FacesVisited;
    totals.CpuFaces += exact.FacesVisited;
  }
  return answers;
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
        // Other splits of the faces and the queries: the same bounds, bit for bit.
        std::vector<UnionGPUAnswer> together, apart;
        std::string error;
        Check(QueryUnionGPU(gl, u, queries, UnionGPUSettings(), together, error),
          "%s",
          std::string("split: " + error).c_str());
        UnionGPUSettings split;
        split.DispatchTests = 1; // one query a dispatch
        split.BlockFaces = 7;
        Check(QueryUnionGPU(gl, u, queries, split, apart, error),
          "%s",
          std::string("split: " + error).c_str());
        Check(together.size() == apart.size() && !apart.empty(), "split: answers");
        // A budget of 40 loop iterations an invocation: every block stops early, U is
        // larger or none, the answers are the same.
        UnionGPUSettings cut;
        cut.IterationBudget = 40;
        Compare(gl, u, queries, "a cut budget", cut);
        for (size_t q = 0; q < together.size() && together.size() == apart.size(); ++q)
        {
          Check(together[q].Estimate == apart[q].Estimate,
            "split: the same U (%.17g)",
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
      Check(!answers.empty() && std::fabs(answers[0].Estimate - expected) < 1e-12,
        "block: U is the outer boundary's distance (%.17g)",
        static_cast<double>(answers.empty() ? 0 : answers[0].Estimate));
    }
  }
  {
    // A slot of free space, 2e-4 wide, from the outside to 0.2 of O: narrower than a
    // pixel of a rendered view from O, but its tip is a face point outside the other
    // pieces, so U is its distance.
    const double w = 1e-4;
    UnionClosestPoint u;
    u.Pieces = {
      Box(-3, 3, -3, 3, -3, -w), Box(-3, 3, -3, 3, w, 3), Box(-3, 0.2, -3, 3, -2 * w, 2 * w)
    };
    const auto answers = Compare(gl, u, { 0, 0, 0 }, "narrow slot");
    Check(!answers.empty() && std::fabs(answers[0].Answer.Distance + 0.2) < 1e-9 &&
        answers[0].Estimate == 0.2,
      "slot: the answer and U are its tip (%.17g)",
      static_cast<double>(answers.empty() ? 0 : answers[0].Estimate));
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
    // No bound: two copies of one cube. Every face's point nearest O lies on the other
    // copy's face, not outside it by more than the tolerance, so the pass finds no point
    // certainly on the boundary; the full search gives the answer.
    UnionClosestPoint u;
    u.Pieces = { Box(-1, 1, -1, 1, -1, 1), Box(-1, 1, -1, 1, -1, 1) };
    const auto answers = Compare(gl, u, { 0.25, 0, 0 }, "two copies of a cube");
    Check(answers.size() == 1 && answers[0].Estimate == HUGE_VAL &&
        std::fabs(answers[0].Answer.Distance + 0.75) < 1e-12,
      "copies: no bound from inside, the full search's answer (%.17g)",
      static_cast<double>(answers.empty() ? 0 : answers[0].Answer.Distance));
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
  std::printf("%d queries (%d inside): U above the answer by at most %.3g of the diagonal, "
              "the full search rerun %d times; faces searched: %lld from U, %lld by the CPU "
              "alone\n",
    totals.Queries,
    totals.Inside,
    totals.WorstGap,
    totals.Reseeded,
    totals.GpuFaces,
    totals.CpuFaces);
  if (Failures == 0)
  {
    std::printf("all GPU union checks passed\n");
  }
  return Verdict();
}
