#include "vtkDistanceFieldArrays.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <new>

namespace vtkdf
{

void AllocateTuples(vtkDataArray* array, vtkIdType tuples)
{
  array->SetNumberOfTuples(tuples);
  if (array->GetNumberOfTuples() != tuples)
  {
    throw std::bad_alloc();
  }
}

vtkDataArray* SampleArray(vtkImageData* image, const char* name, int components, std::string& error)
{
  vtkAbstractArray* abstract = image->GetPointData()->GetAbstractArray(name);
  if (!abstract)
  {
    error = std::string("The input image has no point-data array named ") + name + ".";
    return nullptr;
  }
  vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
  if (!array)
  {
    error = std::string("The ") + name + " array is a " + abstract->GetClassName() +
      ", not a numeric array.";
    return nullptr;
  }
  if (array->GetNumberOfComponents() != components)
  {
    error = std::string("The ") + name + " array has " +
      std::to_string(array->GetNumberOfComponents()) + " components; it needs " +
      std::to_string(components) + ".";
    return nullptr;
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = std::string("The ") + name + " array has " +
      std::to_string(array->GetNumberOfTuples()) + " values for " +
      std::to_string(image->GetNumberOfPoints()) + " samples.";
    return nullptr;
  }
  return array;
}

} // namespace vtkdf
