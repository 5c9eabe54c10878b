// The fast winding number (Filters/Core/Winding/WindingNumber.h), VTK-free, against the
// exact sum of solid angles at every query (itself against a plain sum of atan2's):
// - the approximation within its error bound, at every query, and its gradient within
//   its own; the exact gradient against central differences; the first-order Taylor
//   remainder within HessianBound;
// - Inside() equal to the exact decision wherever |w| is not within 1e-9 of 1/2;
// - a closed sphere: w = 1 inside and 0 outside (to 1e-9 where exact); flipped: -1;
// - an open sphere (one cap removed), random soups, a sheet folded onto itself;
// - repeated triangles with the same orientation count once; opposite ones cancel;
// - WindingSigns on a grid: blocks decide exactly as every sample alone, which agrees with
//   the exact sum wherever |w| is not within 1e-9 of 1/2, and the values within their
//   bounds; the same with distances that skip blocks near the surface; two threads;
// - with the argument gpu: WindingSignsGPU against WindingSigns (CheckGPU).
#include "CoreTest.h"
#include "GL/HeadlessGL.h"
#include "GLCoreTest.h"
#include "ThreadFor.h"
#include "Winding/WindingCrossings.h"
#include "Winding/WindingNumber.h"
#include "Winding/WindingSigns.h"
#include "Winding/WindingSignsGPU.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{
std::mt19937_64 Random(16);

struct Mesh
{
  LargeVector<double> Points;
  LargeVector<int64_t> Triangles;
};

/// A unit sphere: an octahedron subdivided `levels` times, projected, outward.
Mesh Sphere(int levels)
{
  Mesh m;
  m.Points = { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 };
  m.Triangles = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
  for (int l = 0; l < levels; ++l)
  {
    LargeVector<int64_t> next;
    auto middle = [&](int64_t a, int64_t b)
    {
      double p[3], n = 0;
      for (int c = 0; c < 3; ++c)
      {
        p[c] = 0.5 * (m.Points[3 * a + c] + m.Points[3 * b + c]);
        n += p[c] * p[c];
      }
      for (int c = 0; c < 3; ++c)
      {
        m.Points.push_back(p[c] / std::sqrt(n));
      }
      return static_cast<int64_t>(m.Points.size() / 3 - 1);
    };
    for (size_t t = 0; t < m.Triangles.size(); t += 3)
    {
      const int64_t a = m.Triangles[t], b = m.Triangles[t + 1], c = m.Triangles[t + 2];
      const int64_t ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
      next.insert(next.end(), { a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca });
    }
    m.Triangles = next;
  }
  return m;
}

double Uniform(double lo, double hi)
{
  return std::uniform_real_distribution<double>(lo, hi)(Random);
}

