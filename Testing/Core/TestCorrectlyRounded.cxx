// Shaders/CorrectlyRounded.glsl: SqrtRN and DivRN give IEEE 754's results (std::sqrt and
// the quotient, bit for bit) on this context's GL, from the driver's own sqrt and
// division, from seeds spoilt to about single precision (the GLSL minimum) and from seeds
// an ulp or two off (NVIDIA's sqrt). Also prints how far the driver's own double sqrt and
// division are from IEEE's (a reading of the GL, not a check).
#include "CoreTest.h"
#include "GLCoreTest.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace vtkdf;

namespace
{
// Four results per input: the seeds of sqrt(x) and x / y (the driver's, or spoilt),
// SqrtRN(x), DivRN(x, y).
const char* const Shader = R"glsl(#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs
{
  double operand[];
};
layout(std430, binding = 1) writeonly buffer Outputs
{
  double result[];
};
uniform int Count;
#if SEEDS == 1
// The driver's value rounded to single precision and off by up to 4 of its ulps.
double Spoilt(double v)
{
  return double(float(v)) * (1.0lf + 1.2e-7lf * double(int(gl_GlobalInvocationID.x % 9u) - 4));
}
#define DF_SEED_SQRT(x) Spoilt(sqrt(x))
#define DF_SEED_DIV(a, b) Spoilt((a) / (b))
#elif SEEDS == 2
// The driver's value moved by -2 to 2 ulps (a finite, nonzero one).
double Spoilt(double v)
{
  if (v == 0.0lf || isinf(v) || isnan(v))
  {
    return v;
  }
  uvec2 bits = unpackDouble2x32(v);
  int by = int(gl_GlobalInvocationID.x % 5u) - 2;
  for (; by > 0; --by)
  {
    bits.x += 1u;
    bits.y += bits.x == 0u ? 1u : 0u;
  }
  for (; by < 0; ++by)
  {
    bits.y -= bits.x == 0u ? 1u : 0u;
    bits.x -= 1u;
  }
  return packDouble2x32(bits);
}
#define DF_SEED_SQRT(x) Spoilt(sqrt(x))
#define DF_SEED_DIV(a, b) Spoilt((a) / (b))
#endif
//DF::CorrectlyRounded
void main()
{
  int i = int(gl_GlobalInvocationID.x);
  if (i >= Count)
  {
    return;
  }
  precise double x = operand[2 * i], y = operand[2 * i + 1];
  precise double root = DF_SEED_SQRT(x), quotient = DF_SEED_DIV(x, y);
  result[4 * i] = root;
  result[4 * i + 1] = quotient;
  result[4 * i + 2] = SqrtRN(x);
  result[4 * i + 3] = DivRN(x, y);
}
)glsl";

int64_t UlpsApart(double a, double b)
{
  int64_t ia, ib;
  std::memcpy(&ia, &a, 8);
  std::memcpy(&ib, &b, 8);
  return ia > ib ? ia - ib : ib - ia; // both of one sign here
}

bool Same(double a, double b)
{
  return std::memcmp(&a, &b, 8) == 0 || (std::isnan(a) && std::isnan(b));
}

/// Operand pairs: spread over magnitudes, near 1, exact squares and their neighbours,
/// exact quotients and their neighbours, sums of squares of unit vectors' components,
/// negative divisors and dividends.
std::vector<double> Operands()
{
  std::mt19937_64 random(20261127);
  std::uniform_real_distribution<double> unit(0, 1), exponent(-60, 60);
  std::vector<double> pairs;
  auto add = [&](double x, double y)
  {
    pairs.push_back(x);
    pairs.push_back(y);
  };
  for (int i = 0; i < 60000; ++i)
  {
    add(std::exp2(exponent(random)) * (1 + unit(random)),
      std::exp2(exponent(random)) * (1 + unit(random)));
    add(1 + (unit(random) - 0.5) * 1e-8, 1 + (unit(random) - 0.5) * 1e-12);
    const double s = 1 + unit(random), q = 1 + unit(random), b = 1 + unit(random);
    const double square = s * s, product = q * b; // rounded: near the halfway cases
    add(square, b);
    add(std::nextafter(square, 4.0), product);
    add(std::nextafter(square, 0.0), -b);
    add(-product, b);
    double v[3] = { unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5 };
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double u[3] = { v[0] / n, v[1] / n, v[2] / n };
    add(u[0] * u[0] + u[1] * u[1] + u[2] * u[2], n);
  }
  // Exact roots and quotients: the Newton steps must not leave them.
  for (int i = 1; i <= 4096; ++i)
  {
    add(double(i) * i, double(i));
    add(double(i) * 3, 3.0);
  }
  return pairs;
}

