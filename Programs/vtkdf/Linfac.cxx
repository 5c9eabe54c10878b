#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkLinearFactorDistanceField.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace vtkdf::cli
{

int Linfac(int argc, char* argv[])
{
  CommonOptions common;
  std::string png, arrays = "distance,cellid", domains = "auto", culling, route = "auto", sign;
  double maxDistance = 0, band = 0;
  bool signedField = false;
  SparseOptions sparse;
  // --vdb OUT.vdb without -o: the level set alone, as -o OUT.vdb.
  std::vector<char*> args(argv, argv + argc);
  if (std::none_of(args.begin(),
        args.end(),
        [](const char* a) { return a == std::string("-o") || a == std::string("--output"); }))
  {
    for (char*& a : args)
    {
      a = a == std::string("--vdb") ? const_cast<char*>("-o") : a;
    }
  }
  ParseOptions(argc,
    args.data(),
    common,
    { Flag("--signed", signedField),
      Text("--sign", sign),
      Text("--domains", domains),
      Text("--culling", culling),
      Text("--route", route),
      Text("--arrays", arrays),
      Number("--max-distance", maxDistance),
      Number("--band", band),
      Count("--brick-size", sparse.BrickSize),
      Text("--sides", sparse.Sides),
      Text("--vdb", sparse.Vdb),
      Text("--png", png) });
  const bool pieces = EndsWith(common.Output, ".vtpd") || EndsWith(common.Output, ".vdb");
  if (band != 0 && maxDistance != 0)
  {
    std::fprintf(stderr, "vtkdf: --band K is --max-distance K spacings: give one of them\n");
    return 2;
  }
  if ((pieces && band == 0) || ((!sparse.Sides.empty() || !sparse.Vdb.empty()) && !pieces))
  {
    std::fprintf(stderr,
      "vtkdf: a .vtpd or .vdb output (the band's pieces, --sides, --vdb) needs --band K, "
      "and --band K a .vtpd, .vdb or .vti output\n");
    return 2;
  }
  vtkNew<vtkLinearFactorDistanceField> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  Configure(filter, common);
  if (pieces)
  {
    const std::string signWord = sign.empty() ? (signedField ? "pseudonormal" : "unsigned") : sign;
    sparse.SignMode = EnumWord("--sign", signWord, vtkdf::enums::LinearFactorSign);
    sparse.BandWidth = band;
    sparse.Arrays = arrays;
    sparse.DomainShape = EnumWord("--domains", domains, vtkdf::enums::DomainShape);
    return LinfacSparse(
      vtkPolyData::SafeDownCast(filter->GetInputDataObject(0, 0)), common, sparse);
  }
  if (band != 0)
  {
    // The dense field with the same band: K spacings of the grid the filter will use.
    filter->UpdateInformation();
    double spacing[3] = { 1, 1, 1 };
    filter->GetOutputInformation(0)->Get(vtkDataObject::SPACING(), spacing);
    maxDistance = band * std::min(std::min(spacing[0], spacing[1]), spacing[2]);
    if (!(maxDistance > 0))
    {
      maxDistance = band; // an invalid band: the filter names it
    }
  }
  // --culling: the earlier name of --domains, still read.
  if (!culling.empty())
  {
    std::fprintf(stderr, "vtkdf: --culling is deprecated: use --domains\n");
  }
  filter->SetDomainShape(culling.empty()
      ? EnumWord("--domains", domains, vtkdf::enums::DomainShape)
      : EnumWord("--culling", culling, vtkdf::enums::DomainShape));
  filter->SetRoute(EnumWord("--route", route, vtkdf::enums::Route));
  // --sign implies --signed; --signed alone is the pseudonormal sign.
  if (!sign.empty() || signedField)
  {
    filter->SetSignMode(
      EnumWord("--sign", sign.empty() ? "pseudonormal" : sign, vtkdf::enums::LinearFactorSign));
  }
  filter->SetComputeWindingNumber(arrays.find("winding") != std::string::npos);
  filter->SetMaximumDistance(maxDistance);
  filter->SetComputeDistance(arrays.find("distance") != std::string::npos);
  filter->SetComputeClosestCellId(arrays.find("cellid") != std::string::npos);
  filter->SetComputeClosestFeature(arrays.find("feature") != std::string::npos);
  filter->SetComputeClosestPoint(arrays.find("point") != std::string::npos);
  filter->SetComputeClosestBarycentric(arrays.find("barycentric") != std::string::npos);
  filter->SetComputeGradient(arrays.find("gradient") != std::string::npos);
  const int code = Finish("linfac",
    filter,
    common,
    [&]()
    {
      char extra[96];
      std::snprintf(extra,
        sizeof(extra),
        " culling_factor=%.3f route=%s",
        filter->GetLastCullingFactor(),
        std::string(filter->GetLastRoute()) == "sample queries" ? "queries" : "scan");
      if (filter->GetSignMode() == vtkLinearFactorDistanceField::WINDING_NUMBER)
      {
        char blocks[200];
        std::snprintf(blocks,
          sizeof(blocks),
          " winding_block_samples=%lld winding_line_samples=%lld winding_exact_samples=%lld "
          "winding_cpu_samples=%lld sign_backend=%s",
          static_cast<long long>(filter->GetLastWindingBlockSamples()),
          static_cast<long long>(filter->GetLastWindingLineSamples()),
          static_cast<long long>(filter->GetLastWindingExactSamples()),
          static_cast<long long>(filter->GetLastWindingCPUSamples()),
          filter->GetLastSignBackend());
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

} // namespace vtkdf::cli
