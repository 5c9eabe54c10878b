// vtkdf: the command-line front end of VTK Distance Fields.
//
//   vtkdf linfac MESH -o OUT.vti [grid] [--signed] [--sign pseudonormal|winding]
//         [--backend auto|gpu|cpu] [--culling auto|nonmanifold|manifold]
//         [--arrays distance,cellid,feature,point,winding]
//         [--max-distance D] [--png SLICE.png] [--timing]
//   vtkdf voxelize MESH -o OUT.vti [--mode boundary|solid|both] [grid] [--backend ...]
//         [--timing]
//   vtkdf chamfer INPUT -o OUT.vti [--metric manhattan|chessboard18|chessboard26]
//         [--layers M] [--signed] [grid] [--backend ...] [--timing]
//   vtkdf medial INPUT -o OUT.vti [--angle THETA] [--region inside|outside|both]
//         [--sign pseudonormal|winding] [grid]
//         [--backend ...] [--points OUT.vtp] [--png SLICE.png] [--timing]
//   vtkdf segment MESH -o OUT.vti [grid] [--delta D] [--region-offset D] [--uncut]
//         [--surface OUT.vtp] [--feature-angle A] [--paper-vertices]
//   vtkdf blend A.vti B.vti -t T -o OUT.vti [--png SLICE.png]
//   vtkdf union POLYTOPES -o OUT.vtp [--query X Y Z | --queries POINTS] [--piece-array NAME]
//         [--convex-hulls] [--backend ...] [--pixels N] [--uncertified] [--timing]
//   vtkdf pd P Q -o OUT.vtp [--piece-array NAME] [--convex-hulls] [--backend ...]
//         [--pixels N] [--uncertified] [--timing]
//         (penetration depth; P, Q: convex pieces in the forms union takes)
//   vtkdf render FIELD.vti -o IMAGE.png [--mode surface|composite] [--size W H] ...
//         (vtkSegmentedDistanceVolumeMapper; needs an X server)
//
// grid: [--resolution N] [--padding F] [--origin X Y Z --spacing SX SY SZ --dims NX NY NZ]
// MESH: .vtp .vtk .ply .stl .obj; chamfer's INPUT may also be a .vti with a Boundary mask
// (and optionally Solid), e.g. the output of vtkdf voxelize. --timing prints one line
// that scripts can read:
//   vtkdf: linfac dims=NXxNYxNZ backend=cpu renderer="cpu" time_s=0.123 ...
#include "vtkChamferVoxelDistance.h"
#include "vtkDistanceFieldBlend.h"
#include "vtkLinearFactorDistanceField.h"
#include "vtkMedialAxisFilter.h"
#include "vtkPenetrationDepth.h"
#include "vtkPolyDataVoxelizer.h"
#include "vtkSegmentedDistanceContour.h"
#include "vtkSegmentedDistanceField.h"
#include "vtkSegmentedDistanceVolumeMapper.h"
#include "vtkUnionClosestPoint.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCompositeDataSet.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataReader.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLMultiBlockDataReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace
{
void PrintUsage(FILE* out)
{
  std::fprintf(out,
    "usage: vtkdf linfac MESH -o OUT.vti [grid] [--signed] [--sign pseudonormal|winding]\n"
    "             [--backend auto|gpu|cpu] [--culling auto|nonmanifold|manifold]\n"
    "             [--arrays distance,cellid,feature,point,winding] [--max-distance D]\n"
    "             [--png SLICE.png] [--timing]\n"
    "       vtkdf voxelize MESH -o OUT.vti [--mode boundary|solid|both] [grid]\n"
    "             [--backend auto|gpu|cpu] [--timing]\n"
    "       vtkdf chamfer INPUT -o OUT.vti [--metric manhattan|chessboard18|chessboard26]\n"
    "             [--layers M] [--signed] [grid] [--backend auto|gpu|cpu] [--timing]\n"
    "       vtkdf medial INPUT -o OUT.vti [--angle THETA] [--region inside|outside|both]\n"
    "             [--sign pseudonormal|winding] [grid] [--backend auto|gpu|cpu]\n"
    "             [--points OUT.vtp] [--png SLICE.png] [--timing]\n"
    "       vtkdf segment MESH -o OUT.vti [grid] [--delta D] [--region-offset D]\n"
    "             [--uncut] [--backend auto|gpu|cpu] [--surface OUT.vtp [--feature-angle A]\n"
    "             [--paper-vertices]] [--png SLICE.png] [--timing]\n"
    "       vtkdf blend A.vti B.vti -t T -o OUT.vti [--png SLICE.png]\n"
    "             (A and B from vtkdf segment on the same grid; T in [0, 1])\n"
    "       vtkdf union POLYTOPES -o OUT.vtp [--query X Y Z | --queries POINTS]\n"
    "             [--piece-array NAME] [--convex-hulls] [--backend auto|gpu|cpu]\n"
    "             [--pixels N] [--uncertified] [--timing]\n"
    "             (POLYTOPES: a mesh whose connected components are convex pieces, or a\n"
    "             .vtm of them; POINTS: a mesh whose points are the queries)\n"
    "       vtkdf pd P Q -o OUT.vtp [--piece-array NAME] [--convex-hulls]\n"
    "             [--backend auto|gpu|cpu] [--pixels N] [--uncertified] [--timing]\n"
    "             (penetration depth of two solids, each convex pieces as for union;\n"
    "             prints the depth and the direction to translate Q)\n"
    "       vtkdf render FIELD.vti -o IMAGE.png [--mode surface|composite] [--size W H]\n"
    "             [--azimuth A] [--elevation E] [--slices N] [--opacity O]\n"
    "             [--interpolation region-aware|nearest|linear] [--timing]\n"
    "             (needs an X server: xvfb-run -a vtkdf render ...)\n"
    "grid:  [--resolution N] [--padding F]\n"
    "       [--origin X Y Z --spacing SX SY SZ --dims NX NY NZ]\n"
    "MESH:  .vtp .vtk .ply .stl .obj; chamfer's INPUT may also be a .vti with a Boundary mask,\n"
    "       medial's a .vti with Distance and ClosestPoint (vtkdf linfac --signed --arrays\n"
    "       distance,point)\n"
    "       vtkdf --help: this text\n");
}

/// A usage error: the message and the usage on stderr; the exit status 2.
int Usage(const char* message = nullptr)
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

/// An RGB image of w x h pixels to paint a slice on.
vtkSmartPointer<vtkImageData> Canvas(int w, int h)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  return image;
}

