#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkDistanceFieldProximity.h"

#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataWriter.h"

#include <cstdio>
#include <string>

namespace vtkdf::cli
{

/// vtkdf proximity A B -o OUT.vtp [--contacts CONTACTS.vtp] [--models A.vtp B.vtp]
///   [--resolution N | --spacing H] [--margin M] [--sign winding|pseudonormal]
///   [--no-contacts] [--backend auto|gpu|cpu] [--timing]
int Proximity(int argc, char* argv[])
{
  if (argc < 4)
  {
    return Usage("proximity needs two meshes, A and B");
  }
  std::string output, contactsPath, modelA, modelB, sign = "winding", backend = "auto";
  bool timing = false, contacts = true;
  int resolution = 64;
  double spacing = 0, margin = 0;
  for (int a = 4; a < argc; ++a)
  {
    const std::string option = argv[a];
    const bool valued = a + 1 < argc;
    if (option == "--timing")
    {
      timing = true;
    }
    else if (option == "--no-contacts")
    {
      contacts = false;
    }
    else if (option == "-o" && valued)
    {
      output = argv[++a];
    }
    else if (option == "--contacts" && valued)
    {
      contactsPath = argv[++a];
    }
    else if (option == "--models" && a + 2 < argc)
    {
      modelA = argv[++a];
      modelB = argv[++a];
    }
    else if (option == "--resolution" && valued)
    {
      resolution = ParseInt("--resolution", argv[++a]);
    }
    else if (option == "--spacing" && valued)
    {
      spacing = ParseNumber("--spacing", argv[++a]);
    }
    else if (option == "--margin" && valued)
    {
      margin = ParseNumber("--margin", argv[++a]);
    }
    else if (option == "--sign" && valued)
    {
      sign = argv[++a];
      EnumWord("--sign", sign, vtkdf::enums::ProximitySign);
    }
    else if (option == "--backend" && valued)
    {
      backend = argv[++a];
      EnumWord("--backend", backend, vtkdf::enums::Backend);
    }
    else
    {
      const bool known = option == "-o" || option == "--contacts" || option == "--models" ||
        option == "--resolution" || option == "--spacing" || option == "--margin" ||
        option == "--sign" || option == "--backend";
      return Usage((option + (known ? " needs a value" : ": unknown option")).c_str());
    }
  }
  if (output.empty())
  {
    return Usage("proximity needs -o OUT.vtp");
  }
  vtkNew<vtkDistanceFieldProximity> filter;
  filter->SetModelAData(ReadMeshOrExit(argv[2]));
  filter->SetModelBData(ReadMeshOrExit(argv[3]));
  filter->SetResolution(resolution);
  filter->SetSpacing(spacing);
  filter->SetContactMargin(margin);
  filter->SetContactPoints(contacts);
  filter->SetBackend(EnumWord("--backend", backend, vtkdf::enums::Backend));
  filter->SetSignMode(EnumWord("--sign", sign, vtkdf::enums::ProximitySign));
  filter->Update();
  vtkPolyData* answers = filter->GetOutput(0);
  if (filter->GetErrorCode() || !answers->GetFieldData()->GetArray("Colliding"))
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  std::printf("vtkdf: proximity colliding=%d separation_distance=%.17g "
              "max_penetration_ab=%.17g max_penetration_ba=%.17g contacts=%lld\n",
    filter->GetLastColliding() ? 1 : 0,
    filter->GetLastSeparationDistance(),
    filter->GetLastPenetrationAB(),
    filter->GetLastPenetrationBA(),
    static_cast<long long>(filter->GetOutput(1)->GetNumberOfPoints()));
  if (timing)
  {
    std::printf("vtkdf: proximity backend=%s step=%.9g point_queries=%lld bytes_to_gpu=%lld "
                "bytes_from_gpu=%lld time_s=%.6f\n",
      filter->GetLastBackend(),
      filter->GetLastStep(),
      static_cast<long long>(filter->GetLastPointQueries()),
      static_cast<long long>(filter->GetLastBytesToDevice()),
      static_cast<long long>(filter->GetLastBytesFromDevice()),
      filter->GetLastSeconds());
  }
  bool written = WriteXML<vtkXMLPolyDataWriter>(answers, output);
  if (!contactsPath.empty())
  {
    written = WriteXML<vtkXMLPolyDataWriter>(filter->GetOutput(1), contactsPath) && written;
  }
  if (!modelA.empty())
  {
    written = WriteXML<vtkXMLPolyDataWriter>(filter->GetOutput(2), modelA) && written;
    written = WriteXML<vtkXMLPolyDataWriter>(filter->GetOutput(3), modelB) && written;
  }
  return written ? 0 : 1;
}

} // namespace vtkdf::cli
