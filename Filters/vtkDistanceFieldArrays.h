// vtkDistanceFieldArrays: the VTK arrays the cores read and write. Private to the module
// (not wrapped).
#ifndef vtkDistanceFieldArrays_h
#define vtkDistanceFieldArrays_h

#include "vtkNew.h"
#include "vtkType.h"

#include "Common/SampleGrid.h"

#include <algorithm>
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

/// A new array with `from`'s tuples (laid out over the box `box`, x fastest) on the
/// samples of `part`, a box within it.
template<typename ArrayT>
vtkNew<ArrayT> CropArray(ArrayT* from, const IndexBox& box, const IndexBox& part)
{
  const int components = from->GetNumberOfComponents();
  auto to = NewArray<ArrayT>(from->GetName(), static_cast<vtkIdType>(part.Count()), components);
  const vtkIdType nx = box.Size(0), ny = box.Size(1), row = part.Size(0) * components;
  vtkIdType next = 0;
  for (int k = part.Lo[2]; k <= part.Hi[2]; ++k)
  {
    for (int j = part.Lo[1]; j <= part.Hi[1]; ++j)
    {
      const vtkIdType first =
        ((vtkIdType(k - box.Lo[2]) * ny + (j - box.Lo[1])) * nx + (part.Lo[0] - box.Lo[0])) *
        components;
      std::copy(from->GetPointer(first), from->GetPointer(first) + row, to->GetPointer(next));
      next += row;
    }
  }
  return to;
}

/// The point-data array `name` of `image` when it is numeric, has `components`
/// components and one tuple per sample; else null, and `error` says what is wrong.
vtkDataArray* SampleArray(vtkImageData* image,
  const char* name,
  int components,
  std::string& error);

} // namespace vtkdf

#endif
