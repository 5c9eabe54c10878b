// UnionClosestPointGPU: Kim et al.'s query on the GPU (Algorithm 2.1), certified on the
// CPU. Without VTK types.
//
// Six 90-degree views on the faces of a cube around O, rendered at once into the layers
// of a depth-stencil texture array (a geometry shader sends each triangle to the six
// layers), for a batch of queries per draw (instance k draws query k's six layers): the
// draws do not grow with the number of queries. The depth written is the Euclidean
// distance |x - O| over Far, monotone along each ray, so the depth tests compare
// distances and no 1/cos conversion is needed.
// - O outside the union: one pass with the less test gives the nearest surface.
// - O inside: the pieces that contain O (found exactly on the CPU) draw their back faces
//   once with the greater test; then, round after round, every other piece draws its front
//   faces where they pierce or touch the current boundary (less-or-equal, the front faces
//   brought nearer by a small bias so that touching pieces join), which opens a stencil
//   window, and its back faces into that window with the greater test, closing it. An
//   occlusion query per piece tells whether a round changed any pixel; the rounds stop at
//   the first that changes none. Queries inside and outside are batched apart.
// The smallest distance in the six images is a point of the boundary, an upper bound U of
// the answer; a gap of free space narrower than a pixel's angle can be missed, so no
// image-space bound is guaranteed. Certification runs the exact CPU query
// (UnionClosestPoint) seeded with U: only faces nearer than U are searched. If U was not
// above the answer (a gap closed by the touching bias), the seeded search finds nothing
// and the full search runs: the certified answer is exact either way.
#ifndef vtkdf_UnionClosestPointGPU_h
#define vtkdf_UnionClosestPointGPU_h

#include "Common/Parallel.h"
#include "GL/HeadlessGL.h"
#include "Union/UnionClosestPoint.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

struct UnionGPUAnswer
{
  UnionAnswer Answer;  // the certified answer, or the image-space one
  double Estimate = 0; // U: the smallest distance in the images
  /// 0 when certified; else the image-space estimate U tan(alpha), alpha half a pixel's
  /// diagonal at the view's centre (plus the float depth's rounding): not guaranteed.
  double ErrorBound = 0;
  bool Certified = false;
  int Passes = 0; // rendering rounds of its batch (1 from outside; zero hops not counted)
};

struct UnionGPUSettings
{
  int Resolution = 256; // pixels a side of each cube-face view
  bool Certify = true;
  /// The most GPU memory for the views of one batch of queries (8 bytes a pixel, 6
  /// views a query; at least one query a batch).
  int64_t BatchBytes = int64_t(256) << 20;
  /// A parallel loop for the certification, over the queries (serial when empty).
  ParallelFor For;
  /// Told the fraction done after each batch rendered and each block of certified
  /// queries; returning false stops the run (QueryUnionGPU then returns false, with
  /// `error` "aborted").
  ProgressCallback Progress;
  /// The front faces' bias, relative to Far: how close a piece must come to the current
  /// boundary to join it.
  double TouchBias = 1e-6;
};

/// Answers `queries` (xyz triples) over the pieces of `u`. `images`, when given, receives
/// the last query's six views: Resolution^2 distances each (rows bottom-up), NaN where no
/// boundary was seen; `frames` their view frames (9 numbers per view: right, up, forward).
bool QueryUnionGPU(HeadlessGL& context,
  const UnionClosestPoint& u,
  const std::vector<double>& queries,
  const UnionGPUSettings& settings,
  std::vector<UnionGPUAnswer>& answers,
  std::string& error,
  std::vector<float>* images = nullptr,
  std::vector<double>* frames = nullptr);

} // namespace vtkdf

#endif
