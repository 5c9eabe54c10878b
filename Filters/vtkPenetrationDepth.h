/**
 * @class   vtkPenetrationDepth
 * @brief   Penetration depth of two solids made of convex pieces.
 *
 * P (input 0) and Q (input 1) are unions of convex pieces, in the forms
 * vtkConvexQueryAlgorithm describes. The convex decomposition is the user's (robot and CAD
 * collision models come as convex pieces); UseConvexHulls replaces pieces that are not
 * closed and convex by their hulls.
 *
 * The penetration depth is the distance from the origin to the boundary of the
 * Minkowski difference P - Q, the union of the convex sums P_i - Q_j (each the qhull hull
 * of its corners' differences), found by the exact closest-point query of
 * vtkUnionClosestPoint (Algorithm 3.1 of Kim, Hoff, Lin and Manocha, "Closest Point Query
 * Among the Union of Convex Polytopes Using Rasterization Hardware", Journal of Graphics
 * Tools 7(4), 2002) without building the union. Unlike a
 * per-pair depth (FCL, Bullet, libccd), it is the global one: the deepest pair is only a
 * lower bound. Pairs whose sums cannot reach the answer are skipped before their hulls
 * are built. P and Q are in one frame. Backend chooses where the query runs, as for
 * vtkUnionClosestPoint: the CPU, or the GPU's bound from which the CPU's exact search
 * starts; the same answer either way.
 *
 * For two arbitrary (non-convex, open, deforming) meshes, vtkDistanceFieldProximity
 * gives a different answer: each surface's maximum penetration into the other and the
 * contacts, not a separating translation.
 *
 * In a distributed run (a vtkMultiProcessController with several processes), every rank
 * holds both solids, builds its block of the kept sums, and rank 0 gathers them (in the
 * order of one process) and answers; the other ranks' outputs are empty.
 *
 * Output: vtkPolyData with the minimum translation vector as a line (from the point of Q
 * farthest against Direction, the one that leaves P last, to that point translated), and
 * field data `PenetrationDepth` (0 when P and Q do not intersect), `Direction` (unit:
 * translating Q by PenetrationDepth x Direction separates it from P, up to touching),
 * `Intersecting` (0/1), `WitnessPieces` (the pair of pieces, P's
 * then Q's, whose sum holds the answer) and, when P and Q do not intersect,
 * `SeparationDistance` (translating Q by it along Direction brings them into contact).
 */
#ifndef vtkPenetrationDepth_h
#define vtkPenetrationDepth_h

#include "vtkConvexQueryAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#ifndef __VTK_WRAP__
namespace vtkdf
{
struct PenetrationAnswer;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkPenetrationDepth : public vtkConvexQueryAlgorithm
{
public:
  static vtkPenetrationDepth* New();
  vtkTypeMacro(vtkPenetrationDepth, vtkConvexQueryAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The two solids: P on port 0, Q on port 1.
  void SetSolidPConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetSolidQConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSolidPData(vtkDataObject* data) { this->SetInputData(0, data); }
  void SetSolidQData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// The last run's answer.
  vtkGetMacro(LastPenetrationDepth, double);
  vtkGetMacro(LastSeparationDistance, double);
  vtkGetVector3Macro(LastDirection, double);
  vtkGetMacro(LastIntersecting, bool);
  ///@}

  /**
   * The image-space error of the GPU's rendered views, which the GPU backend no longer
   * renders: 0, every answer is exact.
   * @deprecated Nothing replaces it.
   */
  VTK_DEPRECATION("Every answer is exact: LastErrorBound is 0")
  double GetLastErrorBound() { return 0; }

  ///@{
  /// The last run's work: pairs of pieces and those whose sums were built (the faces of
  /// the sums the query visited are LastFacesVisited). In a distributed run the ranks
  /// share the building: LastPairsBuilt is this rank's part of LastPairsKept (all of it
  /// in one process).
  vtkGetMacro(LastPairsTotal, vtkTypeInt64);
  vtkGetMacro(LastPairsKept, vtkTypeInt64);
  vtkGetMacro(LastPairsBuilt, vtkTypeInt64);
  ///@}

protected:
  vtkPenetrationDepth();
  ~vtkPenetrationDepth() override = default;

#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
#ifndef __VTK_WRAP__
  /// The output: the translation as a line, the answer as field data.
  void WriteAnswer(const vtkdf::PenetrationAnswer& answer,
    const vtkdf::ConvexPieceInput& q,
    vtkPolyData* output);
#endif

  double LastPenetrationDepth = 0;
  double LastSeparationDistance = 0;
  double LastDirection[3] = { 0, 0, 0 };
  bool LastIntersecting = false;
  vtkTypeInt64 LastPairsTotal = 0;
  vtkTypeInt64 LastPairsKept = 0;
  vtkTypeInt64 LastPairsBuilt = 0;

private:
  vtkPenetrationDepth(const vtkPenetrationDepth&) = delete;
  void operator=(const vtkPenetrationDepth&) = delete;
};

#endif
