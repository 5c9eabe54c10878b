// vtkDistanceFieldRunRecord: what every filter reports of its last complete run (its
// GetLastTime() and friends), filled by the run every filter shares
// (vtkDistanceFieldRun.h) and held by the module's wrapped bases.
#ifndef vtkDistanceFieldRunRecord_h
#define vtkDistanceFieldRunRecord_h

#include "vtkIndent.h"

#include <ostream>
#include <string>

namespace vtkdf
{
struct RunRecord
{
  std::string Backend = "none";  ///< "gpu", "cpu", or "none" before a complete run
  std::string Renderer = "none"; ///< GL_RENDERER of a GPU run, "cpu"
  std::string Platform = "none"; ///< how the GPU's context was made, "cpu"
  double Time = 0;               ///< seconds of the run, input conversion included
  std::string StageTimes;        ///< "name:seconds,name:seconds,..."
  double PeakMemory = -1;        ///< MiB above the run's start at its peak; -1 unknown
  std::string Reason = "none";   ///< why it ran where it did (ExecutionPlan::Reason)

  /// The lines of a filter's PrintSelf (LastBackend only `withBackend`: the convex
  /// queries report theirs as a BackendType).
  void Print(std::ostream& os, vtkIndent indent, bool withBackend) const
  {
    if (withBackend)
    {
      os << indent << "LastBackend: " << this->Backend << "\n";
    }
    os << indent << "LastRenderer: " << this->Renderer << "\n";
    os << indent << "LastPlatform: " << this->Platform << "\n";
    os << indent << "LastTime: " << this->Time << "\n";
    os << indent << "LastStageTimes: " << this->StageTimes << "\n";
    os << indent << "LastPeakMemory: " << this->PeakMemory << " MiB\n";
    os << indent << "LastBackendReason: " << this->Reason << "\n";
  }
};
} // namespace vtkdf

#endif
