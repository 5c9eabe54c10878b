#include "PreIntegrationTable.h"

#include <cmath>
#include <stdexcept>

namespace vtkdf::render
{
int PreIntegrationSamples(int size)
{
  return (size - 1) * Refinement + 1;
}

std::vector<float> BuildPreIntegrationTable(const TransferSamples& samples, int size)
{
  const int count = PreIntegrationSamples(size);
  if (size < 2 || static_cast<int>(samples.Extinction.size()) != count ||
    static_cast<int>(samples.Colour.size()) != count || !(samples.High > samples.Low))
  {
    throw std::invalid_argument("BuildPreIntegrationTable: bad samples");
  }
  // Cumulative integrals by the trapezoidal rule on the fine grid: T of tau, K of tau*c,
  // C of c (the colour's plain average where there is no extinction).
  const double step = (samples.High - samples.Low) / (count - 1);
  std::vector<double> T(count, 0.0);
  std::vector<std::array<double, 3>> K(count, { 0, 0, 0 }), C(count, { 0, 0, 0 });
  for (int m = 1; m < count; ++m)
  {
    const double t0 = samples.Extinction[m - 1], t1 = samples.Extinction[m];
    T[m] = T[m - 1] + 0.5 * step * (t0 + t1);
    for (int c = 0; c < 3; ++c)
    {
      const double c0 = samples.Colour[m - 1][c], c1 = samples.Colour[m][c];
      K[m][c] = K[m - 1][c] + 0.5 * step * (t0 * c0 + t1 * c1);
      C[m][c] = C[m - 1][c] + 0.5 * step * (c0 + c1);
    }
  }
  std::vector<float> table(4 * static_cast<size_t>(size) * size);
  for (int back = 0; back < size; ++back)
  {
    for (int front = 0; front < size; ++front)
    {
      float* entry = &table[4 * (static_cast<size_t>(back) * size + front)];
      const int mf = front * Refinement, mb = back * Refinement;
      if (front == back)
      {
        entry[3] = static_cast<float>(samples.Extinction[mf]);
        for (int c = 0; c < 3; ++c)
        {
          entry[c] = static_cast<float>(samples.Colour[mf][c]);
        }
        continue;
      }
      const double ds = (mb - mf) * step;
      const double dT = T[mb] - T[mf];
      entry[3] = static_cast<float>(dT / ds);
      // Where the extinction integral vanishes (relative to the values it sums), the
      // colour's weight is meaningless: take the colour's plain average.
      const double scale =
        std::abs(samples.Extinction[mf]) + std::abs(samples.Extinction[mb]) + std::abs(dT / ds);
      const bool weighted = std::abs(dT) > 1e-12 * scale * std::abs(ds) && dT != 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double value = weighted ? (K[mb][c] - K[mf][c]) / dT : (C[mb][c] - C[mf][c]) / ds;
        entry[c] = static_cast<float>(value);
      }
    }
  }
  return table;
}

std::vector<float> StepTable(const std::vector<float>& averages, double length)
{
  if (averages.size() % 4 != 0 || !(length >= 0) || !std::isfinite(length))
  {
    throw std::invalid_argument("StepTable: bad table or length");
  }
  std::vector<float> step(averages.size());
  for (size_t e = 0; e < averages.size(); e += 4)
  {
    const double alpha = -std::expm1(-length * static_cast<double>(averages[e + 3]));
    for (int c = 0; c < 3; ++c)
    {
      step[e + c] = static_cast<float>(averages[e + c] * alpha);
    }
    step[e + 3] = static_cast<float>(alpha);
  }
  return step;
}
} // namespace vtkdf::render
