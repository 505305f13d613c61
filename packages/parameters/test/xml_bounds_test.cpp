#include "parameters/parameter_validation.hpp"
#include "parameters/xml_bounds.hpp"

#include <gtest/gtest.h>

#include <string>

namespace {

using spatula::parameters::check_xml_bounds;
using spatula::parameters::InputError;
using spatula::parameters::XmlBounds;

std::string nested(int depth)
{
  std::string text;
  for (int k = 0; k < depth; ++k) text += "<ParameterList name=\"l" + std::to_string(k) + "\">";
  for (int k = 0; k < depth; ++k) text += "</ParameterList>";
  return text;
}

std::string message_of(const std::string& xml, const XmlBounds& bounds = {})
{
  try {
    check_xml_bounds(xml, bounds);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(XmlBounds, DepthUpToTheBoundPassesOneMoreIsRefusedWithItsPlace)
{
  EXPECT_EQ(message_of(nested(32)), "");
  const std::string refused = message_of("<?xml version=\"1.0\"?>\n" + nested(33));
  EXPECT_NE(refused.find("line 2: elements nested more than 32 deep in 'l1/l2/"), std::string::npos) << refused;
  // Self-closing elements and comments do not nest; a comment's '<' is not a tag.
  EXPECT_EQ(message_of("<a><!-- <b><b><b> --><c/><c/><d><![CDATA[<e><e>]]></d></a>", {1 << 20, 2, 100, 100}), "");
}

TEST(XmlBounds, SizeCountAndValueLength)
{
  EXPECT_NE(message_of(std::string(2000, ' '), {1000, 32, 100, 100}).find("the file has 2000 bytes (at most 1000"),
            std::string::npos);
  std::string many = "<ParameterList><ParameterList name=\"top\">";   // the root, a sublist and five parameters
  for (int k = 0; k < 5; ++k) many += "<Parameter name=\"p\" type=\"int\" value=\"1\"/>";
  many += "</ParameterList></ParameterList>";
  EXPECT_EQ(message_of(many, {1 << 20, 32, 7, 100}), "");
  EXPECT_NE(message_of(many, {1 << 20, 32, 6, 100}).find("more than 6 elements in 'top'"), std::string::npos);
  const std::string long_value = "<ParameterList><ParameterList name=\"Output\"><Parameter name=\"directory\" "
                                 "type=\"string\" value='" + std::string(101, 'x') + "'/></ParameterList></ParameterList>";
  EXPECT_NE(message_of(long_value, {1 << 20, 32, 100, 100}).find("parameter 'Output/directory': a value of 101 characters (at most 100)"),
            std::string::npos) << message_of(long_value, {1 << 20, 32, 100, 100});
  EXPECT_EQ(message_of(long_value, {1 << 20, 32, 100, 101}), "");
}

TEST(XmlBounds, ReadingAFileThatNestsTooDeepIsAnInputErrorNotACrash)
{
  EXPECT_THROW(spatula::parameters::read_xml_string("<ParameterList>" + nested(20000) + "</ParameterList>"), InputError);
}

}  // namespace
