#pragma once
// Bounds on a scene file, checked on its text before the XML parser sees it: the parser recurses once per nested
// element and keeps the whole tree, so a hostile file (sublists nested 20,000 deep, a gigabyte of parameters)
// would overflow its stack or exhaust memory. Each bound is far beyond any real scene (the paper's scenes nest 4
// deep, hold about 100 parameters and fit in 10 kB).
#include <cstddef>
#include <string>

namespace spatula::parameters {

struct XmlBounds {
  std::size_t bytes = 1 << 20;      // file size
  int depth = 32;                   // nested elements, the root included
  int elements = 10000;             // elements (parameters and lists) in the file
  std::size_t value_length = 4096;  // characters of one attribute value (a path: at most 4,000 are used)
};

// Throws InputError naming the line, the bound exceeded and its limit. Reads only the markup's shape
// (tags, quoted attribute values, comments, processing instructions, CDATA); whether the XML is well formed is
// the parser's to say.
void check_xml_bounds(const std::string& xml, const XmlBounds& bounds = {});

}  // namespace spatula::parameters
