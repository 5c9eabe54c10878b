// BenchUnion: timings of the union closest-point query and of the penetration depth
// (Kim et al., JGT 2002), CPU and GPU, on the scenes of the paper's section 2.3 and 3:
//   - 45 convex pieces of 40 faces and 70 of 30 (the paper: 0.1 s and 0.07 s a query on a
//     GeForce 3): one query from inside (the median of repeats), and many queries at once
//     (queries per second);
//   - the penetration depth of two linked tori of 67 pieces each, and of a CAD-like pair
//     of 425 pieces (a plate of boxes and the pins through it; the paper: 0.2 s and 2 s).
// Usage: BenchUnion [--backends cpu,gpu] [--queries 1000]
//          [--write DIR]   (the PD inputs as OBJ files, for other tools)
//          [--only 45x40|70x30|tori|plates]
// Prints one line per measurement. Not a test.
#include "Union/ConvexHull.h"
#include "Union/PenetrationDepth.h"
#include "Union/UnionClosestPointGPU.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace vtkdf;

namespace
{
/// Every hardware thread, pulling chunks of `grain` from a shared counter.
void HardwareFor(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body)
{
  const int64_t threads = std::max(1u, std::thread::hardware_concurrency());
  grain = std::max<int64_t>(1, grain);
  std::atomic<int64_t> next(0);
  auto work = [&]
  {
    for (int64_t begin; (begin = next.fetch_add(grain)) < n;)
    {
      body(begin, std::min(n, begin + grain));
    }
  };
  std::vector<std::thread> pool;
  for (int64_t t = 1; t < threads; ++t)
  {
    pool.emplace_back(work);
  }
  work();
  for (auto& t : pool)
  {
    t.join();
  }
}

double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

ConvexPiece HullPiece(const std::vector<double>& points)
{
  std::vector<std::vector<int64_t>> faces;
  int64_t corners = 0;
  std::string error;
  ConvexPiece piece;
  if (!ConvexHull(points, faces, corners, error) || !piece.Build(points, faces, 1e-9, error))
  {
    std::fprintf(stderr, "BenchUnion: a piece: %s\n", error.c_str());
    std::exit(1);
  }
  return piece;
}

/// m hulls of `corners` random points on ellipsoids (2 corners - 4 triangles), around the
/// origin, overlapping into one blob that holds it.
std::vector<ConvexPiece> Blob(int m, int corners, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<ConvexPiece> pieces;
  const double spread = 0.45 * std::cbrt(double(m));
  for (int i = 0; i < m; ++i)
  {
    const double c[3] = { spread * unit(random), spread * unit(random), spread * unit(random) };
    const double r[3] = {
      0.5 + 0.25 * unit(random), 0.5 + 0.25 * unit(random), 0.5 + 0.25 * unit(random)
    };
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
    pieces.push_back(HullPiece(points));
  }
  // The piece nearest the origin is moved onto it, so that the query starts inside.
  size_t nearest = 0;
  double best = HUGE_VAL;
  for (size_t i = 0; i < pieces.size(); ++i)
  {
    double d = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double c = 0.5 * (pieces[i].Lo[a] + pieces[i].Hi[a]);
      d += c * c;
    }
    if (d < best)
    {
      best = d;
      nearest = i;
    }
  }
  std::vector<double> points = pieces[nearest].Corners();
  double c[3];
  for (int a = 0; a < 3; ++a)
  {
    c[a] = 0.5 * (pieces[nearest].Lo[a] + pieces[nearest].Hi[a]);
  }
  for (size_t k = 0; k < points.size(); ++k)
  {
    points[k] -= c[k % 3];
  }
  pieces[nearest] = HullPiece(points);
  return pieces;
}

/// A torus of `n` overlapping segments (each the hull of two hexagonal cross sections,
/// 3 % longer than its share of the ring, so that neighbours overlap and share no corner).
std::vector<ConvexPiece> Torus(const double c[3], int axis, double R, double r, int n)
{
  std::vector<ConvexPiece> pieces;
  const double half = M_PI / n * 1.03;
  for (int s = 0; s < n; ++s)
  {
    const double mid = 2 * M_PI * (s + 0.5) / n;
    std::vector<double> points;
    for (const double a : { mid - half, mid + half })
    {
      for (int k = 0; k < 6; ++k)
      {
        const double phi = 2 * M_PI * (k + 0.5) / 6;
        const double radial = R + r * std::cos(phi), height = r * std::sin(phi);
        const double x = radial * std::cos(a), y = radial * std::sin(a);
        if (axis == 2)
        {
          points.insert(points.end(), { c[0] + x, c[1] + y, c[2] + height });
        }
        else
        {
          points.insert(points.end(), { c[0] + x, c[1] + height, c[2] + y });
        }
      }
    }
    pieces.push_back(HullPiece(points));
  }
  return pieces;
}