/// Writes an RGB image as PNG; false when the file cannot be written.
bool WritePNG(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->Write();
  return writer->GetErrorCode() == 0;
}

/// The middle z slice of Distance, coloured (blue inside, white at the surface, warm
/// outside) with black isolines, magnified to at least 512 pixels, written as PNG.
bool WriteSlicePNG(vtkImageData* field, const std::string& path)
{
  vtkFloatArray* distance =
    vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("Distance"));
  if (!distance)
  {
    return false;
  }
  int dims[3];
  field->GetDimensions(dims);
  const int k = dims[2] / 2;
  auto at = [&](int i, int j)
  { return distance->GetValue(i + dims[0] * (j + int64_t(dims[1]) * k)); };
  float largest = 0;
  for (int j = 0; j < dims[1]; ++j)
  {
    for (int i = 0; i < dims[0]; ++i)
    {
      largest = std::max(largest, std::fabs(at(i, j)));
    }
  }
  largest = largest > 0 ? largest : 1;
  const float step = largest / 12;
  const int scale = std::max(1, 512 / std::max(dims[0], dims[1]));
  const int w = (dims[0] - 1) * scale + 1, h = (dims[1] - 1) * scale + 1;
  std::vector<float> value(size_t(w) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const double fx = double(x) / scale, fy = double(y) / scale;
      const int i = std::min(int(fx), dims[0] - 2 < 0 ? 0 : dims[0] - 2);
      const int j = std::min(int(fy), dims[1] - 2 < 0 ? 0 : dims[1] - 2);
      const double tx = dims[0] > 1 ? fx - i : 0, ty = dims[1] > 1 ? fy - j : 0;
      const int i1 = std::min(i + 1, dims[0] - 1), j1 = std::min(j + 1, dims[1] - 1);
      value[size_t(y) * w + x] =
        static_cast<float>((1 - ty) * ((1 - tx) * at(i, j) + tx * at(i1, j)) +
          ty * ((1 - tx) * at(i, j1) + tx * at(i1, j1)));
    }
  }
  vtkSmartPointer<vtkImageData> image = Canvas(w, h);
  auto* rgb = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const float v = value[size_t(y) * w + x];
      const float t = std::min(1.f, std::fabs(v) / largest);
      float c[3];
      if (v < 0)
      {
        c[0] = 1 - 0.8f * t, c[1] = 1 - 0.6f * t, c[2] = 1 - 0.1f * t;
      }
      else
      {
        c[0] = 1 - 0.1f * t, c[1] = 1 - 0.7f * t, c[2] = 1 - 0.85f * t;
      }
      const int band = static_cast<int>(std::floor(v / step));
      bool line = false;
      if (x + 1 < w)
      {
        line = line || static_cast<int>(std::floor(value[size_t(y) * w + x + 1] / step)) != band;
      }
      if (y + 1 < h)
      {
        line = line || static_cast<int>(std::floor(value[size_t(y + 1) * w + x] / step)) != band;
      }
      // The surface (zero crossing) in dark blue, the other isolines in black.
      bool surface = false;
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int xx = std::min(std::max(x + dx, 0), w - 1),
                    yy = std::min(std::max(y + dy, 0), h - 1);
          surface = surface || ((value[size_t(yy) * w + xx] < 0) != (v < 0));
        }
      }
      const unsigned char surfaceColour[3] = { 20, 20, 160 };
      for (int ch = 0; ch < 3; ++ch)
      {
        rgb[3 * (size_t(y) * w + x) + ch] = surface ? surfaceColour[ch]
          : line                                    ? 0
                                                    : static_cast<unsigned char>(255 * c[ch]);
      }
    }
  }
  return WritePNG(image, path);
}
/// The options every subcommand shares: output, grid, backend, timing.
struct CommonOptions
{
  std::string Output, Backend = "auto";
  int Resolution = 64;
  double Padding = 0.1;
  double Origin[3], Spacing[3];
  int Dims[3];
  bool ExplicitOrigin = false, ExplicitSpacing = false, ExplicitDims = false;
  bool Timing = false;
};

