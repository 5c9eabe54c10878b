// What the module's C++ tests share: a failure counter with a CHECK macro, the
// arguments and the backend, a one-triangle mesh, and a recorder of a filter's errors and warnings
// for the bad-input tests.
#ifndef vtkdf_TestSupport_h
#define vtkdf_TestSupport_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkWeakPointer.h"

#include <cstdio>
#include <string>

namespace vtkdf::testing
{
inline int Failures = 0;

/// Whether the test got at least `count` arguments; prints its usage (the arguments it
/// takes, after the program's name) when not.
inline bool HasArguments(int argc, char* argv[], int count, const char* usage)
{
  if (argc > count)
  {
    return true;
  }
  std::fprintf(stderr, "usage: %s %s\n", argv[0], usage);
  return false;
}

/// Sets a filter's Backend from a test's "cpu" or "gpu" argument.
template<typename Filter>
void UseBackend(Filter* filter, const std::string& backend)
{
  filter->SetBackend(backend == "gpu" ? Filter::BACKEND_GPU : Filter::BACKEND_CPU);
}

/// One triangle, (0,0,z) (1,0,0) (0,1,0): the smallest valid mesh (z = NaN: an invalid one).
inline vtkNew<vtkPolyData> Triangle(double z = 0)
{
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0, 0, z);
  pts->InsertNextPoint(1, 0, 0);
  pts->InsertNextPoint(0, 1, 0);
  vtkNew<vtkCellArray> polys;
  const vtkIdType t[3] = { 0, 1, 2 };
  polys->InsertNextCell(3, t);
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  return mesh;
}

/// Prints the verdict; the process's exit status.
inline int Verdict()
{
  std::printf("%d failures\n", Failures);
  return Failures ? 1 : 0;
}

/// The errors and warnings a filter (and its executive) report.
class MessageRecorder
{
public:
  explicit MessageRecorder(vtkAlgorithm* filter)
  {
    this->Observer->SetClientData(this);
    this->Observer->SetCallback(
      [](vtkObject*, unsigned long event, void* self, void* text)
      {
        auto* recorder = static_cast<MessageRecorder*>(self);
        (event == vtkCommand::ErrorEvent ? recorder->Errors : recorder->Warnings) +=
          static_cast<const char*>(text);
      });
    filter->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    filter->AddObserver(vtkCommand::WarningEvent, this->Observer);
    filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    this->Filter = filter;
    this->Executive = filter->GetExecutive();
  }
  /// Stops observing (a recorder that left its scope must not be written to when the
  /// filter reports again; the filter may be gone already).
  ~MessageRecorder()
  {
    if (this->Filter)
    {
      this->Filter->RemoveObserver(this->Observer);
    }
    if (this->Executive)
    {
      this->Executive->RemoveObserver(this->Observer);
    }
  }
  MessageRecorder(const MessageRecorder&) = delete;
  MessageRecorder& operator=(const MessageRecorder&) = delete;

  /// Prints what was recorded; true when an expected (non-empty) error and warning are
  /// among them and the output is as expected (`outputPoints` > 0 or not).
  bool Expect(const std::string& mode,
    long long outputPoints,
    const std::string& error,
    const std::string& warning,
    bool expectOutput) const
  {
    std::printf("mode %s: %lld output points\n  errors: %s\n  warnings: %s\n",
      mode.c_str(),
      outputPoints,
      this->Errors.c_str(),
      this->Warnings.c_str());
    bool ok = true;
    if (!error.empty() && this->Errors.find(error) == std::string::npos)
    {
      std::printf("FAIL: expected an error containing '%s'\n", error.c_str());
      ok = false;
    }
    if (!warning.empty() && this->Warnings.find(warning) == std::string::npos)
    {
      std::printf("FAIL: expected a warning containing '%s'\n", warning.c_str());
      ok = false;
    }
    if (expectOutput != (outputPoints > 0))
    {
      std::printf("FAIL: expected %s output\n", expectOutput ? "an" : "an empty");
      ok = false;
    }
    return ok;
  }

  std::string Errors, Warnings;

private:
  vtkNew<vtkCallbackCommand> Observer;
  vtkWeakPointer<vtkAlgorithm> Filter;
  vtkWeakPointer<vtkExecutive> Executive;
};
} // namespace vtkdf::testing

#define CHECK(cond, ...)                                                                           \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::printf("FAIL: " __VA_ARGS__);                                                           \
      std::printf("\n");                                                                           \
      ++vtkdf::testing::Failures;                                                                  \
    }                                                                                              \
  } while (0)

#endif
