// The backend policy's rules (Common/BackendPolicy.h, ChoosePlan), case by case: what
// each Backend and Route runs, Auto's winding sign beside a hardware GPU, the tests' hooks,
// and that the costly questions (a device search, the crossings, the query estimate) are
// asked only where their answer changes the plan.
#include "Common/BackendPolicy.h"
#include "CoreTest.h"

#include <string>

using namespace vtkdf;
using vtkdf::coretest::Check;

namespace
{
/// Counts the calls of a question and answers `answer`.
struct Question
{
  bool Answer = false;
  int Calls = 0;
  std::function<bool()> Ask()
  {
    return [this]
    {
      ++this->Calls;
      return this->Answer;
    };
  }
};
}

int main()
{
  const int64_t large = AutoGPUSignSamples, small = AutoGPUSignSamples - 1;
  for (const bool hardwareAnswer : { false, true })
  {
    for (const bool crossingsAnswer : { false, true })
    {
      for (const int64_t samples : { small, large })
      {
        Question hardware{ hardwareAnswer }, crossings{ crossingsAnswer };
        DeviceDescription device;
        device.Hardware = hardware.Ask();
        WorkDescription work;
        work.Samples = samples;
        work.WindingSign = true;
        work.CrossingsDecide = crossings.Ask();
        const ExecutionPlan plan = ChoosePlan(work, device);
        const bool expected = hardwareAnswer && !crossingsAnswer && samples >= large;
        Check(!plan.FieldOnGPU && plan.SignOnGPU == expected,
          "Auto, hardware %d, crossings decide %d, %lld samples: field on the GPU %d, sign on "
          "the GPU %d (expected 0, %d): %s",
          hardwareAnswer,
          crossingsAnswer,
          static_cast<long long>(samples),
          plan.FieldOnGPU,
          plan.SignOnGPU,
          expected,
          plan.Reason.c_str());
        Check(hardware.Calls == (samples >= large ? 1 : 0),
          "the device searched %d times for %lld samples",
          hardware.Calls,
          static_cast<long long>(samples));
        Check(crossings.Calls == (samples >= large && hardwareAnswer ? 1 : 0),
          "the crossings asked %d times (hardware %d, %lld samples)",
          crossings.Calls,
          hardwareAnswer,
          static_cast<long long>(samples));
        Check(!plan.Reason.empty(), "a plan without a reason");
      }
    }
  }
  // No winding sign: Auto is the CPU whatever the device, which is not searched.
  {
    Question hardware{ true };
    DeviceDescription device;
    device.Hardware = hardware.Ask();
    WorkDescription work;
    work.Samples = large;
    const ExecutionPlan plan = ChoosePlan(work, device);
    Check(!plan.FieldOnGPU && !plan.SignOnGPU && hardware.Calls == 0,
      "Auto without a winding sign: field %d, sign %d, device searched %d times",
      plan.FieldOnGPU,
      plan.SignOnGPU,
      hardware.Calls);
  }
  // GPU and CPU: as asked, with no question.
  for (const BackendChoice backend : { BackendChoice::GPU, BackendChoice::CPU })
  {
    Question hardware{ true }, crossings{ false }, queries{ true };
    DeviceDescription device;
    device.Hardware = hardware.Ask();
    WorkDescription work;
    work.Backend = backend;
    work.Samples = large;
    work.WindingSign = true;
    work.CrossingsDecide = crossings.Ask();
    work.QueriesFaster = queries.Ask();
    const ExecutionPlan plan = ChoosePlan(work, device);
    const bool gpu = backend == BackendChoice::GPU;
    Check(plan.FieldOnGPU == gpu && plan.SignOnGPU == gpu,
      "Backend %s: field on the GPU %d, sign %d",
      gpu ? "GPU" : "CPU",
      plan.FieldOnGPU,
      plan.SignOnGPU);
    Check(hardware.Calls == 0 && crossings.Calls == 0,
      "Backend %s asked the device or the crossings",
      gpu ? "GPU" : "CPU");
    // The route: the queries on the CPU where they are faster, never on the GPU.
    Check(plan.SampleQueries == !gpu && queries.Calls == (gpu ? 0 : 1),
      "Backend %s, route Auto, queries faster: queries %d (asked %d times)",
      gpu ? "GPU" : "CPU",
      plan.SampleQueries,
      queries.Calls);
  }
  // The route as asked.
  for (const RouteChoice route : { RouteChoice::SiteScan, RouteChoice::SampleQueries })
  {
    Question queries{ true };
    WorkDescription work;
    work.Backend = BackendChoice::CPU;
    work.Route = route;
    work.QueriesFaster = queries.Ask();
    const ExecutionPlan plan = ChoosePlan(work, DeviceDescription());
    Check(plan.SampleQueries == (route == RouteChoice::SampleQueries) && queries.Calls == 0,
      "Route %d: queries %d, the estimate asked %d times",
      static_cast<int>(route),
      plan.SampleQueries,
      queries.Calls);
  }
  // The tests' hooks: any device at any size, or never.
  {
    DeviceDescription any;
    any.AutoOnAnyDevice = true;
    WorkDescription work;
    work.Samples = 8;
    work.WindingSign = true;
    Check(ChoosePlan(work, any).SignOnGPU, "the hook AutoOnAnyDevice kept the sign on the CPU");
    DeviceDescription never;
    never.AutoNever = true;
    never.Hardware = [] { return true; };
    work.Samples = large;
    Check(!ChoosePlan(work, never).SignOnGPU, "the hook AutoNever took the GPU");
  }
  return vtkdf::coretest::Verdict();
}
