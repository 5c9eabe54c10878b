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

  // This share's block of the kept sums.
  if (this->Shares > 1)
  {
    const size_t count = kept.size(), shares = static_cast<size_t>(this->Shares);
    const size_t share = static_cast<size_t>(this->Share);
    kept = std::vector<int64_t>(
      kept.begin() + count * share / shares, kept.begin() + count * (share + 1) / shares);
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
    pairs.emplace_back(
      kept[s] / static_cast<int64_t>(q.size()), kept[s] % static_cast<int64_t>(q.size()));
    if (!errors[s].empty())
    {
      error = errors[s];
      return false;
    }
    sums.Pieces.push_back(std::move(built[s]));
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
  UnionClosestPoint sums;
  std::vector<std::pair<int64_t, int64_t>> pairs;
  int64_t total = 0;
  if (!this->BuildSums(p, q, origin, sums, pairs, total, error))
  {
    return false;
  }
  return this->Query(sums, pairs, total, origin, answer, error, gl, settings);
}

bool PenetrationDepth::Query(UnionClosestPoint& sums,
  const std::vector<std::pair<int64_t, int64_t>>& pairs,
  int64_t total,
  const double origin[3],
  PenetrationAnswer& answer,
  std::string& error,
  HeadlessGL* gl,
  const UnionGPUSettings& settings) const
{
  answer = PenetrationAnswer();
  answer.PairsTotal = total;
  answer.PairsKept = static_cast<int64_t>(pairs.size());
  if (pairs.size() != sums.Pieces.size())
  {
    error = "the sums and their pairs differ in number";
    return false;
  }
  sums.Tolerance = this->Tolerance;
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
    answer.Estimate = gpu[0].Estimate;
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

// A share: [1, count, then per sum: i, j, faces, per face its corner count and corners,
// planes (4 a face), Lo, Hi, Centre, InnerRadius], or [0, i, j] for a failed one. Ids
// and counts are below 2^53: exact as doubles.
std::vector<double> PackSums(bool built,
  const std::vector<ConvexPiece>& sums,
  const std::vector<std::pair<int64_t, int64_t>>& pairs)
{
  std::vector<double> data;
  if (!built)
  {
    data = { 0, -1, -1 };
    if (!pairs.empty())
    {
      data[1] = static_cast<double>(pairs.back().first);
      data[2] = static_cast<double>(pairs.back().second);
    }
    return data;
  }
  data.push_back(1);
  data.push_back(static_cast<double>(sums.size()));
  for (size_t s = 0; s < sums.size(); ++s)
  {
    const ConvexPiece& piece = sums[s];
    data.push_back(static_cast<double>(pairs[s].first));
    data.push_back(static_cast<double>(pairs[s].second));
    data.push_back(static_cast<double>(piece.Faces.size()));
    for (const std::vector<double>& face : piece.Faces)
    {
      data.push_back(static_cast<double>(face.size() / 3));
      data.insert(data.end(), face.begin(), face.end());
    }
    data.insert(data.end(), piece.Planes.begin(), piece.Planes.end());
    data.insert(data.end(), piece.Lo, piece.Lo + 3);
    data.insert(data.end(), piece.Hi, piece.Hi + 3);
    data.insert(data.end(), piece.Centre, piece.Centre + 3);
    data.push_back(piece.InnerRadius);
  }
  return data;
}

bool UnpackSums(const double* data,
  size_t size,
  int shares,
  std::vector<ConvexPiece>& sums,
  std::vector<std::pair<int64_t, int64_t>>& pairs,
  std::string& error)
{
  size_t at = 0;
  // The next value as a count no larger than `most` (what the data left can hold).
  auto count = [&](size_t most, int64_t& value)
  {
    if (at >= size)
    {
      return false;
    }
    const double v = data[at++];
    if (!(v >= 0 && v <= static_cast<double>(most)) || v != std::floor(v))
    {
      return false;
    }
    value = static_cast<int64_t>(v);
    return true;
  };
  int share = 0;
  for (; at < size; ++share)
  {
    const double kind = data[at++];
    if (kind == 0 && at + 2 <= size)
    {
      error = "the sum of piece " + std::to_string(static_cast<int64_t>(data[at])) +
        " of P and piece " + std::to_string(static_cast<int64_t>(data[at + 1])) +
        " of Q has no hull (share " + std::to_string(share) + ")";
      return false;
    }
    int64_t n = 0;
    if (kind != 1 || !count(size, n))
    {
      error = "share " + std::to_string(share) + " is not a packed share of sums";
      return false;
    }
    for (int64_t s = 0; s < n; ++s)
    {
      int64_t i = 0, j = 0, faces = 0;
      if (!count(size, i) || !count(size, j) || !count(size, faces))
      {
        error = "share " + std::to_string(share) + " ends inside a sum";
        return false;
      }
      ConvexPiece piece;
      piece.Faces.resize(static_cast<size_t>(faces));
      for (std::vector<double>& face : piece.Faces)
      {
        int64_t corners = 0;
        if (!count(size, corners) || static_cast<size_t>(corners) > (size - at) / 3)
        {
          error = "share " + std::to_string(share) + " ends inside a face";
          return false;
        }
        face.assign(data + at, data + at + 3 * corners);
        at += static_cast<size_t>(3 * corners);
      }
      const size_t rest = 4 * static_cast<size_t>(faces) + 10;
      if (size - at < rest)
      {
        error = "share " + std::to_string(share) + " ends inside a sum";
        return false;
      }
      piece.Planes.assign(data + at, data + at + 4 * faces);
      at += 4 * static_cast<size_t>(faces);
      std::copy(data + at, data + at + 3, piece.Lo);
      std::copy(data + at + 3, data + at + 6, piece.Hi);
      std::copy(data + at + 6, data + at + 9, piece.Centre);
      piece.InnerRadius = data[at + 9];
      at += 10;
      sums.push_back(std::move(piece));
      pairs.emplace_back(i, j);
    }
  }
  if (share != shares)
  {
    error =
      std::to_string(share) + " shares of sums where " + std::to_string(shares) + " were expected";
    return false;
  }
  return true;
}

} // namespace vtkdf
