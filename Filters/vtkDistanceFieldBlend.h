/**
 * @class   vtkDistanceFieldBlend
 * @brief   Blends two segmented distance fields (metamorphosis, Yamazaki et al. (SMI 2003)
 * section 5.2).
 *
 * Inputs: port 0 and port 1, two outputs of vtkSegmentedDistanceField on the same grid
 * whose regions mean the same (identical `RegionSides`, `Delta` and `RegionOffset`); a
 * signed distance field of a closed surface is the two-region case. Where both fields put
 * a sample in the same region, the distances are blended; where they differ, the two are
 * blended as a signed distance across that pair of regions, so that each interface moves
 * linearly from its position in the first field (T = 0) to its position in the second
 * (T = 1); see Filters/Core/Segment/SegmentBlend.h. T = 0 and T = 1 give the inputs
 * exactly. T must lie in [0, 1].
 *
 * Output: the grid with `SegmentedDistance`, `RegionIndex` and `Distance`, and the first
 * input's field data. Mismatched grids or region tables, or missing arrays, are errors
 * that name what differs. Computed on the CPU (vtkSMPTools): one pass over the samples.
 * A requested piece is computed alone: in a distributed run from the fields' pieces
 * (which then compute only theirs) and the whole grid's regions, all-gathered (a
 * sample's distance to a region may be decided by any voxel); in one process from the
 * whole fields. Equal to the whole grid's blend, bit for bit.
 */
#ifndef vtkDistanceFieldBlend_h
#define vtkDistanceFieldBlend_h

#include "vtkDistanceFieldImageAlgorithm.h"
#include "vtkDistanceFieldsModule.h" // For export macro

#ifndef __VTK_WRAP__
namespace vtkdf
{
struct IndexBox;
}
#endif

class VTKDISTANCEFIELDS_EXPORT vtkDistanceFieldBlend : public vtkDistanceFieldImageAlgorithm
{
public:
  static vtkDistanceFieldBlend* New();
  vtkTypeMacro(vtkDistanceFieldBlend, vtkDistanceFieldImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The blend parameter: 0 gives the first field, 1 the second (default 0.5).
  vtkSetMacro(T, double);
  vtkGetMacro(T, double);

protected:
  vtkDistanceFieldBlend();
  ~vtkDistanceFieldBlend() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
  /// The blend of `box` (of the `whole` extent) into the output's point data, from the
  /// fields' samples there and the whole grid's regions; false when aborted.
  bool Blend(vtkImageData* first,
    vtkImageData* second,
    vtkImageData* const wholeRegions[2],
    const int whole[6],
    const vtkdf::IndexBox& box,
    vtkdf::FilterRun& run);
#endif
  /// Whether T and the inputs can be blended (two segmented fields on one grid with the
  /// same regions); else false with the error reported.
  bool CheckInputs(vtkImageData* first, vtkImageData* second);

  double T = 0.5;

private:
  vtkDistanceFieldBlend(const vtkDistanceFieldBlend&) = delete;
  void operator=(const vtkDistanceFieldBlend&) = delete;
};

#endif