/// Checks the hierarchy against the exact sum at random queries; returns how many
/// queries needed the exact evaluation.
int CheckMesh(const char* name,
  const Mesh& mesh,
  int queries,
  double accuracy = WindingNumber::DefaultAccuracy)
{
  WindingNumber w;
  w.Build(mesh.Points, mesh.Triangles, accuracy);
  int exactCalls = 0;
  double worstRatio = 0, worstGradientRatio = 0, worstHessianRatio = 0;
  for (int i = 0; i < queries; ++i)
  {
    const double q[3] = { Uniform(-1.6, 1.6), Uniform(-1.6, 1.6), Uniform(-1.6, 1.6) };
    const double exact = w.Exact(q);
    const WindingValue fast = w.Evaluate(q);
    const double error = std::fabs(fast.Value - exact);
    Check(error <= fast.Bound + 1e-12,
      "the approximation is outside its bound (%.17g)",
      static_cast<double>(error));
    if (fast.Bound > 0)
    {
      worstRatio = std::max(worstRatio, error / fast.Bound);
    }
    double used = 0;
    bool wasExact = false;
    const bool inside = w.Inside(q, &used, &wasExact);
    const bool insideAlone = w.Inside(q); // the coarse-then-fine path
    exactCalls += wasExact;
    if (std::fabs(std::fabs(exact) - 0.5) > 1e-9)
    {
      Check(inside == (std::fabs(exact) > 0.5),
        "Inside() differs from the exact sign (%.17g)",
        static_cast<double>(exact));
      Check(insideAlone == (std::fabs(exact) > 0.5),
        "Inside() without a value differs from the exact sign (%.17g)",
        static_cast<double>(exact));
    }

    // The gradient: the exact one against central differences of the exact sum, the
    // hierarchy's within its bound of it.
    double exactGradient[3] = { 0, 0, 0 };
    for (size_t t = 0; t < mesh.Triangles.size(); t += 3)
    {
      double g[3];
      TriangleSolidAngleGradient(&mesh.Points[3 * mesh.Triangles[t]],
        &mesh.Points[3 * mesh.Triangles[t + 1]],
        &mesh.Points[3 * mesh.Triangles[t + 2]],
        q,
        g);
      for (int a = 0; a < 3; ++a)
      {
        exactGradient[a] += g[a] / (4 * M_PI);
      }
    }
    if (w.TriangleCount() * 3 == int64_t(mesh.Triangles.size()))
    {
      // Exact() (a product of complex numbers with a count of turns) against a plain sum
      // of atan2's.
      double sum = 0;
      for (size_t t = 0; t < mesh.Triangles.size(); t += 3)
      {
        double p[3][3];
        for (int k = 0; k < 3; ++k)
        {
          for (int a = 0; a < 3; ++a)
          {
            p[k][a] = mesh.Points[3 * mesh.Triangles[t + k] + a] - q[a];
          }
        }
        const double l[3] = { std::sqrt(p[0][0] * p[0][0] + p[0][1] * p[0][1] + p[0][2] * p[0][2]),
          std::sqrt(p[1][0] * p[1][0] + p[1][1] * p[1][1] + p[1][2] * p[1][2]),
          std::sqrt(p[2][0] * p[2][0] + p[2][1] * p[2][1] + p[2][2] * p[2][2]) };
        auto dot = [&](int i, int j)
        { return p[i][0] * p[j][0] + p[i][1] * p[j][1] + p[i][2] * p[j][2]; };
        const double det = p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) +
          p[0][1] * (p[1][2] * p[2][0] - p[1][0] * p[2][2]) +
          p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
        sum += 2 *
          std::atan2(
            det, l[0] * l[1] * l[2] + dot(0, 1) * l[2] + dot(0, 2) * l[1] + dot(1, 2) * l[0]);
      }
      Check(std::fabs(sum / (4 * M_PI) - exact) <= 1e-12,
        "Exact() differs from the sum of atan2's (%.17g)",
        static_cast<double>(sum / (4 * M_PI) - exact));
    }
    const WindingGradient fastGradient = w.EvaluateWithGradient(q);
    Check(std::fabs(fastGradient.Value - exact) <= fastGradient.Bound + 1e-12,
      "EvaluateWithGradient's value is outside its bound (%.17g)",
      static_cast<double>(fastGradient.Value - exact));
    double gradientError = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double e = fastGradient.Gradient[a] - exactGradient[a];
      gradientError += e * e;
    }
    Check(std::sqrt(gradientError) <= fastGradient.GradientBound + 1e-9,
      "the gradient is outside its bound (%.17g)",
      static_cast<double>(std::sqrt(gradientError)));
    if (fastGradient.GradientBound > 0)
    {
      worstGradientRatio =
        std::max(worstGradientRatio, std::sqrt(gradientError) / fastGradient.GradientBound);
    }
    if (i % 10 == 0)
    {
      // Central differences, where the step stays clear of the surface (HessianBound
      // finite over the step's ball) and the triangles are not repeated (w.Exact sums
      // the kept ones, the gradient above every one given).
      const double step = 1e-5;
      if (w.HessianBound(q, 2 * step) < HUGE_VAL &&
        w.TriangleCount() * 3 == int64_t(mesh.Triangles.size()))
      {
        for (int a = 0; a < 3; ++a)
        {
          double plus[3] = { q[0], q[1], q[2] }, minus[3] = { q[0], q[1], q[2] };
          plus[a] += step;
          minus[a] -= step;
          const double difference = (w.Exact(plus) - w.Exact(minus)) / (2 * step);
          Check(std::fabs(difference - exactGradient[a]) <= 1e-5 * (1 + std::fabs(difference)),
            "the exact gradient differs from central differences (%.17g)",
            static_cast<double>(difference - exactGradient[a]));
        }
      }
      // The Hessian bound: the first-order Taylor remainder over a ball.
      const double radius = Uniform(0.01, 0.3);
      const double hessian = w.HessianBound(q, radius);
      if (hessian < HUGE_VAL)
      {
        for (int s = 0; s < 5; ++s)
        {
          double y[3], r2 = 0, linear = exact;
          for (int a = 0; a < 3; ++a)
          {
            const double o = Uniform(-radius, radius) / std::sqrt(3.0);
            y[a] = q[a] + o;
            r2 += o * o;
            linear += exactGradient[a] * o;
          }
          const double remainder = std::fabs(w.Exact(y) - linear);
          Check(remainder <= 0.5 * r2 * hessian + 1e-12,
            "the first-order remainder exceeds the Hessian bound (%.17g)",
            static_cast<double>(remainder));
          if (remainder > 1e-12)
          {
            worstHessianRatio = std::max(worstHessianRatio, remainder / (0.5 * r2 * hessian));
          }
        }
      }
    }
  }
  std::printf("%-22s %7lld triangles: %d queries, error at most %.2f of its bound (gradient "
              "%.2f, first-order remainder %.2f), %d evaluated exactly\n",
    name,
    static_cast<long long>(w.TriangleCount()),
    queries,
    worstRatio,
    worstGradientRatio,
    worstHessianRatio,
    exactCalls);
  return exactCalls;
}
/// WindingSignsGPU against WindingSigns deciding every sample alone, on a grid around the
/// mesh whose samples fall on some of its planes (z = 0, x = 0): the same arithmetic, so
/// the same bits: every sign, every value, and the same samples taken to the exact sum.
/// With accuracy 1.01 nearly every sample goes to the exact sum, the GPU's product of
/// complex numbers with its count of turns. A `budget` of loop iterations (0: the
/// context's) below what the samples need sends some to the CPU: the same bits again.
/// Returns how many went there.
int64_t CheckGPU(HeadlessGL& gl,
  const char* name,
  const Mesh& mesh,
  double accuracy,
  int budget = 0)
{
  WindingNumber w;
  w.Build(mesh.Points, mesh.Triangles, accuracy);
  SampleGrid grid;
  grid.Origin = { -1.25, -1.25, -1.25 };
  grid.Spacing = { 0.125, 0.125, 0.125 };
  grid.Whole.Lo = { 0, 0, 0 };
  grid.Whole.Hi = { 20, 20, 20 };
  const int64_t n = grid.Whole.Count();
  int64_t toCPU = 0;
  for (const bool values : { false, true })
  {
    std::vector<uint8_t> cpu(n), gpu(n);
    std::vector<float> cpuValues(n), gpuValues(n);
    WindingSignOptions single;
    single.Blocks = false;
    WindingSignOptions gpuOptions;
    gpuOptions.IterationBudget = budget;
    if (values)
    {
      single.Value = cpuValues.data();
      gpuOptions.Value = gpuValues.data();
    }
    const WindingSignStatistics a =
      WindingSigns(w, grid, grid.Whole, cpu.data(), single, ThreadFor);
    WindingSignStatistics b;
    std::string error;
    if (!WindingSignsGPU(gl, w, grid, grid.Whole, gpu.data(), gpuOptions, ThreadFor, b, error))
    {
      Check(false, "%s", std::string(("the GPU pass failed: " + error).c_str()).c_str());
      return toCPU;
    }
    int64_t signsDiffer = 0, valuesDiffer = 0;
    for (int64_t v = 0; v < n; ++v)
    {
      signsDiffer += cpu[v] != gpu[v];
      valuesDiffer += std::memcmp(&cpuValues[v], &gpuValues[v], sizeof(float)) != 0;
    }
    std::printf("%-22s GPU at accuracy %.2f%s, budget %d: %lld samples, %lld (CPU) and %lld "
                "(GPU) exact, %lld left to the CPU; %lld signs and %lld values differ\n",
      name,
      accuracy,
      values ? " with values" : "",
      budget,
      static_cast<long long>(n),
      static_cast<long long>(a.Exact),
      static_cast<long long>(b.Exact),
      static_cast<long long>(b.CPUSamples),
      static_cast<long long>(signsDiffer),
      static_cast<long long>(valuesDiffer));
    Check(signsDiffer == 0,
      "the GPU's signs differ from the CPU's (%.17g)",
      static_cast<double>(signsDiffer));
    Check(valuesDiffer == 0,
      "the GPU's values differ from the CPU's (%.17g)",
      static_cast<double>(valuesDiffer));
    Check(a.Exact == b.Exact,
      "the GPU took other samples to the exact sum (%.17g)",
      static_cast<double>(b.Exact));
    Check(b.Evaluated == n, "the GPU missed samples (%.17g)", static_cast<double>(b.Evaluated));
    // At the context's budget only exact sums over more triangles than that leave the
    // GPU (the tests' walks fit llvmpipe's loop limit); a budget of 60 cuts most walks.
    const bool longSums = w.TriangleCount() >= gl.InvocationLoopBudget();
    Check(budget > 0 || b.CPUSamples <= (longSums ? a.Exact : 0),
      "samples left to the CPU at the context's budget (%.17g)",
      static_cast<double>(b.CPUSamples));
    Check(budget == 0 || budget > 100 || b.CPUSamples > n / 2,
      "a budget of %d left few samples to the CPU (%.17g)",
      budget,
      static_cast<double>(b.CPUSamples));
    toCPU += b.CPUSamples;
  }
  return toCPU;
}

