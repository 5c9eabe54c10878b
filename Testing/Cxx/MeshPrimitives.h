// MeshPrimitives: a mesh's triangles, segments and points as the brute-force references
// of the tests see them, and the squared distance to one of them.
#ifndef vtkdf_MeshPrimitives_h
#define vtkdf_MeshPrimitives_h

#include "vtkCellArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include "Common/PointTriangleDistance.h"

#include <array>
#include <vector>

namespace vtkdf::testing
{
/// The triangles of a mesh cell by cell (triangle cells only, and line and vertex cells
/// as segments and points: a, b, b and a, a, a), with their cell and index within it.
struct Primitives
{
  std::vector<std::array<double, 9>> X;
  std::vector<vtkIdType> Cell, Sub;
};

inline Primitives Collect(vtkPolyData* mesh)
{
  Primitives p;
  // The filters' cell numbering: vertices, lines, polygons, strips.
  vtkIdType cell = 0;
  auto corner = [&](vtkIdType id, double* x) { mesh->GetPoint(id, x); };
  vtkNew<vtkIdList> ids;
  for (vtkCellArray* cells : { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys() })
  {
    const bool lines = cells == mesh->GetLines(), verts = cells == mesh->GetVerts();
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c, ++cell)
    {
      cells->GetCellAtId(c, ids);
      const vtkIdType n = ids->GetNumberOfIds();
      const vtkIdType parts = verts ? n : (lines ? n - 1 : 1);
      for (vtkIdType k = 0; k < parts; ++k)
      {
        std::array<double, 9> x;
        const vtkIdType a = ids->GetId(k), b = verts ? a : ids->GetId(k + 1),
                        cc = verts || lines ? b : ids->GetId(2);
        corner(a, x.data());
        corner(b, x.data() + 3);
        corner(cc, x.data() + 6);
        p.X.push_back(x);
        p.Cell.push_back(cell);
        p.Sub.push_back(k);
      }
    }
  }
  return p;
}

inline double SquaredDistance(const double q[3], const std::array<double, 9>& t)
{
  return vtkdf::SquaredDistanceToTriangle(q, t.data(), t.data() + 3, t.data() + 6);
}
} // namespace vtkdf::testing

#endif
