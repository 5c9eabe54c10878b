/**
 * @class   vtkChamferVoxelDistance
 * @brief   Chamfer distance transform on voxel lanes.
 *
 * Implements the distance transform of Martinek, Grosso and Greiner, "Fast and
 * Efficient 3D Chamfer Distance Transform for Polygonal Meshes" (VMV 2011), §5: layer
 * n+1 is computed from layer n and the accumulation grid of all earlier layers, a whole
 * voxel lane (64 voxels per word) at a time, with bit shifts and ORs. That wavefront
 * runs on the GPU, and on the CPU for chessboard fields of at most 24 layers; the CPU
 * computes the other fields, the same layer indices bit for bit, in sweeps over the
 * array (the separable L1 transform for Manhattan, three sweeps for the chessboards).
 *
 * Input, either:
 * - a vtkPolyData, voxelized internally (vtkPolyDataVoxelizer's scheme) on the grid
 *   given by the grid properties (Resolution, Padding or an explicit grid); or
 * - a vtkImageData with a `Boundary` point array (any numeric type; non-zero = the zero
 *   set) and optionally a `Solid` one; the output has the input's grid.
 *
 * Metric: Manhattan (6 face neighbours), Chessboard18 (the paper's "chessboard": faces
 * and edges at distance 1) or Chessboard26 (all 26 neighbours at 1). MaximumLayers M
 * stops after layer M (0: until no voxel changes).
 *
 * Output point data: `ChamferDistance` (int32 layer index; voxels not reached hold M+1,
 * also given in the field data array `UnreachedValue`); negative inside when Signed is
 * on and a solid is known (a mesh input is voxelized solid for it; an image input needs
 * `Solid`). With OutputMasks on, `Boundary` and (when known) `Solid` are passed through.
 *
 * A requested piece of the grid (UPDATE_EXTENT) equals the same voxels of the whole
 * grid bit for bit. With MaximumLayers M > 0 it is computed from the masks of the piece
 * and M voxels around it (asked of an image input's producer; a mesh is voxelized whole,
 * then propagated there): a voxel at most M layers from the zero set has a shortest path
 * to it within M voxels on every axis. Without a limit (M = 0), the voxels around a piece
 * that decide it reach as far as its farthest voxel's distance: a mesh's piece is
 * propagated over margins doubling from 16 voxels until every voxel of the piece is
 * reached (the whole grid once the grown piece would exceed a quarter of it); an image
 * input is asked for all of it. LastLayers counts the layers of the voxels computed.
 */
#ifndef vtkChamferVoxelDistance_h
#define vtkChamferVoxelDistance_h

#include "vtkDistanceFieldAlgorithm.h"

#ifndef __VTK_WRAP__
namespace vtkdf
{
class BitVolume;
class HeadlessGL;
struct ChamferRequest;
struct ChamferReport;
struct Execution;
struct MeshInput;
}
#endif
#include "vtkSmartPointer.h" // For Propagate

class vtkIntArray;
#include "vtkDistanceFieldsModule.h" // For export macro

class VTKDISTANCEFIELDS_EXPORT vtkChamferVoxelDistance : public vtkDistanceFieldAlgorithm
{
public:
  static vtkChamferVoxelDistance* New();
  vtkTypeMacro(vtkChamferVoxelDistance, vtkDistanceFieldAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum MetricType
  {
    MANHATTAN = 0,
    CHESSBOARD18 = 1,
    CHESSBOARD26 = 2
  };
  vtkSetMacro(Metric, int);
  vtkGetMacro(Metric, int);
  void SetMetricToManhattan() { this->SetMetric(MANHATTAN); }
  void SetMetricToChessboard18() { this->SetMetric(CHESSBOARD18); }
  void SetMetricToChessboard26() { this->SetMetric(CHESSBOARD26); }

  ///@{
  /// Stop after this many layers (0, the default: until nothing changes); at most
  /// VTK_INT_MAX - 1, so that unreached voxels can hold MaximumLayers + 1.
  vtkSetMacro(MaximumLayers, int);
  vtkGetMacro(MaximumLayers, int);
  ///@}

  ///@{
  /// Negative distances inside the solid (default off).
  vtkSetMacro(Signed, bool);
  vtkGetMacro(Signed, bool);
  vtkBooleanMacro(Signed, bool);
  ///@}

  ///@{
  /// Pass the Boundary (and Solid) masks to the output (default off).
  vtkSetMacro(OutputMasks, bool);
  vtkGetMacro(OutputMasks, bool);
  vtkBooleanMacro(OutputMasks, bool);
  ///@}

  /// Layers computed by the last run.
  vtkGetMacro(LastLayers, int);

protected:
  vtkChamferVoxelDistance();
  ~vtkChamferVoxelDistance() override = default;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
  bool CheckProperties() override;
#ifndef __VTK_WRAP__
  /// The bytes a run on these voxels needs (lanes, bit planes of the layers, the field).
  double EstimateBytes(const vtkdf::IndexBox& voxels) const;
  /// The voxels of `grid` whose masks decide the voxels of `piece`.
  vtkdf::IndexBox PieceVoxels(const vtkdf::IndexBox& piece, const vtkdf::IndexBox& grid) const;
  /// The chamfer field of the masks' grid, or of the voxels that decide `piece` when it
  /// is computed alone (ComputesAlone), into `distance`, which covers `computed`: from
  /// the masks `boundary` and `solid` (unsigned without `haveSolid`) of an image input
  /// (`mesh` null), or from the mesh voxelized into them. False with `error`.
  bool Propagate(vtkdf::MeshInput* mesh,
    vtkdf::BitVolume& boundary,
    vtkdf::BitVolume& solid,
    bool haveSolid,
    const vtkdf::ChamferRequest& request,
    const vtkdf::IndexBox& piece,
    vtkdf::FilterRun& run,
    vtkSmartPointer<vtkIntArray>& distance,
    vtkdf::IndexBox& computed,
    vtkdf::ChamferReport& report,
    std::string& error);
  /// Whether `piece` is computed alone (ComputeChamferPiece) rather than cut from the
  /// whole grid's field: a piece smaller than the masks' grid whose deciding voxels are
  /// fewer too.
  bool ComputesAlone(const vtkdf::IndexBox& piece, const vtkdf::IndexBox& grid) const;
  /// The output: `piece` of `distance` (computed over `computed`), the UnreachedValue,
  /// and the masks when OutputMasks is on (`solid` may be null).
  void WriteOutput(const vtkdf::SampleGrid& grid,
    const vtkdf::IndexBox& piece,
    const vtkdf::IndexBox& computed,
    vtkIntArray* distance,
    const vtkdf::BitVolume& boundary,
    const vtkdf::BitVolume* solid,
    vtkImageData* output) const;
  /// The Boundary mask (required) and Solid mask (optional: `haveSolid`) of an image
  /// input as lanes; false with the error reported.
  bool ReadMasks(vtkImageData* image,
    vtkdf::BitVolume& boundary,
    vtkdf::BitVolume& solid,
    bool& haveSolid);
#endif

  int Metric = CHESSBOARD18;
  int MaximumLayers = 0;
  bool Signed = false;
  bool OutputMasks = false;
  int LastLayers = 0;

private:
  vtkChamferVoxelDistance(const vtkChamferVoxelDistance&) = delete;
  void operator=(const vtkChamferVoxelDistance&) = delete;
};

#endif
