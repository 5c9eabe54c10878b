// vtkMeshDistanceFilter's statistics (field data): each point counted once, where points
// share a global id and where copies are marked as ghosts (VTK's DUPLICATEPOINT), the
// sums exact (the same bits on one thread and two), on random points around the plane
// of the test collection.
// Usage: TestMeshDistanceStatistics DATA_DIR
#include "TestSupport.h"
#include "UnitBoxMesh.h"
#include "vtkMeshDistanceFilter.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using vtkdf::testing::Failures;

namespace
{
void Check(bool ok, const std::string& what)
{
  if (!ok && Failures++ < 20)
  {
    std::printf("FAIL: %s\n", what.c_str());
  }
}

/// `count` points uniform in the box [-1, 1]^3.
vtkSmartPointer<vtkPolyData> RandomPoints(int count)
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(7);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int i = 0; i < count; ++i)
  {
    double x[3];
    for (double& c : x)
    {
      c = random->GetNextRangeValue(-1, 1);
    }
    points->InsertNextPoint(x);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  return cloud;
}

/// The field data of `filter`'s output: max, mean, RMS, farthest id, its point, beyond.
std::vector<double> Summary(vtkMeshDistanceFilter* filter)
{
  std::vector<double> values;
  vtkFieldData* fd = filter->GetOutput()->GetFieldData();
  for (const char* name : { "MaximumAbsoluteDistance",
         "MeanAbsoluteDistance",
         "RootMeanSquareDistance",
         "FarthestPointId",
         "FarthestPoint",
         "PointsBeyond" })
  {
    vtkDataArray* a = fd->GetArray(name);
    for (int k = 0; a && k < a->GetNumberOfComponents(); ++k)
    {
      values.push_back(a->GetComponent(0, k));
    }
  }
  return values;
}

/// The statistics count each point once: points that share a global id, and copies
/// marked as ghosts (VTK's DUPLICATEPOINT), leave them as they are; the sums are exact,
/// the same bits on one thread and on several, and in another order of the points.
void Statistics(const std::string& data)
{
  auto mesh = vtkdf::testing::ReadUnitBoxMesh(data + "/plane.vtp");
  vtkSmartPointer<vtkPolyData> cloud = RandomPoints(2000);
  const vtkIdType n = cloud->GetNumberOfPoints();
  auto run = [&](vtkPolyData* points)
  {
    vtkNew<vtkMeshDistanceFilter> filter;
    filter->SetInputData(0, points);
    filter->SetSurfaceData(mesh);
    filter->SetSignModeToWindingNumber();
    filter->Update();
    return Summary(filter);
  };
  // The points with global ids 0..n-1, then each again (reversed) with its id.
  auto withIds = [&](bool twice, bool ghosts)
  {
    auto points = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> xyz;
    xyz->SetDataTypeToDouble();
    vtkNew<vtkIdTypeArray> ids;
    ids->SetName("GlobalIds");
    vtkNew<vtkUnsignedCharArray> ghost;
    ghost->SetName(vtkDataSetAttributes::GhostArrayName());
    for (vtkIdType i = 0; i < (twice ? 2 * n : n); ++i)
    {
      const vtkIdType source = i < n ? i : 2 * n - 1 - i;
      xyz->InsertNextPoint(cloud->GetPoint(source));
      ids->InsertNextValue(source);
      ghost->InsertNextValue(i < n ? 0 : vtkDataSetAttributes::DUPLICATEPOINT);
    }
    points->SetPoints(xyz);
    if (ghosts)
    {
      points->GetPointData()->AddArray(ghost);
    }
    else
    {
      points->GetPointData()->SetGlobalIds(ids);
    }
    return points;
  };
  const std::vector<double> plain = run(cloud);
  const std::vector<double> once = run(withIds(false, false));
  const std::vector<double> twice = run(withIds(true, false));
  const std::vector<double> ghosted = run(withIds(true, true));
  Check(plain.size() == 8 && once == plain, "global ids 0..n-1 changed the statistics");
  Check(twice == plain, "points that share a global id counted twice");
  Check(ghosted == plain, "ghost points counted");
  vtkSMPTools::Initialize(1);
  const std::vector<double> oneThread = run(cloud);
  vtkSMPTools::Initialize(2);
  Check(oneThread == plain, "one thread and two: other statistics");
  std::printf("statistics of %lld points: max %.17g, mean %.17g, rms %.17g, farthest %g\n",
    static_cast<long long>(n),
    plain.size() > 2 ? plain[0] : NAN,
    plain.size() > 2 ? plain[1] : NAN,
    plain.size() > 2 ? plain[2] : NAN,
    plain.size() > 3 ? plain[3] : NAN);
}

} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 1, "DATA_DIR"))
  {
    return 2;
  }
  Statistics(argv[1]);
  return vtkdf::testing::Verdict();
}