/// A subcommand's own option: its name, and what to do with its value (`Flag` options
/// take none, and get nullptr).
struct Option
{
  const char* Name;
  bool IsFlag;
  std::function<void(const char*)> Set;
};
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
  if (common.Backend == "gpu")
  {
    filter->SetBackendToGPU();
  }
  else if (common.Backend == "cpu")
  {
    filter->SetBackendToCPU();
  }
  else if (common.Backend != "auto")
  {
    std::exit(Usage("--backend takes auto, gpu or cpu"));
  }
}

/// Runs the filter (once: a second Update() of a failed filter runs it again and prints
/// every error twice); prints the timing line, with `extra()` after the time; writes the
/// output. Returns the exit code.
/// Runs `filter`, prints its timing line (with `extra`), runs `then` (what depends on
/// the field: false stops before any file is written) and writes the field.
int Finish(const char* subcommand,
  vtkDistanceFieldAlgorithm* filter,
  const CommonOptions& common,
  const std::function<std::string()>& extra = std::function<std::string()>(),
  const std::function<bool()>& then = std::function<bool()>())
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
    std::printf("vtkdf: %s dims=%dx%dx%d backend=%s renderer=\"%s\" time_s=%.6f%s stages=%s\n",
      subcommand,
      dims[0],
      dims[1],
      dims[2],
      filter->GetLastBackend(),
      filter->GetLastRenderer(),
      filter->GetLastTime(),
      extra ? extra().c_str() : "",
      filter->GetLastStageTimes());
  }
  if ((then && !then()) || !WriteXML<vtkXMLImageDataWriter>(field, common.Output))
  {
    return 1;
  }
  return 0;
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

int Linfac(int argc, char* argv[])
{
  CommonOptions common;
  std::string png, arrays = "distance,cellid", culling = "auto", sign;
  double maxDistance = 0;
  bool signedField = false;
  ParseOptions(argc,
    argv,
    common,
    { Flag("--signed", signedField),
      Text("--sign", sign),
      Text("--culling", culling),
      Text("--arrays", arrays),
      Number("--max-distance", maxDistance),
      Text("--png", png) });
  vtkNew<vtkLinearFactorDistanceField> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  Configure(filter, common);
  if (culling == "nonmanifold")
  {
    filter->SetCullingToNonManifold();
  }
  else if (culling == "manifold")
  {
    filter->SetCullingToManifold();
  }
  else if (culling != "auto")
  {
    return Usage("--culling takes auto, nonmanifold or manifold");
  }
  // --sign implies --signed; --signed alone is the pseudonormal sign.
  if (sign == "winding")
  {
    filter->SetSignModeToWindingNumber();
  }
  else if (sign == "pseudonormal" || (sign.empty() && signedField))
  {
    filter->SetSignModeToPseudoNormal();
  }
  else if (!sign.empty())
  {
    return Usage("--sign takes pseudonormal or winding");
  }
  filter->SetComputeWindingNumber(arrays.find("winding") != std::string::npos);
  filter->SetMaximumDistance(maxDistance);
  filter->SetComputeDistance(arrays.find("distance") != std::string::npos);
  filter->SetComputeClosestCellId(arrays.find("cellid") != std::string::npos);
  filter->SetComputeClosestFeature(arrays.find("feature") != std::string::npos);
  filter->SetComputeClosestPoint(arrays.find("point") != std::string::npos);
  const int code = Finish("linfac",
    filter,
    common,
    [&]()
    {
      char extra[64];
      std::snprintf(extra, sizeof(extra), " culling_factor=%.3f", filter->GetLastCullingFactor());
      if (filter->GetSignMode() == vtkLinearFactorDistanceField::WINDING_NUMBER)
      {
        char blocks[96];
        std::snprintf(blocks,
          sizeof(blocks),
          " winding_block_samples=%lld winding_exact_samples=%lld",
          static_cast<long long>(filter->GetLastWindingBlockSamples()),
          static_cast<long long>(filter->GetLastWindingExactSamples()));
        return std::string(extra) + blocks;
      }
      return std::string(extra);
    });
  if (code == 0 && !png.empty() && !WriteSlicePNG(filter->GetOutput(), png))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s (it needs the distance array)\n", png.c_str());
    return 1;
  }
  return code;
}

