#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkMeshDistanceFilter.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkType.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace vtkdf::cli
{
namespace
{
/// A point cloud of `xyz` (3 doubles a point).
vtkSmartPointer<vtkPolyData> Cloud(const std::vector<double>& xyz)
{
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(static_cast<vtkIdType>(xyz.size() / 3));
  std::copy(xyz.begin(), xyz.end(), coordinates->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  return cloud;
}

/// Points from a .csv: three numbers a line (commas or spaces between them); a first
/// line that is not three numbers is a header. False, with `error`, otherwise.
bool ReadCSV(const std::string& path, std::vector<double>& xyz, std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open " + path;
    return false;
  }
  std::string line;
  for (int number = 1; std::getline(in, line); ++number)
  {
    for (char& c : line)
    {
      c = c == ',' || c == ';' || c == '\t' ? ' ' : c;
    }
    // strtod, not a stream: it reads nan and inf too (the filter then names the point).
    double x[3];
    const char* at = line.c_str();
    char* end = nullptr;
    int read = 0;
    for (; read < 3; ++read, at = end)
    {
      x[read] = std::strtod(at, &end);
      if (end == at)
      {
        break;
      }
    }
    const bool rest = read == 3 && std::string(end).find_first_not_of(" \r") != std::string::npos;
    if (read < 3 || rest)
    {
      if (number == 1 || line.find_first_not_of(" \r") == std::string::npos)
      {
        continue; // a header, or an empty line
      }
      error = path + ", line " + std::to_string(number) + ": not three numbers";
      return false;
    }
    xyz.insert(xyz.end(), x, x + 3);
  }
  return true;
}

/// Points from a .npy holding an array of shape (N, 3) of little-endian float64 or
/// float32 in C order (what numpy.save writes for such an array).
bool ReadNPY(const std::string& path, std::vector<double>& xyz, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, "\x93NUMPY", 6) != 0)
  {
    error = path + " is not a .npy file";
    return false;
  }
  uint32_t headerLength = 0;
  unsigned char bytes[4] = { 0, 0, 0, 0 };
  in.read(reinterpret_cast<char*>(bytes), magic[6] == 1 ? 2 : 4);
  headerLength =
    bytes[0] | (bytes[1] << 8) | (uint32_t(bytes[2]) << 16) | (uint32_t(bytes[3]) << 24);
  std::string header(headerLength, ' ');
  in.read(&header[0], headerLength);
  const bool f8 = header.find("'<f8'") != std::string::npos;
  const bool f4 = header.find("'<f4'") != std::string::npos;
  const size_t shape = header.find("'shape': (");
  long long n = -1, columns = -1;
  if (shape != std::string::npos)
  {
    std::sscanf(header.c_str() + shape + 10, "%lld, %lld", &n, &columns);
  }
  if (!in || (!f8 && !f4) || header.find("'fortran_order': False") == std::string::npos ||
    columns != 3 || n < 0)
  {
    error = path + ": expected an array of shape (N, 3) of float64 or float32 in C order";
    return false;
  }
  xyz.resize(3 * static_cast<size_t>(n));
  if (f8)
  {
    in.read(reinterpret_cast<char*>(xyz.data()), static_cast<std::streamsize>(8 * xyz.size()));
  }
  else
  {
    std::vector<float> values(xyz.size());
    in.read(
      reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(4 * values.size()));
    std::copy(values.begin(), values.end(), xyz.begin());
  }
  if (!in)
  {
    error = path + " is shorter than its header says";
    return false;
  }
  return true;
}

/// Writes `values` as a .npy of shape (N,) float64.
bool WriteNPY(vtkDataArray* values, const std::string& path)
{
  std::ofstream out(path, std::ios::binary);
  const long long n = values ? values->GetNumberOfTuples() : 0;
  std::string header =
    "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(n) + ",), }";
  // The header, padded with spaces and ended by a newline, makes the data start at a
  // multiple of 64 bytes.
  header.append(63 - (10 + header.size()) % 64, ' ');
  header += '\n';
  const uint16_t length = static_cast<uint16_t>(header.size());
  out.write("\x93NUMPY\x01\x00", 8);
  const char lengthBytes[2] = { static_cast<char>(length & 0xff), static_cast<char>(length >> 8) };
  out.write(lengthBytes, 2);
  out << header;
  for (long long i = 0; i < n; ++i)
  {
    const double v = values->GetTuple1(i);
    out.write(reinterpret_cast<const char*>(&v), 8);
  }
  if (!out)
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", path.c_str());
    return false;
  }
  return true;
}

