#include "vtkDistanceFieldBlend.h"

#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Segment/SegmentBlend.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkDistanceFieldBlend);

namespace
{
/// `array` itself when it is a vtkFloatArray (`type` VTK_FLOAT) or a vtkIntArray (VTK_INT),
/// else a copy of its values as one (e.g. read from a file); read only.
vtkSmartPointer<vtkDataArray> OfType(vtkDataArray* array, int type)
{
  if (type == VTK_FLOAT ? vtkFloatArray::SafeDownCast(array) != nullptr
                        : vtkIntArray::SafeDownCast(array) != nullptr)
  {
    return array;
  }
  vtkSmartPointer<vtkDataArray> copy;
  copy.TakeReference(vtkDataArray::CreateDataArray(type));
  copy->DeepCopy(array);
  copy->SetName(array->GetName());
  return copy;
}

/// Whether this is a distributed run (the global controller has several ranks).
bool Distributed()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return controller && controller->GetNumberOfProcesses() > 1;
}

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

/// The samples of `box` (within the image's extent) of point array `name`, as a
/// vtkFloatArray (`type` VTK_FLOAT) or a vtkIntArray (VTK_INT).
vtkSmartPointer<vtkDataArray> PieceSamples(vtkImageData* image,
  const char* name,
  int type,
  const vtkdf::IndexBox& box)
{
  int e[6];
  image->GetExtent(e);
  const vtkdf::IndexBox given{ { { e[0], e[2], e[4] } }, { { e[1], e[3], e[5] } } };
  const vtkSmartPointer<vtkDataArray> copy = OfType(image->GetPointData()->GetArray(name), type);
  if (given == box)
  {
    return copy;
  }
  vtkSmartPointer<vtkDataArray> cropped;
  if (type == VTK_FLOAT)
  {
    cropped = vtkdf::CropArray(vtkFloatArray::SafeDownCast(copy), given, box).GetPointer();
  }
  else
  {
    cropped = vtkdf::CropArray(vtkIntArray::SafeDownCast(copy), given, box).GetPointer();
  }
  return cropped;
}

/// The 32-bit values of a vtkIntArray.
const int32_t* Ints(vtkDataArray* array)
{
  static_assert(sizeof(int) == sizeof(int32_t), "int is 32 bits");
  return reinterpret_cast<const int32_t*>(vtkIntArray::SafeDownCast(array)->GetPointer(0));
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

int vtkDistanceFieldBlend::RequestInformation(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  // A piece is blended alone, from the fields' pieces and the whole grid's regions.
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  return 1;
}

int vtkDistanceFieldBlend::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // A sample's distance to a region may be decided by any voxel of the grid. In one
  // process: both fields whole. In a distributed run: the requested piece of each (the
  // ranks then share their regions), so that the fields upstream compute pieces too.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* in = inputVector[port]->GetInformationObject(0);
    if (!in)
    {
      continue;
    }
    if (!Distributed() || !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    {
      vtkdf::RequestWholeInput(in);
      continue;
    }
    // The piece numbers stay those of this rank (a field upstream that produces
    // sub-extents would otherwise turn "piece 0 of 1" back into the whole extent).
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()),
      6);
  }
  return 1;
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

