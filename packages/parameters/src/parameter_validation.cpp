#include "parameters/parameter_validation.hpp"
#include "parameters/xml_bounds.hpp"

#include <Teuchos_ParameterEntryValidator.hpp>
#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Teuchos_XMLParameterListReader.hpp>
#include <Teuchos_XMLParameterListWriter.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace spatula::parameters {

std::string key_path(const std::string& path, const std::string& name)
{
  return path.empty() ? name : path + "/" + name;
}

std::string shorten(const std::string& value)
{
  return value.size() > 60 ? value.substr(0, 60) + "... (" + std::to_string(value.size()) + " characters)" : value;
}

namespace {

std::string format_number(double value)
{
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

std::string join(const std::vector<std::string>& words)
{
  std::string joined;
  for (const auto& word : words) joined += (joined.empty() ? "" : ", ") + word;
  return joined;
}

// Validator carried by a declared parameter: its type, and a numeric range or a list of allowed strings.
// The checks themselves happen in `validate` below, which knows the key path for the message.
class Constraint : public Teuchos::ParameterEntryValidator {
public:
  enum class Kind { real, integer, boolean, text };

  Constraint(Kind kind, Range range, std::vector<std::string> allowed)
      : kind_(kind), range_(range), allowed_(std::move(allowed))
  {
  }

  Kind kind() const { return kind_; }
  const Range& range() const { return range_; }
  const std::vector<std::string>& allowed() const { return allowed_; }

  std::string type_name() const
  {
    switch (kind_) {
      case Kind::real: return "double";
      case Kind::integer: return "int";
      case Kind::boolean: return "bool";
      case Kind::text: return "string";
    }
    return "";
  }

  std::string describe_allowed() const
  {
    if (kind_ == Kind::text) return allowed_.empty() ? "any string" : "one of: " + join(allowed_);
    if (kind_ == Kind::boolean) return "true or false";
    return type_name() + " in " + range_.describe();
  }

  const std::string getXMLTypeName() const override { return "spatula_constraint"; }
  void printDoc(const std::string& doc, std::ostream& out) const override
  {
    out << "# " << doc << " (" << describe_allowed() << ")\n";
  }
  ValidStringsList validStringValues() const override
  {
    if (allowed_.empty()) return Teuchos::null;
    return Teuchos::rcp(new Teuchos::Array<std::string>(allowed_.begin(), allowed_.end()));
  }
  void validate(const Teuchos::ParameterEntry&, const std::string&, const std::string&) const override {}

private:
  Kind kind_;
  Range range_;
  std::vector<std::string> allowed_;
};

template <class T>
void declare(ParameterList& list, const std::string& name, const T& default_value, const std::string& doc,
             Constraint::Kind kind, Range range, std::vector<std::string> allowed = {})
{
  auto constraint = Teuchos::rcp(new Constraint(kind, range, std::move(allowed)));
  list.set(name, default_value, doc, constraint);
}

std::string describe_entry(const Teuchos::ParameterEntry& entry)
{
  std::ostringstream out;
  std::ostringstream value;
  entry.getAny(false).print(value);
  out << entry.getAny(false).typeName() << " '" << shorten(value.str()) << "'";
  return out.str();
}

void check_value(Teuchos::ParameterEntry& entry, const Constraint& constraint, const std::string& key)
{
  using Kind = Constraint::Kind;
  auto wrong_type = [&]() {
    throw InputError("parameter '" + key + "': expected " + constraint.type_name() + ", got " +
                     describe_entry(entry) + "; allowed: " + constraint.describe_allowed());
  };
  const auto& any = entry.getAny(false);
  switch (constraint.kind()) {
    case Kind::real: {
      double value = 0.0;
      if (any.type() == typeid(double)) value = Teuchos::any_cast<double>(any);
      else if (any.type() == typeid(int)) value = Teuchos::any_cast<int>(any);
      else wrong_type();
      if (!std::isfinite(value) || !constraint.range().contains(value))
        throw InputError("parameter '" + key + "' = " + format_number(value) + " is out of range; allowed: " +
                         constraint.describe_allowed());
      entry.setValue(value, entry.isDefault(), entry.docString(), entry.validator());
      break;
    }
    case Kind::integer: {
      if (any.type() != typeid(int)) wrong_type();
      const int value = Teuchos::any_cast<int>(any);
      if (!constraint.range().contains(value))
        throw InputError("parameter '" + key + "' = " + std::to_string(value) + " is out of range; allowed: " +
                         constraint.describe_allowed());
      break;
    }
    case Kind::boolean:
      if (any.type() != typeid(bool)) wrong_type();
      break;
    case Kind::text: {
      if (any.type() != typeid(std::string)) wrong_type();
      const auto& value = Teuchos::any_cast<std::string>(any);
      const auto& allowed = constraint.allowed();
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), value) == allowed.end())
        throw InputError("parameter '" + key + "' = '" + shorten(value) + "' is not allowed; allowed: " +
                         constraint.describe_allowed());
      break;
    }
  }
}

}  // namespace

