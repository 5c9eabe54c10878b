// QueryTree: the tree of a mesh's primitives (triangles, and the segments and points of
// degenerate cells) that answers exact nearest-primitive queries with the tie rules of
// the linear factorization (built in QueryTree.cxx, searched in QueryTreeSearch.cxx).
// NearestTriangleQueries asks it for the samples of a grid, PointDistance for any points,
// HausdorffDistance for points and pieces of another mesh. Private to the
// linear-factorization family.
#ifndef vtkdf_QueryTree_h
#define vtkdf_QueryTree_h

#include "Common/LargeVector.h"
#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/PointTriangleDistance.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{
namespace nearest
{
constexpr int LeafSize = 8;
constexpr int StackSize = 128; // see QueryTree::Nearest

/// The corners a, b, c of a triangle, segment (b = c) or point (a = b = c) of the mesh.
struct Primitive
{
  double X[9];
};

/// A primitive as the tree stores it: its corners' indices into the tree's points (12
/// bytes where the corners themselves take 72: a fine mesh's tree is written to fresh
/// memory once, and most of it is read a few times).
using CornerIds = std::array<uint32_t, 3>;

/// The tree the queries descend: up to four children's boxes side by side (a binary
/// node's grandchildren, their boxes rounded outward to float), so that one node's memory
/// holds every box the next step tests.
/// Child c is a wide node (Count[c] == 0, at First[c]), leaf First[c] (Count[c] > 0,
/// its number of primitives), or absent (Count[c] < 0).
struct WideNode
{
  float Lo[3][4], Hi[3][4];
  int32_t First[4];
  int32_t Count[4];
};

/// A leaf's primitives [First, First + Count) and the box that holds them in the frame
/// of their mean normal: on a finely tessellated surface the axis-aligned boxes of
/// neighbouring leaves overlap a sample's sphere of reach far more often than these
/// thin ones do.
struct Leaf
{
  float Centre[3];
  float Axes[3][3]; // unit and orthogonal, up to float rounding
  float Extent[3];
  int32_t First, Count;
};

/// MeshSites' face test and unit normal: distinct corners, and twice the area above
/// `degenerate` times the longest side.
bool FaceNormal(const double* x, double degenerate, double normal[3]);
/// The same test alone (ProperFace), with the normal not normalized and its length.
bool IsProperFace(const double* x, double degenerate, double n[3], double& area2);

struct PrimitiveCorners;

class QueryTree
{
public:
  /// The tree of the mesh's primitives: checked and bounded (BoundUsedPoints), in Morton
  /// order (SortedMortonKeys), copied (GatherPrimitives), oriented (FacesVolume), then
  /// the nodes built, widened and their leaves framed.
  bool Build(const MeshInput& mesh, const ParallelFor& parallelFor, std::string& error);

  /// The nearest primitive to p: its index, squared distance, closest point and feature
  /// (TriangleFeature). Exact ties go to the smaller cell, then the smaller index, so the
  /// answer does not depend on `bound2` (an upper bound on the squared distance, or
  /// HUGE_VAL). Returns the number of primitives evaluated; index -1 when none lies
  /// within the bound.
  int64_t Nearest(const double p[3],
    double bound2,
    int64_t& index,
    double& best2,
    double closest[3],
    int& feature) const;

  /// The primitive whose largest squared distance from the `count` points (at most 3,
  /// xyz each) is the smallest, below `bound2`: min over primitives t of max over i of
  /// |p_i - t|^2, as `index` and `worst2` (index -1 when none is below the bound). The
  /// search stops at the first primitive at or below `enough2`. Every point of a convex
  /// set within the points' hull is within that distance of the primitive, the bound the
  /// Hausdorff distance subdivides by. Returns the primitive distances computed.
  int64_t NearestToAll(const double* points,
    int count,
    double bound2,
    double enough2,
    int64_t& index,
    double& worst2) const;

  /// The proper triangles (faces) whose boxes meet the box lo..hi, into `found`; false
  /// when there are more than `limit`.
  bool GatherFaces(const double lo[3],
    const double hi[3],
    size_t limit,
    std::vector<int32_t>& found) const;

  /// The smallest cell among the primitives with a corner at `a` (and at `b` too, when
  /// given), and the pseudonormal of that vertex or edge: the faces' unit normals, each
  /// weighted by its angle at `a` for a vertex. With `primitive`, the primitive of that
  /// cell holding the feature (the first in the mesh's order where the cell has several).
  void FeatureCellAndNormal(const double* a,
    const double* b,
    int64_t& cell,
    double normal[3],
    int64_t* primitive = nullptr) const;

