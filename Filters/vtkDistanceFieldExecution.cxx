#include "vtkDistanceFieldExecution.h"

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkSMPTools.h"
#include "vtkSetGet.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "GL/HeadlessGL.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <new>
#include <stdexcept>

namespace vtkdf
{

DeviceDescription DescribeDevice()
{
  DeviceDescription device;
  const char* setting = std::getenv("VTKDF_AUTO_GPU_SIGN");
  const std::string choice = setting ? setting : "";
  device.AutoOnAnyDevice = choice == "1";
  device.AutoNever = choice == "0";
  device.Hardware = []
  {
    static const bool hardware = HeadlessGL::HasHardwareDevice();
    return hardware;
  };
  return device;
}

bool FieldContext(const ExecutionPlan& plan, HeadlessGL*& gl, std::string& error)
{
  gl = nullptr;
  if (!plan.FieldOnGPU)
  {
    return true;
  }
  std::string why;
  gl = HeadlessGL::Get(why);
  if (!gl)
  {
    error = "Backend is GPU but " + why;
    return false;
  }
  return true;
}

HeadlessGL* SignContext(const ExecutionPlan& plan)
{
  if (!plan.SignOnGPU || plan.FieldOnGPU)
  {
    return nullptr;
  }
  // The context is made once per process; a software rasterizer (llvmpipe, OSMesa) is
  // not taken but under the tests' hook.
  static const bool anyDevice = DescribeDevice().AutoOnAnyDevice;
  static HeadlessGL* const chosen = []() -> HeadlessGL*
  {
    std::string why;
    HeadlessGL* gl = HeadlessGL::Get(why);
    if (!gl)
    {
      return nullptr;
    }
    return !gl->IsSoftware() || anyDevice ? gl : nullptr;
  }();
  return chosen;
}

void SMPFor(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body)
{
  std::atomic<bool> failed{ false };
  std::exception_ptr first;
  std::mutex lock;
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(n),
    static_cast<vtkIdType>(grain),
    [&](vtkIdType begin, vtkIdType end)
    {
      if (failed.load(std::memory_order_relaxed))
      {
        return;
      }
      try
      {
        body(begin, end);
      }
      catch (...)
      {
        std::lock_guard<std::mutex> guard(lock);
        if (!failed.exchange(true))
        {
          first = std::current_exception();
        }
      }
    });
  if (first)
  {
    std::rethrow_exception(first);
  }
}

void RequestWholeInput(vtkInformation* input)
{
  if (input->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    input->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      input->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()),
      6);
  }
  input->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  input->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  input->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
}

void RequestWholeInputs(vtkInformationVector** inputVector, int ports)
{
  for (int port = 0; port < ports; ++port)
  {
    if (vtkInformation* in = inputVector[port]->GetInformationObject(0))
    {
      RequestWholeInput(in);
    }
  }
}

vtkTypeBool ProcessRequestOrEmpty(vtkAlgorithm* filter,
  bool newRun,
  const std::function<vtkTypeBool()>& process,
  const std::function<void(unsigned long)>& setErrorCode)
{
  if (newRun)
  {
    setErrorCode(vtkErrorCode::NoError);
  }
  vtkTypeBool result = 0;
  std::string failure;
  try
  {
    result = process();
  }
  catch (const std::bad_alloc&)
  {
    failure = "Out of memory: an allocation failed (the grid or the mesh is too large for the "
              "memory this process can get; MemoryLimit is checked against estimates).";
  }
  catch (const std::length_error& e)
  {
    failure = std::string("A buffer would exceed its largest size (") + e.what() +
      "): the grid is too large.";
  }
  catch (const std::exception& e)
  {
    failure = std::string("Failed: ") + e.what();
  }
  if (!failure.empty())
  {
    vtkErrorWithObjectMacro(filter, << failure);
  }
  if (!result)
  {
    if (filter->GetErrorCode() == vtkErrorCode::NoError)
    {
      setErrorCode(vtkErrorCode::UserError);
    }
    // No output of a failed run may pass for a result.
    for (int port = 0; port < filter->GetNumberOfOutputPorts(); ++port)
    {
      if (vtkDataObject* output = filter->GetOutputDataObject(port))
      {
        output->Initialize();
      }
    }
  }
  return result;
}

} // namespace vtkdf