int Voxelize(int argc, char* argv[])
{
  CommonOptions common;
  std::string mode = "both";
  ParseOptions(argc, argv, common, { Text("--mode", mode) });
  vtkNew<vtkPolyDataVoxelizer> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  Configure(filter, common);
  if (mode == "boundary")
  {
    filter->SetModeToBoundary();
  }
  else if (mode == "solid")
  {
    filter->SetModeToSolid();
  }
  else if (mode != "both")
  {
    return Usage("--mode takes boundary, solid or both");
  }
  return Finish("voxelize", filter, common);
}

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
  if (metric == "manhattan")
  {
    filter->SetMetricToManhattan();
  }
  else if (metric == "chessboard26")
  {
    filter->SetMetricToChessboard26();
  }
  else if (metric != "chessboard18")
  {
    return Usage("--metric takes manhattan, chessboard18 or chessboard26");
  }
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
/// The middle z slice: |distance| in grey levels, medial voxels in red, magnified.
bool WriteMedialPNG(vtkImageData* field, const std::string& path)
{
  auto* medial = vtkUnsignedCharArray::SafeDownCast(field->GetPointData()->GetArray("Medial"));
  auto* radius = vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("Radius"));
  if (!medial || !radius)
  {
    return false;
  }
  int dims[3];
  field->GetDimensions(dims);
  const int k = dims[2] / 2;
  const int scale = std::max(1, 512 / std::max(dims[0], dims[1]));
  const double largest = std::max(1e-30, double(radius->GetRange()[1]));
  vtkSmartPointer<vtkImageData> image = Canvas(dims[0] * scale, dims[1] * scale);
  auto* rgb = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < dims[1] * scale; ++y)
  {
    for (int x = 0; x < dims[0] * scale; ++x)
    {
      const vtkIdType v = x / scale + dims[0] * (y / scale + vtkIdType(dims[1]) * k);
      const unsigned char grey =
        static_cast<unsigned char>(255 - 200 * radius->GetValue(v) / largest);
      unsigned char* pixel = rgb + 3 * (size_t(y) * dims[0] * scale + x);
      pixel[0] = medial->GetValue(v) ? 220 : grey;
      pixel[1] = medial->GetValue(v) ? 20 : grey;
      pixel[2] = medial->GetValue(v) ? 20 : grey;
    }
  }
  return WritePNG(image, path);
}

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
  if (region == "outside")
  {
    filter->SetRegionToOutside();
  }
  else if (region == "both")
  {
    filter->SetRegionToBoth();
  }
  else if (region != "inside")
  {
    return Usage("--region takes inside, outside or both");
  }
  if (sign == "winding")
  {
    filter->SetSignModeToWindingNumber();
  }
  else if (sign != "pseudonormal")
  {
    return Usage("--sign takes pseudonormal or winding");
  }
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
/// The middle z slice of a segmented field: each region in its own hue, lighter away
/// from the surface (up to Delta), black where two regions meet across an interface
/// (adjacent samples whose distances sum to less than their spacing), magnified.
bool WriteRegionPNG(vtkImageData* field, double delta, const std::string& path)
{
  auto* region = vtkIntArray::SafeDownCast(field->GetPointData()->GetArray("RegionIndex"));
  auto* distance = vtkFloatArray::SafeDownCast(field->GetPointData()->GetArray("Distance"));
  if (!region || !distance)
  {
    return false;
  }
  int dims[3];
  double spacing[3];
  field->GetDimensions(dims);
  field->GetSpacing(spacing);
  const int k = dims[2] / 2;
  const int scale = std::max(1, 512 / std::max(dims[0], dims[1]));
  auto at = [&](int i, int j) { return i + dims[0] * (j + vtkIdType(dims[1]) * k); };
  vtkSmartPointer<vtkImageData> image = Canvas(dims[0] * scale, dims[1] * scale);
  auto* rgb = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < dims[1] * scale; ++y)
  {
    for (int x = 0; x < dims[0] * scale; ++x)
    {
      const int i = x / scale, j = y / scale;
      const vtkIdType v = at(i, j);
      bool interface = false;
      if (i + 1 < dims[0] && x % scale == scale - 1)
      {
        const vtkIdType w = at(i + 1, j);
        interface = region->GetValue(v) != region->GetValue(w) &&
          distance->GetValue(v) + distance->GetValue(w) <= spacing[0] * (1 + 1e-5);
      }
      if (j + 1 < dims[1] && y % scale == scale - 1)
      {
        const vtkIdType w = at(i, j + 1);
        interface = interface ||
          (region->GetValue(v) != region->GetValue(w) &&
            distance->GetValue(v) + distance->GetValue(w) <= spacing[1] * (1 + 1e-5));
      }
      // Hues by the golden angle, so that neighbouring indices differ.
      const double hue = std::fmod(0.618034 * std::max(0, region->GetValue(v)), 1.0) * 6;
      const double light = 0.45 + 0.5 * std::min(1.0, distance->GetValue(v) / delta);
      double c[3] = { std::fabs(hue - 3) - 1, 2 - std::fabs(hue - 2), 2 - std::fabs(hue - 4) };
      unsigned char* pixel = rgb + 3 * (size_t(y) * dims[0] * scale + x);
      for (int ch = 0; ch < 3; ++ch)
      {
        c[ch] = std::min(1.0, std::max(0.0, c[ch]));
        pixel[ch] = interface ? 0 : static_cast<unsigned char>(255 * (0.35 * c[ch] + 0.65) * light);
      }
    }
  }
  return WritePNG(image, path);
}