/// Runs the shader (seeds: 0 the driver's, 1 spoilt, 2 nudged) over the operand pairs;
/// false when GL failed.
bool Run(HeadlessGL& context,
  int seeds,
  const std::vector<double>& pairs,
  std::vector<double>& results)
{
  const std::string source = std::string(Shader).replace(
    std::string(Shader).find('\n') + 1, 0, "#define SEEDS " + std::to_string(seeds) + "\n");
  return coretest::RunDoubleShader(
    context, source, pairs, static_cast<int>(pairs.size() / 2), 4, results);
}
} // namespace

int main()
{
  HeadlessGL* gl = vtkdf::coretest::GLContext();
  if (!gl)
  {
    return 1;
  }
  const std::vector<double> pairs = Operands();
  const size_t count = pairs.size() / 2;
  const char* seedNames[3] = { "the driver's", "spoilt", "nudged" };
  for (int seeds = 0; seeds < 3; ++seeds)
  {
    const bool spoil = seeds > 0;
    std::vector<double> results;
    if (!Run(*gl, seeds, pairs, results))
    {
      return vtkdf::coretest::Verdict();
    }
    int64_t driverSqrt = 0, driverDiv = 0, worstSqrt = 0, worstDiv = 0, badSqrt = 0, badDiv = 0;
    for (size_t i = 0; i < count; ++i)
    {
      const double x = pairs[2 * i], y = pairs[2 * i + 1];
      const double root = std::sqrt(x), quotient = x / y;
      const double* r = &results[4 * i];
      if (spoil)
      {
        driverSqrt += !Same(r[0], root);
        driverDiv += !Same(r[1], quotient);
      }
      else
      {
        driverSqrt += !Same(r[0], root);
        driverDiv += !Same(r[1], quotient);
        worstSqrt = std::max(worstSqrt, UlpsApart(r[0], root));
        worstDiv = std::max(worstDiv, UlpsApart(r[1], quotient));
      }
      if (!Same(r[2], root) && ++badSqrt <= 5)
      {
        std::printf(
          "SqrtRN(%.17g) = %.17g, IEEE %.17g (%s seeds)\n", x, r[2], root, seedNames[seeds]);
      }
      if (!Same(r[3], quotient) && ++badDiv <= 5)
      {
        std::printf("DivRN(%.17g, %.17g) = %.17g, IEEE %.17g (%s seeds)\n",
          x,
          y,
          r[3],
          quotient,
          seedNames[seeds]);
      }
    }
    if (spoil)
    {
      // Else the refinement would not be under test.
      vtkdf::coretest::Check(driverSqrt > int64_t(count) / 2 && driverDiv > int64_t(count) / 2,
        "the %s seeds are IEEE's in too many cases (%lld and %lld of %zu differ)",
        seedNames[seeds],
        (long long)driverSqrt,
        (long long)driverDiv,
        count);
    }
    else
    {
      std::printf("the driver's double sqrt: %lld of %zu differ from IEEE's, by up to %lld "
                  "ulps; its division: %lld differ, by up to %lld ulps\n",
        (long long)driverSqrt,
        count,
        (long long)worstSqrt,
        (long long)driverDiv,
        (long long)worstDiv);
    }
    vtkdf::coretest::Check(badSqrt == 0 && badDiv == 0,
      "%s seeds: SqrtRN differs from IEEE's in %lld of %zu, DivRN in %lld",
      seedNames[seeds],
      (long long)badSqrt,
      count,
      (long long)badDiv);
  }
  return vtkdf::coretest::Verdict();
}