/// A CAD-like pair: P a plate of 212 slightly overlapping boxes (16 x 14, 0.6 thick), Q
/// 213 hexagonal pins through it, one per box, leaning by 0.1.
void Plates(std::vector<ConvexPiece>& p, std::vector<ConvexPiece>& q)
{
  for (int x = 0; x < 16; ++x)
  {
    for (int y = 0; y < 14 && p.size() < 212; ++y)
    {
      std::vector<double> points;
      for (int k = 0; k < 8; ++k)
      {
        points.insert(points.end(),
          { x + (k & 1 ? 1.02 : -0.02), y + (k & 2 ? 1.02 : -0.02), k & 4 ? 0.6 : 0.0 });
      }
      p.push_back(HullPiece(points));
    }
  }
  const double tilt = 0.1;
  for (int x = 0; x < 16 && q.size() < 213; ++x)
  {
    for (int y = 0; y < 14 && q.size() < 213; ++y)
    {
      // A pin: a hexagonal prism from z = -0.5 to 1.2, radius 0.3, leaning by `tilt`.
      std::vector<double> points;
      for (const double z : { -0.5, 1.2 })
      {
        for (int k = 0; k < 6; ++k)
        {
          const double a = 2 * M_PI * k / 6;
          points.insert(points.end(),
            { x + 0.5 + 0.3 * std::cos(a) + tilt * z, y + 0.5 + 0.3 * std::sin(a), z });
        }
      }
      q.push_back(HullPiece(points));
    }
  }
}

void WriteOBJ(const std::string& path, const std::vector<const std::vector<ConvexPiece>*>& sets)
{
  std::ofstream out(path);
  out.precision(17);
  size_t base = 1;
  for (const auto* set : sets)
  {
    for (const ConvexPiece& piece : *set)
    {
      const std::vector<double> corners = piece.Corners();
      for (size_t k = 0; k < corners.size(); k += 3)
      {
        out << "v " << corners[k] << " " << corners[k + 1] << " " << corners[k + 2] << "\n";
      }
      for (const auto& face : piece.Faces)
      {
        out << "f";
        for (size_t k = 0; k < face.size(); k += 3)
        {
          // The corner's index among the sorted distinct corners.
          const auto it =
            std::lower_bound(reinterpret_cast<const std::array<double, 3>*>(corners.data()),
              reinterpret_cast<const std::array<double, 3>*>(corners.data() + corners.size()),
              std::array<double, 3>{ face[k], face[k + 1], face[k + 2] });
          out << " "
              << base + (it - reinterpret_cast<const std::array<double, 3>*>(corners.data()));
        }
        out << "\n";
      }
      base += corners.size() / 3;
    }
  }
}

