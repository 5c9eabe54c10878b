/**
 * @class   vtkSegmentedDistanceContour
 * @brief   The surface of a segmented distance field, boundaries and junctions kept.
 *
 * The polygonizer of paper 004 (section 3.3, eqs. 5-7) for the output of
 * vtkSegmentedDistanceField: an interface point on every grid edge between two regions
 * whose samples' distances add up to at most the edge's length, where eq. 6 puts it; the
 * points joined cell by cell (Filters/Core/Segment/SegmentContour.h): by marching cubes
 * where a cell holds two regions and every edge between them has its point (so a closed
 * surface gives what vtkFlyingEdges3D gives at 0 on its signed field), else around a
 * vertex at the cell's centre of interface points, which is where junctions of three or
 * more sheets meet and where open sheets end (a boundary is where eq. 7 suppresses the
 * points: no spurious sheet across a hole, unlike a signed field's zero level set).
 *
 * Input: vtkImageData with `SegmentedDistance` and the field-data `RegionOffset` (what
 * vtkSegmentedDistanceField makes); each sample's region and distance are read back
 * from f = min(d, Delta) + RegionOffset * r. Output: vtkPolyData of triangles with the
 * cell array `Regions` (int, 2 components: the lower and the higher region the triangle
 * separates; it faces the higher). CPU.
 */
#ifndef vtkSegmentedDistanceContour_h
#define vtkSegmentedDistanceContour_h

#include "vtkDistanceFieldsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class VTKDISTANCEFIELDS_EXPORT vtkSegmentedDistanceContour : public vtkPolyDataAlgorithm
{
public:
  static vtkSegmentedDistanceContour* New();
  vtkTypeMacro(vtkSegmentedDistanceContour, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Cells of the last run done by marching cubes, and around a cell vertex (junctions
  /// and boundaries).
  vtkGetMacro(LastMarchingCells, vtkTypeInt64);
  vtkGetMacro(LastOtherCells, vtkTypeInt64);

protected:
  vtkSegmentedDistanceContour() = default;
  ~vtkSegmentedDistanceContour() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkTypeInt64 LastMarchingCells = 0;
  vtkTypeInt64 LastOtherCells = 0;

private:
  vtkSegmentedDistanceContour(const vtkSegmentedDistanceContour&) = delete;
  void operator=(const vtkSegmentedDistanceContour&) = delete;
};

#endif
