#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkDistanceFieldBlend.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkXMLImageDataWriter.h"

#include <cmath>

namespace vtkdf::cli
{

/// vtkdf blend A.vti B.vti -t T -o OUT.vti [--png SLICE.png]
int Blend(int argc, char* argv[])
{
  if (argc < 4)
  {
    return Usage("blend takes two .vti fields");
  }
  double t = std::nan("");
  std::string output, png;
  for (int a = 4; a < argc; ++a)
  {
    const std::string option = argv[a];
    if (a + 1 >= argc)
    {
      return Usage((option + " needs a value").c_str());
    }
    if (option == "-t")
    {
      t = ParseNumber("-t", argv[++a]);
    }
    else if (option == "-o")
    {
      output = argv[++a];
    }
    else if (option == "--png")
    {
      png = argv[++a];
    }
    else
    {
      return Usage(("unknown option " + option).c_str());
    }
  }
  if (output.empty() || std::isnan(t))
  {
    return Usage("blend needs -t T and -o OUT.vti");
  }
  if (!EndsWith(argv[2], ".vti") || !EndsWith(argv[3], ".vti"))
  {
    return Usage("blend takes two .vti fields (from vtkdf segment)");
  }
  vtkNew<vtkDistanceFieldBlend> blend;
  blend->SetInputData(0, ReadMeshOrImageOrExit(argv[2]));
  blend->SetInputData(1, ReadMeshOrImageOrExit(argv[3]));
  blend->SetT(t);
  blend->Update();
  vtkImageData* field = blend->GetOutput();
  if (blend->GetErrorCode() || field->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  if (!WriteXML<vtkXMLImageDataWriter>(field, output))
  {
    return 1;
  }
  vtkDataArray* delta = field->GetFieldData()->GetArray("Delta");
  if (!png.empty() && !(delta && WriteRegionPNG(field, delta->GetTuple1(0), png)))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", png.c_str());
    return 1;
  }
  return 0;
}

} // namespace vtkdf::cli