  /// The signed count of the crossings of the mesh's triangles with the ray from p to
  /// x = -infinity (WindingCrossings.h's rule: exact orientation tests, the ray moved
  /// symbolically off edges and corners): the winding number at p when the triangles
  /// form a closed chain. False when p may lie on a triangle (then undecided).
  bool CrossingCount(const double p[3], int64_t& count) const;

  /// The corners of primitive i.
  Primitive Get(int64_t i) const
  {
    Primitive t;
    for (int k = 0; k < 3; ++k)
    {
      const double* x = this->Corner(i, k);
      t.X[3 * k] = x[0], t.X[3 * k + 1] = x[1], t.X[3 * k + 2] = x[2];
    }
    return t;
  }
  /// Corner k of primitive i.
  const double* Corner(int64_t i, int k) const
  {
    return this->Points.data() + 3 * int64_t(this->Corners[i][k]);
  }
  /// The squared distance from p to primitive i (its edges only where it is not a proper
  /// triangle), as Nearest computes it.
  double Distance2(int64_t i, const double p[3]) const
  {
    const double *a = this->Corner(i, 0), *b = this->Corner(i, 1), *c = this->Corner(i, 2);
    return this->Faces[i] ? SquaredDistanceToTriangle(p, a, b, c)
                          : SquaredDistanceToTriangleEdges(p, a, b, c);
  }
  int64_t Size() const { return static_cast<int64_t>(this->Corners.size()); }
  /// Whether primitive i is a proper triangle (else only its edges count).
  bool IsFace(int64_t i) const { return this->Faces[i] != 0; }
  int64_t Cell(int64_t i) const { return this->Cells[i]; }
  /// The primitive's index in the mesh's order: its triangles, then its segments, then
  /// its vertices.
  int64_t Source(int64_t i) const { return this->Sources[i]; }
  /// A face's pseudonormal: its unit normal, turned by the mesh's orientation.
  void FaceNormalOf(int64_t i, double normal[3]) const
  {
    FaceNormal(this->Get(i).X, this->Degenerate, normal);
    for (int k = 0; k < 3; ++k)
    {
      normal[k] *= this->Orientation;
    }
  }
  // -1 when the faces' signed volume is negative. MeshSites measures it from another
  // point: the same sign on a closed mesh; on an open one (where the pseudonormal sign is
  // arbitrary anyway) the two may differ.
  double Orientation = 1;
  double Degenerate = 0;
  int64_t Triangles = 0; // primitives of the mesh's triangles: Source() below this
  double Tolerance2 = 0; // absolute slack on squared distances (coordinates' rounding)

private:
  /// The points, and the primitives' corners, cells, face flags and codes in the order of
  /// the sorted `keys`.
  void GatherPrimitives(const PrimitiveCorners& corners,
    const LargeVector<uint64_t>& keys,
    const ParallelFor& parallelFor);
  /// The faces' signed volume (times 6) seen from `lo`, in a fixed order (the same sum on
  /// any thread count).
  double FacesVolume(const double lo[3]) const;
  /// The wide nodes and leaves of the binary tree that splits the primitives where their
  /// Morton codes differ (SplitCodes), down to leaves of at most LeafSize.
  void BuildWideNodes(int32_t n, const ParallelFor& parallelFor);
  void FrameLeaves(const ParallelFor& parallelFor);
  double LeafDistance2(const Leaf& leaf, const double p[3]) const;
  template<typename InBox, typename Visit>
  bool VisitPrimitives(const InBox& inBox, const Visit& visit) const;

  // The points the primitives use (xyz, in the order the tree's primitives first use
  // them), and per primitive, in the tree's order: its corners, input cell, index in the
  // mesh's order, whether it is a proper triangle (MeshSites' rule; otherwise only its
  // edges count) and, while the tree is built, its Morton code.
  LargeVector<double> Points;
  LargeVector<CornerIds> Corners;
  LargeVector<int64_t> Cells;
  LargeVector<uint32_t> Sources;
  LargeVector<uint8_t> Faces;
  LargeVector<uint32_t> Codes;
  LargeVector<WideNode> WideNodes;
  LargeVector<Leaf> Leaves;
  double Margin = 0; // how far the leaves' frames are widened beyond rounding
};
} // namespace nearest
} // namespace vtkdf

#endif