Mesh OpenSphere(const Mesh& sphere)
{
  Mesh open;
  open.Points = sphere.Points;
  for (size_t t = 0; t < sphere.Triangles.size(); t += 3)
  {
    if (sphere.Points[3 * sphere.Triangles[t] + 2] < 0.6)
    {
      open.Triangles.insert(
        open.Triangles.end(), sphere.Triangles.begin() + t, sphere.Triangles.begin() + t + 3);
    }
  }
  return open;
}
} // namespace

/// An axis-aligned box, outward (inward when flipped), 12 triangles, appended to m.
void AddBox(Mesh& m, const double lo[3], const double hi[3], bool flipped = false)
{
  const int64_t base = static_cast<int64_t>(m.Points.size() / 3);
  for (int c = 0; c < 8; ++c)
  {
    m.Points.insert(
      m.Points.end(), { c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2] });
  }
  // Corner c has bits x, y, z; each face as two triangles, outward.
  const int faces[6][4] = {
    { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 }
  };
  for (const auto& f : faces)
  {
    const int64_t t[6] = { f[0], f[1], f[2], f[0], f[2], f[3] };
    for (int k = 0; k < 6; k += 3)
    {
      m.Triangles.insert(m.Triangles.end(),
        { base + t[k],
          base + (flipped ? t[k + 2] : t[k + 1]),
          base + (flipped ? t[k + 1] : t[k + 2]) });
    }
  }
}

