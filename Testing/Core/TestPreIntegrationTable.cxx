// The pre-integration table against the integrals it stands for, summed independently:
// for every (front, back) pair of a table over a transfer function with sharp and smooth
// parts, the average extinction (1/(sb - sf)) * integral of tau, and the colour
// integral of tau * c / integral of tau, by Simpson's rule on 20000 intervals of the
// transfer function evaluated directly from its nodes. Also: the slab opacity
// 1 - exp(-d * tauBar) is the exact transmittance of a linear ramp, so two half slabs
// compose to one whole (the table is exact in the slab's length). The step table (one
// slab length baked in) against the same formula in double precision.
#include "CoreTest.h"
#include "PreIntegrationTable.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

using namespace vtkdf::coretest;

namespace
{

struct Node
{
  double s, opacity, r, g, b;
};
// Opacity per unit distance and colour, piecewise linear; a narrow peak and a step-like
// rise (what point sampling misses).
const std::vector<Node> nodes = { { 0.0, 0.0, 1, 0, 0 },
  { 0.30, 0.05, 1, 0.5, 0 },
  { 0.32, 0.9, 0, 1, 0 },
  { 0.34, 0.05, 0, 1, 1 },
  { 0.70, 0.1, 0, 0, 1 },
  { 0.71, 0.6, 1, 1, 1 },
  { 1.0, 0.6, 0.5, 0.5, 0.5 } };
const double unit = 0.05;

void Evaluate(double s, double& tau, double rgb[3])
{
  size_t k = 1;
  while (k + 1 < nodes.size() && nodes[k].s < s)
  {
    ++k;
  }
  const Node& a = nodes[k - 1];
  const Node& b = nodes[k];
  const double t = std::clamp((s - a.s) / (b.s - a.s), 0.0, 1.0);
  const double opacity = a.opacity + t * (b.opacity - a.opacity);
  tau = -std::log1p(-std::min(opacity, 1.0 - 1e-7)) / unit;
  rgb[0] = a.r + t * (b.r - a.r);
  rgb[1] = a.g + t * (b.g - a.g);
  rgb[2] = a.b + t * (b.b - a.b);
}

/// Simpson's rule of tau and tau * c over [s0, s1].
void Integrate(double s0, double s1, double& T, double K[3])
{
  const int n = 20000;
  const double h = (s1 - s0) / n;
  T = 0;
  K[0] = K[1] = K[2] = 0;
  for (int i = 0; i <= n; ++i)
  {
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    double tau, rgb[3];
    Evaluate(s0 + i * h, tau, rgb);
    T += w * tau * h / 3;
    for (int c = 0; c < 3; ++c)
    {
      K[c] += w * tau * rgb[c] * h / 3;
    }
  }
}
} // namespace

int main()
{
  const int size = 64;
  const int count = vtkdf::render::PreIntegrationSamples(size);
  vtkdf::render::TransferSamples samples;
  samples.Low = 0;
  samples.High = 1;
  for (int m = 0; m < count; ++m)
  {
    double tau, rgb[3];
    Evaluate(static_cast<double>(m) / (count - 1), tau, rgb);
    samples.Extinction.push_back(tau);
    samples.Colour.push_back({ rgb[0], rgb[1], rgb[2] });
  }
  const std::vector<float> table = vtkdf::render::BuildPreIntegrationTable(samples, size);
  double worstTau = 0, worstColour = 0;
  for (int back = 0; back < size; back += 3)
  {
    for (int front = 0; front < size; front += 3)
    {
      const float* entry = &table[4 * (static_cast<size_t>(back) * size + front)];
      const double sf = static_cast<double>(front) / (size - 1);
      const double sb = static_cast<double>(back) / (size - 1);
      double tauBar, colour[3];
      if (front == back)
      {
        Evaluate(sf, tauBar, colour);
      }
      else
      {
        double T, K[3];
        Integrate(std::min(sf, sb), std::max(sf, sb), T, K);
        tauBar = T / std::abs(sb - sf);
        for (int c = 0; c < 3; ++c)
        {
          colour[c] = K[c] / T;
        }
      }
      worstTau = std::max(worstTau, std::abs(entry[3] - tauBar) / std::max(tauBar, 1.0));
      for (int c = 0; c < 3; ++c)
      {
        worstColour = std::max(worstColour, std::abs(entry[c] - colour[c]));
      }
    }
  }
  std::printf("table %d x %d against Simpson: extinction within %.2e (relative), colour within "
              "%.2e\n",
    size,
    size,
    worstTau,
    worstColour);
  Check(worstTau < 1e-3, "average extinction off by %.2e", worstTau);
  Check(worstColour < 1e-3, "average colour off by %.2e", worstColour);

  // Exact in the slab length: the opacity of a ramp from s0 to s2 over length d equals
  // the two halves (s0 -> s1 -> s2, d/2 each) composed, for table points s0, s1, s2.
  double worstCompose = 0;
  for (int i0 = 0; i0 + 2 < size; i0 += 5)
  {
    for (int i2 = i0 + 2; i2 < size; i2 += 6)
    {
      if ((i2 - i0) % 2)
      {
        continue;
      }
      const int i1 = (i0 + i2) / 2;
      const double d = 0.04;
      auto alpha = [&](int f, int b, double length)
      { return 1.0 - std::exp(-length * table[4 * (static_cast<size_t>(b) * size + f) + 3]); };
      const double whole = alpha(i0, i2, d);
      const double halves = 1.0 - (1.0 - alpha(i0, i1, d / 2)) * (1.0 - alpha(i1, i2, d / 2));
      worstCompose = std::max(worstCompose, std::abs(whole - halves));
    }
  }
  std::printf("whole slab against two halves: opacity within %.2e\n", worstCompose);
  Check(worstCompose < 1e-5, "the table is not consistent in the slab length (%.2e)", worstCompose);

  // The step table: each entry's opacity is the averages' over the step's length, and its
  // colour the average colour premultiplied by it (against the double-precision formula);
  // a length of zero is transparent, and a negative length is refused.
  const double length = 0.04;
  const std::vector<float> step = vtkdf::render::StepTable(table, length);
  double worstStep = 0;
  for (size_t e = 0; e < table.size(); e += 4)
  {
    const double alpha = 1.0 - std::exp(-length * table[e + 3]);
    worstStep = std::max(worstStep, std::abs(step[e + 3] - alpha));
    for (int c = 0; c < 3; ++c)
    {
      worstStep = std::max(worstStep, std::abs(step[e + c] - table[e + c] * alpha));
    }
  }
  std::printf("step table against 1 - exp(-d * tauBar): within %.2e\n", worstStep);
  Check(step.size() == table.size() && worstStep < 1e-6, "step table off by %.2e", worstStep);
  const std::vector<float> none = vtkdf::render::StepTable(table, 0.0);
  Check(std::all_of(none.begin(), none.end(), [](float v) { return v == 0.0f; }),
    "a step of length 0 is not transparent");
  bool refusedLength = false;
  try
  {
    vtkdf::render::StepTable(table, -1.0);
  }
  catch (const std::invalid_argument&)
  {
    refusedLength = true;
  }
  Check(refusedLength, "a negative step length was accepted");

  // Bad samples are refused.
  samples.Extinction.pop_back();
  bool refused = false;
  try
  {
    vtkdf::render::BuildPreIntegrationTable(samples, size);
  }
  catch (const std::invalid_argument&)
  {
    refused = true;
  }
  Check(refused, "a short sample list was accepted");
  return Verdict();
}
