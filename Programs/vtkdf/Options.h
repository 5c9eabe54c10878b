// Options: what vtkdf's subcommands share: the usage text and its errors, the parser of
// the common options (output, grid, backend, timing) and of a subcommand's own, and the
// end of a filter's run (the timing line, the output file).
#ifndef vtkdf_Options_h
#define vtkdf_Options_h

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

class vtkDistanceFieldAlgorithm;
namespace vtkdf
{
class EnumTable;
}

namespace vtkdf::cli
{

void PrintUsage(FILE* out);

/// A usage error: the message and the usage on stderr; the exit status 2.
int Usage(const char* message = nullptr);

bool EndsWith(const std::string& s, const char* suffix);

/// The value of `table` (vtkDistanceFieldEnums.h) that `word`, given to `option`, names;
/// exits with a usage error listing the table's words when it names none.
int EnumWord(const char* option, const std::string& word, const vtkdf::EnumTable& table);

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

Option Flag(const char* name, bool& target);
Option Text(const char* name, std::string& target);

/// The whole of `text` as a number (strtod: decimal, exponent, "nan", "inf"); exits with
/// a usage error naming `option` otherwise. Range checks are the filters' (they name the
/// property), except what cannot be passed on at all.
double ParseNumber(const char* option, const char* text);

/// The whole of `text` as an int (decimal); exits with a usage error naming `option`
/// when it is not one or does not fit in an int (no wrapping: 4294967312 is not 16).
int ParseInt(const char* option, const char* text);

Option Number(const char* name, double& target);
Option Count(const char* name, int& target);

/// Parses the options of argv[3...] (after `vtkdf SUBCOMMAND INPUT`): the common ones,
/// then the subcommand's `own`. Exits on a usage error.
void ParseOptions(int argc, char* argv[], CommonOptions& common, const std::vector<Option>& own);

/// Grid and backend options onto a filter.
void Configure(vtkDistanceFieldAlgorithm* filter, CommonOptions& common);

/// Runs the filter (once: a second Update() of a failed filter runs it again and prints
/// every error twice); prints the timing line, with `extra()` after the time; writes the
/// output. Returns the exit code.
/// Runs `filter`, prints its timing line (with `extra`), runs `then` (what depends on
/// the field: false stops before any file is written) and writes the field.
int Finish(const char* subcommand,
  vtkDistanceFieldAlgorithm* filter,
  const CommonOptions& common,
  const std::function<std::string()>& extra = std::function<std::string()>(),
  const std::function<bool()>& then = std::function<bool()>());

} // namespace vtkdf::cli

#endif
