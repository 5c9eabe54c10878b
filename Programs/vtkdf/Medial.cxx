#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkMedialAxisFilter.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkXMLPolyDataWriter.h"

#include <string>

namespace vtkdf::cli
{

int Medial(int argc, char* argv[])
{
  CommonOptions common;
  std::string region = "inside", points, png, sign = "pseudonormal";
  double angle = 90;
  ParseOptions(argc,
    argv,
    common,
    { Number("--angle", angle),
      Text("--region", region),
      Text("--sign", sign),
      Text("--points", points),
      Text("--png", png) });
  vtkNew<vtkMedialAxisFilter> filter;
  filter->SetInputData(ReadMeshOrImageOrExit(argv[2]));
  Configure(filter, common);
  filter->SetSeparationAngle(angle);
  filter->SetRegion(EnumWord("--region", region, vtkdf::enums::MedialRegion));
  filter->SetSignMode(EnumWord("--sign", sign, vtkdf::enums::MedialSign));
  int code = Finish("medial",
    filter,
    common,
    [&]() { return " medial_voxels=" + std::to_string(filter->GetLastMedialCount()); });
  if (code == 0 && !points.empty())
  {
    code = WriteXML<vtkXMLPolyDataWriter>(filter->GetMedialPoints(), points) ? 0 : 1;
  }
  if (code == 0 && !png.empty() && !WriteMedialPNG(filter->GetOutput(), png))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", png.c_str());
    code = 1;
  }
  return code;
}

} // namespace vtkdf::cli
