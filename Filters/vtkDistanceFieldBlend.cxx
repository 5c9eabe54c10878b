#include "vtkDistanceFieldBlend.h"

#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Segment/SegmentBlend.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldExecution.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkDistanceFieldBlend);

namespace
{
/// The whole of field data array `name` as doubles; empty when absent.
std::vector<double> FieldValues(vtkImageData* image, const char* name)
{
  std::vector<double> values;
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  for (vtkIdType i = 0; a && i < a->GetNumberOfValues(); ++i)
  {
    values.push_back(a->GetVariantValue(i).ToDouble());
  }
  return values;
}

/// Whether `image` has what a segmented field has; if not, `error` names what is missing.
bool IsSegmented(vtkImageData* image, const char* which, std::string& error)
{
  for (const char* name : { "Distance", "RegionIndex" })
  {
    if (!image->GetPointData()->GetArray(name) ||
      image->GetPointData()->GetArray(name)->GetNumberOfTuples() != image->GetNumberOfPoints() ||
      image->GetPointData()->GetArray(name)->GetNumberOfComponents() != 1)
    {
      error = std::string("the ") + which + " input has no point-data array " + name +
        " with one value per sample: blend outputs of vtkSegmentedDistanceField";
      return false;
    }
  }
  for (const char* name : { "Delta", "RegionOffset", "RegionSides" })
  {
    if (!image->GetFieldData()->GetArray(name))
    {
      error = std::string("the ") + which + " input has no field-data array " + name +
        ": blend outputs of vtkSegmentedDistanceField";
      return false;
    }
  }
  return true;
}
} // namespace

vtkDistanceFieldBlend::vtkDistanceFieldBlend()
{
  this->SetNumberOfInputPorts(2);
}

int vtkDistanceFieldBlend::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkDistanceFieldBlend::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Both inputs whole: a blend compares the fields sample by sample.
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* in = inputVector[port]->GetInformationObject(0);
    if (in)
    {
      vtkdf::RequestWholeInput(in);
    }
  }
  return 1;
}

vtkTypeBool vtkDistanceFieldBlend::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vtkdf::ProcessRequestOrEmpty(
    this,
    request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()),
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); },
    [this](unsigned long code) { this->SetErrorCode(code); });
}

bool vtkDistanceFieldBlend::CheckInputs(vtkImageData* first, vtkImageData* second)
{
  if (!(this->T >= 0 && this->T <= 1))
  {
    vtkErrorMacro("T must lie in [0, 1]; it is " << this->T << ".");
    return false;
  }
  if (!first || !second)
  {
    vtkErrorMacro("Two inputs are needed (ports 0 and 1).");
    return false;
  }
  std::string error;
  if (!IsSegmented(first, "first", error) || !IsSegmented(second, "second", error))
  {
    vtkErrorMacro(<< "Cannot blend: " << error << ".");
    return false;
  }
  int dims[2][3];
  double origin[2][3], spacing[2][3];
  first->GetDimensions(dims[0]);
  second->GetDimensions(dims[1]);
  first->GetOrigin(origin[0]);
  second->GetOrigin(origin[1]);
  first->GetSpacing(spacing[0]);
  second->GetSpacing(spacing[1]);
  for (int a = 0; a < 3; ++a)
  {
    const double scale = std::fabs(spacing[0][a]) * std::max(1, dims[0][a]);
    if (dims[0][a] != dims[1][a] || std::fabs(origin[0][a] - origin[1][a]) > 1e-9 * scale ||
      std::fabs(spacing[0][a] - spacing[1][a]) > 1e-9 * std::fabs(spacing[0][a]))
    {
      vtkErrorMacro("Cannot blend fields on different grids: dimensions "
        << dims[0][0] << "x" << dims[0][1] << "x" << dims[0][2] << " and " << dims[1][0] << "x"
        << dims[1][1] << "x" << dims[1][2] << ", origins and spacings must be equal.");
      return false;
    }
  }
  for (const char* name : { "RegionSides", "Delta", "RegionOffset" })
  {
    if (FieldValues(first, name) != FieldValues(second, name))
    {
      vtkErrorMacro("Cannot blend fields whose regions do not mean the same: their "
        << name << " differ (segment both with the same region table, Delta and RegionOffset).");
      return false;
    }
  }
  return true;
}

int vtkDistanceFieldBlend::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* first = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* second = vtkImageData::GetData(inputVector[1], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  if (!this->CheckInputs(first, second))
  {
    return 0;
  }
  const vtkIdType n = first->GetNumberOfPoints();
  // Plain copies when the arrays are of other types (e.g. read from files).
  auto floats = [](vtkDataArray* array)
  {
    vtkNew<vtkFloatArray> copy;
    copy->DeepCopy(array);
    return vtkSmartPointer<vtkFloatArray>(copy.GetPointer());
  };
  auto ints = [](vtkDataArray* array)
  {
    vtkNew<vtkIntArray> copy;
    copy->DeepCopy(array);
    return vtkSmartPointer<vtkIntArray>(copy.GetPointer());
  };
  vtkSmartPointer<vtkFloatArray> da = floats(first->GetPointData()->GetArray("Distance"));
  vtkSmartPointer<vtkFloatArray> db = floats(second->GetPointData()->GetArray("Distance"));
  vtkSmartPointer<vtkIntArray> ra = ints(first->GetPointData()->GetArray("RegionIndex"));
  vtkSmartPointer<vtkIntArray> rb = ints(second->GetPointData()->GetArray("RegionIndex"));
  auto distance = vtkdf::NewArray<vtkFloatArray>("Distance", n);
  auto segmented = vtkdf::NewArray<vtkFloatArray>("SegmentedDistance", n);
  auto region = vtkdf::NewArray<vtkIntArray>("RegionIndex", n);
  static_assert(sizeof(int) == sizeof(int32_t), "int is 32 bits");
  vtkdf::SegmentedSamples a, b;
  a.Distance = da->GetPointer(0);
  a.Region = reinterpret_cast<const int32_t*>(ra->GetPointer(0));
  b.Distance = db->GetPointer(0);
  b.Region = reinterpret_cast<const int32_t*>(rb->GetPointer(0));
  vtkdf::BlendGrid grid;
  first->GetDimensions(grid.Dims);
  for (int c = 0; c < 3; ++c)
  {
    grid.Spacing[c] = std::abs(first->GetSpacing()[c]);
  }
  vtkdf::BlendSegmentedFields(a,
    b,
    this->T,
    grid,
    FieldValues(first, "Delta")[0],
    FieldValues(first, "RegionOffset")[0],
    distance->GetPointer(0),
    reinterpret_cast<int32_t*>(region->GetPointer(0)),
    segmented->GetPointer(0),
    vtkdf::SMPFor);
  output->SetDimensions(first->GetDimensions());
  output->SetOrigin(first->GetOrigin());
  output->SetSpacing(first->GetSpacing());
  output->GetPointData()->SetScalars(segmented);
  output->GetPointData()->AddArray(region);
  output->GetPointData()->AddArray(distance);
  output->GetFieldData()->ShallowCopy(first->GetFieldData());
  return 1;
}

void vtkDistanceFieldBlend::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "T: " << this->T << "\n";
}
