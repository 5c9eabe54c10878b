// SlicePictures: the PNGs vtkdf writes of a field's middle z slice (--png), each above a
// legend: a colour bar with the array's name, its unit and range, what the lines and
// colours mean, and the slice's axis and position.
#ifndef vtkdf_SlicePictures_h
#define vtkdf_SlicePictures_h

#include "vtkSmartPointer.h"

#include <string>

class vtkImageData;

namespace vtkdf::cli
{

/// An RGB image of w x h pixels to paint a slice on.
vtkSmartPointer<vtkImageData> Canvas(int w, int h);

/// Writes an RGB image as PNG; false when the file cannot be written.
bool WritePNG(vtkImageData* image, const std::string& path);

/// The middle z slice of Distance, coloured (blue inside, white at the surface, warm
/// outside) with black isolines, magnified to at least 512 pixels, written as PNG.
bool WriteSlicePNG(vtkImageData* field, const std::string& path);

/// The middle z slice: |distance| in grey levels, medial voxels in red, magnified.
bool WriteMedialPNG(vtkImageData* field, const std::string& path);

/// The middle z slice of a segmented field: each region in its own hue, lighter away
/// from the surface (up to Delta), black where two regions meet across an interface
/// (adjacent samples whose distances sum to less than their spacing), magnified.
bool WriteRegionPNG(vtkImageData* field, double delta, const std::string& path);

} // namespace vtkdf::cli

#endif
