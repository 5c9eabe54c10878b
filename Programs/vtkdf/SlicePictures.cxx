#include "SlicePictures.h"

#include "vtkFloatArray.h"
#include "vtkFreeTypeTools.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkTextProperty.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace vtkdf::cli
{

/// An RGB image of w x h pixels to paint a slice on.
vtkSmartPointer<vtkImageData> Canvas(int w, int h)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  return image;
}

namespace
{
/// "%.4g" of a value.
std::string Number(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}

/// The legends' text: black, 14 points, VTK's own Arial (no font or X server needed).
vtkSmartPointer<vtkTextProperty> TextStyle()
{
  auto property = vtkSmartPointer<vtkTextProperty>::New();
  property->SetFontFamilyToArial();
  property->SetFontSize(14);
  property->SetColor(0, 0, 0);
  property->SetJustificationToLeft();
  property->SetVerticalJustificationToBottom();
  return property;
}

/// `text` in lines no wider than `width` pixels, broken between words.
std::vector<std::string> Wrap(const std::string& text, int width)
{
  auto fits = [&](const std::string& line)
  {
    int box[4] = { 0, 0, 0, 0 };
    return !vtkFreeTypeTools::GetInstance()->GetBoundingBox(TextStyle(), line, 72, box) ||
      box[1] - box[0] <= width;
  };
  std::vector<std::string> lines;
  std::string line;
  size_t start = 0;
  while (start < text.size())
  {
    size_t end = text.find(' ', start);
    end = end == std::string::npos ? text.size() : end;
    const std::string word = text.substr(start, end - start);
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && !fits(longer))
    {
      lines.push_back(line);
      line = word;
    }
    else
    {
      line = longer;
    }
    start = end + 1;
  }
  if (!line.empty())
  {
    lines.push_back(line);
  }
  return lines;
}

/// Draws `text` into the RGB `canvas` with its lower-left corner at (x, y), blended by
/// the glyphs' coverage.
void DrawText(vtkImageData* canvas, const std::string& text, int x, int y)
{
  vtkSmartPointer<vtkTextProperty> property = TextStyle();
  vtkNew<vtkImageData> glyphs;
  if (!vtkFreeTypeTools::GetInstance()->RenderString(property, text, 72, glyphs))
  {
    return;
  }
  int size3[3], canvasSize[3];
  glyphs->GetDimensions(size3);
  canvas->GetDimensions(canvasSize);
  auto* rgba = static_cast<unsigned char*>(glyphs->GetScalarPointer());
  auto* rgb = static_cast<unsigned char*>(canvas->GetScalarPointer());
  const int components = glyphs->GetNumberOfScalarComponents();
  for (int j = 0; j < size3[1]; ++j)
  {
    for (int i = 0; i < size3[0]; ++i)
    {
      const int cx = x + i, cy = y + j;
      if (cx < 0 || cy < 0 || cx >= canvasSize[0] || cy >= canvasSize[1])
      {
        continue;
      }
      const unsigned char* g = rgba + components * (size_t(j) * size3[0] + i);
      const double alpha = components == 4 ? g[3] / 255.0 : 0;
      unsigned char* pixel = rgb + 3 * (size_t(cy) * canvasSize[0] + cx);
      for (int ch = 0; ch < 3; ++ch)
      {
        pixel[ch] = static_cast<unsigned char>((1 - alpha) * pixel[ch] + alpha * g[ch] + 0.5);
      }
    }
  }
}

/// What a picture's legend says: an optional colour bar (Colour maps a value of [Lo, Hi]
/// to RGB in [0, 1]) with its title, then lines of text.
struct Legend
{
  std::string Title;
  double Lo = 0, Hi = 1;
  std::function<void(double, float[3])> Colour;
  std::vector<std::string> Lines;
};

