/**
 * @class   vtkMedialAxisFilter
 * @brief   The theta-simplified medial axis of a distance field.
 *
 * Implements §6.3 of Sud et al. (I3D 2006): from the distance field and the closest
 * boundary point of every voxel, two 6-adjacent voxels x and y whose closest points
 * c(x), c(y) are seen from their midpoint m at an angle of at least SeparationAngle
 * (theta) straddle the medial surface; the one with the larger |distance| (ties: the
 * lower index) is marked, so the axis is one voxel thin. This is the separation-angle
 * criterion of Foskey, Lin and Manocha's theta-SMA: a larger theta keeps fewer, more
 * significant branches, and the set for a larger theta is a subset of the set for a
 * smaller one.
 *
 * Input, either:
 * - a vtkImageData with point arrays `Distance` and `ClosestPoint` (what
 *   vtkLinearFactorDistanceField makes); or
 * - a vtkPolyData, whose signed field (with closest points) the filter computes on the
 *   grid given by the grid properties (Resolution, Padding or an explicit grid).
 *
 * Region: Inside (negative distances: needs a signed field; the default), Outside, Both.
 *
 * Output port 0: vtkImageData with `Medial` (uint8), `SeparationAngle` (float, degrees;
 * 0 where not medial) and `Radius` (|distance|). Output port 1: vtkPolyData with one
 * vertex per medial voxel and the same arrays (spheres of radius Radius by glyphing).
 * Both backends give the same voxels (the pair cosines are computed in double on both).
 */
#ifndef vtkMedialAxisFilter_h
#define vtkMedialAxisFilter_h

#include "vtkDistanceFieldAlgorithm.h"
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

  /// The medial voxels as points (output port 1).
  vtkPolyData* GetMedialPoints();

  /// Medial voxels found by the last run.
  vtkGetMacro(LastMedialCount, vtkIdType);

protected:
  vtkMedialAxisFilter();
  ~vtkMedialAxisFilter() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool CheckProperties() override;

  double SeparationAngle = 90;
  int Region = INSIDE;
  vtkIdType LastMedialCount = 0;

private:
  vtkMedialAxisFilter(const vtkMedialAxisFilter&) = delete;
  void operator=(const vtkMedialAxisFilter&) = delete;
};

#endif
