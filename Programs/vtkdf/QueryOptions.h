// QueryOptions: the options vtkdf union and vtkdf pd share.
#ifndef vtkdf_QueryOptions_h
#define vtkdf_QueryOptions_h

#include "Options.h"
#include "vtkDistanceFieldEnums.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace vtkdf::cli
{

/// The options vtkdf union and vtkdf pd share: the output, the pieces, where the union
/// query runs, --timing.
struct QueryOptions
{
  std::string Output, PieceArray;
  bool Timing = false, Hulls = false;
  std::string Backend = "auto";

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
    if (option == "--timing" || option == "--convex-hulls")
    {
      (option == "--timing" ? this->Timing : this->Hulls) = true;
      return true;
    }
    // The options of the GPU's rendered views, which it no longer renders.
    if (option == "--uncertified" || (option == "--pixels" && a + 1 < argc))
    {
      a += option == "--pixels" ? 1 : 0;
      std::fprintf(stderr,
        "vtkdf: %s is deprecated and does nothing: the GPU backend renders no views and "
        "every answer is exact\n",
        option.c_str());
      return true;
    }
    if ((option == "-o" || option == "--piece-array") && a + 1 < argc)
    {
      (option == "-o" ? this->Output : this->PieceArray) = argv[++a];
      return true;
    }
    if (option == "--backend" && a + 1 < argc)
    {
      this->Backend = argv[++a];
      return true;
    }
    return false;
  }

  template<typename Filter>
  void Apply(Filter* filter) const
  {
    filter->SetBackend(EnumWord("--backend", this->Backend, vtkdf::enums::Backend));
    filter->SetPieceArray(this->PieceArray.c_str());
    filter->SetUseConvexHulls(this->Hulls);
  }
};

} // namespace vtkdf::cli

#endif