int Faces(const std::vector<ConvexPiece>& pieces)
{
  size_t faces = 0;
  for (const auto& p : pieces)
  {
    faces += p.Faces.size();
  }
  return static_cast<int>(faces);
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> backends = { "cpu", "gpu" };
  int manyQueries = 1000;
  std::string write, only;
  for (int a = 1; a + 1 < argc; a += 2)
  {
    const std::string option = argv[a];
    if (option == "--backends")
    {
      backends.clear();
      std::string list = argv[a + 1];
      for (size_t at = 0; at <= list.size();)
      {
        const size_t comma = std::min(list.find(',', at), list.size());
        backends.push_back(list.substr(at, comma - at));
        at = comma + 1;
      }
    }
    else if (option == "--queries")
    {
      manyQueries = std::atoi(argv[a + 1]);
    }
    else if (option == "--write")
    {
      write = argv[a + 1];
    }
    else if (option == "--only")
    {
      only = argv[a + 1]; // a scene: 45x40, 70x30, tori, plates
    }
  }
  HeadlessGL* gl = nullptr;
  if (std::find(backends.begin(), backends.end(), "gpu") != backends.end())
  {
    std::string error;
    gl = HeadlessGL::Get(error);
    if (!gl)
    {
      std::fprintf(stderr, "BenchUnion: no GPU: %s\n", error.c_str());
      return 1;
    }
    std::printf("gpu: %s (%s)\n", gl->Renderer().c_str(), gl->Platform().c_str());
  }
  std::printf("threads: %u\n", std::thread::hardware_concurrency());

  // The union query.
  struct Scene
  {
    const char* Name;
    int Pieces, Corners;
  };
  for (const Scene scene : { Scene{ "45x40", 45, 22 }, Scene{ "70x30", 70, 17 } })
  {
    if (!only.empty() && only != scene.Name)
    {
      continue;
    }
    UnionClosestPoint u;
    u.Pieces = Blob(scene.Pieces, scene.Corners, 2026);
    u.Tolerance = 1e-9;
    const double origin[3] = { 0, 0, 0 };
    std::mt19937 random(7);
    std::vector<double> many;
    double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (const auto& p : u.Pieces)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], p.Lo[a]);
        hi[a] = std::max(hi[a], p.Hi[a]);
      }
    }
    for (int k = 0; k < manyQueries; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        many.push_back(std::uniform_real_distribution<double>(lo[a], hi[a])(random));
      }
    }
    const UnionAnswer reference = u.Query(origin);
    std::printf("union %s: %zu pieces, %d faces; from the origin: distance %.9f, %lld faces "
                "visited\n",
      scene.Name,
      u.Pieces.size(),
      Faces(u.Pieces),
      reference.Distance,
      static_cast<long long>(reference.FacesVisited));
    for (const std::string& backend : backends)
    {
      {
        const std::string& label = backend;
        // The GPU query of `queries`; false, said on stderr, when it fails.
        auto onGPU = [&](const std::vector<double>& queries, std::vector<UnionGPUAnswer>& answers)
        {
          UnionGPUSettings settings;
          settings.For = HardwareFor;
          std::string error;
          const bool ok = QueryUnionGPU(*gl, u, queries, settings, answers, error);
          if (!ok)
          {
            std::fprintf(stderr, "BenchUnion: %s\n", error.c_str());
          }
          return ok;
        };
        // One query: the median of 7.
        std::vector<double> times;
        double answer = 0, bound = 0;
        for (int r = 0; r < 7; ++r)
        {
          const double start = Now();
          if (backend == "cpu")
          {
            u.For = HardwareFor;
            answer = u.Query(origin).Distance;
            u.For = nullptr;
          }
          else
          {
            std::vector<UnionGPUAnswer> answers;
            if (!onGPU(std::vector<double>(origin, origin + 3), answers))
            {
              return 1;
            }
            answer = answers[0].Answer.Distance;
            bound = answers[0].Estimate;
          }
          times.push_back(Now() - start);
        }
        std::sort(times.begin(), times.end());
        // Many queries at once.
        const double start = Now();
        if (backend == "cpu")
        {
          std::vector<UnionAnswer> out(many.size() / 3);
          HardwareFor(static_cast<int64_t>(out.size()),
            4,
            [&](int64_t b, int64_t e)
            {
              for (int64_t q = b; q < e; ++q)
              {
                out[q] = u.Query(&many[3 * q]);
              }
            });
        }
        else
        {
          std::vector<UnionGPUAnswer> answers;
          if (!onGPU(many, answers))
          {
            return 1;
          }
        }
        const double seconds = Now() - start;
        std::printf("union %s %-4s one query: %.4f s (distance %.9f, the GPU's bound %.9f); "
                    "%d queries: %.3f s = %.0f queries/s\n",
          scene.Name,
          label.c_str(),
          times[times.size() / 2],
          answer,
          bound,
          manyQueries,
          seconds,
          manyQueries / seconds);
      }
    }
  }

  // Penetration depth.
  std::vector<ConvexPiece> torusP, torusQ, plateP, plateQ;
  const double c0[3] = { 0, 0, 0 }, c1[3] = { 1, 0, 0 };
  torusP = Torus(c0, 2, 1.0, 0.25, 67);
  torusQ = Torus(c1, 1, 0.45, 0.25, 67);
  Plates(plateP, plateQ);
  if (!write.empty())
  {
    WriteOBJ(write + "/tori.obj", { &torusP, &torusQ });
    WriteOBJ(write + "/plates.obj", { &plateP, &plateQ });
    std::printf("wrote %s/tori.obj and %s/plates.obj\n", write.c_str(), write.c_str());
  }
  struct Pair
  {
    const char* Name;
    const std::vector<ConvexPiece>* P;
    const std::vector<ConvexPiece>* Q;
  };
  for (const Pair pair :
    { Pair{ "tori 67+67", &torusP, &torusQ }, Pair{ "plates 212+213", &plateP, &plateQ } })
  {
    if (!only.empty() && std::string(pair.Name).find(only) != 0)
    {
      continue;
    }
    for (const std::string& backend : backends)
    {
      {
        PenetrationDepth depth;
        depth.Tolerance = 1e-9;
        depth.For = HardwareFor;
        UnionGPUSettings settings;
        settings.For = HardwareFor;
        const double origin[3] = { 0, 0, 0 };
        PenetrationAnswer answer;
        std::string error;
        UnionClosestPoint sums;
        std::vector<std::pair<int64_t, int64_t>> kept;
        int64_t total = 0;
        const double hullStart = Now();
        depth.BuildSums(*pair.P, *pair.Q, origin, sums, kept, total, error);
        const double hulls = Now() - hullStart;
        const double start = Now();
        if (!depth.Compute(
              *pair.P, *pair.Q, origin, answer, error, backend == "gpu" ? gl : nullptr, settings))
        {
          std::fprintf(stderr, "BenchUnion: %s\n", error.c_str());
          return 1;
        }
        const double seconds = Now() - start;
        std::printf("pd %s %-4s: %.3f s (of which sums' hulls ~%.3f s): depth %.9f, pairs %lld of "
                    "%lld kept, sums' faces %d, faces visited %lld, the GPU's bound %.9f\n",
          pair.Name,
          backend.c_str(),
          seconds,
          hulls,
          answer.Distance,
          static_cast<long long>(answer.PairsKept),
          static_cast<long long>(answer.PairsTotal),
          Faces(sums.Pieces),
          static_cast<long long>(answer.FacesVisited),
          answer.Estimate);
      }
    }
  }
  return 0;
}
