// vtkDistanceFieldEnums: the names of every enumeration property's values, one table per
// enumeration, read by the filters (CheckProperties' messages, PrintSelf), by vtkdf (its
// option words, their parsing and its usage text) and by Architecture.Enums, which checks
// the plugin's XML against the tables. Private to the module (not wrapped).
#ifndef vtkDistanceFieldEnums_h
#define vtkDistanceFieldEnums_h

#include "vtkDistanceFieldsModule.h" // For export macro

#include <initializer_list>
#include <string>
#include <vector>

namespace vtkdf
{
/// One value of an enumeration: its number, its name (the property's, as the XML's
/// entries, PrintSelf and the SetXToY() methods spell it) and vtkdf's word for it.
struct EnumValue
{
  int Value;
  const char* Name;
  const char* Word;
};

/// An enumeration property and the proxies of the plugin's XML that have it.
class VTKDISTANCEFIELDS_EXPORT EnumTable
{
public:
  EnumTable(const char* property,
    std::initializer_list<const char*> proxies,
    std::initializer_list<EnumValue> values);

  const char* Property() const { return this->PropertyName; }
  /// Whether `value` is one of the table's.
  bool Has(int value) const;
  /// The name of `value`, or "(invalid)" (PrintSelf may run before a check).
  const char* Name(int value) const;
  /// The value vtkdf's `word` stands for; false when it is none of the table's.
  bool FromWord(const std::string& word, int& value) const;
  /// vtkdf's words joined by "|" ("auto|gpu|cpu"), for a usage text.
  std::string Words() const;
  /// vtkdf's words as a sentence lists them ("auto, gpu or cpu"), for a message.
  std::string WordList() const;
  /// Whether `value` is valid; else false and `error`: "Backend must be 0 (Auto), 1 (GPU)
  /// or 2 (CPU); it is 7."
  bool Check(int value, std::string& error) const;

private:
  const char* PropertyName;
  std::vector<const char*> Proxies;
  std::vector<EnumValue> Values;
};

namespace enums
{
extern VTKDISTANCEFIELDS_EXPORT const EnumTable Backend;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable LinearFactorSign;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable DomainShape;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable Route;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable VoxelMode;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable Metric;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable MedialRegion;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable MedialSign;
extern VTKDISTANCEFIELDS_EXPORT const EnumTable ProximitySign;
} // namespace enums
} // namespace vtkdf

#endif
