// ProximityGPU: the proximity queries' nearest-triangle searches on the GPU, a compute
// shader over each model's box hierarchy (Shaders/ProximityNearest.comp.glsl), kept
// between frames in a ProximityDevice: a model whose topology the device already holds
// uploads only its coordinates (points and node boxes). The searches are
// ProximitySearch.h's NearestTriangle operation for operation in double precision, so
// that the answers are the CPU's but for the roundings of a driver's double division.
// Private to the Proximity family.
#ifndef vtkdf_ProximityGPU_h
#define vtkdf_ProximityGPU_h

#include "Common/TriangleBoxTree.h"
#include "Proximity/ProximityQuery.h"
#include "Proximity/ProximitySearch.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{
/// Nearest triangles of the other model, as the searches return them.
struct NearestAnswers
{
  std::vector<double> Values;     // 4 per point: the closest point, the squared distance
  std::vector<int32_t> Triangles; // the nearest triangle of the other model
};

/// The face samples of a batch of triangles: per triangle, its index, its first sample
/// and its divisions n (FaceSamples' lattice without the three corners, so
/// (n + 1)(n + 2) / 2 - 3 samples).
struct SampleBatch
{
  std::vector<int32_t> Items; // 4 per triangle: triangle, first sample, n, 0
  int64_t Samples = 0;
};

/// The face samples a batch should hold at most: 2^22 (36 bytes each come back), or one
/// dispatch's where the storage blocks are smaller.
int64_t DeviceBatchSamples(ProximityDevice& device);

/// The bytes sent to the device and read from it since the last reset.
void DeviceResetTraffic(ProximityDevice& device);
void DeviceTraffic(ProximityDevice& device, int64_t& sent, int64_t& read);

/// Puts a model on the device in `slot` (0: A, 1: B): its topology (triangles, the
/// hierarchy's links and order) when the device does not hold generation `topology` of
/// it, its coordinates (points, node boxes) every time.
bool DeviceLoadModel(ProximityDevice& device,
  int slot,
  const TriangleModel& model,
  const TriangleBoxTree& tree,
  uint64_t topology,
  std::string& error);

/// The nearest triangle of model `other` to every point of model `self` (slots); the
/// triangles stay on the device as the starting hints of `self`'s face samples.
bool DeviceNearestToPoints(ProximityDevice& device,
  int self,
  int other,
  NearestAnswers& answers,
  std::string& error);

/// The nearest triangle of model `other` to every face sample of `batch` (triangles of
/// `self`), in the batch's order; DeviceNearestToPoints(self, other) must have run.
bool DeviceNearestToSamples(ProximityDevice& device,
  int self,
  int other,
  const SampleBatch& batch,
  NearestAnswers& answers,
  std::string& error);
} // namespace vtkdf

#endif
