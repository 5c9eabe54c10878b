// A downstream program: the signed distance field of the unit cube, built by hand, with
// vtkLinearFactorDistanceField, checked against the exact distance to the cube at every
// sample. Exit status 0 when every sample is within 1e-5 of it.
#include "vtkLinearFactorDistanceField.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace
{
/// The signed distance from p to the cube [0, 1]^3 (negative inside).
double CubeDistance(const double p[3])
{
  double outside = 0, inside = -HUGE_VAL;
  for (int a = 0; a < 3; ++a)
  {
    const double below = -p[a], above = p[a] - 1; // signed distances to the two faces
    const double d = std::max(below, above);
    outside += d > 0 ? d * d : 0;
    inside = std::max(inside, d);
  }
  return outside > 0 ? std::sqrt(outside) : inside;
}
} // namespace

int main()
{
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 8; ++k)
  {
    points->InsertNextPoint(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  }
  // Two triangles per face, counter-clockwise seen from outside.
  const vtkIdType faces[6][4] = {
    { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 }
  };
  vtkNew<vtkCellArray> triangles;
  for (const auto& f : faces)
  {
    const vtkIdType a[3] = { f[0], f[1], f[2] }, b[3] = { f[0], f[2], f[3] };
    triangles->InsertNextCell(3, a);
    triangles->InsertNextCell(3, b);
  }
  vtkNew<vtkPolyData> cube;
  cube->SetPoints(points);
  cube->SetPolys(triangles);

  vtkNew<vtkLinearFactorDistanceField> field;
  field->SetInputData(cube);
  field->ExplicitGridOn();
  field->SetGridOrigin(-0.5, -0.5, -0.5);
  field->SetGridSpacing(0.125, 0.125, 0.125);
  field->SetGridDimensions(17, 17, 17);
  field->SetSignModeToPseudoNormal();
  field->Update();

  vtkImageData* image = field->GetOutput();
  vtkDataArray* distance = image->GetPointData()->GetArray("Distance");
  if (!distance)
  {
    std::printf("no Distance array\n");
    return 1;
  }
  double worst = 0;
  for (vtkIdType v = 0; v < image->GetNumberOfPoints(); ++v)
  {
    double p[3];
    image->GetPoint(v, p);
    worst = std::max(worst, std::fabs(distance->GetTuple1(v) - CubeDistance(p)));
  }
  std::printf("signed distance to the unit cube on 17^3 samples (%s backend): largest error "
              "%.2g\n",
    field->GetLastBackend(),
    worst);
  return worst <= 1e-5 ? 0 : 1;
}