/// The crossings' route (closed meshes) against every sample decided alone, on meshes
/// whose corners lie on the grid's lattice: lines through projected edges and corners,
/// samples on faces, edges and corners, triangles seen edge-on, overlaps, folds.
void CheckCrossings()
{
  std::vector<std::pair<const char*, Mesh>> meshes(9);
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 2, 1.5, 2.5 };
  meshes[0].first = "box on the lattice";
  AddBox(meshes[0].second, lo, hi);
  meshes[1].first = "hollow box (flipped box inside)";
  AddBox(meshes[1].second, lo, hi);
  const double innerLo[3] = { 0.5, 0.5, 0.5 }, innerHi[3] = { 1.5, 1, 2 };
  AddBox(meshes[1].second, innerLo, innerHi, true);
  meshes[2].first = "two overlapping boxes";
  AddBox(meshes[2].second, lo, hi);
  const double otherLo[3] = { 1, 0.5, -0.5 }, otherHi[3] = { 3, 2.5, 1.5 };
  AddBox(meshes[2].second, otherLo, otherHi);
  // The sphere scaled and its corners snapped to the lattice: degenerate and repeated
  // triangles, coincident corners, folds; still a closed chain.
  meshes[3].first = "snapped sphere";
  meshes[3].second = Sphere(2);
  for (double& x : meshes[3].second.Points)
  {
    x = std::round(3 * x) / 2 + 1;
  }
  meshes[4].first = "octahedron on the lattice";
  meshes[4].second.Points = { 2, 1, 1, 0, 1, 1, 1, 2, 1, 1, 0, 1, 1, 1, 2, 1, 1, 0 };
  meshes[4].second.Triangles = {
    0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5
  };
  // Open meshes, closed by cones over their boundaries: a box without a face's triangle
  // and without a whole face, and the hollow box with a hole in each shell.
  meshes[5].first = "box without a triangle (open)";
  meshes[5].second = meshes[0].second;
  meshes[5].second.Triangles.resize(meshes[5].second.Triangles.size() - 3);
  meshes[6].first = "box without a face (open)";
  meshes[6].second = meshes[0].second;
  meshes[6].second.Triangles.erase(
    meshes[6].second.Triangles.begin(), meshes[6].second.Triangles.begin() + 6);
  meshes[7].first = "hollow box with holes (open)";
  meshes[7].second = meshes[1].second;
  meshes[7].second.Triangles.erase(
    meshes[7].second.Triangles.begin() + 36, meshes[7].second.Triangles.begin() + 39);
  meshes[7].second.Triangles.erase(
    meshes[7].second.Triangles.begin(), meshes[7].second.Triangles.begin() + 3);
  // Two cups on one rim (their tops removed): every rim edge is used twice more in one
  // direction, so two cones close them.
  meshes[8].first = "two cups on one rim (open)";
  const double cupLo[3] = { 0, 0, 1 };
  AddBox(meshes[8].second, lo, hi);
  AddBox(meshes[8].second, cupLo, hi);
  for (const int top : { 36 + 6, 6 })
  {
    meshes[8].second.Triangles.erase(
      meshes[8].second.Triangles.begin() + top, meshes[8].second.Triangles.begin() + top + 6);
  }
  SampleGrid lattice;
  lattice.Origin = { -1, -1, -1 };
  lattice.Spacing = { 0.5, 0.25, 0.5 };
  lattice.Whole.Lo = { 0, 0, 0 };
  lattice.Whole.Hi = { 12, 16, 10 };
  const int64_t n = lattice.Whole.Count();
  const SampleGrid& grid = lattice;
  for (const auto& [name, mesh] : meshes)
  {
    WindingNumber w;
    w.Build(mesh.Points, mesh.Triangles);
    const bool open = std::string(name).find("open") != std::string::npos;
    Check(IsClosedChain(mesh.Points, mesh.Triangles) != open, "%s: closed or not", name);
    std::vector<uint8_t> lines(n), alone(n);
    WindingSignOptions single;
    single.Blocks = false;
    const WindingSignStatistics a =
      WindingSigns(w, grid, grid.Whole, lines.data(), WindingSignOptions(), ThreadFor);
    WindingSigns(w, grid, grid.Whole, alone.data(), single, ThreadFor);
    int64_t differ = 0, inside = 0;
    for (int64_t v = 0; v < n; ++v)
    {
      differ += lines[v] != alone[v];
      inside += lines[v];
    }
    std::printf("%s: %lld samples by lines, %lld by blocks, %lld alone, %lld inside, %lld "
                "differ from every sample alone\n",
      name,
      static_cast<long long>(a.LineSamples),
      static_cast<long long>(a.BlockSamples),
      static_cast<long long>(a.Evaluated),
      static_cast<long long>(inside),
      static_cast<long long>(differ));
    Check(differ == 0 && a.LineSamples + a.BlockSamples + a.Evaluated == n && a.Evaluated > 0 &&
        inside > 0 && a.LineSamples > 0 && (a.BlockSamples > 0) == open,
      "%s: the crossings decide as every sample alone (%.17g differ)",
      name,
      static_cast<double>(differ));
  }
  // The closed meshes scaled (with a grid a quarter step off the lattice, so that no
  // sample is on the surface) by powers of two, which keep every coincidence: near the
  // least and the largest doubles the exact predicates decide alone (the hierarchy's
  // sums under- and overflow there: ComputeWindingSigns scales such input first, below).
  SampleGrid shifted = lattice;
  for (int a = 0; a < 3; ++a)
  {
    shifted.Origin[a] += 0.25 * shifted.Spacing[a];
  }
  // A mesh and the shifted grid scaled by `scale`.
  const auto scaledMesh = [](Mesh mesh, double scale)
  {
    for (double& x : mesh.Points)
    {
      x *= scale;
    }
    return mesh;
  };
  const auto scaledGrid = [&shifted](double scale)
  {
    SampleGrid scaled = shifted;
    for (int a = 0; a < 3; ++a)
    {
      scaled.Origin[a] *= scale;
      scaled.Spacing[a] *= scale;
    }
    return scaled;
  };
  for (size_t m = 0; m < 5; ++m)
  {
    std::vector<uint8_t> reference(n);
    for (const double scale : { 1.0, std::ldexp(1.0, -1000), std::ldexp(1.0, 1000) })
    {
      const Mesh mesh = scaledMesh(meshes[m].second, scale);
      const SampleGrid scaled = scaledGrid(scale);
      WindingNumber w;
      w.Build(mesh.Points, mesh.Triangles);
      std::vector<uint8_t> lines(n);
      const WindingSignStatistics a =
        WindingSigns(w, scaled, scaled.Whole, lines.data(), WindingSignOptions(), ThreadFor);
      if (scale == 1)
      {
        WindingSignOptions single;
        single.Blocks = false;
        WindingSigns(w, scaled, scaled.Whole, reference.data(), single, ThreadFor);
      }
      Check(lines == reference && a.LineSamples == n,
        "%s scaled by %g: the crossings decide as every sample alone at scale 1",
        meshes[m].first,
        scale);
    }
  }
  // Every mesh, open ones included, through the family's entry point at 2^+-1000: every
  // sample decided alone by the hierarchy, and the default routes, as at scale 1 (the
  // entry scales such coordinates by a power of two first).
  for (const auto& [name, original] : meshes)
  {
    std::vector<uint8_t> reference(n);
    for (const double scale : { 1.0, std::ldexp(1.0, -1000), std::ldexp(1.0, 1000) })
    {
      const Mesh mesh = scaledMesh(original, scale);
      const SampleGrid scaled = scaledGrid(scale);
      for (const bool blocks : { false, true })
      {
        WindingSignOptions options;
        options.Blocks = blocks;
        std::vector<uint8_t> signs(n);
        WindingSignStatistics stats;
        std::string error;
        ComputeWindingSigns(mesh.Points,
          mesh.Triangles,
          scaled,
          scaled.Whole,
          signs.data(),
          options,
          nullptr,
          ThreadFor,
          stats,
          error);
        if (scale == 1 && !blocks)
        {
          reference = signs;
        }
        int64_t inside = 0;
        for (const uint8_t sign : signs)
        {
          inside += sign;
        }
        Check(signs == reference && inside > 0,
          "%s scaled by %g, %s: the signs differ from every sample alone at scale 1",
          name,
          scale,
          blocks ? "routes" : "every sample alone");
      }
    }
  }
  // An open box (one triangle missing) is not a closed chain; a box with a repeated
  // corner point (same coordinates, another id) is.
  Mesh open = meshes[0].second;
  open.Triangles.resize(open.Triangles.size() - 3);
  Check(!IsClosedChain(open.Points, open.Triangles), "an open box is not a closed chain");
  // A box with a triangle repeated (the winding number counts it once): not closed.
  Mesh repeated = meshes[0].second;
  repeated.Triangles.insert(repeated.Triangles.end(), { 0, 2, 3 });
  Check(!IsClosedChain(repeated.Points, repeated.Triangles), "a repeated triangle is not closed");
  // A box whose corners are repeated points (same coordinates, other ids): closed.
  Mesh split = meshes[0].second;
  for (size_t t = 0; t < split.Triangles.size(); t += 3)
  {
    const int64_t copy = static_cast<int64_t>(split.Points.size() / 3);
    const double* from = &split.Points[3 * split.Triangles[t]];
    const double corner[3] = { from[0], from[1], from[2] };
    split.Points.insert(split.Points.end(), corner, corner + 3);
    split.Triangles[t] = copy;
  }
  Check(IsClosedChain(split.Points, split.Triangles), "a box with split points is closed");
}