/// The query points: a .csv or .npy of points, a mesh, or any VTK XML dataset.
vtkSmartPointer<vtkDataSet> ReadPointsOrExit(const std::string& path)
{
  std::string error;
  std::vector<double> xyz;
  if (EndsWith(path, ".csv") || EndsWith(path, ".npy"))
  {
    if (!(EndsWith(path, ".csv") ? ReadCSV(path, xyz, error) : ReadNPY(path, xyz, error)))
    {
      std::exit(Usage(error.c_str()));
    }
    return Cloud(xyz);
  }
  return ReadDataSetOrExit(path);
}
} // namespace

/// vtkdf probe MESH POINTS -o OUT [--signed] [--sign pseudonormal|winding]
///   [--max-distance D] [--winding] [--timing]
int Probe(int argc, char* argv[])
{
  if (argc < 4)
  {
    return Usage("probe needs a mesh and the points");
  }
  std::string output, sign;
  bool signedDistance = false, winding = false, timing = false;
  double cap = 0;
  for (int a = 4; a < argc; ++a)
  {
    const std::string option = argv[a];
    const bool valued = a + 1 < argc;
    if (option == "--timing" || option == "--signed" || option == "--winding")
    {
      (option == "--timing" ? timing : (option == "--signed" ? signedDistance : winding)) = true;
    }
    else if (option == "-o" && valued)
    {
      output = argv[++a];
    }
    else if (option == "--sign" && valued)
    {
      sign = argv[++a];
      EnumWord("--sign", sign, vtkdf::enums::LinearFactorSign);
    }
    else if (option == "--max-distance" && valued)
    {
      cap = ParseNumber("--max-distance", argv[++a]);
    }
    else
    {
      const bool known = option == "-o" || option == "--sign" || option == "--max-distance";
      return Usage((option + (known ? " needs a value" : ": unknown option")).c_str());
    }
  }
  if (output.empty())
  {
    return Usage("probe needs -o OUT (.vtp, .vtu, .vti, .vts, .vtr or .npy)");
  }
  // --signed alone: the winding number (right on open meshes too); --sign names it.
  const int mode = !sign.empty()
    ? EnumWord("--sign", sign, vtkdf::enums::LinearFactorSign)
    : (signedDistance ? vtkMeshDistanceFilter::WINDING_NUMBER : vtkMeshDistanceFilter::UNSIGNED);
  vtkNew<vtkMeshDistanceFilter> filter;
  filter->SetSurfaceData(ReadMeshOrExit(argv[2]));
  filter->SetInputData(0, ReadPointsOrExit(argv[3]));
  filter->SetSignMode(mode);
  filter->SetMaximumDistance(cap);
  filter->SetComputeWindingNumber(winding);
  filter->Update();
  vtkDataSet* result = filter->GetOutput();
  vtkDataArray* distance = result->GetPointData()->GetArray("Distance");
  if (filter->GetErrorCode() || !distance)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  vtkFieldData* fd = result->GetFieldData();
  auto value = [fd](const char* name)
  {
    vtkDataArray* array = fd->GetArray(name);
    return array ? array->GetTuple1(0) : 0.0;
  };
  std::printf("vtkdf: probe points=%lld max_abs_distance=%.17g mean_abs_distance=%.17g "
              "rms_distance=%.17g farthest_point=%lld beyond=%lld\n",
    static_cast<long long>(result->GetNumberOfPoints()),
    value("MaximumAbsoluteDistance"),
    value("MeanAbsoluteDistance"),
    value("RootMeanSquareDistance"),
    static_cast<long long>(value("FarthestPointId")),
    static_cast<long long>(filter->GetLastPointsBeyond()));
  if (timing)
  {
    std::printf("vtkdf: probe time_s=%.6f stages=%s evaluations=%lld peak_memory_mb=%.1f\n",
      filter->GetLastTime(),
      filter->GetLastStageTimes(),
      static_cast<long long>(filter->GetLastEvaluations()),
      filter->GetLastPeakMemory());
  }
  if (EndsWith(output, ".npy"))
  {
    return WriteNPY(distance, output) ? 0 : 1;
  }
  return WriteDataSet(result, output);
}

} // namespace vtkdf::cli
