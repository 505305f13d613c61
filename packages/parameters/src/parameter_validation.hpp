#pragma once
// Declaring, reading and validating Teuchos XML parameter lists with errors a user can act on.
//
// Each class declares its parameters next to itself (name, default, doc, validator) into a valid list;
// `validate` walks a user's list against it once: an unknown key, a wrong type or an out-of-range value is an
// `InputError` naming the full key path, the value and what is allowed. Defaults are filled in, so the typed
// structs built afterwards read every key without further checks.
#include <Teuchos_ParameterList.hpp>

#include <algorithm>

#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace spatula::parameters {

using Teuchos::ParameterList;

// Any problem with user input (XML file, parameter value, parameter combination).
class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Interval bounds for numeric parameters; `open` bounds exclude the end point.
struct Range {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_open = false;
  bool upper_open = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double lower, double upper) { return {lower, upper, false, false}; }
  static Range at_least(double lower) { return {lower, std::numeric_limits<double>::infinity(), false, false}; }

  bool contains(double value) const;
  std::string describe() const;   // e.g. "(0, inf)" or "[1, 64]"
};

void declare_double(ParameterList& list, const std::string& name, double default_value, const std::string& doc,
                    Range range = {});
void declare_int(ParameterList& list, const std::string& name, int default_value, const std::string& doc,
                 Range range = {});
void declare_bool(ParameterList& list, const std::string& name, bool default_value, const std::string& doc);
void declare_string(ParameterList& list, const std::string& name, const std::string& default_value,
                    const std::string& doc, const std::vector<std::string>& allowed = {});
// The enum choice a name stands for (enumerators in the order of `names`), or nothing if it is not one of them: for
// names read outside a parameter list (command-line options of the benchmarks).
template <class Choice>
std::optional<Choice> choice_named(const std::string& name, const std::vector<std::string>& names)
{
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) return std::nullopt;
  return static_cast<Choice>(found - names.begin());
}

// The name of an enum choice (its enumerators in the order of `names`): how a typed default is declared.
template <class Choice>
const std::string& name_of(Choice value, const std::vector<std::string>& names)
{
  return names.at(static_cast<std::size_t>(value));
}

// A validated string choice as the enum whose enumerators are in the order of `names` (the list it was declared
// with): choices become types once, where they are read, and nothing downstream compares strings.
template <class Choice>
Choice choice(const ParameterList& list, const std::string& name, const std::vector<std::string>& names)
{
  return choice_named<Choice>(list.get<std::string>(name), names).value();   // validated: always one of `names`
}
// A sublist declared empty accepts any keys (e.g. a free-form list handed to a third-party solver).
ParameterList& declare_sublist(ParameterList& list, const std::string& name, const std::string& doc);

// Checks `user` against `valid` recursively and fills in defaults. Throws InputError with the key path.
void validate(ParameterList& user, const ParameterList& valid, const std::string& path = "");

// Reads an XML parameter list; missing or unreadable files and malformed XML are InputErrors naming the file.
ParameterList read_xml_file(const std::string& file_name);
ParameterList read_xml_string(const std::string& xml, const std::string& origin = "<string>");

// Writes a (validated) list as XML, values only (validators and docs are not part of a scene file).
void write_xml_file(const ParameterList& list, const std::string& file_name);

// The path of a key for messages, e.g. "Geometry/l_p".
std::string key_path(const std::string& path, const std::string& name);
// A value as quoted in a message: at most 60 characters of it (and its length when longer).
std::string shorten(const std::string& value);

// Throws InputError("<key>: <value> <message>") for cross-parameter checks done after validation.
[[noreturn]] void fail(const std::string& key, double value, const std::string& message);

}  // namespace spatula::parameters
