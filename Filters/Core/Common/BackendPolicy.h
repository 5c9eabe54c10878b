// BackendPolicy: where each stage of a filter runs, decided in one place. A filter
// describes the work (the Backend and Route properties, the samples, whether it takes a
// winding sign) and the device as found without making a context; ChoosePlan says what
// runs where, and why (the filters report it: GetLastBackendReason()).
//
// The rules, from the measurements of docs/benchmarks.md ("GPU: an NVIDIA H100"): on a
// data-centre GPU beside 16 CPU threads the distance fields ran 1.6-9 times slower on the
// GPU and the union queries 50-60 times, so Auto runs the CPU; but the winding-number
// sign took half the CPU's time there, so beside a hardware GPU Auto takes the GPU for
// it from 2^22 samples on (below, the context's 0.4 s is not repaid), unless the CPU
// reads the signs from the crossings along the grid lines (a fraction of any winding
// pass). On the CPU, the per-sample query route replaces the site scan where the mesh's
// cells outnumber the samples to query (NearestTriangleQueries.h, PreferSampleQueries);
// the GPU has the scan only.
#ifndef vtkdf_BackendPolicy_h
#define vtkdf_BackendPolicy_h

#include <cstdint>
#include <functional>
#include <string>

namespace vtkdf
{

/// The values of every filter's Backend property.
enum class BackendChoice
{
  Auto = 0,
  GPU = 1,
  CPU = 2
};

/// The values of the linear factorization's Route property.
enum class RouteChoice
{
  Auto = 0,
  SiteScan = 1,
  SampleQueries = 2
};

/// The GPU as the policy sees it before any context is made.
struct DeviceDescription
{
  /// Whether an EGL device that is not a software rasterizer is present
  /// (HeadlessGL::HasHardwareDevice); asked only where the answer changes the plan, so
  /// that a CPU run of a small grid pays nothing.
  std::function<bool()> Hardware;
  /// Test hooks (the tests' environment VTKDF_AUTO_GPU_SIGN=1 or 0, read by the module):
  /// Auto's GPU stages taken on any context at any size, or never.
  bool AutoOnAnyDevice = false;
  bool AutoNever = false;
};

/// The work of one run, as far as the choice depends on it.
struct WorkDescription
{
  BackendChoice Backend = BackendChoice::Auto;
  RouteChoice Route = RouteChoice::Auto;
  int64_t Samples = 0;
  /// A winding-number sign (or the WindingNumber array) is computed.
  bool WindingSign = false;
  /// Whether the CPU reads every sign from the crossings along the grid lines; asked
  /// only where the answer changes the plan.
  std::function<bool()> CrossingsDecide;
  /// Whether the per-sample queries beat the site scan for this mesh and grid; asked
  /// only for an Auto route on the CPU.
  std::function<bool()> QueriesFaster;
};

struct ExecutionPlan
{
  bool FieldOnGPU = false;    // the field (or the filter's whole work) on the GPU
  bool SignOnGPU = false;     // the winding sign on the GPU
  bool SampleQueries = false; // the per-sample query route instead of the site scan
  std::string Reason;         // why, in a sentence a user can act on
};

/// Samples from which Auto takes a hardware GPU for the winding sign.
constexpr int64_t AutoGPUSignSamples = int64_t(1) << 22;

inline ExecutionPlan ChoosePlan(const WorkDescription& work, const DeviceDescription& device)
{
  ExecutionPlan plan;
  if (work.Backend == BackendChoice::GPU)
  {
    plan.FieldOnGPU = plan.SignOnGPU = true;
    plan.Reason = "Backend is GPU";
  }
  else if (work.Backend == BackendChoice::CPU)
  {
    plan.Reason = "Backend is CPU";
  }
  else
  {
    plan.Reason = "Auto: the CPU (on the GPUs measured the fields ran slower)";
    const bool large = device.AutoOnAnyDevice || work.Samples >= AutoGPUSignSamples;
    if (work.WindingSign && large && !device.AutoNever &&
      (device.AutoOnAnyDevice || (device.Hardware && device.Hardware())))
    {
      if (work.CrossingsDecide && work.CrossingsDecide())
      {
        plan.Reason += "; the signs from the crossings along the grid lines, on the CPU";
      }
      else
      {
        plan.SignOnGPU = true;
        plan.Reason += "; the winding sign on the hardware GPU (faster there)";
      }
    }
  }
  if (work.Route == RouteChoice::SampleQueries)
  {
    plan.SampleQueries = true;
    plan.Reason += "; Route is SampleQueries";
  }
  else if (work.Route == RouteChoice::Auto && !plan.FieldOnGPU && work.QueriesFaster &&
    work.QueriesFaster())
  {
    plan.SampleQueries = true;
    plan.Reason += "; the per-sample queries (more cells than samples to query)";
  }
  return plan;
}

} // namespace vtkdf

#endif
