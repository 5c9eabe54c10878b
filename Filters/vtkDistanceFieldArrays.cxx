#include "vtkDistanceFieldArrays.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include "Common/LargeVector.h"

#include <new>

namespace vtkdf
{

void AllocateTuples(vtkDataArray* array, vtkIdType tuples)
{
  // A large array in contiguous memory gets its block from AllocateLarge (huge pages
  // where the kernel offers them: fresh memory is first touched as the filter writes it),
  // which VTK releases with free().
  const vtkIdType components = array->GetNumberOfComponents();
  const size_t typeSize = static_cast<size_t>(array->GetDataTypeSize());
  const bool countable = tuples > 0 && components > 0 && typeSize > 0 &&
    tuples <= VTK_ID_MAX / components &&
    static_cast<size_t>(tuples * components) <= SIZE_MAX / typeSize;
  const size_t bytes = countable ? static_cast<size_t>(tuples * components) * typeSize : 0;
  if (countable && array->HasStandardMemoryLayout() && bytes >= (size_t(2) << 20))
  {
    void* block = AllocateLarge(bytes);
    if (!block)
    {
      throw std::bad_alloc();
    }
    array->SetVoidArray(block, tuples * components, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  }
  else
  {
    array->SetNumberOfTuples(tuples);
  }
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
