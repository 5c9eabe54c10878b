// ArcTangent2 (Filters/Core/Common/ArcTangent.h), the arctangent that the winding
// number's CPU and GPU passes share:
// - against std::atan2 on random points of every quadrant and magnitude, on the axes,
//   near the reduction's points k/8 and the diagonals, and at huge and tiny ratios:
//   within 4 ulps of it (the result's), in [-pi, pi] and on y's side;
// - Shaders/ArcTangent2.glsl on this context's GL gives the same bits on every point.
#include "Common/ArcTangent.h"
#include "CoreTest.h"
#include "GL/GridUniforms.h"
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
//DF::CorrectlyRounded
//DF::ArcTangent2
void main()
{
  int i = int(gl_GlobalInvocationID.x);
  if (i < Count)
  {
    result[i] = ArcTangent2(operand[2 * i], operand[2 * i + 1]);
  }
}
)glsl";

int64_t UlpsApart(double a, double b)
{
  if ((a < 0) != (b < 0))
  {
    return a == b ? 0 : INT64_MAX; // +0 and -0 are one value
  }
  int64_t ia, ib;
  std::memcpy(&ia, &a, 8);
  std::memcpy(&ib, &b, 8);
  return ia > ib ? ia - ib : ib - ia;
}

/// (y, x) pairs.
std::vector<double> Points()
{
  std::mt19937_64 random(20261130);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-100, 100);
  std::vector<double> pairs;
  auto add = [&](double y, double x)
  {
    pairs.push_back(y);
    pairs.push_back(x);
  };
  for (int i = 0; i < 40000; ++i)
  {
    add(unit(random), unit(random));
    add(unit(random) * std::exp2(exponent(random)), unit(random) * std::exp2(exponent(random)));
    // Near the points k/8 of the reduction (and their midpoints), in every octant.
    const double t = std::floor((unit(random) + 1) * 8) / 16 + unit(random) * 1e-9;
    const double sy = unit(random) < 0 ? -1 : 1, sx = unit(random) < 0 ? -1 : 1;
    add(sy * t, sx * 1.0);
    add(sy * 1.0, sx * t);
  }
  for (const double s : { 1.0, -1.0 })
  {
    for (const double v : { 0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 1e300 })
    {
      add(v, s);
      add(s, v);
    }
    add(s, s);
    add(s * 3, s * 3);
    add(s * 1e-200, 1.0);
    add(1.0, s * 1e-200);
  }
  return pairs;
}

} // namespace

int main()
{
  const std::vector<double> pairs = Points();
  const size_t count = pairs.size() / 2;
  std::vector<double> cpu(count);
  int64_t worst = 0, outside = 0;
  for (size_t i = 0; i < count; ++i)
  {
    const double y = pairs[2 * i], x = pairs[2 * i + 1];
    cpu[i] = ArcTangent2(y, x);
    // std::atan2 with ArcTangent2's convention for a zero y: +0 of either sign.
    const double reference = std::atan2(y == 0 ? 0.0 : y, x);
    const int64_t apart = UlpsApart(cpu[i], reference);
    if (apart > worst)
    {
      worst = apart;
    }
    if (apart > 4)
    {
      std::printf("ArcTangent2(%.17g, %.17g) = %.17g, atan2 %.17g\n", y, x, cpu[i], reference);
    }
    // In [-pi, pi] (-pi is the rounding of an angle just above it, as atan2 gives it) and
    // on y's side.
    const bool side = y < 0 ? cpu[i] < 0 : (y > 0 ? cpu[i] > 0 : cpu[i] >= 0);
    if (!(cpu[i] >= -M_PI && cpu[i] <= M_PI && side) && ++outside <= 5)
    {
      std::printf("ArcTangent2(%.17g, %.17g) = %.17g\n", y, x, cpu[i]);
    }
  }
  std::printf("ArcTangent2 against std::atan2 on %zu points: up to %lld ulps apart\n",
    count,
    static_cast<long long>(worst));
  coretest::Check(worst <= 4, "ArcTangent2 strays from atan2 (%.17g ulps)", double(worst));
  coretest::Check(outside == 0, "results outside [-pi, pi] or y's side (%.17g)", double(outside));

  HeadlessGL* gl = coretest::GLContext();
  if (!gl)
  {
    return 1;
  }
  std::vector<double> gpu;
  if (!coretest::RunDoubleShader(*gl,
        Shader,
        pairs,
        static_cast<int>(count),
        1,
        gpu,
        [](const GLFunctions& functions, GLuint program)
        { SetArcTangentUniforms(functions, program); }))
  {
    return coretest::Verdict();
  }
  int64_t differ = 0;
  for (size_t i = 0; i < count; ++i)
  {
    if (std::memcmp(&cpu[i], &gpu[i], 8) != 0 && ++differ <= 5)
    {
      std::printf("GLSL ArcTangent2(%.17g, %.17g) = %.17g, C++ %.17g\n",
        pairs[2 * i],
        pairs[2 * i + 1],
        gpu[i],
        cpu[i]);
    }
  }
  std::printf("the shader's ArcTangent2: %lld of %zu differ from the C++ bits\n",
    static_cast<long long>(differ),
    count);
  coretest::Check(differ == 0, "the shader's ArcTangent2 differs (%.17g)", double(differ));
  return coretest::Verdict();
}
