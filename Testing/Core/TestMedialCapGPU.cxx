// The medial pass's cap search on this context's GL (Shaders/MedialAxis.comp.glsl's
// SmallestCapCosine, run by a probe in place of the pass's main) against the CPU's
// (Medial/MedialAxis.h), bit for bit, with its steps (the widest pair, the pair's cap, its
// test) on 80,000 sets of 8 directions: nearly equal ones (a cell beside a face), fans in
// a plane (beside a cylinder's axis), caps of every size and directions anywhere.
#include "CoreTest.h"
#include "GL/GLFunctions.h"
#include "GLCoreTest.h"
#include "Medial/MedialAxis.h"
#include "MedialAxis_comp.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace vtkdf;

namespace
{
constexpr int Steps = 6; // Dot(u0, u1), widest, pair index, |s|, the pair's cosine, its test
constexpr int Outputs = Steps + 1;

const char* const ProbeMain = R"glsl(
layout(std430, binding = 3) readonly buffer DirectionSets
{
  double direction[]; // 24 per set
};
layout(std430, binding = 4) writeonly buffer ProbeResults
{
  double probe[]; // 7 per set, then 3 readings per set
};
uniform int Sets;
void main()
{
  int i = int(gl_GlobalInvocationID.x);
  if (i >= Sets)
  {
    return;
  }
  for (int k = 0; k < 8; ++k)
  {
    SetU(k, dvec3(direction[24 * i + 3 * k], direction[24 * i + 3 * k + 1],
      direction[24 * i + 3 * k + 2]));
  }
  probe[7 * i] = Dot(U(0), U(1));
  int wi = 0, wj = 1;
  double widest = Dot(U(0), U(1));
  for (int a = 0; a < 8; ++a)
  {
    for (int b = a + 1; b < 8; ++b)
    {
      double c = Dot(U(a), U(b));
      if (c < widest)
      {
        widest = c;
        wi = a;
        wj = b;
      }
    }
  }
  probe[7 * i + 1] = widest;
  probe[7 * i + 2] = double(8 * wi + wj);
  precise dvec3 s = U(wi) + U(wj);
  precise double sn = SqrtRN(Dot(s, s));
  s = dvec3(DivRN(s.x, sn), DivRN(s.y, sn), DivRN(s.z, sn));
  double pairCos = Dot(s, U(wi));
  probe[7 * i + 3] = sn;
  probe[7 * i + 4] = pairCos;
  probe[7 * i + 5] = HoldsAll(s, pairCos) ? 1.0lf : 0.0lf;
  probe[7 * i + 6] = SmallestCapCosine();
  // Readings of the GL, printed: Dot(u0, u1) from dvec3 values, inline, and from a local
  // dvec3 array indexed at run time.
  dvec3 a = dvec3(direction[24 * i], direction[24 * i + 1], direction[24 * i + 2]);
  dvec3 b = dvec3(direction[24 * i + 3], direction[24 * i + 4], direction[24 * i + 5]);
  probe[Sets * 7 + 3 * i] = Dot(a, b);
  precise double direct = a.x * b.x + a.y * b.y + a.z * b.z;
  probe[Sets * 7 + 3 * i + 1] = direct;
  dvec3 local[8];
  for (int k = 0; k < 8; ++k)
  {
    local[k] = dvec3(direction[24 * i + 3 * k], direction[24 * i + 3 * k + 1],
      direction[24 * i + 3 * k + 2]);
  }
  probe[Sets * 7 + 3 * i + 2] = Dot(local[wi % 2], local[1 - wi % 2]);
}
)glsl";

void Unit(double v[3])
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int a = 0; a < 3; ++a)
  {
    v[a] /= n;
  }
}