int Segment(int argc, char* argv[])
{
  CommonOptions common;
  std::string png, surface;
  double delta = 0, offset = 0, featureAngle = 30;
  bool paperVertices = false, uncut = false;
  ParseOptions(argc,
    argv,
    common,
    { Number("--delta", delta),
      Number("--region-offset", offset),
      Flag("--uncut", uncut),
      Text("--png", png),
      Text("--surface", surface),
      Number("--feature-angle", featureAngle),
      Flag("--paper-vertices", paperVertices) });
  vtkNew<vtkSegmentedDistanceField> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  Configure(filter, common);
  filter->SetDelta(delta);
  filter->SetRegionOffset(offset);
  filter->SetCutSelfIntersections(!uncut);
  // The surface, before any file is written: its errors (a FeatureAngle out of range)
  // leave no output behind.
  auto polygonize = [&]()
  {
    if (surface.empty())
    {
      return true;
    }
    vtkNew<vtkSegmentedDistanceContour> contour;
    contour->SetInputData(filter->GetOutput());
    contour->SetFeatureAngle(featureAngle);
    contour->SetUseClosestPoints(!paperVertices);
    const auto start = std::chrono::steady_clock::now();
    contour->Update();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (contour->GetErrorCode() || !WriteXML<vtkXMLPolyDataWriter>(contour->GetOutput(), surface))
    {
      return false;
    }
    if (common.Timing)
    {
      std::printf("vtkdf: surface time_s=%g triangles=%lld marching_cells=%lld "
                  "feature_cells=%lld other_cells=%lld\n",
        seconds,
        static_cast<long long>(contour->GetOutput()->GetNumberOfCells()),
        static_cast<long long>(contour->GetLastMarchingCells()),
        static_cast<long long>(contour->GetLastFeatureCells()),
        static_cast<long long>(contour->GetLastOtherCells()));
    }
    return true;
  };
  int code = Finish(
    "segment",
    filter,
    common,
    [&]()
    {
      return " regions=" + std::to_string(filter->GetLastRegionCount()) +
        " patches=" + std::to_string(filter->GetLastPatchCount()) +
        " crossed_triangles=" + std::to_string(filter->GetLastCrossedTriangles()) +
        " refused_merges=" + std::to_string(filter->GetLastRefusedMerges());
    },
    polygonize);
  vtkDataArray* usedDelta = filter->GetOutput()->GetFieldData()->GetArray("Delta");
  if (code == 0 && !png.empty() &&
    !(usedDelta && WriteRegionPNG(filter->GetOutput(), usedDelta->GetTuple1(0), png)))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", png.c_str());
    code = 1;
  }
  return code;
}
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
/// The options vtkdf union and vtkdf pd share: the output, the pieces, where the union
/// query runs, --timing.
struct QueryOptions
{
  std::string Output, PieceArray;
  bool Timing = false, Hulls = false;
  std::string Backend = "auto";
  int Pixels = 256;
  bool Uncertified = false;

  /// The usage error for an option Parse did not take: a value missing, or unknown.
  static std::string Refuse(const std::string& option)
  {
    for (const char* valued :
      { "-o", "--piece-array", "--backend", "--pixels", "--query", "--queries" })
    {
      if (option == valued)
      {
        return option + (option == "--query" ? " needs three numbers" : " needs a value");
      }
    }
    return "unknown option " + option;
  }

