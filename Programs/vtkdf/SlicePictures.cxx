#include "SlicePictures.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vtkdfcli
{

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

} // namespace vtkdfcli
