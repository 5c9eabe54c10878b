#include "Files.h"

#include "Options.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkImageData.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkPolyDataReader.h"
#include "vtkSTLReader.h"
#include "vtkXMLDataObjectWriter.h"
#include "vtkXMLGenericDataObjectReader.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLMultiBlockDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>

namespace vtkdf::cli
{

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path)
{
  vtkSmartPointer<vtkPolyData> mesh;
  auto run = [&](auto reader)
  {
    reader->SetFileName(path.c_str());
    reader->Update();
    // A reader that failed (a missing, truncated or garbled file) says so in its error
    // code; its output is then not the file's mesh.
    mesh = reader->GetErrorCode() == 0 ? reader->GetOutput() : nullptr;
  };
  if (EndsWith(path, ".vtp"))
  {
    run(vtkSmartPointer<vtkXMLPolyDataReader>::New());
  }
  else if (EndsWith(path, ".vtk"))
  {
    run(vtkSmartPointer<vtkPolyDataReader>::New());
  }
  else if (EndsWith(path, ".ply"))
  {
    run(vtkSmartPointer<vtkPLYReader>::New());
  }
  else if (EndsWith(path, ".stl"))
  {
    run(vtkSmartPointer<vtkSTLReader>::New());
  }
  else if (EndsWith(path, ".obj"))
  {
    run(vtkSmartPointer<vtkOBJReader>::New());
  }
  return mesh;
}

vtkSmartPointer<vtkPolyData> ReadMeshOrExit(const std::string& input)
{
  vtkSmartPointer<vtkPolyData> mesh = ReadMesh(input);
  // Some readers report a file they cannot parse only by an empty output.
  if (!mesh || mesh->GetNumberOfPoints() == 0)
  {
    std::exit(Usage(("cannot read a mesh from " + input +
      " (missing, unreadable, or no points; expected .vtp .vtk .ply .stl .obj)")
                      .c_str()));
  }
  return mesh;
}

/// Convex pieces: a .vtm (one piece per leaf) or a mesh (its connected components).
vtkSmartPointer<vtkDataObject> ReadPolytopesOrExit(const std::string& input)
{
  if (!EndsWith(input, ".vtm"))
  {
    return ReadMeshOrExit(input);
  }
  vtkNew<vtkXMLMultiBlockDataReader> reader;
  reader->SetFileName(input.c_str());
  reader->Update();
  if (reader->GetErrorCode() || !reader->GetOutput())
  {
    std::exit(Usage(("cannot read " + input).c_str()));
  }
  return reader->GetOutput();
}

/// A .vti (an image of masks or a field) or a mesh.
vtkSmartPointer<vtkDataObject> ReadMeshOrImageOrExit(const std::string& input)
{
  if (!EndsWith(input, ".vti"))
  {
    return ReadMeshOrExit(input);
  }
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(input.c_str());
  reader->Update();
  if (reader->GetErrorCode() || !reader->GetOutput() ||
    reader->GetOutput()->GetNumberOfPoints() == 0)
  {
    std::exit(
      Usage(("cannot read an image from " + input + " (missing, unreadable or empty)").c_str()));
  }
  return reader->GetOutput();
}

vtkSmartPointer<vtkDataSet> ReadDataSetOrExit(const std::string& path)
{
  if (!(EndsWith(path, ".vtu") || EndsWith(path, ".vti") || EndsWith(path, ".vts") ||
        EndsWith(path, ".vtr")))
  {
    return ReadMeshOrExit(path);
  }
  vtkNew<vtkXMLGenericDataObjectReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkDataSet* data = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
  if (reader->GetErrorCode() || !data)
  {
    std::exit(Usage(("cannot read " + path).c_str()));
  }
  return data;
}

int WriteDataSet(vtkDataSet* data, const std::string& path)
{
  const int type = data->GetDataObjectType();
  const char* extension = type == VTK_POLY_DATA ? ".vtp"
    : type == VTK_UNSTRUCTURED_GRID             ? ".vtu"
    : type == VTK_IMAGE_DATA                    ? ".vti"
    : type == VTK_STRUCTURED_GRID               ? ".vts"
    : type == VTK_RECTILINEAR_GRID              ? ".vtr"
                                                : ".vtk";
  if (!EndsWith(path, extension))
  {
    std::fprintf(
      stderr, "vtkdf: the output is a %s: name it OUT%s\n", data->GetClassName(), extension);
    return 2;
  }
  vtkNew<vtkXMLDataObjectWriter> writer;
  writer->SetInputData(data);
  writer->SetFileName(path.c_str());
  if (!writer->Write() || writer->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", path.c_str());
    return 1;
  }
  return 0;
}

} // namespace vtkdf::cli
