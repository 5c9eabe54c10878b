#include "vtkSegmentedDistanceRepresentation.h"

#include "vtkObjectFactory.h"
#include "vtkSegmentedDistanceVolumeMapper.h"

vtkStandardNewMacro(vtkSegmentedDistanceRepresentation);

vtkSegmentedDistanceRepresentation::vtkSegmentedDistanceRepresentation()
{
  // The superclass delivers the data to this mapper and sets its input, array and
  // property; it checks the type before using anything particular to its own mappers.
  this->VolumeMapper = vtkSmartPointer<vtkSegmentedDistanceVolumeMapper>::New();
}

vtkSegmentedDistanceVolumeMapper* vtkSegmentedDistanceRepresentation::GetSegmentedMapper()
{
  return vtkSegmentedDistanceVolumeMapper::SafeDownCast(this->VolumeMapper);
}

void vtkSegmentedDistanceRepresentation::SetMode(int mode)
{
  this->GetSegmentedMapper()->SetMode(mode);
  this->Modified();
}

void vtkSegmentedDistanceRepresentation::SetInterpolation(int interpolation)
{
  this->GetSegmentedMapper()->SetInterpolation(interpolation);
  this->Modified();
}

void vtkSegmentedDistanceRepresentation::SetSurfaceOpacity(double opacity)
{
  this->GetSegmentedMapper()->SetSurfaceOpacity(opacity);
  this->Modified();
}

void vtkSegmentedDistanceRepresentation::SetNumberOfSlices(int slices)
{
  this->GetSegmentedMapper()->SetNumberOfSlices(slices);
  this->Modified();
}

void vtkSegmentedDistanceRepresentation::SetSampleDistance(double distance)
{
  this->GetSegmentedMapper()->SetSampleDistance(distance);
  this->Modified();
}

void vtkSegmentedDistanceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mapper:\n";
  this->VolumeMapper->PrintSelf(os, indent.GetNextIndent());
}
