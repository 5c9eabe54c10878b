// UnitBoxMesh: a mesh file's triangles scaled into a unit box centred at the origin, in
// double precision, turned by an angle about z and moved: the proximity tests' and
// benchmark's models (so that every pose and step is in the same units).
#ifndef UnitBoxMesh_h
#define UnitBoxMesh_h

#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace vtkdf::testing
{
/// The triangles of the .vtp file `path` (vertices and lines dropped) in the unit box
/// centred at the origin (longest side 1), turned by `angle` about z, then moved by
/// `offset`.
inline vtkSmartPointer<vtkPolyData> ReadUnitBoxMesh(const std::string& path,
  double angle = 0,
  const double offset[3] = nullptr)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(reader->GetOutputPort());
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(triangles->GetOutput());
  double b[6];
  mesh->GetBounds(b);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  const double c = std::cos(angle), s = std::sin(angle);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double x[3];
    mesh->GetPoint(i, x);
    for (int k = 0; k < 3; ++k)
    {
      x[k] = (x[k] - 0.5 * (b[2 * k] + b[2 * k + 1])) / size;
    }
    const double t[3] = { offset ? offset[0] : 0, offset ? offset[1] : 0, offset ? offset[2] : 0 };
    points->InsertNextPoint(c * x[0] - s * x[1] + t[0], s * x[0] + c * x[1] + t[1], x[2] + t[2]);
  }
  mesh->SetPoints(points);
  return mesh;
}
} // namespace vtkdf::testing

#endif
