// Files: how vtkdf reads its inputs (meshes by extension, images, convex pieces) and
// writes VTK XML files.
#ifndef vtkdf_Files_h
#define vtkdf_Files_h

#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkPolyData.h" // ReadMesh's smart pointers convert where they are used
#include "vtkSmartPointer.h"

#include <cstdio>
#include <string>

namespace vtkdf::cli
{

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path);

vtkSmartPointer<vtkPolyData> ReadMeshOrExit(const std::string& input);

/// Convex pieces: a .vtm (one piece per leaf) or a mesh (its connected components).
vtkSmartPointer<vtkDataObject> ReadPolytopesOrExit(const std::string& input);

/// A .vti (an image of masks or a field) or a mesh.
vtkSmartPointer<vtkDataObject> ReadMeshOrImageOrExit(const std::string& input);

/// Writes `data` as a VTK XML file (`Writer`: vtkXMLImageDataWriter or
/// vtkXMLPolyDataWriter); false, with a message, when the file cannot be written (VTK
/// 9.1's XML writers return 1 from Write() even when the file cannot be opened).
template<typename Writer>
bool WriteXML(vtkDataObject* data, const std::string& path)
{
  vtkNew<Writer> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(data);
  if (!writer->Write() || writer->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", path.c_str());
    return false;
  }
  return true;
}

} // namespace vtkdf::cli

#endif
