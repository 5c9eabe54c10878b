/**
 * @class   vtkMedialAxisFilter
 * @brief   The theta-simplified medial axis of a distance field.
 *
 * Implements §6.3 of Sud et al. (I3D 2006) with the separation-angle criterion of
 * Foskey, Lin and Manocha's theta-SMA: from the distance field and the closest boundary
 * point of every voxel, each 2x2x2 cell of voxels gets an aperture, that of the smallest
 * cone holding its 8 corners' directions to their closest points. A cell whose aperture
 * reaches SeparationAngle (theta) straddles the medial axis; it marks its corner of
 * largest |distance| (ties: the lower index), the one nearest the axis, so the axis stays
 * thin. The aperture is the true separation angle of a medial sheet through the cell,
 * and 180 degrees for a line (a tube's axis) or a point (a sphere's centre) through it,
 * so any theta below 180 finds them wherever the grid falls. Near the surface, a cell
 * counts only where no single vertex or edge could give it its aperture (see
 * Filters/Core/Medial/MedialAxis.h). A larger theta keeps fewer, more significant branches, and
 * the set for a larger theta is a subset of the set for a smaller one.
 *
 * Input, either:
 * - a vtkImageData with point arrays `Distance` and `ClosestPoint` (what
 *   vtkLinearFactorDistanceField makes); or
 * - a vtkPolyData, whose signed field (with closest points) the filter computes on the
 *   grid given by the grid properties (Resolution, Padding or an explicit grid).
 *
 * Region: Inside (negative distances: needs a signed field; the default), Outside, Both.
 *
 * Output port 0: vtkImageData with `Medial` (uint8), `SeparationAngle` (float, degrees:
 * the largest aperture of the cells that marked the voxel, at most 180; 0 where not
 * medial) and `Radius` (|distance|). Output port 1: vtkPolyData with one
 * vertex per medial voxel and the same arrays (spheres of radius Radius by glyphing).
 * Both backends give the same voxels and apertures (computed in the same double
 * arithmetic on both).
 *
 * A requested piece of the grid (UPDATE_EXTENT) is computed alone, from the field on the
 * piece and one voxel around it (computed here from a mesh, or asked of the field's
 * producer), and equals the same voxels of the whole grid bit for bit. Port 1 holds the
 * medial voxels the piece owns (pieces share boundary planes; a plane belongs to the
 * piece below it); in a distributed run rank 0 gathers every rank's and alone outputs
 * them, in voxel order, as one process would.
 */
#ifndef vtkMedialAxisFilter_h
#define vtkMedialAxisFilter_h

#include "vtkDistanceFieldAlgorithm.h"
#include "vtkSmartPointer.h" // For ReadField

#include <vector> // For OwnedMedialVoxels

class vtkFloatArray;
class vtkImageData;
class vtkUnsignedCharArray;
#ifndef __VTK_WRAP__
namespace vtkdf
{
struct MedialInput;
}
#endif
#include "vtkDistanceFieldsModule.h" // For export macro

class vtkPolyData;

class VTKDISTANCEFIELDS_EXPORT vtkMedialAxisFilter : public vtkDistanceFieldAlgorithm
{
public:
  static vtkMedialAxisFilter* New();
  vtkTypeMacro(vtkMedialAxisFilter, vtkDistanceFieldAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The separation angle theta, in degrees, in (0, 180) (default 90). A value outside
  /// is reported as an error when the filter runs.
  vtkSetMacro(SeparationAngle, double);
  vtkGetMacro(SeparationAngle, double);
  ///@}

  enum RegionType
  {
    INSIDE = 0,  ///< voxels with a negative distance (needs a signed field)
    OUTSIDE = 1, ///< voxels with a positive distance
    BOTH = 2
  };
  vtkSetMacro(Region, int);
  vtkGetMacro(Region, int);
  void SetRegionToInside() { this->SetRegion(INSIDE); }
  void SetRegionToOutside() { this->SetRegion(OUTSIDE); }
  void SetRegionToBoth() { this->SetRegion(BOTH); }

  /// How the field computed from a mesh input is signed (as
  /// vtkLinearFactorDistanceField's SignMode): PseudoNormal (the default) or
  /// WindingNumber (inside where |w| > 1/2: meshes with holes and soups). An image input
  /// comes signed already.
  enum SignModeType
  {
    PSEUDO_NORMAL = 0,
    WINDING_NUMBER = 1
  };
  vtkSetMacro(SignMode, int);
  vtkGetMacro(SignMode, int);
  void SetSignModeToPseudoNormal() { this->SetSignMode(PSEUDO_NORMAL); }
  void SetSignModeToWindingNumber() { this->SetSignMode(WINDING_NUMBER); }

  /// The medial voxels as points (output port 1).
  vtkPolyData* GetMedialPoints();

  /// Medial voxels found by the last run (in a distributed run: those of this rank's
  /// piece of the grid).
  vtkGetMacro(LastMedialCount, vtkIdType);

protected:
  vtkMedialAxisFilter();
  ~vtkMedialAxisFilter() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
#ifndef __VTK_WRAP__
  vtkdf::RunStatus Execute(vtkInformationVector** inputVector,
    vtkInformationVector* outputVector,
    vtkdf::FilterRun& run) override;
#endif
  bool CheckProperties() override;

#ifndef __VTK_WRAP__
  /// The arrays computed for a box of voxels (the piece and its neighbours).
  struct MedialPart;
  /// The medial axis on `needed` (the mesh's field computed there), or on what the
  /// field input holds; false with the error reported.
  bool ComputePart(vtkPolyData* mesh,
    vtkImageData* image,
    const vtkdf::SampleGrid& whole,
    const vtkdf::IndexBox& needed,
    vtkdf::FilterRun& run,
    MedialPart& part);
  /// The medial voxels that `piece` owns (pieces share boundary planes: a plane belongs
  /// to the piece below it), as (index in `whole`, angle, radius) triples.
  void OwnedMedialVoxels(const MedialPart& part,
    const vtkdf::IndexBox& piece,
    const vtkdf::IndexBox& whole,
    std::vector<double>& owned) const;
  /// In a distributed run, rank 0 receives every rank's triples, in voxel order (true on
  /// rank 0 when every rank succeeded); one process keeps its own (true when `ok`).
  bool GatherMedialVoxels(bool ok, std::vector<double>& owned) const;
  /// The field of an image input (Distance and ClosestPoint as float), checked against
  /// Region and the memory limit; false with the error reported.
  bool ReadField(vtkImageData* image,
    vtkdf::MedialInput& field,
    vtkSmartPointer<vtkFloatArray>& distance,
    vtkSmartPointer<vtkFloatArray>& closest);
  /// Output port 1: a vertex at every medial voxel (triples as OwnedMedialVoxels makes).
  static void WriteMedialPoints(const vtkdf::SampleGrid& grid,
    const std::vector<double>& voxels,
    vtkPolyData* points);
#endif

  double SeparationAngle = 90;
  int Region = INSIDE;
  int SignMode = PSEUDO_NORMAL;
  vtkIdType LastMedialCount = 0;

private:
  vtkMedialAxisFilter(const vtkMedialAxisFilter&) = delete;
  void operator=(const vtkMedialAxisFilter&) = delete;
};

#endif
