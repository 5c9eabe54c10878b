#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkChamferVoxelDistance.h"
#include "vtkDistanceFieldEnums.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include <string>

namespace vtkdf::cli
{

int Chamfer(int argc, char* argv[])
{
  CommonOptions common;
  std::string metric = "chessboard18";
  int layers = 0;
  bool signedField = false;
  ParseOptions(argc,
    argv,
    common,
    { Text("--metric", metric), Count("--layers", layers), Flag("--signed", signedField) });
  vtkNew<vtkChamferVoxelDistance> filter;
  filter->SetInputData(ReadMeshOrImageOrExit(argv[2]));
  Configure(filter, common);
  filter->SetMetric(EnumWord("--metric", metric, vtkdf::enums::Metric));
  if (layers < 0)
  {
    return Usage("--layers takes a count >= 0");
  }
  filter->SetMaximumLayers(layers);
  filter->SetSigned(signedField);
  filter->OutputMasksOn();
  return Finish("chamfer",
    filter,
    common,
    [&]() { return " layers=" + std::to_string(filter->GetLastLayers()); });
}

} // namespace vtkdf::cli