/// 8 directions as the medial pass makes them: from float closest points to corners.
std::vector<double> DirectionSets(int perKind)
{
  std::mt19937_64 random(2026);
  std::uniform_real_distribution<double> unit(0, 1), signed1(-1, 1);
  std::normal_distribution<double> gauss;
  std::vector<double> sets;
  auto randomUnit = [&](double v[3])
  {
    v[0] = gauss(random);
    v[1] = gauss(random);
    v[2] = gauss(random);
    Unit(v);
  };
  for (int kind = 0; kind < 4; ++kind)
  {
    for (int s = 0; s < perKind; ++s)
    {
      double axis[3], side[3], third[3];
      randomUnit(axis);
      randomUnit(side);
      third[0] = axis[1] * side[2] - axis[2] * side[1];
      third[1] = axis[2] * side[0] - axis[0] * side[2];
      third[2] = axis[0] * side[1] - axis[1] * side[0];
      Unit(third);
      side[0] = third[1] * axis[2] - third[2] * axis[1];
      side[1] = third[2] * axis[0] - third[0] * axis[2];
      side[2] = third[0] * axis[1] - third[1] * axis[0];
      const double spread = M_PI * std::pow(unit(random), 3); // many narrow ones
      for (int k = 0; k < 8; ++k)
      {
        double d[3];
        if (kind == 0) // beside a face: one direction, from float closest points
        {
          std::copy(axis, axis + 3, d);
        }
        else if (kind == 1) // a fan in the plane of axis and side
        {
          const double angle = spread * (unit(random) - 0.5);
          for (int a = 0; a < 3; ++a)
          {
            d[a] = std::cos(angle) * axis[a] + std::sin(angle) * side[a];
          }
        }
        else if (kind == 2) // in a cap of half-angle spread / 2
        {
          const double polar = 0.5 * spread * std::sqrt(unit(random)),
                       turn = 2 * M_PI * unit(random);
          for (int a = 0; a < 3; ++a)
          {
            d[a] = std::cos(polar) * axis[a] +
              std::sin(polar) * (std::cos(turn) * side[a] + std::sin(turn) * third[a]);
          }
        }
        else
        {
          randomUnit(d);
        }
        // The corner x and its float closest point at distance r along d.
        const double r = 0.5 + 3 * unit(random);
        double x[3], v[3];
        for (int a = 0; a < 3; ++a)
        {
          x[a] = 10 * signed1(random);
          v[a] = double(static_cast<float>(x[a] + r * d[a])) - x[a];
        }
        Unit(v);
        sets.insert(sets.end(), v, v + 3);
      }
    }
  }
  return sets;
}

/// The CPU's steps, as the probe writes them.
void CPUSteps(const double u[8][3], double out[Outputs])
{
  auto dot = [](const double* a, const double* b)
  { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  out[0] = dot(u[0], u[1]);
  int wi = 0, wj = 1;
  double widest = dot(u[0], u[1]);
  for (int a = 0; a < 8; ++a)
  {
    for (int b = a + 1; b < 8; ++b)
    {
      const double c = dot(u[a], u[b]);
      if (c < widest)
      {
        widest = c;
        wi = a;
        wj = b;
      }
    }
  }
  out[1] = widest;
  out[2] = 8 * wi + wj;
  double s[3] = { u[wi][0] + u[wj][0], u[wi][1] + u[wj][1], u[wi][2] + u[wj][2] };
  const double sn = std::sqrt(dot(s, s));
  for (int a = 0; a < 3; ++a)
  {
    s[a] /= sn;
  }
  const double pairCos = dot(s, u[wi]);
  bool holds = true;
  for (int k = 0; k < 8; ++k)
  {
    holds = holds && !(dot(s, u[k]) < pairCos - MedialCapTolerance);
  }
  out[3] = sn;
  out[4] = pairCos;
  out[5] = holds ? 1 : 0;
  out[6] = SmallestCapCosine(u);
}
} // namespace

