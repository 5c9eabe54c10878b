#include "Options.h"

#include "Files.h"
#include "vtkDistanceFieldAlgorithm.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkImageData.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace vtkdf::cli
{

void PrintUsage(FILE* out)
{
  // The enumerations' words come from their tables (vtkDistanceFieldEnums.h), which the
  // options are parsed with too.
  std::string text =
    "usage: vtkdf linfac MESH -o OUT.vti [grid] [--signed] [--sign {linfac-sign}]\n"
    "             [--backend {backend}] [--domains {domains}]\n"
    "             [--route {route}]\n"
    "             [--arrays distance,cellid,feature,point,winding,barycentric,gradient]\n"
    "             [--max-distance D | --band K] [--png SLICE.png] [--timing]\n"
    "       vtkdf linfac MESH -o OUT.vtpd --band K [grid] [--signed]\n"
    "             [--sign {linfac-sign}] [--domains {domains}] [--brick-size N]\n"
    "             [--sides SIDES.vti]\n"
    "             [--arrays distance,cellid,feature,point] [--timing]\n"
    "             (the exact field within K spacings of the mesh, in bricks of N\n"
    "             samples: only those the band touches; SIDES: a cell per brick)\n"
    "       vtkdf voxelize MESH -o OUT.vti [--mode {mode}] [grid]\n"
    "             [--backend {backend}] [--timing]\n"
    "       vtkdf chamfer INPUT -o OUT.vti [--metric {metric}]\n"
    "             [--layers M] [--signed] [grid] [--backend {backend}] [--timing]\n"
    "       vtkdf medial INPUT -o OUT.vti [--angle THETA] [--region {region}]\n"
    "             [--sign {medial-sign}] [grid] [--backend {backend}]\n"
    "             [--points OUT.vtp] [--png SLICE.png] [--timing]\n"
    "       vtkdf segment MESH -o OUT.vti [grid] [--delta D] [--region-offset D]\n"
    "             [--uncut] [--backend {backend}] [--surface OUT.vtp [--feature-angle A]\n"
    "             [--paper-vertices]] [--png SLICE.png] [--timing]\n"
    "       vtkdf blend A.vti B.vti -t T -o OUT.vti [--png SLICE.png]\n"
    "             (A and B from vtkdf segment on the same grid; T in [0, 1])\n"
    "       vtkdf union POLYTOPES -o OUT.vtp [--query X Y Z | --queries POINTS]\n"
    "             [--piece-array NAME] [--convex-hulls] [--backend {backend}] [--timing]\n"
    "             (POLYTOPES: a mesh whose connected components are convex pieces, or a\n"
    "             .vtm of them; POINTS: a mesh whose points are the queries)\n"
    "       vtkdf pd P Q -o OUT.vtp [--piece-array NAME] [--convex-hulls]\n"
    "             [--backend {backend}] [--timing]\n"
    "             (penetration depth of two solids, each convex pieces as for union;\n"
    "             prints the depth and the direction to translate Q)\n"
    "       vtkdf proximity A B -o OUT.vtp [--contacts OUT.vtp] [--models A.vtp B.vtp]\n"
    "             [--resolution N | --spacing H] [--margin M] [--sign {proximity-sign}]\n"
    "             [--no-contacts] [--backend ...] [--timing]\n"
    "             (collision, separation, penetration and contacts of two meshes)\n"
    "       vtkdf probe MESH POINTS -o OUT [--signed] [--sign {linfac-sign}]\n"
    "             [--max-distance D] [--winding] [--timing]\n"
    "             (exact distance at POINTS: a mesh, .vtu .vti .vts .vtr, or .csv/.npy of\n"
    "             xyz; OUT the points' type (.vtp .vtu ...) or .npy of the distances;\n"
    "             --signed alone: by the winding number)\n"
    "       vtkdf hausdorff A B -o A_OUT.vtp [--output-b B_OUT.vtp]\n"
    "             [--relative-error E] [--timing]\n"
    "             (the Hausdorff distance of two meshes, certified within E times the\n"
    "             diagonal; each point's distance to the other mesh in the outputs)\n"
    "       vtkdf clip MESH DATASET -o OUT.vtu [--value V] [--sign {linfac-sign}]\n"
    "             [--outside] [--timing]\n"
    "             (DATASET, any .vtu .vti .vts .vtr or mesh, cut where the distance to\n"
    "             MESH crosses V, by default the winding-signed distance: the inside)\n"
    "       vtkdf render FIELD.vti -o IMAGE.png [--mode surface|composite] [--size W H]\n"
    "             [--azimuth A] [--elevation E] [--slices N] [--opacity O]\n"
    "             [--interpolation region-aware|nearest|linear] [--timing]\n"
    "             (needs an X server: xvfb-run -a vtkdf render ...)\n"
    "grid:  [--resolution N] [--padding F]\n"
    "       [--origin X Y Z --spacing SX SY SZ --dims NX NY NZ]\n"
    "MESH:  .vtp .vtk .ply .stl .obj; chamfer's INPUT may also be a .vti with a Boundary mask,\n"
    "       medial's a .vti with Distance and ClosestPoint (vtkdf linfac --signed --arrays\n"
    "       distance,point)\n"
    "       vtkdf --help: this text\n";
  const std::pair<const char*, const vtkdf::EnumTable*> words[] = {
    { "{backend}", &vtkdf::enums::Backend },
    { "{linfac-sign}", &vtkdf::enums::LinearFactorSign },
    { "{domains}", &vtkdf::enums::DomainShape },
    { "{route}", &vtkdf::enums::Route },
    { "{mode}", &vtkdf::enums::VoxelMode },
    { "{metric}", &vtkdf::enums::Metric },
    { "{region}", &vtkdf::enums::MedialRegion },
    { "{medial-sign}", &vtkdf::enums::MedialSign },
    { "{proximity-sign}", &vtkdf::enums::ProximitySign },
  };
  for (const auto& [token, table] : words)
  {
    for (size_t at = text.find(token); at != std::string::npos; at = text.find(token, at))
    {
      text.replace(at, std::strlen(token), table->Words());
    }
  }
  std::fputs(text.c_str(), out);
}

int EnumWord(const char* option, const std::string& word, const vtkdf::EnumTable& table)
{
  int value = 0;
  if (!table.FromWord(word, value))
  {
    std::exit(Usage((std::string(option) + " takes " + table.WordList()).c_str()));
  }
  return value;
}

/// A usage error: the message and the usage on stderr; the exit status 2.
int Usage(const char* message)
{
  if (message)
  {
    std::fprintf(stderr, "vtkdf: %s\n", message);
  }
  PrintUsage(stderr);
  return 2;
}

bool EndsWith(const std::string& s, const char* suffix)
{
  const size_t n = std::strlen(suffix);
  if (s.size() < n)
  {
    return false;
  }
  std::string tail = s.substr(s.size() - n);
  std::transform(tail.begin(), tail.end(), tail.begin(), ::tolower);
  return tail == suffix;
}

Option Flag(const char* name, bool& target)
{
  return { name, true, [&target](const char*) { target = true; } };
}
Option Text(const char* name, std::string& target)
{
  return { name, false, [&target](const char* value) { target = value; } };
}
/// The whole of `text` as a number (strtod: decimal, exponent, "nan", "inf"); exits with
/// a usage error naming `option` otherwise. Range checks are the filters' (they name the
/// property), except what cannot be passed on at all.
double ParseNumber(const char* option, const char* text)
{
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || errno == ERANGE)
  {
    std::exit(Usage((std::string(option) + " takes a number, not '" + text + "'").c_str()));
  }
  return value;
}

