// A pipeline of the module's filters, as a user would write it in C++: a mesh's exact
// signed distance field, its chamfer field, and its medial axis, written as .vti/.vtp.
//
// usage: MeshToFields MESH.vtp OUT_DIR [RESOLUTION]
#include "vtkChamferVoxelDistance.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkMedialAxisFilter.h"

#include "vtkNew.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include <vtksys/SystemTools.hxx>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: %s MESH.vtp OUT_DIR [RESOLUTION]\n", argv[0]);
    return 2;
  }
  const std::string out = argv[2];
  const int resolution = argc > 3 ? std::atoi(argv[3]) : 96;
  // (VTK 9.1's XML writers return 1 from Write() even on failure: the error code tells.)
  if (!vtksys::SystemTools::MakeDirectory(out))
  {
    std::fprintf(stderr, "cannot create the directory %s\n", out.c_str());
    return 1;
  }

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(argv[1]);

  // Exact signed distance with closest points (Backend Auto: the CPU, measured faster).
  vtkNew<vtkLinearFactorDistanceField> distance;
  distance->SetInputConnection(reader->GetOutputPort());
  distance->SetResolution(resolution);
  distance->SetSignModeToPseudoNormal();
  distance->ComputeClosestPointOn();

  // The medial axis from that field (no second field computation).
  vtkNew<vtkMedialAxisFilter> medial;
  medial->SetInputConnection(distance->GetOutputPort());
  medial->SetSeparationAngle(75);

  // The chessboard chamfer field of the same mesh, on its own voxelization.
  vtkNew<vtkChamferVoxelDistance> chamfer;
  chamfer->SetInputConnection(reader->GetOutputPort());
  chamfer->SetResolution(resolution);
  chamfer->SetMetricToChessboard18();
  chamfer->SignedOn();

  vtkNew<vtkXMLImageDataWriter> imageWriter;
  imageWriter->SetInputConnection(distance->GetOutputPort());
  imageWriter->SetFileName((out + "/distance.vti").c_str());
  if (!imageWriter->Write() || imageWriter->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "could not write %s/distance.vti\n", out.c_str());
    return 1;
  }
  std::printf("distance: %s (%s) %.3f s\n",
    distance->GetLastBackend(),
    distance->GetLastRenderer(),
    distance->GetLastTime());

  vtkNew<vtkXMLPolyDataWriter> pointsWriter;
  pointsWriter->SetInputConnection(medial->GetOutputPort(1));
  pointsWriter->SetFileName((out + "/medial.vtp").c_str());
  if (!pointsWriter->Write() || pointsWriter->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "could not write %s/medial.vtp\n", out.c_str());
    return 1;
  }
  std::printf("medial axis: %lld voxels, %.3f s\n",
    static_cast<long long>(medial->GetLastMedialCount()),
    medial->GetLastTime());

  imageWriter->SetInputConnection(chamfer->GetOutputPort());
  imageWriter->SetFileName((out + "/chamfer.vti").c_str());
  if (!imageWriter->Write() || imageWriter->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "could not write %s/chamfer.vti\n", out.c_str());
    return 1;
  }
  std::printf("chamfer: %d layers, %s, %.3f s\n",
    chamfer->GetLastLayers(),
    chamfer->GetLastBackend(),
    chamfer->GetLastTime());
  std::printf("wrote %s/distance.vti, %s/medial.vtp, %s/chamfer.vti\n",
    out.c_str(),
    out.c_str(),
    out.c_str());
  return 0;
}