bool Range::contains(double value) const
{
  const bool above = lower_open ? value > lower : value >= lower;
  const bool below = upper_open ? value < upper : value <= upper;
  return above && below;
}

std::string Range::describe() const
{
  return std::string(lower_open || std::isinf(lower) ? "(" : "[") + format_number(lower) + ", " +
         format_number(upper) + (upper_open || std::isinf(upper) ? ")" : "]");
}

void declare_double(ParameterList& list, const std::string& name, double default_value, const std::string& doc,
                    Range range)
{
  declare(list, name, default_value, doc, Constraint::Kind::real, range);
}

void declare_int(ParameterList& list, const std::string& name, int default_value, const std::string& doc,
                 Range range)
{
  declare(list, name, default_value, doc, Constraint::Kind::integer, range);
}

void declare_bool(ParameterList& list, const std::string& name, bool default_value, const std::string& doc)
{
  declare(list, name, default_value, doc, Constraint::Kind::boolean, {});
}

void declare_string(ParameterList& list, const std::string& name, const std::string& default_value,
                    const std::string& doc, const std::vector<std::string>& allowed)
{
  declare(list, name, default_value, doc, Constraint::Kind::text, {}, allowed);
}

ParameterList& declare_sublist(ParameterList& list, const std::string& name, const std::string& doc)
{
  return list.sublist(name, false, doc);
}

void validate(ParameterList& user, const ParameterList& valid, const std::string& path)
{
  if (valid.numParams() == 0) return;   // free-form sublist
  std::vector<std::string> valid_names;
  for (auto it = valid.begin(); it != valid.end(); ++it) valid_names.push_back(valid.name(it));

  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    const std::string key = key_path(path, name);
    if (!valid.isParameter(name))
      throw InputError("unknown parameter '" + key + "'; allowed keys in '" + (path.empty() ? "/" : path) +
                       "': " + join(valid_names));
    const auto& valid_entry = valid.getEntry(name);
    auto& user_entry = user.getEntry(name);
    if (valid_entry.isList() != user_entry.isList())
      throw InputError("parameter '" + key + "' must be " + (valid_entry.isList() ? "a sublist" : "a value") +
                       (valid_entry.isList() ? "" : " (got a sublist)"));
    if (valid_entry.isList()) {
      validate(user.sublist(name), valid.sublist(name), key);
      continue;
    }
    auto constraint = Teuchos::rcp_dynamic_cast<const Constraint>(valid_entry.validator());
    if (constraint.is_null())
      throw std::logic_error("parameter '" + key + "' was declared without spatula::parameters::declare_*");
    check_value(user_entry, *constraint, key);
  }

  // Defaults for everything the user left out (recursively for sublists).
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const auto& valid_entry = valid.entry(it);
    if (valid_entry.isList()) {
      if (!user.isSublist(name)) validate(user.sublist(name), valid.sublist(name), key_path(path, name));
    } else if (!user.isParameter(name)) {
      user.setEntry(name, valid_entry);
    }
  }
}

// Checks the XML tree before Teuchos converts it, because Teuchos is lenient where a scene must not be: it reads
// value="abc" of type double as 0, an int beyond its range modulo 2^32, a repeated key as the last one given and a
// repeated sublist as the two merged. Every problem is an InputError naming the key (and, for a repeated key, the
// lines of the text that give it).
namespace {

// The lines of `text` on which name="<name>" appears (1-based), for messages about repeated keys.
std::string lines_naming(const std::string& text, const std::string& name)
{
  const std::string needle = "name=\"" + name + "\"";
  std::string lines;
  int count = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
    lines += (count++ == 0 ? "" : ", ") + std::to_string(line);
  }
  return count == 2 ? " (lines " + lines + ")" : "";   // more: the name is also used elsewhere, lines would mislead
}

