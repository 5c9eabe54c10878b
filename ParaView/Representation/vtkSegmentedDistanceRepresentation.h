/**
 * @class   vtkSegmentedDistanceRepresentation
 * @brief   ParaView's volume representation of image data drawn by
 *          vtkSegmentedDistanceVolumeMapper.
 *
 * ParaView's image volume representation (data delivery, outline, ordered compositing,
 * the colour and opacity transfer functions) with the project's mapper in place of
 * ParaView's: a segmented or signed field's surfaces (Mode Surface, the mapper's
 * default) or the pre-integrated composite of the coloured array (Mode Composite). The
 * plugin adds it to image data as the representation "Segmented Distance Volume".
 * Mode, Interpolation, SurfaceOpacity, NumberOfSlices and SampleDistance are the
 * mapper's properties.
 */
#ifndef vtkSegmentedDistanceRepresentation_h
#define vtkSegmentedDistanceRepresentation_h

#include "vtkDistanceFieldsParaViewModule.h" // For export macro
#include "vtkImageVolumeRepresentation.h"

class vtkSegmentedDistanceVolumeMapper;

class VTKDISTANCEFIELDSPARAVIEW_EXPORT vtkSegmentedDistanceRepresentation
  : public vtkImageVolumeRepresentation
{
public:
  static vtkSegmentedDistanceRepresentation* New();
  vtkTypeMacro(vtkSegmentedDistanceRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Forwarded to vtkSegmentedDistanceVolumeMapper.
  void SetMode(int mode);
  void SetInterpolation(int interpolation);
  void SetSurfaceOpacity(double opacity);
  void SetNumberOfSlices(int slices);
  void SetSampleDistance(double distance);
  ///@}

  /// The mapper (for tests and scripts that read its Last* figures).
  vtkSegmentedDistanceVolumeMapper* GetSegmentedMapper();

protected:
  vtkSegmentedDistanceRepresentation();
  ~vtkSegmentedDistanceRepresentation() override = default;

private:
  vtkSegmentedDistanceRepresentation(const vtkSegmentedDistanceRepresentation&) = delete;
  void operator=(const vtkSegmentedDistanceRepresentation&) = delete;
};

#endif
