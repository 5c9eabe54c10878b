// LinearFactorField: the entry point of the linear factorization family. The exact
// Euclidean distance field of a polygon mesh on a grid, after A. Sud, N. Govindaraju,
// R. Gayle and D. Manocha, "Interactive 3D Distance Field Computation using Linear
// Factorization", ACM Symposium on Interactive 3D Graphics and Games (I3D), 2006.
//
// The stages, each in its own file of this folder: the mesh's sites (vertices, edges,
// triangles) and the convex domains that bound their Voronoi regions (MeshSites), the
// regions of the grid where each site can still win (RangeCulling), the scan that keeps
// every sample's nearest site (LinearFactorScan on the CPU, LinearFactorGPU on the GPU),
// the arrays from the nearest sites in double precision (Finalize), and the sign
// (pseudonormal at the closest feature, or the winding number, Winding/). Where the
// mesh's triangles outnumber the samples, one nearest-triangle query per sample
// (NearestTriangleQueries) gives the same exact field without building the sites.
//
// Everything runs in the grid's local frame (SampleGrid.h, GridFrame), so that a mesh
// and grid scaled by 2^k give the same numbers bit for bit; the arrays come out in world
// units.
#ifndef vtkdf_LinearFactorField_h
#define vtkdf_LinearFactorField_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace vtkdf
{
class HeadlessGL;
class NearestSiteBuffer;

/// Memory a host keeps from one run to the next (a filter executed again for a new
/// resolution or new arrays): the site scan's nearest-site buffer, 8 bytes a sample,
/// whose block a run reuses when it is large enough, so that its pages are not touched
/// for the first time again (on some machines that costs more than the scan writing
/// them). Empty until a run uses it.
class LinearFactorWorkspace
{
public:
  LinearFactorWorkspace();
  ~LinearFactorWorkspace();
  LinearFactorWorkspace(const LinearFactorWorkspace&) = delete;
  LinearFactorWorkspace& operator=(const LinearFactorWorkspace&) = delete;

  /// The bytes held now.
  int64_t Bytes() const;
  /// Frees what is held.
  void Release();
  /// The nearest-site buffer for a run of `samples` samples: the kept one, freed first
  /// when it is more than twice that size (the memory follows the output).
  NearestSiteBuffer& Nearest(int64_t samples);

private:
  std::unique_ptr<NearestSiteBuffer> NearestSites;
};

/// Which domains bound the sites' Voronoi regions.
enum class DomainShape
{
  Auto,        // tightest exact domains for every site, whatever the topology
  NonManifold, // triangle prism, edge slab, whole space for points
  Manifold     // the paper's manifold domains where the neighbourhood is a closed manifold
};

enum class SignMode
{
  Unsigned,
  PseudoNormal, // the angle-weighted pseudonormal of the closest feature
  WindingNumber // inside where the generalized winding number has |w| > 1/2
};

/// How the CPU finds every sample's nearest feature. Both are exact (the same
/// distances, features and cells but where a sample lies within rounding of two).
enum class FieldRoute
{
  Auto,         // SampleQueries where the mesh has 2.5 times more cells than samples to
                //   query (NearestTriangleQueries.h, PreferSampleQueries)
  SiteScan,     // the linear factorization: every site's domain scanned over the grid
  SampleQueries // one nearest-primitive query per sample (CPU only)
};

struct LinearFactorRequest
{
  SampleGrid Grid; // world coordinates
  IndexBox Extent; // the samples to compute, within Grid.Whole
  DomainShape Domains = DomainShape::Auto;
  SignMode Sign = SignMode::Unsigned;
  /// A cap on the distances (a narrow band), in world units; 0: none.
  double MaximumDistance = 0;
  /// The field on the CPU (no `gl`) with the winding sign on this context: a hardware
  /// GPU's winding pass is faster than the CPU's, its scan is not (Backend Auto). The
  /// signs are the same (the same rigorous rule); w itself within float rounding. Where
  /// the crossings decide (Winding/WindingCrossings.h), the signs stay on the CPU.
  HeadlessGL* SignContext = nullptr;
  /// The site scan or per-sample queries (Auto: by the counts of cells and samples).
  FieldRoute Route = FieldRoute::Auto;
  /// Where the scan's buffers come from and stay after the run (null: the run's own).
  LinearFactorWorkspace* Workspace = nullptr;
};

/// Where the field goes: any pointer may be null. Each array covers the request's
/// Extent, x fastest; distances and points in world units.
struct LinearFactorArrays
{
  float* Distance = nullptr;
  int64_t* ClosestCellId = nullptr;  // the mesh's cell id of the closest site
  uint8_t* ClosestFeature = nullptr; // 0 vertex, 1 edge, 2 face
  float* ClosestPoint = nullptr;     // 3 per sample
  float* WindingNumber = nullptr;    // the winding number w itself
  /// Where on its cell each closest point lies (SurfaceCoordinates.h): the index of the
  /// triangle within the cell's triangulation, the barycentric coordinates there (3 per
  /// sample), and the unit gradient of the (signed) distance (3 per sample).
  int64_t* ClosestSubTriangle = nullptr;
  float* ClosestBarycentric = nullptr;
  float* Gradient = nullptr;
};

struct LinearFactorReport
{
  /// The mesh has no cell the field can use: nothing was written.
  bool NoUsableCell = false;
  /// The host asked to abort (Execution::Progress): the arrays are incomplete.
  bool Aborted = false;
  /// Distance evaluations of the scan (per sample: the culling factor); -1 when the GPU
  /// did not count them.
  int64_t Evaluations = 0;
  /// Samples whose winding sign a block decided, those a closed mesh's crossings along
  /// the grid lines decided, and samples decided by the exact sum.
  int64_t WindingBlockSamples = 0;
  int64_t WindingLineSamples = 0;
  bool WindingOnGPU = false; // where the sign ran
  int64_t WindingExactSamples = 0;
  /// Of the GPU's samples, those a software renderer's loop limit left to the CPU.
  int64_t WindingCPUSamples = 0;
  /// The route that ran: SiteScan or SampleQueries (whose Evaluations count
  /// point-triangle distances).
  FieldRoute Route = FieldRoute::SiteScan;
};

/// The field of `mesh` (world coordinates, Bounds filled; taken by value: it is moved
/// into the grid's local frame in place) on the CPU, or on the GPU when `gl` is given.
/// Stages: sites, culling, scan, finalize and, with a winding-number sign or value,
/// sign. Progress runs from 0 to 0.9 (the scan from 0.1). False and `error` on invalid
/// input (a grid that cannot carry float32 distances with the mesh, a bad mesh) or when
/// the GPU fails.
bool ComputeLinearFactorField(MeshInput mesh,
  const LinearFactorRequest& request,
  HeadlessGL* gl,
  const LinearFactorArrays& arrays,
  const Execution& execution,
  LinearFactorReport& report,
  std::string& error);

/// The field as GL buffers on the GPU, for passes that read it where it lies (the medial
/// axis, the segmented field's side labels): per sample of the extent (x fastest) the
/// distance (float) and the closest point (3 floats), in world units (the CPU backend's
/// output floats, bit for bit), and the nearest site's index (int); per site, its cell id
/// and type (0 vertex, 1 edge, 2 face).
struct GPUField
{
  unsigned Distance = 0, ClosestPoint = 0, SiteIds = 0;
  SampleGrid Grid; // the request's grid in the local frame
  IndexBox Extent;
  GridFrame Frame;
  std::vector<int64_t> SiteCells;
  std::vector<uint8_t> SiteTypes;
};

/// Computes the field of `mesh` on the GPU (request.Sign Unsigned or PseudoNormal, no
/// MaximumDistance) and calls `use` with it while the context is current; the buffers
/// are deleted afterwards. Progress (the scan's) and abort as ComputeLinearFactorField;
/// `use` is not called when the run aborts. False and `error` on invalid input, a GPU
/// failure, or when `use` returns false (with its error).
bool ComputeLinearFactorFieldOnGPU(HeadlessGL& gl,
  MeshInput mesh,
  const LinearFactorRequest& request,
  const Execution& execution,
  const std::function<bool(const GPUField&, std::string&)>& use,
  LinearFactorReport& report,
  std::string& error);

} // namespace vtkdf

#endif