int main(int argc, char* argv[])
{
  if (argc > 1 && std::string(argv[1]) == "gpu")
  {
    HeadlessGL* gl = vtkdf::coretest::GLContext();
    if (!gl)
    {
      return 1;
    }
    const Mesh sphere = Sphere(3); // 512 triangles
    Mesh flipped = sphere;
    for (size_t t = 0; t < flipped.Triangles.size(); t += 3)
    {
      std::swap(flipped.Triangles[t + 1], flipped.Triangles[t + 2]);
    }
    for (const double accuracy : { WindingNumber::DefaultAccuracy, 1.01 })
    {
      CheckGPU(*gl, "closed sphere", sphere, accuracy);
      CheckGPU(*gl, "flipped sphere", flipped, accuracy);
      CheckGPU(*gl, "open sphere", OpenSphere(sphere), accuracy);
      // Samples just below a sheet have |w| near 1/2: the exact sum decides them and gives
      // their values.
      Mesh sheet;
      sheet.Points = { -1.1, -1.1, 0.001, 1.1, -1.1, 0.001, 1.1, 1.1, 0.001, -1.1, 1.1, 0.001 };
      sheet.Triangles = { 0, 1, 2, 0, 2, 3 };
      CheckGPU(*gl, "sheet", sheet, accuracy);
    }
    {
      // The sheet in 70,688 triangles, more than llvmpipe's loop limit: the exact sums
      // below it would be cut short there, and go to the CPU instead.
      Mesh sheet;
      const int m = 188;
      for (int j = 0; j <= m; ++j)
      {
        for (int i = 0; i <= m; ++i)
        {
          sheet.Points.insert(
            sheet.Points.end(), { -1.1 + 2.2 * i / m, -1.1 + 2.2 * j / m, 0.001 });
        }
      }
      for (int j = 0; j < m; ++j)
      {
        for (int i = 0; i < m; ++i)
        {
          const int64_t c = int64_t(j) * (m + 1) + i;
          sheet.Triangles.insert(
            sheet.Triangles.end(), { c, c + 1, c + m + 2, c, c + m + 2, c + m + 1 });
        }
      }
      const int64_t toCPU = CheckGPU(*gl, "sheet of 70,688", sheet, WindingNumber::DefaultAccuracy);
      Check(!gl->IsSoftware() || toCPU > 0, "the large sheet's exact sums stayed on llvmpipe");
    }
    // Budgets that cut the walks (60) and the exact sums (700: the sphere's 512
    // triangles fit after a short walk, not after a long one).
    for (const int budget : { 60, 700 })
    {
      CheckGPU(*gl, "closed sphere", sphere, 1.01, budget);
      CheckGPU(*gl, "open sphere", OpenSphere(sphere), WindingNumber::DefaultAccuracy, budget);
    }
    return Verdict();
  }

  CheckCrossings();
  const Mesh sphere = Sphere(4); // 2048 triangles
  {
    WindingNumber w;
    w.Build(sphere.Points, sphere.Triangles);
    double worst = 0;
    for (int i = 0; i < 2000; ++i)
    {
      const double q[3] = { Uniform(-1.5, 1.5), Uniform(-1.5, 1.5), Uniform(-1.5, 1.5) };
      const double r = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
      if (std::fabs(r - 1) < 0.05)
      {
        continue; // near the polyhedron's surface, which is not the unit sphere's
      }
      worst = std::max(worst, std::fabs(w.Exact(q) - (r < 1 ? 1 : 0)));
    }
    std::printf("closed sphere: exact w within %.2g of 1 inside and 0 outside\n", worst);
    Check(worst <= 1e-9,
      "a closed sphere's w is not 1 inside and 0 outside (%.17g)",
      static_cast<double>(worst));
  }
  CheckMesh("closed sphere", sphere, 3000);
  CheckMesh("closed sphere, accuracy 2", sphere, 300, 2);
  {
    Mesh flipped = sphere;
    for (size_t t = 0; t < flipped.Triangles.size(); t += 3)
    {
      std::swap(flipped.Triangles[t + 1], flipped.Triangles[t + 2]);
    }
    WindingNumber w;
    w.Build(flipped.Points, flipped.Triangles);
    const double centre[3] = { 0.1, -0.2, 0.05 };
    std::printf("flipped sphere: w = %.12f at the centre\n", w.Exact(centre));
    Check(std::fabs(w.Exact(centre) + 1) <= 1e-9 && w.Inside(centre),
      "a flipped sphere is not w = -1, inside (%.17g)",
      static_cast<double>(w.Exact(centre)));
    CheckMesh("flipped sphere", flipped, 1000);

    // Opposite copies cancel; repeated ones count once.
    Mesh both = sphere, twice = sphere;
    const int64_t offset = static_cast<int64_t>(sphere.Points.size() / 3);
    both.Points.insert(both.Points.end(), flipped.Points.begin(), flipped.Points.end());
    twice.Points.insert(twice.Points.end(), sphere.Points.begin(), sphere.Points.end());
    for (size_t t = 0; t < sphere.Triangles.size(); ++t)
    {
      both.Triangles.push_back(flipped.Triangles[t] + offset);
      // The same triangle from another corner: the same cyclic order.
      twice.Triangles.push_back(sphere.Triangles[t - t % 3 + (t % 3 + 1) % 3] + offset);
    }
    WindingNumber wb, wt;
    wb.Build(both.Points, both.Triangles);
    wt.Build(twice.Points, twice.Triangles);
    std::printf("sphere + flipped copy: w = %.2g; sphere twice: %lld triangles kept, w = %.12f\n",
      wb.Exact(centre),
      static_cast<long long>(wt.TriangleCount()),
      wt.Exact(centre));
    Check(std::fabs(wb.Exact(centre)) <= 1e-9,
      "opposite copies do not cancel (%.17g)",
      static_cast<double>(wb.Exact(centre)));
    Check(wt.TriangleCount() == static_cast<int64_t>(sphere.Triangles.size() / 3),
      "repeated triangles are not kept once (%.17g)",
      static_cast<double>(static_cast<double>(wt.TriangleCount())));
    Check(std::fabs(wt.Exact(centre) - 1) <= 1e-9,
      "a repeated sphere is not w = 1 (%.17g)",
      static_cast<double>(wt.Exact(centre)));
  }
  {
    // An open sphere: the triangles above z = 0.7 removed.
    Mesh open;
    open.Points = sphere.Points;
    for (size_t t = 0; t < sphere.Triangles.size(); t += 3)
    {
      double z = 0;
      for (int k = 0; k < 3; ++k)
      {
        z += sphere.Points[3 * sphere.Triangles[t + k] + 2] / 3;
      }
      if (z < 0.7)
      {
        open.Triangles.insert(
          open.Triangles.end(), sphere.Triangles.begin() + t, sphere.Triangles.begin() + t + 3);
      }
    }
    CheckMesh("open sphere", open, 3000);
  }
  {
    // A soup: random triangles, some large, some tiny, some degenerate.
    Mesh soup;
    for (int t = 0; t < 3000; ++t)
    {
      const double size = t % 3 == 0 ? 0.8 : 0.05;
      const double c[3] = { Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1) };
      for (int k = 0; k < 3; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          soup.Points.push_back(t % 97 == 0 && k == 2 ? soup.Points[soup.Points.size() - 3]
                                                      : c[a] + size * Uniform(-1, 1));
        }
        soup.Triangles.push_back(3 * t + k);
      }
    }
    CheckMesh("soup", soup, 2000);
  }
  {
    // A sheet folded onto itself: two coincident squares with opposite orientations,
    // whose vector areas cancel in every node (the bound must not).
    Mesh folded;
    const int n = 24;
    for (int side = 0; side < 2; ++side)
    {
      const int64_t base = static_cast<int64_t>(folded.Points.size() / 3);
      for (int j = 0; j <= n; ++j)
      {
        for (int i = 0; i <= n; ++i)
        {
          folded.Points.insert(
            folded.Points.end(), { -1 + 2.0 * i / n, -1 + 2.0 * j / n, side * 1e-3 });
        }
      }
      for (int j = 0; j < n; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          const int64_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
          if (side == 0)
          {
            folded.Triangles.insert(folded.Triangles.end(), { a, b, d, a, d, c });
          }
          else
          {
            folded.Triangles.insert(folded.Triangles.end(), { a, d, b, a, c, d });
          }
        }
      }
    }
    CheckMesh("folded sheet", folded, 2000);
  }
  {
    // WindingSigns on a 32^3 grid around the closed and the open sphere.
    const Mesh open = OpenSphere(sphere);
    for (const Mesh* mesh : std::vector<const Mesh*>{ &sphere, &open })
    {
      WindingNumber w;
      w.Build(mesh->Points, mesh->Triangles);
      SampleGrid grid;
      grid.Origin = { -1.3, -1.3, -1.3 };
      grid.Spacing = { 2.6 / 31, 2.6 / 31, 2.6 / 31 };
      grid.Whole.Lo = { 0, 0, 0 };
      grid.Whole.Hi = { 31, 31, 31 };
      const int64_t n = grid.Whole.Count();
      std::vector<uint8_t> blocked(n), alone(n), valued(n), skipping(n);
      std::vector<float> values(n), distance(n);
      for (int64_t v = 0; v < n; ++v)
      {
        // Distance to the unit sphere, which the mesh approximates: WindingSigns uses it
        // only to skip attempts, so an approximation must not change any sign.
        const double q[3] = { grid.Coordinate(0, v % 32),
          grid.Coordinate(1, (v / 32) % 32),
          grid.Coordinate(2, v / 1024) };
        distance[v] =
          static_cast<float>(std::fabs(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - 1));
      }
      WindingSignOptions blocks, single, near, valuesToo;
      single.Blocks = false;
      near.Distance = distance.data();
      valuesToo.Value = values.data();
      const WindingSignStatistics a =
        WindingSigns(w, grid, grid.Whole, blocked.data(), blocks, ThreadFor);
      const WindingSignStatistics b =
        WindingSigns(w, grid, grid.Whole, alone.data(), single, ThreadFor);
      const WindingSignStatistics c =
        WindingSigns(w, grid, grid.Whole, skipping.data(), near, ThreadFor);
      WindingSigns(w, grid, grid.Whole, valued.data(), valuesToo, ThreadFor);
      int64_t wrong = 0, differ = 0, outOfBound = 0;
      for (int64_t v = 0; v < n; ++v)
      {
        const double q[3] = { grid.Coordinate(0, v % 32),
          grid.Coordinate(1, (v / 32) % 32),
          grid.Coordinate(2, v / 1024) };
        const double exact = w.Exact(q);
        differ += blocked[v] != alone[v] || valued[v] != alone[v] || skipping[v] != alone[v];
        if (std::fabs(std::fabs(exact) - 0.5) > 1e-9)
        {
          wrong += alone[v] != (std::fabs(exact) > 0.5);
        }
        const WindingValue fast = w.Evaluate(q, WindingNumber::ValueAccuracy);
        const double used =
          std::fabs(std::fabs(fast.Value) - 0.5) > fast.Bound ? fast.Value : exact;
        outOfBound += std::fabs(values[v] - used) > 1e-6 * std::max(1.0, std::fabs(used));
      }
      std::printf("%s on 32^3: lines decided %lld samples, blocks %lld, %lld alone (%lld "
                  "exact); with distances %lld and %lld; every sample alone: %lld exact; %lld "
                  "differ, %lld wrong, %lld values off\n",
        mesh == &sphere ? "closed sphere" : "open sphere",
        static_cast<long long>(a.LineSamples),
        static_cast<long long>(a.BlockSamples),
        static_cast<long long>(a.Evaluated),
        static_cast<long long>(a.Exact),
        static_cast<long long>(c.BlockSamples + c.LineSamples),
        static_cast<long long>(c.Evaluated),
        static_cast<long long>(b.Exact),
        static_cast<long long>(differ),
        static_cast<long long>(wrong),
        static_cast<long long>(outOfBound));
      Check(differ == 0,
        "blocks and single samples decide differently (%.17g)",
        static_cast<double>(double(differ)));
      Check(wrong == 0,
        "a sign differs from the exact sum's (%.17g)",
        static_cast<double>(double(wrong)));
      Check(outOfBound == 0,
        "a written value is not the evaluation's (%.17g)",
        static_cast<double>(double(outOfBound)));
      Check(a.BlockSamples + a.LineSamples + a.Evaluated == n && b.Evaluated == n &&
          c.BlockSamples + c.LineSamples + c.Evaluated == n,
        "samples missed (%.17g)",
        static_cast<double>(double(a.BlockSamples + a.LineSamples + a.Evaluated)));
      // The closed sphere takes the crossings' route alone; the open one is closed by a
      // cone over its hole, and blocks decide w = N - w_cone.
      Check(mesh == &sphere ? a.BlockSamples == 0 && a.LineSamples == n : a.BlockSamples > 0,
        "the route (%.17g samples by lines)",
        static_cast<double>(a.LineSamples));
    }
  }
  return Verdict();
}
