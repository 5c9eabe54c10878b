/**
 * @class   vtkLinearFactorDistanceField
 * @brief   Exact Euclidean distance field of a polygon mesh by linear factorization.
 *
 * Implements Sud, Govindaraju, Gayle and Manocha, "Interactive 3D Distance Field
 * Computation using Linear Factorization" (I3D 2006). The mesh is split into sites
 * (vertices, edges, triangles). Each site gets a convex domain that contains its
 * Voronoi region; on every slice of the grid the domain becomes a polygon, across which
 * the site's distance vector is an affine function of position, so interpolating the
 * corner vectors gives the exact vector at every sample; the nearest site wins.
 *
 * Input: triangles, polygons (triangulated), strips, lines and polylines (edge sites),
 * vertices (point sites). Open and non-manifold meshes, polygon soups, duplicate
 * points and degenerate triangles are valid input and their distances are exact.
 *
 * Output point data (each switchable): `Distance` (float; negative inside with
 * SignMode = PseudoNormal or WindingNumber), `ClosestCellId` (input cell id),
 * `ClosestFeature` (uint8: 0 vertex, 1 edge, 2 face interior), `ClosestPoint` (float
 * x3), `WindingNumber` (float), `ClosestBarycentric` with `ClosestSubTriangle`, and
 * `Gradient` (float x3): vtkMeshDistanceFilter's arrays, at the grid's samples.
 *
 * Domains (DomainShape): Auto gives every site the tightest exact domain whatever the
 * topology (edges bounded by all incident faces, vertices by the planes orthogonal to
 * all incident edges); NonManifold uses the triangle prism, the edge slab and the whole
 * slice for points; Manifold uses the paper's manifold domains (edge wedge,
 * convex-vertex polytope, Theorem 1's pyramid for hyperbolic vertices) where the
 * neighbourhood is a closed manifold. Every mode is exact; they differ in speed.
 * Domains are also clipped to where a site can still be nearest (range culling).
 *
 * Accuracy: at most 1e-4 of the smallest spacing from the exact distance (domains are
 * widened by that much so that neighbouring domains overlap despite rounding); the
 * value is recomputed in double precision from the winning site.
 *
 * Memory between executions: the site scan's nearest-site buffer (8 bytes a sample)
 * stays with the filter, so that executing it again (a new resolution, new arrays) on a
 * grid at most as large does not touch fresh pages for it; it goes when the grid needs
 * less than half of it, when the input changes, when the filter is deleted, or with
 * ReleaseWorkBuffers().
 */
#ifndef vtkLinearFactorDistanceField_h
#define vtkLinearFactorDistanceField_h

