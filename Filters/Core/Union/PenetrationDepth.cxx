#include "Union/PenetrationDepth.h"

#include "Union/ConvexHull.h"

#include <algorithm>
#include <cmath>

namespace vtkdf
{

bool PenetrationDepth::BuildSums(const std::vector<ConvexPiece>& p,
  const std::vector<ConvexPiece>& q,
  const double origin[3],
  UnionClosestPoint& sums,
  std::vector<std::pair<int64_t, int64_t>>& pairs,
  int64_t& total,
  std::string& error) const
{
  sums.Pieces.clear();
  sums.Tolerance = this->Tolerance;
  pairs.clear();
  total = static_cast<int64_t>(p.size() * q.size());
  if (total == 0)
  {
    error = "no pieces";
    return false;
  }
  // The sums' boxes: [loP - hiQ, hiP - loQ].
  struct Box
  {
    double Lo[3], Hi[3];
  };
  std::vector<Box> boxes(total);
  Box all;
  for (int a = 0; a < 3; ++a)
  {
    all.Lo[a] = HUGE_VAL, all.Hi[a] = -HUGE_VAL;
  }
  double outside = HUGE_VAL; // the farthest box corner of the nearest sum: O outside M
  for (size_t i = 0; i < p.size(); ++i)
  {
    for (size_t j = 0; j < q.size(); ++j)
    {
      Box& box = boxes[i * q.size() + j];
      double far2 = 0;
      for (int a = 0; a < 3; ++a)
      {
        box.Lo[a] = p[i].Lo[a] - q[j].Hi[a];
        box.Hi[a] = p[i].Hi[a] - q[j].Lo[a];
        all.Lo[a] = std::min(all.Lo[a], box.Lo[a]);
        all.Hi[a] = std::max(all.Hi[a], box.Hi[a]);
        const double f =
          std::max(std::fabs(origin[a] - box.Lo[a]), std::fabs(box.Hi[a] - origin[a]));
        far2 += f * f;
      }
      outside = std::min(outside, std::sqrt(far2));
    }
  }
  // O inside M: the boundary of the box of all sums is outside M, a bound of the answer.
  // Which case holds is not known yet: the larger bound is valid in both.
  double bound = outside;
  bool inBox = true;
  double inside = HUGE_VAL;
  for (int a = 0; a < 3; ++a)
  {
    inBox = inBox && origin[a] >= all.Lo[a] && origin[a] <= all.Hi[a];
    inside = std::min(inside, std::min(origin[a] - all.Lo[a], all.Hi[a] - origin[a]));
  }
  if (inBox)
  {
    bound = std::max(bound, inside);
  }
  std::vector<int64_t> kept;
  for (int64_t k = 0; k < total; ++k)
  {
    double near2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double g =
        std::max(0.0, std::max(boxes[k].Lo[a] - origin[a], origin[a] - boxes[k].Hi[a]));
      near2 += g * g;
    }
    if (std::sqrt(near2) <= bound + this->Tolerance)
    {
      kept.push_back(k);
    }
  }

  // The kept sums' hulls, in parallel (qhull's reentrant API: one context per hull).
  std::vector<ConvexPiece> built(kept.size());
  std::vector<std::string> errors(kept.size());
  auto work = [&](int64_t begin, int64_t end)
  {
    for (int64_t s = begin; s < end; ++s)
    {
      const int64_t i = kept[s] / static_cast<int64_t>(q.size());
      const int64_t j = kept[s] % static_cast<int64_t>(q.size());
      const std::vector<double> a = p[i].Corners(), b = q[j].Corners();
      std::vector<double> differences;
      differences.reserve(a.size() * b.size() / 3);
      for (size_t u = 0; u < a.size(); u += 3)
      {
        for (size_t v = 0; v < b.size(); v += 3)
        {
          for (int c = 0; c < 3; ++c)
          {
            differences.push_back(a[u + c] - b[v + c]);
          }
        }
      }
      std::vector<std::vector<int64_t>> faces;
      int64_t corners = 0;
      std::string why;
      if (!ConvexHull(differences, faces, corners, why) ||
        !built[s].Build(differences, faces, this->Tolerance, why))
      {
        errors[s] = "the sum of piece " + std::to_string(i) + " of P and piece " +
          std::to_string(j) + " of Q: " + why;
      }
    }
  };
  if (this->For)
  {
    this->For(static_cast<int64_t>(kept.size()), 1, work);
  }
  else
  {
    work(0, static_cast<int64_t>(kept.size()));
  }
  for (size_t s = 0; s < kept.size(); ++s)
  {
    if (!errors[s].empty())
    {
      error = errors[s];
      return false;
    }
    sums.Pieces.push_back(std::move(built[s]));
    pairs.emplace_back(
      kept[s] / static_cast<int64_t>(q.size()), kept[s] % static_cast<int64_t>(q.size()));
  }
  return true;
}

bool PenetrationDepth::Compute(const std::vector<ConvexPiece>& p,
  const std::vector<ConvexPiece>& q,
  const double origin[3],
  PenetrationAnswer& answer,
  std::string& error,
  HeadlessGL* gl,
  const UnionGPUSettings& settings) const
{
  answer = PenetrationAnswer();
  UnionClosestPoint sums;
  std::vector<std::pair<int64_t, int64_t>> pairs;
  if (!this->BuildSums(p, q, origin, sums, pairs, answer.PairsTotal, error))
  {
    return false;
  }
  answer.PairsKept = static_cast<int64_t>(pairs.size());
  sums.For = this->For; // one query: parallel over its faces
  UnionAnswer closest;
  if (gl)
  {
    std::vector<UnionGPUAnswer> gpu;
    if (!QueryUnionGPU(*gl, sums, std::vector<double>(origin, origin + 3), settings, gpu, error))
    {
      return false;
    }
    closest = gpu[0].Answer;
    answer.ErrorBound = gpu[0].ErrorBound;
    answer.Certified = gpu[0].Certified;
    answer.Passes = gpu[0].Passes;
  }
  else
  {
    closest = sums.Query(origin);
  }
  answer.Intersecting = closest.Inside;
  answer.Distance = std::fabs(closest.Distance);
  answer.FacesVisited = closest.FacesVisited;
  for (int a = 0; a < 3; ++a)
  {
    answer.Translation[a] = closest.Closest[a] - origin[a];
  }
  if (closest.Piece >= 0)
  {
    answer.PieceP = pairs[closest.Piece].first;
    answer.PieceQ = pairs[closest.Piece].second;
  }
  return true;
}

} // namespace vtkdf
