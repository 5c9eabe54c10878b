// Progress and abort on both backends: vtkLinearFactorDistanceField and
// vtkChamferVoxelDistance report progress per batch (GPU: per batch of slices or of
// layers, once the GPU has finished it) and stop within one batch when aborted at 30 %,
// with an empty output; the same filter then runs to the end and matches a fresh run.
// usage: TestAbort DATA_DIR linfac|linfac-queries|chamfer cpu|gpu
#include "vtkChamferVoxelDistance.h"
#include "vtkLinearFactorDistanceField.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include "TestSupport.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{
struct Recorder
{
  vtkAlgorithm* Filter = nullptr;
  double AbortAt = 2; // abort when progress reaches this
  double AbortedAt = -1;
  std::vector<double> Values;      // before the abort
  std::vector<double> ValuesAfter; // reported after it
};

void OnProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* r = static_cast<Recorder*>(clientData);
  const double value = *static_cast<double*>(callData);
  (r->AbortedAt >= 0 ? r->ValuesAfter : r->Values).push_back(value);
  if (r->AbortedAt < 0 && value >= r->AbortAt)
  {
    r->AbortedAt = value;
    r->Filter->SetAbortExecute(1);
  }
}

vtkSmartPointer<vtkDistanceFieldAlgorithm> Make(const std::string& name,
  vtkPolyData* mesh,
  const std::string& backend)
{
  vtkSmartPointer<vtkDistanceFieldAlgorithm> filter;
  if (name == "linfac" || name == "linfac-queries")
  {
    auto linfac = vtkSmartPointer<vtkLinearFactorDistanceField>::New();
    if (name == "linfac-queries")
    {
      linfac->SetRouteToSampleQueries();
    }
    filter = linfac;
  }
  else
  {
    auto chamfer = vtkSmartPointer<vtkChamferVoxelDistance>::New();
    chamfer->SetMetricToManhattan(); // the most layers: many batches of 8
    filter = chamfer;
  }
  filter->SetInputData(mesh);
  filter->SetResolution(80);
  vtkdf::testing::UseBackend(filter.Get(), backend);
  return filter;
}

/// The largest difference between the first arrays of two outputs.
double Difference(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = a->GetPointData()->GetArray(0);
  vtkDataArray* y = b->GetPointData()->GetArray(0);
  if (!x || !y || x->GetNumberOfTuples() != y->GetNumberOfTuples())
  {
    return HUGE_VAL;
  }
  double largest = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    largest = std::max(largest, std::fabs(x->GetTuple1(i) - y->GetTuple1(i)));
  }
  return largest;
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(
        argc, argv, 3, "DATA_DIR linfac|linfac-queries|chamfer cpu|gpu"))
  {
    return 2;
  }
  const std::string name = argv[2], backend = argv[3];
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((std::string(argv[1]) + "/bunny_small.vtp").c_str());
  reader->Update();

  auto filter = Make(name, reader->GetOutput(), backend);
  Recorder recorder;
  recorder.Filter = filter;
  recorder.AbortAt = 0.3;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(OnProgress);
  observer->SetClientData(&recorder);
  filter->AddObserver(vtkCommand::ProgressEvent, observer);
  filter->Update();

  // Batches: the steps between the values reported before the abort (past the setup).
  double step = 0;
  for (size_t i = 1; i < recorder.Values.size(); ++i)
  {
    step = std::max(step, recorder.Values[i] - recorder.Values[i - 1]);
  }
  const double last = recorder.ValuesAfter.empty()
    ? recorder.AbortedAt
    : *std::max_element(recorder.ValuesAfter.begin(), recorder.ValuesAfter.end());
  std::printf("%s %s: %zu progress values before the abort at %.3f (largest step %.3f), %zu "
              "after it (largest %.3f); output %lld points\n",
    name.c_str(),
    backend.c_str(),
    recorder.Values.size(),
    recorder.AbortedAt,
    step,
    recorder.ValuesAfter.size(),
    last,
    static_cast<long long>(filter->GetOutput()->GetNumberOfPoints()));
  CHECK(recorder.AbortedAt >= 0.3 && recorder.AbortedAt < 0.9,
    "no progress between 0.3 and 0.9 to abort at (aborted at %g)",
    recorder.AbortedAt);
  // Reported per batch: linfac's GPU batches start at a sixteenth of the slices and at
  // most double, also bounded by time (on the CPU, every tenth); chamfer reports every
  // batch of layers, as the share of voxels reached, which the first layers around a
  // surface raise fastest.
  const size_t fewest = name == "chamfer" ? 2 : 3;
  const double coarsest = 0.5;
  CHECK(recorder.Values.size() >= fewest,
    "only %zu progress values before 30 %%",
    recorder.Values.size());
  CHECK(step <= coarsest, "a batch takes %.3f of the run: progress is too coarse", step);
  CHECK(last <= recorder.AbortedAt + step, "the run went on after the abort (to %.3f)", last);
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0, "an aborted run left an output");

  // The same filter runs to the end once asked again.
  filter->RemoveObserver(observer);
  filter->SetAbortExecute(0);
  filter->Modified();
  filter->Update();
  auto fresh = Make(name, reader->GetOutput(), backend);
  fresh->Update();
  const double difference = Difference(filter->GetOutput(), fresh->GetOutput());
  CHECK(filter->GetOutput()->GetNumberOfPoints() > 0 && difference == 0,
    "after the abort, the run differs from a fresh one by %g",
    difference);
  return vtkdf::testing::Verdict();
}