#include "vtkDeprecation.h" // For VTK_DEPRECATION
#include "vtkDistanceFieldAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkImageData;
#ifndef __VTK_WRAP__
namespace vtkdf
{
struct LinearFactorArrays;
class LinearFactorWorkspace;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkLinearFactorDistanceField : public vtkDistanceFieldAlgorithm
{
public:
  static vtkLinearFactorDistanceField* New();
  vtkTypeMacro(vtkLinearFactorDistanceField, vtkDistanceFieldAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How Distance is signed (negative inside). PseudoNormal: by the angle-weighted
  /// pseudonormal of the closest feature, exact for closed manifold meshes (flipped by
  /// the mesh's signed volume when it is oriented inward) and arbitrary elsewhere.
  /// WindingNumber: inside where the generalized winding number has |w| > 1/2, the
  /// intuitive sign on meshes with holes, cracks and flipped or repeated faces, and
  /// graceful on soups (a triangle repeated with the same orientation counts once; two
  /// copies with opposite orientations cancel, as if absent). The magnitudes are the
  /// same in every mode.
  enum SignModeType
  {
    UNSIGNED = 0,
    PSEUDO_NORMAL = 1,
    WINDING_NUMBER = 2
  };
  vtkSetMacro(SignMode, int);
  vtkGetMacro(SignMode, int);
  void SetSignModeToUnsigned() { this->SetSignMode(UNSIGNED); }
  void SetSignModeToPseudoNormal() { this->SetSignMode(PSEUDO_NORMAL); }
  void SetSignModeToWindingNumber() { this->SetSignMode(WINDING_NUMBER); }

  /// The sites' domains (above): Auto (the default), NonManifold or Manifold.
  enum DomainShapeType
  {
    DOMAIN_SHAPE_AUTO = 0,
    DOMAIN_SHAPE_NON_MANIFOLD = 1,
    DOMAIN_SHAPE_MANIFOLD = 2
  };
  vtkSetMacro(DomainShape, int);
  vtkGetMacro(DomainShape, int);
  void SetDomainShapeToAuto() { this->SetDomainShape(DOMAIN_SHAPE_AUTO); }
  void SetDomainShapeToNonManifold() { this->SetDomainShape(DOMAIN_SHAPE_NON_MANIFOLD); }
  void SetDomainShapeToManifold() { this->SetDomainShape(DOMAIN_SHAPE_MANIFOLD); }

  ///@{
  /**
   * The earlier name of DomainShape, kept for existing code: it chooses the domains'
   * shapes, while range culling is another step that always runs.
   * @deprecated Use SetDomainShape()/GetDomainShape() and the DOMAIN_SHAPE_ values.
   */
  enum CullingType
  {
    CULLING_AUTO = DOMAIN_SHAPE_AUTO,
    CULLING_NON_MANIFOLD = DOMAIN_SHAPE_NON_MANIFOLD,
    CULLING_MANIFOLD = DOMAIN_SHAPE_MANIFOLD
  };
  VTK_DEPRECATION("Culling is now DomainShape: use SetDomainShape")
  void SetCulling(int value) { this->SetDomainShape(value); }
  VTK_DEPRECATION("Culling is now DomainShape: use GetDomainShape")
  int GetCulling() { return this->GetDomainShape(); }
  VTK_DEPRECATION("Culling is now DomainShape: use SetDomainShapeToAuto")
  void SetCullingToAuto() { this->SetDomainShape(DOMAIN_SHAPE_AUTO); }
  VTK_DEPRECATION("Culling is now DomainShape: use SetDomainShapeToNonManifold")
  void SetCullingToNonManifold() { this->SetDomainShape(DOMAIN_SHAPE_NON_MANIFOLD); }
  VTK_DEPRECATION("Culling is now DomainShape: use SetDomainShapeToManifold")
  void SetCullingToManifold() { this->SetDomainShape(DOMAIN_SHAPE_MANIFOLD); }
  ///@}

  /// How the CPU finds each sample's nearest feature. SiteScan: the linear factorization
  /// above. SampleQueries: one nearest-triangle query per sample through a bounding-volume
  /// hierarchy, faster where the mesh has more cells than the grid has samples (a fine
  /// mesh on a coarse grid; CPU only). Auto (the default) takes SampleQueries on the CPU
  /// where the mesh has at least 2.5 times more cells than the whole grid has samples
  /// (with a MaximumDistance, samples within the band, estimated from the mesh's area).
  /// Both are exact: the same distances, features and cell ids, but where a sample lies
  /// within rounding of two features.
  enum RouteType
  {
    ROUTE_AUTO = 0,
    ROUTE_SITE_SCAN = 1,
    ROUTE_SAMPLE_QUERIES = 2
  };
  vtkSetMacro(Route, int);
  vtkGetMacro(Route, int);
  void SetRouteToAuto() { this->SetRoute(ROUTE_AUTO); }
  void SetRouteToSiteScan() { this->SetRoute(ROUTE_SITE_SCAN); }
  void SetRouteToSampleQueries() { this->SetRoute(ROUTE_SAMPLE_QUERIES); }
  /// The route the last run took: "site scan", "sample queries" or "none".
  const char* GetLastRoute() const { return this->LastRoute.c_str(); }

  ///@{
  /// Samples farther than this hold exactly this value (a narrow band); it also clips
  /// the domains, which saves time. 0 (the default) means no limit. Otherwise it must be
  /// finite, and at least 1e-3 of the smallest spacing (the field's accuracy: a smaller
  /// cap could not be told apart from rounding).
  vtkSetMacro(MaximumDistance, double);
  vtkGetMacro(MaximumDistance, double);
  ///@}

  ///@{
  /// Which arrays to produce (Distance and ClosestCellId by default).
  vtkSetMacro(ComputeDistance, bool);
  vtkGetMacro(ComputeDistance, bool);
  vtkBooleanMacro(ComputeDistance, bool);
  vtkSetMacro(ComputeClosestCellId, bool);
  vtkGetMacro(ComputeClosestCellId, bool);
  vtkBooleanMacro(ComputeClosestCellId, bool);
  vtkSetMacro(ComputeClosestFeature, bool);
  vtkGetMacro(ComputeClosestFeature, bool);
  vtkBooleanMacro(ComputeClosestFeature, bool);
  vtkSetMacro(ComputeClosestPoint, bool);
  vtkGetMacro(ComputeClosestPoint, bool);
  vtkBooleanMacro(ComputeClosestPoint, bool);
  /// `WindingNumber` (float): w at every sample, within the evaluation's error bound
  /// (exact where the bound could not decide the sign). Off by default; any SignMode.
  vtkSetMacro(ComputeWindingNumber, bool);
  vtkGetMacro(ComputeWindingNumber, bool);
  vtkBooleanMacro(ComputeWindingNumber, bool);
  /// `ClosestBarycentric` (float x3) and `ClosestSubTriangle` (vtkIdType): the closest
  /// point's coordinates on triangle ClosestSubTriangle of the closest cell as the module
  /// splits it (vtkMeshDistanceFilter's arrays, with its conventions for line and vertex
  /// cells); -1 and NaN beyond MaximumDistance. Off by default.
  vtkSetMacro(ComputeClosestBarycentric, bool);
  vtkGetMacro(ComputeClosestBarycentric, bool);
  vtkBooleanMacro(ComputeClosestBarycentric, bool);
  /// `Gradient` (float x3): the unit vector from the closest point to the sample times
  /// the distance's sign, the gradient of Distance wherever it is differentiable; at a
  /// sample on the surface itself, the closest feature's unit angle-weighted pseudonormal
  /// (0 on a vertex or line cell); NaN beyond MaximumDistance. Off by default.
  vtkSetMacro(ComputeGradient, bool);
  vtkGetMacro(ComputeGradient, bool);
  vtkBooleanMacro(ComputeGradient, bool);
  ///@}

  /// Distance evaluations of the last run (samples covered by a domain, the same on both
  /// backends, or with SampleQueries point-triangle distances) and that number divided by
  /// the number of samples.
  vtkGetMacro(LastEvaluations, vtkTypeInt64);
  vtkGetMacro(LastCullingFactor, double);
  /// Samples whose winding-number sign a block decided at once in the last run (the rest
  /// were evaluated one by one; Filters/Core/Winding/WindingSigns.h).
  vtkGetMacro(LastWindingBlockSamples, vtkTypeInt64);
  /// Samples whose winding-number sign the last run read from the surface's crossings
  /// along the grid lines (a closed mesh; Filters/Core/Winding/WindingCrossings.h).
  vtkGetMacro(LastWindingLineSamples, vtkTypeInt64);
  /// Samples whose winding number the last run had to sum exactly, triangle by triangle
  /// (the hierarchy's error bound reached |w| = 1/2).
  vtkGetMacro(LastWindingExactSamples, vtkTypeInt64);
  /// Samples of a GPU winding pass that the renderer could not finish within its loop
  /// limit and the CPU decided by the same function (only on a software renderer:
  /// Mesa's llvmpipe silently ends a shader's loops after 65,535 iterations).
  vtkGetMacro(LastWindingCPUSamples, vtkTypeInt64);
  /// Where the last run computed the winding-number sign: "cpu", "gpu" (Backend GPU, or
  /// Auto beside a hardware GPU, vtkDistanceFieldExecution.h, but for signs alone where
  /// the crossings decide them: on the CPU they cost less) or "none".
  const char* GetLastSignBackend() const { return this->LastSignBackend.c_str(); }

  /// The bytes the filter keeps for its next execution (see the class's description).
  vtkTypeInt64 GetWorkBufferBytes() const;
  /// Frees them now.
  void ReleaseWorkBuffers();

protected:
  vtkLinearFactorDistanceField();
  ~vtkLinearFactorDistanceField() override;

#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
  /// The requested output arrays on `output`'s point data, `n` samples each.
  vtkdf::LinearFactorArrays AddArrays(vtkImageData* output, vtkIdType n) const;
#endif
  bool CheckProperties() override;
  std::string PointCloudRefusal() override;

  int SignMode = UNSIGNED;
  int DomainShape = DOMAIN_SHAPE_AUTO;
  int Route = ROUTE_AUTO;
  double MaximumDistance = 0;
  bool ComputeDistance = true;
  bool ComputeClosestCellId = true;
  bool ComputeClosestFeature = false;
  bool ComputeClosestPoint = false;
  bool ComputeWindingNumber = false;
  bool ComputeClosestBarycentric = false;
  bool ComputeGradient = false;
  vtkTypeInt64 LastEvaluations = 0;
  double LastCullingFactor = 0;
  vtkTypeInt64 LastWindingBlockSamples = 0;
  vtkTypeInt64 LastWindingLineSamples = 0;
  vtkTypeInt64 LastWindingExactSamples = 0;
  vtkTypeInt64 LastWindingCPUSamples = 0;
  std::string LastSignBackend = "none";
  std::string LastRoute = "none";
#ifndef __VTK_WRAP__
  // Kept between executions on one input (the input's address and time).
  std::unique_ptr<vtkdf::LinearFactorWorkspace> Workspace;
  const void* WorkspaceInput = nullptr;
  vtkMTimeType WorkspaceInputTime = 0;
#endif

private:
  vtkLinearFactorDistanceField(const vtkLinearFactorDistanceField&) = delete;
  void operator=(const vtkLinearFactorDistanceField&) = delete;
};

#endif
