#include "vtkSegmentedDistanceContour.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMarchingCubesTriangleCases.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Segment/SegmentContour.h"
#include "vtkDistanceFieldArrays.h"
#include "vtkDistanceFieldExecution.h"
#include "vtkDistanceFieldPartitions.h"
#include "vtkDistanceFieldRun.h"

#include <cmath>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkSegmentedDistanceContour);

int vtkSegmentedDistanceContour::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

vtkdf::RunStatus vtkSegmentedDistanceContour::Execute(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector,
  vtkdf::FilterRun& run)
{
  this->LastMarchingCells = this->LastFeatureCells = this->LastOtherCells = 0;
  if (!(this->FeatureAngle > 0 && this->FeatureAngle <= 180))
  {
    std::ostringstream text;
    text << "FeatureAngle must be in (0, 180] degrees; it is " << this->FeatureAngle << ".";
    return run.Fail(text.str());
  }
  // A distributed field comes in pieces: rank 0 gathers the whole field and outputs the
  // surface, once (a cell's triangles depend on the regions around it, and one process's
  // order of cells and points is kept); the other ranks output nothing.
  std::string error;
  int wholeExtent[6];
  inputVector[0]->GetInformationObject(0)->Get(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
  vtkSmartPointer<vtkImageData> whole;
  if (!vtkdf::GatherWholeImage(vtkImageData::GetData(inputVector[0], 0),
        wholeExtent,
        { "SegmentedDistance", "ClosestPoint" },
        whole,
        error))
  {
    return run.Fail("The segmented field could not be gathered: " + error + ".");
  }
  if (!vtkdf::IsFirstRank())
  {
    return vtkdf::RunStatus::Done;
  }
  vtkdf::ContourInput input;
  std::vector<float> distance;
  std::vector<int32_t> region;
  std::vector<double> closest;
  if (!this->ReadField(whole, input, distance, region, closest))
  {
    return vtkdf::RunStatus::Failed;
  }
  run.Timer.End("read");
  // VTK's marching cubes table, as plain rows.
  std::vector<int> table(256 * 16);
  vtkMarchingCubesTriangleCases* cases = vtkMarchingCubesTriangleCases::GetCases();
  for (int c = 0; c < 256; ++c)
  {
    std::copy(cases[c].edges, cases[c].edges + 16, table.begin() + 16 * c);
  }
  input.Cases = reinterpret_cast<const int(*)[16]>(table.data());
  vtkdf::ContourResult result;
  if (!vtkdf::ContourSegmented(input, result, run.MakeExecution(0.1, 0.9)))
  {
    return run.Empty(); // aborted
  }
  run.Timer.End("contour");
  this->LastMarchingCells = result.MarchingCells;
  this->LastOtherCells = result.OtherCells;
  this->LastFeatureCells = result.FeatureCells;
  WriteSurface(result, vtkPolyData::GetData(outputVector, 0));
  run.Timer.End("arrays");
  return vtkdf::RunStatus::Done;
}

bool vtkSegmentedDistanceContour::ReadField(vtkImageData* field,
  vtkdf::ContourInput& input,
  std::vector<float>& distance,
  std::vector<int32_t>& region,
  std::vector<double>& closest)
{
  std::string error;
  vtkDataArray* values = vtkdf::SampleArray(field, "SegmentedDistance", 1, error);
  vtkDataArray* offsetArray = field ? field->GetFieldData()->GetArray("RegionOffset") : nullptr;
  if (!values)
  {
    vtkErrorMacro(<< error << " (vtkSegmentedDistanceField makes it).");
    return false;
  }
  const double offset = offsetArray ? offsetArray->GetTuple1(0) : 0;
  if (!(offset > 0 && std::isfinite(offset)))
  {
    vtkErrorMacro("The input has no positive field-data RegionOffset: it is not the output of "
                  "vtkSegmentedDistanceField.");
    return false;
  }
  const vtkIdType n = field->GetNumberOfPoints();
  distance.resize(n);
  region.resize(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    const double f = values->GetTuple1(v);
    if (!(f >= 0 && std::isfinite(f)))
    {
      vtkErrorMacro("SegmentedDistance holds " << f << " at sample " << v
                                               << ": a segmented field is finite and >= 0.");
      return false;
    }
    const double r = std::floor(f / offset);
    region[v] = static_cast<int32_t>(r);
    distance[v] = static_cast<float>(f - offset * r);
  }
  int extent[6];
  field->GetExtent(extent);
  for (int a = 0; a < 3; ++a)
  {
    input.Grid.Origin[a] = field->GetOrigin()[a];
    input.Grid.Spacing[a] = field->GetSpacing()[a];
    input.Grid.Whole.Lo[a] = extent[2 * a];
    input.Grid.Whole.Hi[a] = extent[2 * a + 1];
  }
  input.Distance = distance.data();
  input.Region = region.data();
  // The closest points, when there and wanted, in double.
  vtkDataArray* closestArray = field->GetPointData()->GetArray("ClosestPoint");
  if (this->UseClosestPoints && closestArray)
  {
    if (closestArray->GetNumberOfComponents() != 3 || closestArray->GetNumberOfTuples() != n)
    {
      vtkErrorMacro("ClosestPoint must have 3 components per sample; it has "
        << closestArray->GetNumberOfComponents() << " and " << closestArray->GetNumberOfTuples()
        << " tuples for " << n << " samples.");
      return false;
    }
    closest.resize(3 * static_cast<size_t>(n));
    for (vtkIdType v = 0; v < n; ++v)
    {
      closestArray->GetTuple(v, &closest[3 * v]);
    }
    input.ClosestPoint = closest.data();
    input.FeatureAngle = this->FeatureAngle;
  }
  return true;
}

void vtkSegmentedDistanceContour::WriteSurface(const vtkdf::ContourResult& result,
  vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(result.Points.size() / 3));
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    points->SetPoint(p, &result.Points[3 * p]);
  }
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkIntArray> pairs;
  pairs->SetName("Regions");
  pairs->SetNumberOfComponents(2);
  const vtkIdType count = static_cast<vtkIdType>(result.Triangles.size() / 3);
  triangles->AllocateExact(count, 3 * count);
  pairs->SetNumberOfTuples(count);
  for (vtkIdType t = 0; t < count; ++t)
  {
    const vtkIdType ids[3] = {
      result.Triangles[3 * t], result.Triangles[3 * t + 1], result.Triangles[3 * t + 2]
    };
    triangles->InsertNextCell(3, ids);
    pairs->SetTypedComponent(t, 0, result.Pairs[2 * t]);
    pairs->SetTypedComponent(t, 1, result.Pairs[2 * t + 1]);
  }
  output->SetPoints(points);
  output->SetPolys(triangles);
  output->GetCellData()->AddArray(pairs);
}

void vtkSegmentedDistanceContour::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UseClosestPoints: " << this->UseClosestPoints << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "LastMarchingCells: " << this->LastMarchingCells << "\n";
  os << indent << "LastFeatureCells: " << this->LastFeatureCells << "\n";
  os << indent << "LastOtherCells: " << this->LastOtherCells << "\n";
}
