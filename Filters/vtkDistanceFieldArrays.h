// vtkDistanceFieldArrays: the VTK arrays the cores read and write. Private to the module
// (not wrapped).
#ifndef vtkDistanceFieldArrays_h
#define vtkDistanceFieldArrays_h

#include "vtkNew.h"
#include "vtkType.h"

#include <string>

class vtkDataArray;
class vtkImageData;

namespace vtkdf
{

/// Gives `array` `tuples` tuples; throws std::bad_alloc when VTK could not allocate
/// them (it then reports and leaves the array short, which must not be written).
void AllocateTuples(vtkDataArray* array, vtkIdType tuples);

/// A new array named `name` of `tuples` tuples of `components`, allocated (AllocateTuples).
template<typename ArrayT>
vtkNew<ArrayT> NewArray(const char* name, vtkIdType tuples, int components = 1)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  AllocateTuples(array, tuples);
  return array;
}

/// The point-data array `name` of `image` when it is numeric, has `components`
/// components and one tuple per sample; else null, and `error` says what is wrong.
vtkDataArray* SampleArray(vtkImageData* image,
  const char* name,
  int components,
  std::string& error);

} // namespace vtkdf

#endif
