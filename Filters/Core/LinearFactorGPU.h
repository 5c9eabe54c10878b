// LinearFactorGPU: the scan pass of LinearFactorField on the GPU. Domain polygons are
// built by a geometry shader, many slices per draw (layered rendering into texture
// arrays); the depth test keeps the nearest site; the field is read back once per batch.
#ifndef vtkdf_LinearFactorGPU_h
#define vtkdf_LinearFactorGPU_h

#include "HeadlessGL.h"
#include "LinearFactorField.h"

#include <string>

namespace vtkdf
{

/// Fills `nearest` like ScanSitesCPU; false (and `error`) when the GPU cannot run it.
bool ScanSitesGPU(HeadlessGL& gl,
  const MeshSites& sites,
  const RangeCulling& culling,
  const FieldRequest& request,
  NearestSiteBuffer& nearest,
  const ProgressCallback& progress,
  ScanStatistics& stats,
  std::string& error);

} // namespace vtkdf

#endif