/// The whole of `text` as an int (decimal); exits with a usage error naming `option`
/// when it is not one or does not fit in an int (no wrapping: 4294967312 is not 16).
int ParseInt(const char* option, const char* text)
{
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || value < INT_MIN || value > INT_MAX)
  {
    std::exit(Usage((std::string(option) + " takes an integer, not '" + text + "'").c_str()));
  }
  return static_cast<int>(value);
}

Option Number(const char* name, double& target)
{
  return { name, false, [name, &target](const char* value) { target = ParseNumber(name, value); } };
}
Option Count(const char* name, int& target)
{
  return { name, false, [name, &target](const char* value) { target = ParseInt(name, value); } };
}

/// Parses the options of argv[3...] (after `vtkdf SUBCOMMAND INPUT`): the common ones,
/// then the subcommand's `own`. Exits on a usage error.
void ParseOptions(int argc, char* argv[], CommonOptions& common, const std::vector<Option>& own)
{
  for (int a = 3; a < argc; ++a)
  {
    const std::string arg = argv[a];
    auto next = [&]() -> const char*
    {
      if (a + 1 >= argc)
      {
        std::exit(Usage((arg + " needs a value").c_str()));
      }
      return argv[++a];
    };
    if (arg == "-o" || arg == "--output")
    {
      common.Output = next();
    }
    else if (arg == "--resolution")
    {
      common.Resolution = ParseInt("--resolution", next());
    }
    else if (arg == "--padding")
    {
      common.Padding = ParseNumber("--padding", next());
    }
    else if (arg == "--origin" || arg == "--spacing")
    {
      double* v = arg == "--origin" ? common.Origin : common.Spacing;
      for (int k = 0; k < 3; ++k)
      {
        v[k] = ParseNumber(arg.c_str(), next());
      }
      (arg == "--origin" ? common.ExplicitOrigin : common.ExplicitSpacing) = true;
    }
    else if (arg == "--dims")
    {
      for (int k = 0; k < 3; ++k)
      {
        common.Dims[k] = ParseInt("--dims", next());
      }
      common.ExplicitDims = true;
    }
    else if (arg == "--backend")
    {
      common.Backend = next();
    }
    else if (arg == "--timing")
    {
      common.Timing = true;
    }
    else
    {
      auto option =
        std::find_if(own.begin(), own.end(), [&](const Option& o) { return arg == o.Name; });
      if (option == own.end())
      {
        std::exit(Usage(("unknown option " + arg).c_str()));
      }
      option->Set(option->IsFlag ? nullptr : next());
    }
  }
  if (common.Output.empty())
  {
    std::exit(Usage("-o OUT.vti is required"));
  }
  const bool any = common.ExplicitOrigin || common.ExplicitSpacing || common.ExplicitDims;
  const bool all = common.ExplicitOrigin && common.ExplicitSpacing && common.ExplicitDims;
  if (any && !all)
  {
    std::exit(Usage("an explicit grid needs --origin, --spacing and --dims together"));
  }
}