vtkdf::RunStatus vtkDistanceFieldBlend::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  vtkImageData* first = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* second = vtkImageData::GetData(inputVector[1], 0);
  // The piece asked for, within the whole grid.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6], piece[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  std::copy(whole, whole + 6, piece);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), piece);
  }
  for (int a = 0; a < 3; ++a)
  {
    piece[2 * a] = std::max(piece[2 * a], whole[2 * a]);
    piece[2 * a + 1] = std::min(piece[2 * a + 1], whole[2 * a + 1]);
  }
  // In a distributed run every rank shares its regions, a rank with nothing to blend
  // too (the others would wait), so the checks that differ by rank come after.
  const bool inputsOk = this->CheckInputs(first, second);
  vtkSmartPointer<vtkImageData> regions[2];
  if (Distributed())
  {
    std::string error;
    vtkImageData* inputs[2] = { inputsOk ? first : nullptr, inputsOk ? second : nullptr };
    for (int f = 0; f < 2; ++f)
    {
      if (!vtkdf::GatherWholeImage(inputs[f], whole, { "RegionIndex" }, regions[f], error, true))
      {
        return run.Fail(
          "The fields' regions could not be shared between the ranks: " + error + ".");
      }
    }
  }
  if (!inputsOk)
  {
    return vtkdf::RunStatus::Failed;
  }
  if (piece[1] < piece[0] || piece[3] < piece[2] || piece[5] < piece[4])
  {
    return run.Empty(); // an empty piece
  }
  const vtkdf::IndexBox box =
    vtkdf::IndexBox{ { { piece[0], piece[2], piece[4] } }, { { piece[1], piece[3], piece[5] } } };
  for (int f = 0; f < 2; ++f)
  {
    int e[6];
    (f == 0 ? first : second)->GetExtent(e);
    const vtkdf::IndexBox given{ { { e[0], e[2], e[4] } }, { { e[1], e[3], e[5] } } };
    if (!given.Contains(box))
    {
      return run.Fail(std::string("The ") + (f == 0 ? "first" : "second") +
        " field covers less than the piece asked for.");
    }
  }
  // The whole grid's regions: the inputs themselves in one process.
  vtkImageData* wholeRegions[2] = { regions[0] ? regions[0].Get() : first,
    regions[1] ? regions[1].Get() : second };
  if (!this->Blend(first, second, wholeRegions, whole, box, run))
  {
    return run.Empty(); // aborted
  }
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->SetExtent(piece);
  output->SetOrigin(first->GetOrigin());
  output->SetSpacing(first->GetSpacing());
  output->GetFieldData()->ShallowCopy(first->GetFieldData());
  return vtkdf::RunStatus::Done;
}

bool vtkDistanceFieldBlend::Blend(vtkImageData* first,
  vtkImageData* second,
  vtkImageData* const wholeRegions[2],
  const int whole[6],
  const vtkdf::IndexBox& box,
  vtkdf::FilterRun& run)
{
  // The piece's samples, as plain float and int arrays.
  const vtkSmartPointer<vtkDataArray> da = PieceSamples(first, "Distance", VTK_FLOAT, box);
  const vtkSmartPointer<vtkDataArray> db = PieceSamples(second, "Distance", VTK_FLOAT, box);
  const vtkSmartPointer<vtkDataArray> ra = PieceSamples(first, "RegionIndex", VTK_INT, box);
  const vtkSmartPointer<vtkDataArray> rb = PieceSamples(second, "RegionIndex", VTK_INT, box);
  vtkSmartPointer<vtkDataArray> regions[2];
  for (int f = 0; f < 2; ++f)
  {
    regions[f] = OfType(wholeRegions[f]->GetPointData()->GetArray("RegionIndex"), VTK_INT);
  }
  const vtkIdType n = static_cast<vtkIdType>(box.Count());
  auto distance = vtkdf::NewArray<vtkFloatArray>("Distance", n);
  auto segmented = vtkdf::NewArray<vtkFloatArray>("SegmentedDistance", n);
  auto region = vtkdf::NewArray<vtkIntArray>("RegionIndex", n);
  vtkdf::SegmentedSamples a, b;
  a.Distance = vtkFloatArray::SafeDownCast(da)->GetPointer(0);
  a.Region = Ints(ra);
  b.Distance = vtkFloatArray::SafeDownCast(db)->GetPointer(0);
  b.Region = Ints(rb);
  vtkdf::BlendGrid grid;
  vtkdf::BlendBox blendBox;
  for (int c = 0; c < 3; ++c)
  {
    grid.Dims[c] = whole[2 * c + 1] - whole[2 * c] + 1;
    grid.Spacing[c] = std::abs(first->GetSpacing()[c]);
    blendBox.Lo[c] = box.Lo[c] - whole[2 * c];
    blendBox.Hi[c] = box.Hi[c] - whole[2 * c];
  }
  run.Timer.End("read");
  if (!vtkdf::BlendSegmentedFields(a,
        b,
        Ints(regions[0]),
        Ints(regions[1]),
        blendBox,
        this->T,
        grid,
        FieldValues(first, "Delta")[0],
        FieldValues(first, "RegionOffset")[0],
        distance->GetPointer(0),
        reinterpret_cast<int32_t*>(region->GetPointer(0)),
        segmented->GetPointer(0),
        run.MakeExecution()))
  {
    return false;
  }
  run.Timer.End("blend");
  vtkImageData* output = vtkImageData::GetData(this->GetOutputInformation(0));
  output->GetPointData()->SetScalars(segmented);
  output->GetPointData()->AddArray(region);
  output->GetPointData()->AddArray(distance);
  return true;
}

void vtkDistanceFieldBlend::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "T: " << this->T << "\n";
}
