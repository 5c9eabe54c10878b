// What the regression image tests share: the surface's cross-section on a slice.
#ifndef vtkdf_ImageTestSupport_h
#define vtkdf_ImageTestSupport_h

#include "vtkActor.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCutter.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"

namespace vtkdf::testing
{
/// The cut of `surface` by the plane z = `z`, drawn as lines of `rgb`, lifted by `lift`
/// towards the camera so that it shows above an image slice at z.
inline vtkSmartPointer<vtkActor> SurfaceCut(vtkAlgorithmOutput* surface,
  double z,
  const double rgb[3],
  double lift)
{
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0, 0, z);
  plane->SetNormal(0, 0, 1);
  vtkNew<vtkCutter> cutter;
  cutter->SetInputConnection(surface);
  cutter->SetCutFunction(plane);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cutter->GetOutputPort());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(rgb[0], rgb[1], rgb[2]);
  actor->GetProperty()->SetLineWidth(2);
  actor->SetPosition(0, 0, lift);
  return actor;
}
} // namespace vtkdf::testing

#endif
