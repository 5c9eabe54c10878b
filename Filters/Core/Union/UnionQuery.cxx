#include "Union/UnionQuery.h"

#include "GL/HeadlessGL.h"

#include <algorithm>

namespace vtkdf
{

bool QueryUnion(UnionClosestPoint& query,
  const std::vector<double>& queries,
  HeadlessGL* gl,
  const UnionQueryOptions& options,
  const Execution& execution,
  std::vector<UnionGPUAnswer>& answers,
  bool& aborted,
  std::string& error)
{
  aborted = false;
  const int64_t n = static_cast<int64_t>(queries.size() / 3);
  answers.assign(n, UnionGPUAnswer());
  // Parallel over the queries (or their certification), or over each query's faces when
  // there are too few queries to keep the threads busy.
  const bool fewQueries = n < 4 * options.Threads;
  if (fewQueries)
  {
    query.For = execution.For;
  }
  if (gl)
  {
    UnionGPUSettings settings;
    if (!fewQueries)
    {
      settings.For = execution.For;
    }
    bool stopped = false;
    settings.Progress = [&](double fraction)
    {
      stopped = !execution.Report(0.1 + 0.8 * fraction);
      return !stopped;
    };
    if (!QueryUnionGPU(*gl, query, queries, settings, answers, error))
    {
      aborted = stopped;
      return stopped;
    }
    return true;
  }
  // In twenty blocks, between which progress is told and an abort heard.
  const int64_t block = std::max<int64_t>(1, (n + 19) / 20);
  for (int64_t first = 0; first < n; first += block)
  {
    const int64_t last = std::min(n, first + block);
    execution.For(last - first,
      0, // the host's own grain
      [&](int64_t begin, int64_t end)
      {
        for (int64_t i = first + begin; i < first + end; ++i)
        {
          answers[i].Answer = query.Query(&queries[3 * i]);
        }
      });
    if (!execution.Report(0.1 + 0.8 * double(last) / double(n)))
    {
      aborted = true;
      return true;
    }
  }
  return true;
}

} // namespace vtkdf
