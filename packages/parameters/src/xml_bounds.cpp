#include "parameters/xml_bounds.hpp"

#include "parameters/parameter_validation.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

namespace spatula::parameters {

namespace {

// A cursor over the text that knows its line, for messages.
class Scanner {
public:
  explicit Scanner(const std::string& text) : text_(text) {}
  bool done() const { return at_ >= text_.size(); }
  bool starts(const char* prefix) const { return text_.compare(at_, std::char_traits<char>::length(prefix), prefix) == 0; }
  char peek() const { return text_[at_]; }
  void advance(std::size_t count = 1) { at_ = std::min(text_.size(), at_ + count); }
  // Moves past the next `end`; false if the text ends first.
  bool skip_past(const char* end)
  {
    const auto found = text_.find(end, at_);
    if (found == std::string::npos) return false;
    at_ = found + std::char_traits<char>::length(end);
    return true;
  }
  std::size_t position() const { return at_; }
  std::string text(std::size_t from, std::size_t length) const { return text_.substr(from, length); }
  long line_of(std::size_t position) const
  {
    return 1 + std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(position), '\n');
  }

private:
  const std::string& text_;
  std::size_t at_ = 0;
};

[[noreturn]] void refuse(const Scanner& scanner, std::size_t position, const std::string& what)
{
  throw InputError("line " + std::to_string(scanner.line_of(position)) + ": " + what +
                   " (a bound of scene files, far beyond any real scene)");
}

// A start tag's attributes, from after its name to its '>' (the scanner is left past it): whether the element closes
// itself ("/>"), and its name attribute. A value longer than the bound is refused with the key it belongs to
// (`path` and the element's name, where the name comes first).
struct StartTag {
  bool closed = false;
  std::string name;
};

StartTag scan_attributes(Scanner& scanner, const std::string& path, const XmlBounds& bounds)
{
  StartTag tag;
  std::string attribute;   // the name of the attribute whose value comes next
  while (!scanner.done()) {
    const char c = scanner.peek();
    if (c == '>') {
      scanner.advance();
      return tag;
    }
    if (c == '/' && scanner.starts("/>")) {
      scanner.advance(2);
      tag.closed = true;
      return tag;
    }
    if (c == '"' || c == '\'') {
      const std::size_t opened = scanner.position();
      scanner.advance();
      const char quote[2] = {c, '\0'};
      if (!scanner.skip_past(quote)) return tag;   // unterminated: the parser reports it
      const std::size_t length = scanner.position() - opened - 2;
      if (length > bounds.value_length) {
        const std::string owner =
            tag.name.empty() ? std::string("an attribute value") : "parameter '" + key_path(path, tag.name) + "': a value";
        refuse(scanner, opened, owner + " of " + std::to_string(length) + " characters (at most " +
                                    std::to_string(bounds.value_length) + ")");
      }
      while (!attribute.empty() && attribute.back() == ' ') attribute.pop_back();
      if (attribute == "name") tag.name = scanner.text(opened + 1, length);
      attribute.clear();
      continue;
    }
    // An attribute's name: the run of name characters before its '='; any other character starts a new one.
    const bool name_character = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '-';
    if (name_character && (attribute.empty() || attribute.back() != ' ')) attribute += c;
    else if (name_character) attribute = std::string(1, c);
    else if (c != '=' && !attribute.empty()) attribute += ' ';   // ended: the next name character starts anew
    scanner.advance();
  }
  return tag;
}

}  // namespace

void check_xml_bounds(const std::string& xml, const XmlBounds& bounds)
{
  if (xml.size() > bounds.bytes)
    throw InputError("the file has " + std::to_string(xml.size()) + " bytes (at most " + std::to_string(bounds.bytes) +
                     ", a bound of scene files, far beyond any real scene)");
  Scanner scanner(xml);
  std::vector<std::string> names;   // the name attributes of the open elements, the root's first
  int elements = 0;
  auto path = [&] {
    std::string joined;
    for (std::size_t k = 1; k < names.size(); ++k) joined = key_path(joined, names[k]);
    return joined;
  };
  auto where = [&] { return names.size() > 1 ? " in '" + shorten(path()) + "'" : std::string(); };
  while (!scanner.done()) {
    if (scanner.peek() != '<') {
      scanner.advance();
      continue;
    }
    const std::size_t tag = scanner.position();
    if (scanner.starts("<!--")) {
      if (!scanner.skip_past("-->")) return;
    } else if (scanner.starts("<![CDATA[")) {
      if (!scanner.skip_past("]]>")) return;
    } else if (scanner.starts("<?") || scanner.starts("<!")) {
      if (!scanner.skip_past(">")) return;
    } else if (scanner.starts("</")) {
      if (!names.empty()) names.pop_back();
      if (!scanner.skip_past(">")) return;
    } else {
      scanner.advance();
      if (++elements > bounds.elements)
        refuse(scanner, tag, "more than " + std::to_string(bounds.elements) + " elements" + where());
      const StartTag start = scan_attributes(scanner, path(), bounds);
      if (start.closed) continue;
      names.push_back(start.name);
      if (static_cast<int>(names.size()) > bounds.depth)
        refuse(scanner, tag, "elements nested more than " + std::to_string(bounds.depth) + " deep" + where());
    }
  }
}

}  // namespace spatula::parameters
