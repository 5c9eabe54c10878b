// Shapes the segmentation and rendering tests share.
#ifndef vtkdf_TestShapes_h
#define vtkdf_TestShapes_h

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <initializer_list>

namespace testsupport
{
/// The box [-1, 1]^3 with a wall at x = 0.13; the right chamber (x > 0.13) has no lid.
inline vtkSmartPointer<vtkPolyData> OpenWalledBox()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  auto quad = [&](std::initializer_list<std::array<double, 3>> corners)
  {
    vtkIdType ids[4], k = 0;
    for (const auto& c : corners)
    {
      ids[k++] = points->InsertNextPoint(c.data());
    }
    const vtkIdType t0[3] = { ids[0], ids[1], ids[2] }, t1[3] = { ids[0], ids[2], ids[3] };
    polys->InsertNextCell(3, t0);
    polys->InsertNextCell(3, t1);
  };
  const double w = 0.13, xs[3] = { -1, w, 1 };
  for (int i = 0; i < 2; ++i)
  {
    const double x0 = xs[i], x1 = xs[i + 1];
    quad({ { x0, -1, -1 }, { x1, -1, -1 }, { x1, -1, 1 }, { x0, -1, 1 } });
    quad({ { x0, 1, -1 }, { x0, 1, 1 }, { x1, 1, 1 }, { x1, 1, -1 } });
    quad({ { x0, -1, -1 }, { x0, 1, -1 }, { x1, 1, -1 }, { x1, -1, -1 } });
    if (i == 0)
    {
      quad({ { x0, -1, 1 }, { x1, -1, 1 }, { x1, 1, 1 }, { x0, 1, 1 } }); // the left lid only
    }
  }
  quad({ { -1, -1, -1 }, { -1, -1, 1 }, { -1, 1, 1 }, { -1, 1, -1 } });
  quad({ { 1, -1, -1 }, { 1, 1, -1 }, { 1, 1, 1 }, { 1, -1, 1 } });
  quad({ { w, -1, -1 }, { w, 1, -1 }, { w, 1, 1 }, { w, -1, 1 } });
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

} // namespace testsupport

#endif
