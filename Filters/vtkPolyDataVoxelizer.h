/**
 * @class   vtkPolyDataVoxelizer
 * @brief   Boundary and solid voxelization of a polygon mesh, on voxel lanes.
 *
 * Implements the voxelization of Martinek, Grosso and Greiner, "Fast and Efficient 3D
 * Chamfer Distance Transform for Polygonal Meshes" (VMV 2011), §4. The voxels are the
 * samples of the output grid (the default grid of Resolution and Padding, or an
 * explicit one, of any dimensions); voxel (i, j, k) is the cell of one spacing centred
 * on its sample.
 *
 * The mesh is rasterized along the three axes; each view sets, on every lane of sample
 * centres that meets a triangle, the bit of the voxel holding the meeting point.
 * - `Boundary`: the three views OR-ed. No set voxel's centre is farther than half the
 *   cell diagonal from the surface.
 * - `Solid`: per view, front-facing and back-facing triangles are kept apart and the
 *   voxels of every [front, back] interval are set; the three views are AND-ed, so
 *   open sheets (the paper's leaves of a potted plant) add no volume. Meant for closed,
 *   consistently oriented parts (the orientation is taken from the signed volume).
 *
 * Output point data: `Boundary` and/or `Solid` (uint8, 0 or 1), per `Mode`. Only
 * triangles, polygons and strips have area: vertex and line cells are ignored (with a
 * warning). Storage while working: 64-bit lanes, one bit per voxel and view.
 */
#ifndef vtkPolyDataVoxelizer_h
#define vtkPolyDataVoxelizer_h

#include "vtkDistanceFieldAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

class VTKDISTANCEFIELDS_EXPORT vtkPolyDataVoxelizer : public vtkDistanceFieldAlgorithm
{
public:
  static vtkPolyDataVoxelizer* New();
  vtkTypeMacro(vtkPolyDataVoxelizer, vtkDistanceFieldAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ModeType
  {
    BOUNDARY = 0, ///< the voxels the surface passes through
    SOLID = 1,    ///< the voxels inside closed parts (and on them)
    BOTH = 2      ///< both masks from one pass
  };
  vtkSetMacro(Mode, int);
  vtkGetMacro(Mode, int);
  void SetModeToBoundary() { this->SetMode(BOUNDARY); }
  void SetModeToSolid() { this->SetMode(SOLID); }
  void SetModeToBoth() { this->SetMode(BOTH); }

protected:
  vtkPolyDataVoxelizer();
  ~vtkPolyDataVoxelizer() override = default;

#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
  bool CheckProperties() override;

  int Mode = BOTH;

private:
  vtkPolyDataVoxelizer(const vtkPolyDataVoxelizer&) = delete;
  void operator=(const vtkPolyDataVoxelizer&) = delete;
};

#endif
