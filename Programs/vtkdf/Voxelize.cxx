#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkPolyDataVoxelizer.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

namespace vtkdf::cli
{

int Voxelize(int argc, char* argv[])
{
  CommonOptions common;
  std::string mode = "both";
  ParseOptions(argc, argv, common, { Text("--mode", mode) });
  vtkNew<vtkPolyDataVoxelizer> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  Configure(filter, common);
  filter->SetMode(EnumWord("--mode", mode, vtkdf::enums::VoxelMode));
  return Finish("voxelize", filter, common);
}

} // namespace vtkdf::cli
