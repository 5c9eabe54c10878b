#include "Union/ConvexHull.h"

extern "C"
{
#include "libqhull_r/qhull_ra.h"
}

#include <cstdio>
#include <set>

namespace vtkdf
{

bool ConvexHull(const std::vector<double>& points,
  std::vector<std::vector<int64_t>>& faces,
  int64_t& corners,
  std::string& error)
{
  faces.clear();
  corners = 0;
  const int count = static_cast<int>(points.size() / 3);
  if (count < 4)
  {
    error = "fewer than 4 points have no three-dimensional hull";
    return false;
  }
  // qhull writes its messages to a FILE: a memory stream keeps them for the error.
  char* messages = nullptr;
  size_t length = 0;
  FILE* errors = open_memstream(&messages, &length);
  qhT context;
  qhT* qh = &context;
  qh_zero(qh, errors);
  std::vector<coordT> coordinates(points.begin(), points.end());
  // Qt: triangulated facets; the default joggle-free run merges coplanar facets first.
  char options[] = "qhull Qt";
  const int status =
    qh_new_qhull(qh, 3, count, coordinates.data(), False, options, nullptr, errors);
  if (status == 0)
  {
    std::set<int64_t> onHull;
    facetT* facet;
    FORALLfacets
    {
      std::vector<int64_t> triangle;
      vertexT* vertex;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices)
      {
        triangle.push_back(qh_pointid(qh, vertex->point));
        onHull.insert(triangle.back());
      }
      faces.push_back(std::move(triangle));
    }
    corners = static_cast<int64_t>(onHull.size());
  }
  qh_freeqhull(qh, !qh_ALL);
  int shortCount = 0, longCount = 0;
  qh_memfreeshort(qh, &shortCount, &longCount);
  std::fclose(errors);
  if (status != 0)
  {
    std::string text = messages ? std::string(messages, length) : std::string();
    // qhull's first line says what went wrong.
    const size_t end = text.find('\n', text.find_first_not_of("\n "));
    error = "qhull found no three-dimensional hull (" +
      (text.empty() ? std::string("status ") + std::to_string(status) : text.substr(0, end)) + ")";
  }
  std::free(messages);
  return status == 0;
}

} // namespace vtkdf