int main()
{
  HeadlessGL* context = vtkdf::coretest::GLContext();
  if (!context)
  {
    return 1;
  }
  std::string error;
  const std::vector<double> sets = DirectionSets(20000);
  const int count = static_cast<int>(sets.size() / 24);
  std::vector<double> gpu(size_t(count) * (Outputs + 3));
  {
    HeadlessGL::Scope scope(*context);
    if (!scope.Ok(error))
    {
      std::printf("FAIL: %s\n", error.c_str());
      return 1;
    }
    const GLFunctions& gl = context->GL();
    std::string source = MedialAxis_comp;
    const size_t at = source.find("void main()");
    vtkdf::coretest::Check(at != std::string::npos, "the medial pass has no main()");
    if (at == std::string::npos)
    {
      return vtkdf::coretest::Verdict();
    }
    source.replace(at, 11, "void MedialPass()");
    source += ProbeMain;
    std::string log;
    const GLuint program = context->BuildProgram({ { GL_COMPUTE_SHADER, source.c_str() } }, log);
    if (!program)
    {
      std::printf("FAIL: the probe does not build: %s\n", log.c_str());
      return 1;
    }
    GLuint buffers[2];
    gl.GenBuffers(2, buffers);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[0]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, sets.size() * 8, sets.data(), GL_STATIC_DRAW);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, gpu.size() * 8, nullptr, GL_DYNAMIC_READ);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, buffers[0]);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, buffers[1]);
    gl.UseProgram(program);
    gl.Uniform1i(gl.GetUniformLocation(program, "Sets"), count);
    gl.Uniform1d(gl.GetUniformLocation(program, "CapTolerance"), MedialCapTolerance);
    gl.DispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, gpu.size() * 8, gpu.data());
    gl.DeleteBuffers(2, buffers);
    gl.DeleteProgram(program);
    if (!NoGLError(gl, "in the cap probe", error))
    {
      std::printf("FAIL: %s\n", error.c_str());
      return 1;
    }
  }
  const char* names[Outputs] = { "Dot(u0, u1)",
    "the widest pair's cosine",
    "the widest pair",
    "|s|",
    "the pair's cosine",
    "the pair's test",
    "SmallestCapCosine" };
  int differ[Outputs] = {};
  int shown = 0;
  for (int s = 0; s < count; ++s)
  {
    double u[8][3], cpu[Outputs];
    std::memcpy(u, &sets[24 * size_t(s)], sizeof(u));
    CPUSteps(u, cpu);
    const double* g = &gpu[size_t(s) * Outputs];
    bool any = false;
    for (int o = 0; o < Outputs; ++o)
    {
      if (std::memcmp(&g[o], &cpu[o], 8) != 0)
      {
        ++differ[o];
        any = true;
      }
    }
    if (any && shown++ < 4)
    {
      std::printf("set %d (kind %d):", s, s / 20000);
      for (int o = 0; o < Outputs; ++o)
      {
        std::printf(" %s %.17g/%.17g;", names[o], g[o], cpu[o]);
      }
      std::printf(" (GPU/CPU)\n");
    }
  }
  const char* readings[3] = { "a dvec3 function argument", "inline", "a local dvec3 array" };
  for (int r = 0; r < 3; ++r)
  {
    int off = 0;
    for (int s = 0; s < count; ++s)
    {
      const double* u = &sets[24 * size_t(s)];
      const double cpu = u[0] * u[3] + u[1] * u[4] + u[2] * u[5];
      off += std::memcmp(&gpu[size_t(count) * Outputs + 3 * size_t(s) + r], &cpu, 8) != 0;
    }
    std::printf("the GL's dot product of two dvec3 (%s): %d of %d differ from the CPU's\n",
      readings[r],
      off,
      count);
  }
  for (int o = 0; o < Outputs; ++o)
  {
    vtkdf::coretest::Check(
      differ[o] == 0, "%s differs from the CPU's in %d of %d sets", names[o], differ[o], count);
  }
  return vtkdf::coretest::Verdict();
}
