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

namespace vtkdf::testing
{
/// The box [-width, width] x [-1, 1] x [-1, 1] with a wall at x = `wall`; the right
/// chamber (x > wall) has no lid when `openRight`. Built alike for every wall and width,
/// so that the patches correspond.
inline vtkSmartPointer<vtkPolyData> WalledBox(double wall, bool openRight, double width = 1)
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
  const double w = wall, xs[3] = { -width, w, width };
  for (int i = 0; i < 2; ++i)
  {
    const double x0 = xs[i], x1 = xs[i + 1];
    quad({ { x0, -1, -1 }, { x1, -1, -1 }, { x1, -1, 1 }, { x0, -1, 1 } });
    quad({ { x0, 1, -1 }, { x0, 1, 1 }, { x1, 1, 1 }, { x1, 1, -1 } });
    quad({ { x0, -1, -1 }, { x0, 1, -1 }, { x1, 1, -1 }, { x1, -1, -1 } });
    if (i == 0 || !openRight)
    {
      quad({ { x0, -1, 1 }, { x1, -1, 1 }, { x1, 1, 1 }, { x0, 1, 1 } }); // the lids
    }
  }
  quad({ { -width, -1, -1 }, { -width, -1, 1 }, { -width, 1, 1 }, { -width, 1, -1 } });
  quad({ { width, -1, -1 }, { width, 1, -1 }, { width, 1, 1 }, { width, -1, 1 } });
  quad({ { w, -1, -1 }, { w, 1, -1 }, { w, 1, 1 }, { w, -1, 1 } });
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

/// The box [-1, 1]^3 with a wall at x = 0.13; the right chamber (x > 0.13) has no lid.
inline vtkSmartPointer<vtkPolyData> OpenWalledBox()
{
  return WalledBox(0.13, true);
}

} // namespace vtkdf::testing

#endif
