// vtkdf: the command-line front end of VTK Distance Fields.
//
//   vtkdf linfac INPUT -o OUT.vti [--resolution N] [--padding F]
//         [--origin X Y Z --spacing SX SY SZ --dims NX NY NZ] [--signed]
//         [--backend auto|gpu|cpu] [--culling auto|nonmanifold|manifold]
//         [--arrays distance,cellid,feature,point] [--max-distance D]
//         [--png SLICE.png] [--timing]
//
// INPUT: .vtp .vtk .ply .stl .obj. --timing prints one line that scripts can read:
//   vtkdf: linfac dims=NXxNYxNZ backend=cpu renderer="cpu" time_s=0.123
#include "vtkLinearFactorDistanceField.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataReader.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{
int Usage(const char* message = nullptr)
{
  if (message)
  {
    std::fprintf(stderr, "vtkdf: %s\n", message);
  }
  std::fprintf(stderr,
    "usage: vtkdf linfac INPUT -o OUT.vti [--resolution N] [--padding F]\n"
    "             [--origin X Y Z --spacing SX SY SZ --dims NX NY NZ] [--signed]\n"
    "             [--backend auto|gpu|cpu] [--culling auto|nonmanifold|manifold]\n"
    "             [--arrays distance,cellid,feature,point] [--max-distance D]\n"
    "             [--png SLICE.png] [--timing]\n"
    "INPUT: .vtp .vtk .ply .stl .obj\n");
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
    mesh = reader->GetOutput();
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
  vtkNew<vtkImageData> image;
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
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
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->Write();
  return writer->GetErrorCode() == 0;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3 || std::string(argv[1]) != "linfac")
  {
    return Usage(argc >= 2 && std::string(argv[1]) != "linfac" ? "unknown subcommand" : nullptr);
  }
  const std::string input = argv[2];
  std::string output, png, arrays = "distance,cellid", backend = "auto", culling = "auto";
  int resolution = 64;
  double padding = 0.1, maxDistance = 0;
  double origin[3], spacing[3];
  int dims[3];
  bool explicitOrigin = false, explicitSpacing = false, explicitDims = false;
  bool signedField = false, timing = false;
  for (int a = 3; a < argc; ++a)
  {
    const std::string arg = argv[a];
    auto need = [&](int count)
    {
      if (a + count >= argc)
      {
        std::exit(Usage((arg + " needs " + std::to_string(count) + " value(s)").c_str()));
      }
    };
    if (arg == "-o" || arg == "--output")
    {
      need(1);
      output = argv[++a];
    }
    else if (arg == "--resolution")
    {
      need(1);
      resolution = std::atoi(argv[++a]);
    }
    else if (arg == "--padding")
    {
      need(1);
      padding = std::atof(argv[++a]);
    }
    else if (arg == "--origin" || arg == "--spacing")
    {
      need(3);
      double* v = arg == "--origin" ? origin : spacing;
      for (int k = 0; k < 3; ++k)
      {
        v[k] = std::atof(argv[++a]);
      }
      (arg == "--origin" ? explicitOrigin : explicitSpacing) = true;
    }
    else if (arg == "--dims")
    {
      need(3);
      for (int k = 0; k < 3; ++k)
      {
        dims[k] = std::atoi(argv[++a]);
      }
      explicitDims = true;
    }
    else if (arg == "--signed")
    {
      signedField = true;
    }
    else if (arg == "--backend")
    {
      need(1);
      backend = argv[++a];
    }
    else if (arg == "--culling")
    {
      need(1);
      culling = argv[++a];
    }
    else if (arg == "--arrays")
    {
      need(1);
      arrays = argv[++a];
    }
    else if (arg == "--max-distance")
    {
      need(1);
      maxDistance = std::atof(argv[++a]);
    }
    else if (arg == "--png")
    {
      need(1);
      png = argv[++a];
    }
    else if (arg == "--timing")
    {
      timing = true;
    }
    else
    {
      return Usage(("unknown option " + arg).c_str());
    }
  }
  if (output.empty())
  {
    return Usage("-o OUT.vti is required");
  }
  if ((explicitOrigin || explicitSpacing || explicitDims) &&
    !(explicitOrigin && explicitSpacing && explicitDims))
  {
    return Usage("an explicit grid needs --origin, --spacing and --dims together");
  }

  vtkSmartPointer<vtkPolyData> mesh = ReadMesh(input);
  if (!mesh)
  {
    return Usage(("cannot read " + input + " (expected .vtp .vtk .ply .stl .obj)").c_str());
  }

  vtkNew<vtkLinearFactorDistanceField> filter;
  filter->SetInputData(mesh);
  filter->SetResolution(resolution);
  filter->SetPadding(padding);
  if (explicitDims)
  {
    filter->ExplicitGridOn();
    filter->SetGridOrigin(origin);
    filter->SetGridSpacing(spacing);
    filter->SetGridDimensions(dims);
  }
  if (backend == "gpu")
  {
    filter->SetBackendToGPU();
  }
  else if (backend == "cpu")
  {
    filter->SetBackendToCPU();
  }
  else if (backend != "auto")
  {
    return Usage("--backend takes auto, gpu or cpu");
  }
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
  filter->SetSignMode(signedField ? vtkLinearFactorDistanceField::PSEUDO_NORMAL
                                  : vtkLinearFactorDistanceField::UNSIGNED);
  filter->SetMaximumDistance(maxDistance);
  filter->SetComputeDistance(arrays.find("distance") != std::string::npos);
  filter->SetComputeClosestCellId(arrays.find("cellid") != std::string::npos);
  filter->SetComputeClosestFeature(arrays.find("feature") != std::string::npos);
  filter->SetComputeClosestPoint(arrays.find("point") != std::string::npos);
  filter->Update();
  vtkImageData* field = filter->GetOutput();
  if (filter->GetErrorCode() || field->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: no field was computed\n");
    return 1;
  }
  field->GetDimensions(dims);
  if (timing)
  {
    std::printf("vtkdf: linfac dims=%dx%dx%d backend=%s renderer=\"%s\" time_s=%.6f "
                "culling_factor=%.3f stages=%s\n",
      dims[0],
      dims[1],
      dims[2],
      filter->GetLastBackend(),
      filter->GetLastRenderer(),
      filter->GetLastTime(),
      filter->GetLastCullingFactor(),
      filter->GetLastStageTimes());
  }
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(output.c_str());
  writer->SetInputData(field);
  if (!writer->Write())
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", output.c_str());
    return 1;
  }
  if (!png.empty() && !WriteSlicePNG(field, png))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s (it needs the distance array)\n", png.c_str());
    return 1;
  }
  return 0;
}