  /// Consumes argv[a] (and its value) when it is one of these options.
  bool Parse(int argc, char* argv[], int& a)
  {
    const std::string option = argv[a];
    if (option == "--uncertified" || option == "--timing" || option == "--convex-hulls")
    {
      (option == "--uncertified" ? this->Uncertified
          : option == "--timing" ? this->Timing
                                 : this->Hulls) = true;
      return true;
    }
    if ((option == "-o" || option == "--piece-array") && a + 1 < argc)
    {
      (option == "-o" ? this->Output : this->PieceArray) = argv[++a];
      return true;
    }
    if ((option == "--backend" || option == "--pixels") && a + 1 < argc)
    {
      if (option == "--backend")
      {
        this->Backend = argv[++a];
      }
      else
      {
        this->Pixels = ParseInt("--pixels", argv[++a]);
      }
      return true;
    }
    return false;
  }

  template<typename Filter>
  void Apply(Filter* filter) const
  {
    if (this->Backend == "gpu")
    {
      filter->SetBackendToGPU();
    }
    else if (this->Backend == "cpu")
    {
      filter->SetBackendToCPU();
    }
    else if (this->Backend != "auto")
    {
      std::exit(Usage("--backend takes auto, gpu or cpu"));
    }
    filter->SetViewResolution(this->Pixels);
    filter->SetCertify(!this->Uncertified);
    filter->SetPieceArray(this->PieceArray.c_str());
    filter->SetUseConvexHulls(this->Hulls);
  }
};

