#include "vtkDistanceFieldEnums.h"

#include <sstream>

namespace vtkdf
{

EnumTable::EnumTable(const char* property,
  std::initializer_list<const char*> proxies,
  std::initializer_list<EnumValue> values)
  : PropertyName(property)
  , Proxies(proxies)
  , Values(values)
{
}

bool EnumTable::Has(int value) const
{
  for (const EnumValue& v : this->Values)
  {
    if (v.Value == value)
    {
      return true;
    }
  }
  return false;
}

const char* EnumTable::Name(int value) const
{
  for (const EnumValue& v : this->Values)
  {
    if (v.Value == value)
    {
      return v.Name;
    }
  }
  return "(invalid)";
}

bool EnumTable::FromWord(const std::string& word, int& value) const
{
  for (const EnumValue& v : this->Values)
  {
    if (word == v.Word)
    {
      value = v.Value;
      return true;
    }
  }
  return false;
}

std::string EnumTable::Words() const
{
  std::string words;
  for (const EnumValue& v : this->Values)
  {
    words += (words.empty() ? "" : "|") + std::string(v.Word);
  }
  return words;
}

std::string EnumTable::WordList() const
{
  std::string words;
  for (size_t i = 0; i < this->Values.size(); ++i)
  {
    words += (i == 0 ? "" : (i + 1 == this->Values.size() ? " or " : ", ")) +
      std::string(this->Values[i].Word);
  }
  return words;
}

bool EnumTable::Check(int value, std::string& error) const
{
  if (this->Has(value))
  {
    return true;
  }
  std::ostringstream text;
  text << this->PropertyName << " must be ";
  for (size_t i = 0; i < this->Values.size(); ++i)
  {
    text << (i == 0 ? "" : (i + 1 == this->Values.size() ? " or " : ", ")) << this->Values[i].Value
         << " (" << this->Values[i].Name << ")";
  }
  text << "; it is " << value << ".";
  error = text.str();
  return false;
}

// The tables. Architecture.Enums (Testing/Architecture/check_enums.py) reads them as they
// are written here: one EnumTable a table, its proxies' names, then { value, "Name",
// "word" } per value.
namespace enums
{
const EnumTable Backend("Backend",
  { "FieldFromMesh", "ConvexQuery", "DistanceFieldProximity" },
  { { 0, "Auto", "auto" }, { 1, "GPU", "gpu" }, { 2, "CPU", "cpu" } });
const EnumTable LinearFactorSign("SignMode",
  { "LinearFactorDistanceField",
    "MeshDistanceFilter",
    "ClipByMeshDistance",
    "SparseDistanceField" },
  { { 0, "Unsigned", "unsigned" },
    { 1, "PseudoNormal", "pseudonormal" },
    { 2, "WindingNumber", "winding" } });
const EnumTable DomainShape("DomainShape",
  { "LinearFactorDistanceField", "SparseDistanceField" },
  { { 0, "Auto", "auto" }, { 1, "NonManifold", "nonmanifold" }, { 2, "Manifold", "manifold" } });
const EnumTable Route("Route",
  { "LinearFactorDistanceField" },
  { { 0, "Auto", "auto" }, { 1, "SiteScan", "scan" }, { 2, "SampleQueries", "queries" } });
const EnumTable VoxelMode("Mode",
  { "PolyDataVoxelizer" },
  { { 0, "Boundary", "boundary" }, { 1, "Solid", "solid" }, { 2, "Both", "both" } });
const EnumTable Metric("Metric",
  { "ChamferVoxelDistance" },
  { { 0, "Manhattan", "manhattan" },
    { 1, "Chessboard18", "chessboard18" },
    { 2, "Chessboard26", "chessboard26" } });
const EnumTable MedialRegion("Region",
  { "MedialAxisFilter" },
  { { 0, "Inside", "inside" }, { 1, "Outside", "outside" }, { 2, "Both", "both" } });
const EnumTable MedialSign("SignMode",
  { "MedialAxisFilter" },
  { { 0, "PseudoNormal", "pseudonormal" }, { 1, "WindingNumber", "winding" } });
const EnumTable ProximitySign("SignMode",
  { "DistanceFieldProximity" },
  { { 1, "PseudoNormal", "pseudonormal" }, { 2, "WindingNumber", "winding" } });
} // namespace enums

} // namespace vtkdf
