#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkLinearFactorDistanceField.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include <cstdio>

namespace vtkdf::cli
{

int Linfac(int argc, char* argv[])
{
  CommonOptions common;
  std::string png, arrays = "distance,cellid", domains = "auto", culling, route = "auto", sign;
  double maxDistance = 0;
  bool signedField = false;
  ParseOptions(argc,
    argv,
    common,
    { Flag("--signed", signedField),
      Text("--sign", sign),
      Text("--domains", domains),
      Text("--culling", culling),
      Text("--route", route),
      Text("--arrays", arrays),
      Number("--max-distance", maxDistance),
      Text("--png", png) });
  vtkNew<vtkLinearFactorDistanceField> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  Configure(filter, common);
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
        char blocks[160];
        std::snprintf(blocks,
          sizeof(blocks),
          " winding_block_samples=%lld winding_line_samples=%lld winding_exact_samples=%lld "
          "sign_backend=%s",
          static_cast<long long>(filter->GetLastWindingBlockSamples()),
          static_cast<long long>(filter->GetLastWindingLineSamples()),
          static_cast<long long>(filter->GetLastWindingExactSamples()),
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
