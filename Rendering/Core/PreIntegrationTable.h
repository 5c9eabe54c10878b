// The pre-integration table of Engel, Kraus and Ertl (2001), the rendering module's one
// algorithm core (plain C++, no VTK types).
//
// Between two slices the scalar along a ray is taken to vary linearly from the front
// sample's value sf to the back sample's value sb. With extinction tau(s) and colour c(s)
// from the transfer functions, the slab's opacity and colour are
//   alpha = 1 - exp(-d * tauBar),   tauBar = (T(sb) - T(sf)) / (sb - sf),
//   colour = cBar * alpha,          cBar = (K(sb) - K(sf)) / (T(sb) - T(sf)),
// with T and K the cumulative integrals of tau and tau * c (the colour neglects the
// attenuation inside the slab, as in the paper). The table holds tauBar and cBar per
// (sf, sb) pair, independent of the slab length d, so that slabs of any length (rays at
// an angle, slabs cut by opaque geometry or the volume's box) are exact in d, and is
// built in O(n^2) from the cumulative integrals, which are summed on a grid `Refinement`
// times finer than the table so that sharp transfer functions are integrated, not
// point-sampled.
#ifndef vtkdf_PreIntegrationTable_h
#define vtkdf_PreIntegrationTable_h

#include <array>
#include <vector>

namespace vtkdf::render
{
/// The transfer functions sampled at `count` evenly spaced scalar values over
/// [Low, High] (both ends included): extinction per unit length (>= 0) and colour.
struct TransferSamples
{
  double Low = 0;
  double High = 1;
  std::vector<double> Extinction;
  std::vector<std::array<double, 3>> Colour;
};

/// How many transfer-function samples BuildPreIntegrationTable wants for a table of
/// `size` entries a side: (size - 1) * Refinement + 1.
int PreIntegrationSamples(int size);
constexpr int Refinement = 32;

/// The size x size table, RGBA floats, row-major with the back value's index as the row
/// and the front value's as the column: rgb = cBar, a = tauBar. Entry (i, j) is for the
/// front value Low + j (High - Low) / (size - 1) and the back value Low + i (...).
/// `samples` must hold PreIntegrationSamples(size) samples.
std::vector<float> BuildPreIntegrationTable(const TransferSamples& samples, int size);

/// The table for slabs of one world length `length` (a ray's whole steps), from
/// BuildPreIntegrationTable's: rgb = cBar * alpha and a = alpha = 1 - exp(-length * tauBar),
/// so that a ray's loop reads a step's premultiplied colour and opacity without an
/// exponential. Rebuilt when the step's length changes: size^2 exponentials.
std::vector<float> StepTable(const std::vector<float>& averages, double length);
} // namespace vtkdf::render

#endif