bool is_number(const std::string& value, double& number)
{
  // strtod, unlike a stream, reads "nan" and "inf": they are numbers here and refused below by name.
  if (value.empty() || std::isspace(static_cast<unsigned char>(value.front()))) return false;
  errno = 0;
  char* end = nullptr;
  number = std::strtod(value.c_str(), &end);
  while (end && *end && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return end && *end == '\0' && !(errno == ERANGE && std::isinf(number));
}

void check_literal(const std::string& key, const std::string& type, const std::string& value)
{
  auto invalid = [&](const std::string& why) {
    throw InputError("parameter '" + key + "': value '" + shorten(value) + "' " + why);
  };
  if (type == "double") {
    double number = 0.0;
    if (!is_number(value, number)) invalid("is not a valid double (or is beyond its range, about 1.8e308)");
    if (!std::isfinite(number)) invalid("is not a finite number");
  } else if (type == "int") {
    errno = 0;
    char* end = nullptr;
    const long long number = value.empty() ? 0 : std::strtoll(value.c_str(), &end, 10);
    if (value.empty() || !end || *end != '\0' || std::isspace(static_cast<unsigned char>(value.front())))
      invalid("is not a valid int");
    if (errno == ERANGE || number < std::numeric_limits<int>::min() || number > std::numeric_limits<int>::max())
      invalid("is outside the range of int [" + std::to_string(std::numeric_limits<int>::min()) + ", " +
              std::to_string(std::numeric_limits<int>::max()) + "]");
  } else if (type == "bool") {
    if (value != "true" && value != "false" && value != "1" && value != "0") invalid("is not a valid bool (true or false)");
  }
}

void check_tree(const Teuchos::XMLObject& node, const std::string& path, const std::string& text)
{
  std::vector<std::string> names;
  for (int i = 0; i < node.numChildren(); ++i) {
    const auto& child = node.getChild(i);
    const std::string& tag = child.getTag();
    if (tag != "ParameterList" && tag != "Parameter") continue;   // Teuchos' own elements (validators) pass on
    const std::string where = path.empty() ? "the top level" : "'" + path + "'";
    if (!child.hasAttribute("name"))
      throw InputError("a <" + tag + "> in " + where + " has no name attribute");
    const std::string name = child.getAttribute("name");
    const std::string key = key_path(path, name);
    if (std::find(names.begin(), names.end(), name) != names.end())
      throw InputError(std::string(tag == "ParameterList" ? "sublist" : "parameter") + " '" + key +
                       "' is given twice" + lines_naming(text, name) + " in " + where + ": give each key once");
    names.push_back(name);
    if (tag == "ParameterList") {
      check_tree(child, key, text);
      continue;
    }
    if (!child.hasAttribute("type")) throw InputError("parameter '" + key + "' has no type attribute");
    if (!child.hasAttribute("value")) throw InputError("parameter '" + key + "' has no value attribute");
    const std::string type = child.getAttribute("type");
    if (type != "double" && type != "int" && type != "bool" && type != "string")
      throw InputError("parameter '" + key + "': type '" + shorten(type) + "' is not one of double, int, bool, string");
    check_literal(key, child.getAttribute("type"), child.getAttribute("value"));
  }
}

}  // namespace

ParameterList read_xml_string(const std::string& xml, const std::string& origin)
{
  try {
    check_xml_bounds(xml);
    const Teuchos::XMLObject root = Teuchos::StringInputSource(xml).getObject();
    check_tree(root, "", xml);
    return Teuchos::XMLParameterListReader().toParameterList(root);
  } catch (const InputError& error) {
    throw InputError("in " + origin + ": " + error.what());
  } catch (const std::exception& error) {
    std::string message = error.what();
    const auto cut = message.find_last_of('\n', message.size() > 1 ? message.size() - 2 : 0);
    throw InputError("cannot read parameter list from " + origin + ": " +
                     (cut == std::string::npos ? message : message.substr(cut + 1)));
  }
}

ParameterList read_xml_file(const std::string& file_name)
{
  std::ifstream file(file_name);
  if (!file) throw InputError("cannot open input file '" + file_name + "' (missing or unreadable)");
  // At most one byte past the bound is read (a device or a pipe that never ends is refused like a large file).
  const std::size_t limit = XmlBounds().bytes + 1;
  std::string content(limit, '\0');
  file.read(content.data(), static_cast<std::streamsize>(limit));
  if (file.bad()) throw InputError("cannot read input file '" + file_name + "'");
  content.resize(static_cast<std::size_t>(file.gcount()));
  return read_xml_string(content, "file '" + file_name + "'");
}

namespace {

ParameterList values_only(const ParameterList& list)
{
  ParameterList copy(list.name());
  for (auto it = list.begin(); it != list.end(); ++it) {
    const auto& entry = list.entry(it);
    if (entry.isList()) copy.set(list.name(it), values_only(list.sublist(list.name(it))));
    else copy.setEntry(list.name(it), Teuchos::ParameterEntry(entry.getAny(false)));
  }
  return copy;
}

}  // namespace

void write_xml_file(const ParameterList& list, const std::string& file_name)
{
  // Written through a string and checked: a full disk is an error naming the file, not a truncated scene.
  std::ostringstream text;
  Teuchos::XMLParameterListWriter writer;
  text << writer.toXML(values_only(list));
  errno = 0;
  std::ofstream out(file_name);
  out << text.str();
  out.close();
  if (!out)
    throw std::runtime_error("cannot write '" + file_name + "': " + (errno != 0 ? std::strerror(errno) : "the write failed"));
}

void fail(const std::string& key, double value, const std::string& message)
{
  throw InputError("parameter '" + key + "' = " + format_number(value) + ": " + message);
}

}  // namespace spatula::parameters