/// Grid and backend options onto a filter.
void Configure(vtkDistanceFieldAlgorithm* filter, CommonOptions& common)
{
  filter->SetResolution(common.Resolution);
  filter->SetPadding(common.Padding);
  if (common.ExplicitDims)
  {
    filter->ExplicitGridOn();
    filter->SetGridOrigin(common.Origin);
    filter->SetGridSpacing(common.Spacing);
    filter->SetGridDimensions(common.Dims);
  }
  filter->SetBackend(EnumWord("--backend", common.Backend, vtkdf::enums::Backend));
}

/// Runs the filter (once: a second Update() of a failed filter runs it again and prints
/// every error twice); prints the timing line, with `extra()` after the time; writes the
/// output. Returns the exit code.
/// Runs `filter`, prints its timing line (with `extra`), runs `then` (what depends on
/// the field: false stops before any file is written) and writes the field.
int Finish(const char* subcommand,
  vtkDistanceFieldAlgorithm* filter,
  const CommonOptions& common,
  const std::function<std::string()>& extra,
  const std::function<bool()>& then)
{
  filter->Update();
  vtkImageData* field = filter->GetOutput();
  if (filter->GetErrorCode() || field->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  int dims[3];
  field->GetDimensions(dims);
  if (common.Timing)
  {
    std::printf("vtkdf: %s dims=%dx%dx%d backend=%s renderer=\"%s\" time_s=%.6f%s stages=%s "
                "peak_memory_mb=%.1f\n",
      subcommand,
      dims[0],
      dims[1],
      dims[2],
      filter->GetLastBackend(),
      filter->GetLastRenderer(),
      filter->GetLastTime(),
      extra ? extra().c_str() : "",
      filter->GetLastStageTimes(),
      filter->GetLastPeakMemory());
  }
  if ((then && !then()) || !WriteXML<vtkXMLImageDataWriter>(field, common.Output))
  {
    return 1;
  }
  return 0;
}

} // namespace vtkdf::cli