/// vtkdf union POLYTOPES -o OUT.vtp [--query X Y Z | --queries POINTS]
///   [--piece-array NAME] [--convex-hulls] [--timing]
int Union(int argc, char* argv[])
{
  std::string queriesPath;
  double query[3] = { 0, 0, 0 };
  QueryOptions where;
  for (int a = 3; a < argc; ++a)
  {
    const std::string option = argv[a];
    if (where.Parse(argc, argv, a))
    {
      continue;
    }
    if (option == "--query" && a + 3 < argc)
    {
      for (int c = 0; c < 3; ++c)
      {
        query[c] = ParseNumber("--query", argv[++a]);
      }
      continue;
    }
    if (option == "--queries" && a + 1 < argc)
    {
      queriesPath = argv[++a];
      continue;
    }
    return Usage(QueryOptions::Refuse(option).c_str());
  }
  if (where.Output.empty())
  {
    return Usage("union needs -o OUT.vtp");
  }
  vtkNew<vtkUnionClosestPoint> filter;
  filter->SetInputData(0, ReadPolytopesOrExit(argv[2]));
  if (!queriesPath.empty())
  {
    filter->SetQueryData(ReadMeshOrExit(queriesPath));
  }
  filter->SetQueryPoint(query);
  where.Apply(filter.Get());
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkPolyData* result = filter->GetOutput();
  if (filter->GetErrorCode() || result->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  if (where.Timing)
  {
    std::printf("vtkdf: union pieces=%d queries=%lld backend=%s renderer=\"%s\" time_s=%.6f "
                "faces_visited=%lld passes=%lld\n",
      filter->GetLastPieceCount(),
      static_cast<long long>(result->GetNumberOfPoints() / 2),
      filter->GetLastBackend() == vtkUnionClosestPoint::BACKEND_GPU ? "gpu" : "cpu",
      filter->GetLastRenderer(),
      seconds,
      static_cast<long long>(filter->GetLastFacesVisited()),
      static_cast<long long>(filter->GetLastPasses()));
  }
  return WriteXML<vtkXMLPolyDataWriter>(result, where.Output) ? 0 : 1;
}
/// vtkdf pd P Q -o OUT.vtp [--piece-array NAME] [--convex-hulls] [--timing]
int PenetrationDepth(int argc, char* argv[])
{
  if (argc < 4)
  {
    return Usage("pd needs two solids, P and Q");
  }
  QueryOptions where;
  for (int a = 4; a < argc; ++a)
  {
    const std::string option = argv[a];
    if (!where.Parse(argc, argv, a))
    {
      return Usage(QueryOptions::Refuse(option).c_str());
    }
  }
  if (where.Output.empty())
  {
    return Usage("pd needs -o OUT.vtp");
  }
  vtkNew<vtkPenetrationDepth> filter;
  filter->SetSolidPData(ReadPolytopesOrExit(argv[2]));
  filter->SetSolidQData(ReadPolytopesOrExit(argv[3]));
  where.Apply(filter.Get());
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (filter->GetErrorCode() || filter->GetOutput()->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  const double* n = filter->GetLastDirection();
  std::printf("vtkdf: pd intersecting=%d penetration_depth=%.17g separation_distance=%.17g "
              "direction=%.9f,%.9f,%.9f error_bound=%.3g\n",
    filter->GetLastIntersecting() ? 1 : 0,
    filter->GetLastPenetrationDepth(),
    filter->GetLastSeparationDistance(),
    n[0],
    n[1],
    n[2],
    filter->GetLastErrorBound());
  if (where.Timing)
  {
    std::printf("vtkdf: pd pairs=%lld pairs_kept=%lld backend=%s renderer=\"%s\" time_s=%.6f "
                "faces_visited=%lld passes=%d\n",
      static_cast<long long>(filter->GetLastPairsTotal()),
      static_cast<long long>(filter->GetLastPairsKept()),
      filter->GetLastBackend() == vtkPenetrationDepth::BACKEND_GPU ? "gpu" : "cpu",
      filter->GetLastRenderer(),
      seconds,
      static_cast<long long>(filter->GetLastFacesVisited()),
      filter->GetLastPasses());
  }
  return WriteXML<vtkXMLPolyDataWriter>(filter->GetOutput(), where.Output) ? 0 : 1;
}
/// vtkdf render FIELD.vti -o IMAGE.png [--mode surface|composite] [--size W H]
///   [--azimuth A] [--elevation E] [--slices N] [--interpolation region-aware|nearest|linear]
///   [--opacity O] [--timing]
int Render(int argc, char* argv[])
{
  std::string output, mode = "surface", interpolation = "region-aware";
  int size[2] = { 512, 512 }, slices = 0;
  double azimuth = 30, elevation = 20, opacity = 1;
  bool timing = false;
  for (int a = 3; a < argc; ++a)
  {
    const std::string option = argv[a];
    if (option == "--timing")
    {
      timing = true;
      continue;
    }
    if (option == "--size" && a + 2 < argc)
    {
      size[0] = ParseInt("--size", argv[++a]);
      size[1] = ParseInt("--size", argv[++a]);
      continue;
    }
    if (a + 1 >= argc)
    {
      return Usage((option + " needs a value").c_str());
    }
    const char* value = argv[++a];
    if (option == "-o")
    {
      output = value;
    }
    else if (option == "--mode")
    {
      mode = value;
    }
    else if (option == "--interpolation")
    {
      interpolation = value;
    }
    else if (option == "--azimuth")
    {
      azimuth = ParseNumber("--azimuth", value);
    }
    else if (option == "--elevation")
    {
      elevation = ParseNumber("--elevation", value);
    }
    else if (option == "--slices")
    {
      slices = ParseInt("--slices", value);
    }
    else if (option == "--opacity")
    {
      opacity = ParseNumber("--opacity", value);
    }
    else
    {
      return Usage(("unknown option " + option).c_str());
    }
  }
  if (output.empty() || !EndsWith(output, ".png"))
  {
    return Usage("render needs -o IMAGE.png");
  }
  if (mode != "surface" && mode != "composite")
  {
    return Usage("--mode is surface or composite");
  }
  if (interpolation != "region-aware" && interpolation != "nearest" && interpolation != "linear")
  {
    return Usage("--interpolation is region-aware, nearest or linear");
  }
  if (size[0] < 1 || size[1] < 1 || size[0] > 16384 || size[1] > 16384 || slices < 0 ||
    !(opacity >= 0 && opacity <= 1) || !std::isfinite(azimuth) || !std::isfinite(elevation))
  {
    return Usage("--size takes 1 to 16384 pixels, --slices N >= 0, --opacity 0 to 1, and the "
                 "angles finite numbers");
  }
  if (!EndsWith(argv[2], ".vti"))
  {
    return Usage("render takes a .vti field");
  }
  // Debian's VTK renders through X11 only.
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    std::fprintf(stderr,
      "vtkdf: render needs an X server and DISPLAY is not set; run it "
      "under one, e.g. xvfb-run -a vtkdf render ...\n");
    return 1;
  }
  vtkSmartPointer<vtkDataObject> data = ReadMeshOrImageOrExit(argv[2]);
  vtkImageData* field = vtkImageData::SafeDownCast(data);
  if (!field || field->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: %s holds no image data\n", argv[2]);
    return 1;
  }
  vtkNew<vtkSegmentedDistanceVolumeMapper> mapper;
  mapper->SetInputData(field);
  mapper->SetNumberOfSlices(slices);
  mapper->SetSurfaceOpacity(opacity);
  mapper->SetInterpolation(interpolation == "nearest" ? vtkSegmentedDistanceVolumeMapper::Nearest
      : interpolation == "linear"                     ? vtkSegmentedDistanceVolumeMapper::Linear
                                  : vtkSegmentedDistanceVolumeMapper::RegionAware);
  vtkNew<vtkVolumeProperty> property;
  property->ShadeOn();
  property->SetAmbient(0.2);
  property->SetDiffuse(0.75);
  property->SetSpecular(0.25);
  property->SetSpecularPower(24);
  if (mode == "composite")
  {
    // Distance shells: the surface (value 0) opaque, a halo a few voxels out, cool inside
    // and warm outside; over the scalars' range for any other data.
    mapper->SetModeToComposite();
    vtkDataArray* scalars = field->GetPointData()->GetScalars();
    if (!scalars)
    {
      std::fprintf(stderr, "vtkdf: %s has no point scalars to composite\n", argv[2]);
      return 1;
    }
    double range[2];
    scalars->GetRange(range);
    const double h =
      std::min({ field->GetSpacing()[0], field->GetSpacing()[1], field->GetSpacing()[2] });
    vtkNew<vtkColorTransferFunction> colour;
    vtkNew<vtkPiecewiseFunction> alpha;
    if (range[0] < 0 && range[1] > 0)
    {
      colour->AddRGBPoint(range[0], 0.25, 0.45, 0.95);
      colour->AddRGBPoint(0, 0.95, 0.85, 0.6);
      colour->AddRGBPoint(range[1], 0.95, 0.4, 0.2);
      alpha->AddPoint(range[0], 0.02);
      alpha->AddPoint(-h, 0.02);
      alpha->AddPoint(0, 1.0);
      alpha->AddPoint(h, 0.0);
      alpha->AddPoint(3 * h, 0.0);
      alpha->AddPoint(4 * h, 0.25);
      alpha->AddPoint(5 * h, 0.0);
      alpha->AddPoint(std::max(range[1], 6 * h), 0.0);
    }
    else
    {
      colour->AddRGBPoint(range[0], 0.25, 0.45, 0.95);
      colour->AddRGBPoint(range[1], 0.95, 0.4, 0.2);
      alpha->AddPoint(range[0], 0.0);
      alpha->AddPoint(range[1], 0.5);
    }
    property->SetColor(colour);
    property->SetScalarOpacity(alpha);
    property->SetScalarOpacityUnitDistance(h);
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(size[0], size[1]);
  window->SetMultiSamples(0);
  window->OffScreenRenderingOn();
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(azimuth);
  renderer->GetActiveCamera()->Elevation(elevation);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCamera();
  // The first frame uploads the field (and builds the table); the next ones only draw.
  auto seconds = [](auto start)
  { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto start = std::chrono::steady_clock::now();
  window->Render();
  window->WaitForCompletion();
  const double first = seconds(start);
  if (mapper->GetLastNumberOfSlices() == 0)
  {
    std::fprintf(stderr, "vtkdf: nothing was rendered\n");
    return 1;
  }
  const int frames = 3;
  start = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f)
  {
    window->Render();
  }
  window->WaitForCompletion();
  const double frame = seconds(start) / frames;
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  if (!WritePNG(grab->GetOutput(), output))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", output.c_str());
    return 1;
  }
  if (timing)
  {
    int dims[3];
    field->GetDimensions(dims);
    // The GL renderer's name, from VTK's report of the context.
    const std::string report = window->ReportCapabilities();
    const std::string key = "OpenGL renderer string:";
    std::string renderer = "unknown";
    const size_t at = report.find(key);
    if (at != std::string::npos)
    {
      const size_t begin = report.find_first_not_of(' ', at + key.size());
      renderer = report.substr(begin, report.find('\n', begin) - begin);
    }
    std::printf("vtkdf: render dims=%dx%dx%d mode=%s size=%dx%d slices=%d regions=%d "
                "first_frame_s=%.4f frame_s=%.4f renderer=\"%s\"\n",
      dims[0],
      dims[1],
      dims[2],
      mode.c_str(),
      size[0],
      size[1],
      mapper->GetLastNumberOfSlices(),
      mapper->GetLastRegionCount(),
      first,
      frame,
      renderer.c_str());
  }
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0)
    {
      PrintUsage(stdout);
      return 0;
    }
  }
  if (argc < 3)
  {
    return Usage();
  }
  const std::string subcommand = argv[1];
  const std::pair<const char*, int (*)(int, char*[])> subcommands[] = { { "linfac", Linfac },
    { "voxelize", Voxelize },
    { "chamfer", Chamfer },
    { "medial", Medial },
    { "segment", Segment },
    { "blend", Blend },
    { "union", Union },
    { "pd", PenetrationDepth },
    { "render", Render } };
  for (const auto& entry : subcommands)
  {
    if (subcommand == entry.first)
    {
      return entry.second(argc, argv);
    }
  }
  return Usage(("unknown subcommand " + subcommand).c_str());
}
