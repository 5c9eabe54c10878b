// Files: how vtkdf reads its inputs (meshes by extension, images, convex pieces) and
// writes VTK XML files.
#ifndef vtkdf_Files_h
#define vtkdf_Files_h

#include "vtkDataObject.h"
#include "vtkDataSet.h" // ReadDataSetOrExit's smart pointer
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

/// Any dataset: a VTK XML .vtu, .vti, .vts or .vtr, or a mesh.
vtkSmartPointer<vtkDataSet> ReadDataSetOrExit(const std::string& path);

/// Writes `data` as VTK XML: the exit status, 0 when written, 2 (a usage error) when
/// `path` does not end with its type's extension (.vtp, .vtu, .vti, .vts, .vtr), 1 when
/// it cannot be written; with a message.
int WriteDataSet(vtkDataSet* data, const std::string& path);

/// Writes `data` as a VTK XML file (`Writer`: vtkXMLImageDataWriter or
/// vtkXMLPolyDataWriter); false, with a message, when the file cannot be written (VTK
/// 9.1's XML writers return 1 from Write() even when the file cannot be opened).
template<typename Writer>
bool WriteXML(vtkDataObject* data, const std::string& path)
{
  vtkNew<Writer> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputDataObject(data);
  if (!writer->Write() || writer->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", path.c_str());
    return false;
  }
  return true;
}

} // namespace vtkdf::cli

#endif