/// `slice` (RGB) above a white band with the legend: the colour bar, its range (and 0
/// when it spans it), and the lines of text. Slices are at least 512 pixels wide or tall.
vtkSmartPointer<vtkImageData> WithLegend(vtkImageData* slice, const Legend& legend)
{
  int dims[3];
  slice->GetDimensions(dims);
  const int lineHeight = 19, barHeight = 16, margin = 10;
  const int width = std::max(dims[0], 420);
  std::vector<std::string> lines;
  for (const std::string& text : legend.Lines)
  {
    for (const std::string& line : Wrap(text, width - 2 * margin))
    {
      lines.push_back(line);
    }
  }
  const int band = margin + (legend.Colour ? barHeight + 4 + lineHeight + lineHeight : 0) +
    lineHeight * static_cast<int>(lines.size()) + margin;
  vtkSmartPointer<vtkImageData> canvas = Canvas(width, dims[1] + band);
  auto* rgb = static_cast<unsigned char*>(canvas->GetScalarPointer());
  std::fill(rgb, rgb + 3 * size_t(width) * (dims[1] + band), 255);
  const auto* picture = static_cast<const unsigned char*>(slice->GetScalarPointer());
  for (int y = 0; y < dims[1]; ++y)
  {
    std::copy(picture + 3 * size_t(y) * dims[0],
      picture + 3 * size_t(y + 1) * dims[0],
      rgb + 3 * (size_t(y + band) * width));
  }
  int top = band - margin; // the next row to fill, downwards
  if (legend.Colour)
  {
    DrawText(canvas, legend.Title, margin, top - lineHeight + 4);
    top -= lineHeight;
    const int barWidth = std::min(width - 2 * margin, 512);
    for (int c = 0; c < barWidth; ++c)
    {
      float colour[3];
      legend.Colour(legend.Lo + (legend.Hi - legend.Lo) * (c + 0.5) / barWidth, colour);
      for (int r = top - barHeight; r < top; ++r)
      {
        for (int ch = 0; ch < 3; ++ch)
        {
          rgb[3 * (size_t(r) * width + margin + c) + ch] =
            static_cast<unsigned char>(255 * colour[ch] + 0.5);
        }
      }
    }
    top -= barHeight + 4;
    const int labelRow = top - lineHeight + 4;
    DrawText(canvas, Number(legend.Lo), margin, labelRow);
    const std::string hi = Number(legend.Hi);
    DrawText(canvas, hi, margin + barWidth - 8 * static_cast<int>(hi.size()), labelRow);
    if (legend.Lo < 0 && legend.Hi > 0)
    {
      DrawText(
        canvas, "0", margin + int(barWidth * -legend.Lo / (legend.Hi - legend.Lo)) - 4, labelRow);
    }
    top -= lineHeight;
  }
  for (const std::string& line : lines)
  {
    DrawText(canvas, line, margin, top - lineHeight + 4);
    top -= lineHeight;
  }
  return canvas;
}

/// "slice z = 0.25 (sample 12 of 0..23); x to the right, y up".
std::string SliceLine(vtkImageData* field, int k)
{
  double origin[3], spacing[3];
  int dims[3];
  field->GetOrigin(origin);
  field->GetSpacing(spacing);
  field->GetDimensions(dims);
  return "slice z = " + Number(origin[2] + spacing[2] * k) + " (sample " + std::to_string(k) +
    " of 0.." + std::to_string(dims[2] - 1) + "); x to the right, y up";
}

/// A segmented field's colours: hues by the golden angle (neighbouring indices differ),
/// lighter as `fraction` (the distance over Delta) grows.
void RegionColour(int region, double fraction, float c[3])
{
  const double hue = std::fmod(0.618034 * std::max(0, region), 1.0) * 6;
  const double light = 0.45 + 0.5 * std::min(1.0, std::max(0.0, fraction));
  const double rgb[3] = { std::fabs(hue - 3) - 1, 2 - std::fabs(hue - 2), 2 - std::fabs(hue - 4) };
  for (int ch = 0; ch < 3; ++ch)
  {
    c[ch] = static_cast<float>((0.35 * std::min(1.0, std::max(0.0, rgb[ch])) + 0.65) * light);
  }
}

/// The signed fields' colours: blue inside (t < 0), white at the surface, warm outside.
void SignedColour(double t, float c[3])
{
  const float a = static_cast<float>(std::min(1.0, std::fabs(t)));
  if (t < 0)
  {
    c[0] = 1 - 0.8f * a, c[1] = 1 - 0.6f * a, c[2] = 1 - 0.1f * a;
  }
  else
  {
    c[0] = 1 - 0.1f * a, c[1] = 1 - 0.7f * a, c[2] = 1 - 0.85f * a;
  }
}
} // namespace

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
      float c[3];
      SignedColour(v / largest, c);
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
  Legend legend;
  const bool signedField = distance->GetValueRange()[0] < 0;
  legend.Title = "Distance (world units: the mesh file's own)";
  legend.Lo = signedField ? -largest : 0;
  legend.Hi = largest;
  legend.Colour = [largest](double v, float c[3]) { SignedColour(v / largest, c); };
  legend.Lines = { "black isolines every " + Number(step) +
      (signedField ? "; dark blue: the surface (distance 0, negative inside)" : ""),
    SliceLine(field, k) };
  return WritePNG(WithLegend(image, legend), path);
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
  Legend legend;
  legend.Title = "Radius: distance to the surface (world units: the mesh file's own)";
  legend.Hi = largest;
  legend.Colour = [largest](double r, float c[3])
  { c[0] = c[1] = c[2] = static_cast<float>(255 - 200 * r / largest) / 255; };
  legend.Lines = { "red: medial samples", SliceLine(field, k) };
  return WritePNG(WithLegend(image, legend), path);
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
      float c[3];
      RegionColour(region->GetValue(v), distance->GetValue(v) / delta, c);
      unsigned char* pixel = rgb + 3 * (size_t(y) * dims[0] * scale + x);
      for (int ch = 0; ch < 3; ++ch)
      {
        pixel[ch] = interface ? 0 : static_cast<unsigned char>(255 * c[ch]);
      }
    }
  }
  Legend legend;
  legend.Title = "Distance in region 0's hue (world units: the mesh file's own)";
  legend.Hi = delta;
  legend.Colour = [delta](double d, float c[3]) { RegionColour(0, d / delta, c); };
  legend.Lines = { "one hue per RegionIndex, lighter away from the surface up to Delta = " +
      Number(delta),
    "black: where two regions meet",
    SliceLine(field, k) };
  return WritePNG(WithLegend(image, legend), path);
}

} // namespace vtkdf::cli
