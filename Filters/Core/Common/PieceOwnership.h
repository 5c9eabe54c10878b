// PieceOwnership: which samples of a grid each piece of a distributed run owns, for the
// results that count samples once across the pieces (the segmented field's region
// evidence). The pieces of a run may share samples: VTK's pieces of an image share their
// boundary planes, and a piece may even be the whole grid on every rank. A sample belongs
// to the first piece, in rank order, that holds it.
#ifndef vtkdf_PieceOwnership_h
#define vtkdf_PieceOwnership_h

#include "Common/SampleGrid.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace vtkdf
{

struct PieceOwnership
{
  IndexBox Piece;               // this rank's
  std::vector<IndexBox> Before; // the pieces of the ranks before it

  /// The samples of row (j, k) of Piece that it owns, as runs [first, last] of i in
  /// increasing order (none when the row is not in Piece).
  void Runs(int j, int k, std::vector<std::pair<int, int>>& runs) const
  {
    runs.clear();
    if (this->Piece.Empty() || j < this->Piece.Lo[1] || j > this->Piece.Hi[1] ||
      k < this->Piece.Lo[2] || k > this->Piece.Hi[2])
    {
      return;
    }
    // The rows of earlier pieces through (j, k): the samples taken already.
    std::vector<std::pair<int, int>> taken;
    for (const IndexBox& box : this->Before)
    {
      if (!box.Empty() && j >= box.Lo[1] && j <= box.Hi[1] && k >= box.Lo[2] && k <= box.Hi[2])
      {
        taken.emplace_back(box.Lo[0], box.Hi[0]);
      }
    }
    std::sort(taken.begin(), taken.end());
    int next = this->Piece.Lo[0]; // the first sample not yet decided
    for (const auto& span : taken)
    {
      if (span.first > next)
      {
        runs.emplace_back(next, std::min(span.first - 1, this->Piece.Hi[0]));
      }
      next = std::max(next, span.second + 1);
      if (next > this->Piece.Hi[0])
      {
        return;
      }
    }
    runs.emplace_back(next, this->Piece.Hi[0]);
  }
};

/// How many samples of `whole` the `pieces` hold together, each sample once: the
/// pieces tile the grid when it is whole.Count(). Exact for any boxes (the count runs
/// over the cells between the boxes' faces, at most (2 pieces)^3 of them).
inline int64_t CoveredSamples(const std::vector<IndexBox>& pieces, const IndexBox& whole)
{
  std::vector<IndexBox> boxes;
  for (const IndexBox& piece : pieces)
  {
    const IndexBox box = piece.Intersect(whole);
    if (!box.Empty())
    {
      boxes.push_back(box);
    }
  }
  // Per axis, the boundaries [cut[c], cut[c + 1]) of the cells.
  std::vector<int> cuts[3];
  for (int a = 0; a < 3; ++a)
  {
    for (const IndexBox& box : boxes)
    {
      cuts[a].push_back(box.Lo[a]);
      cuts[a].push_back(box.Hi[a] + 1);
    }
    std::sort(cuts[a].begin(), cuts[a].end());
    cuts[a].erase(std::unique(cuts[a].begin(), cuts[a].end()), cuts[a].end());
  }
  int64_t covered = 0;
  for (size_t x = 0; x + 1 < cuts[0].size(); ++x)
  {
    for (size_t y = 0; y + 1 < cuts[1].size(); ++y)
    {
      for (size_t z = 0; z + 1 < cuts[2].size(); ++z)
      {
        const int at[3] = { cuts[0][x], cuts[1][y], cuts[2][z] };
        const bool held = std::any_of(boxes.begin(),
          boxes.end(),
          [&](const IndexBox& box)
          {
            return at[0] >= box.Lo[0] && at[0] <= box.Hi[0] && at[1] >= box.Lo[1] &&
              at[1] <= box.Hi[1] && at[2] >= box.Lo[2] && at[2] <= box.Hi[2];
          });
        if (held)
        {
          covered +=
            int64_t(cuts[0][x + 1] - at[0]) * (cuts[1][y + 1] - at[1]) * (cuts[2][z + 1] - at[2]);
        }
      }
    }
  }
  return covered;
}

} // namespace vtkdf

#endif
