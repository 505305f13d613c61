// Validation turns every kind of bad input into an InputError that names the key, the value and what is allowed.
#include "parameters/parameter_validation.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

using namespace spatula::parameters;

namespace {

ParameterList valid_list()
{
  ParameterList valid;
  auto& geometry = declare_sublist(valid, "Geometry", "shape");
  declare_double(geometry, "l_p", 350.0, "pad length", Range::positive());
  declare_int(valid.sublist("Mesh"), "refinement factor", 1, "factor", Range::closed(1, 64));
  declare_string(valid.sublist("Mesh"), "level", "coarse", "level", {"coarse", "medium", "fine"});
  declare_bool(valid, "write output", true, "write files");
  return valid;
}

std::string error_of(const std::string& xml)
{
  try {
    auto user = read_xml_string(xml);
    validate(user, valid_list());
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

void expect_contains(const std::string& text, const std::string& part)
{
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

}  // namespace

TEST(ParameterValidation, DefaultsAreFilledIn)
{
  auto user = read_xml_string(R"(<ParameterList><ParameterList name="Mesh">
      <Parameter name="level" type="string" value="fine"/></ParameterList></ParameterList>)");
  validate(user, valid_list());
  EXPECT_EQ(user.sublist("Mesh").get<std::string>("level"), "fine");
  EXPECT_EQ(user.sublist("Mesh").get<int>("refinement factor"), 1);
  EXPECT_DOUBLE_EQ(user.sublist("Geometry").get<double>("l_p"), 350.0);
  EXPECT_TRUE(user.get<bool>("write output"));
}

TEST(ParameterValidation, IntegerGivenForARealIsAccepted)
{
  auto user = read_xml_string(R"(<ParameterList><ParameterList name="Geometry">
      <Parameter name="l_p" type="int" value="420"/></ParameterList></ParameterList>)");
  validate(user, valid_list());
  EXPECT_DOUBLE_EQ(user.sublist("Geometry").get<double>("l_p"), 420.0);
}

TEST(ParameterValidation, UnknownKeyNamesKeyAndAllowedKeys)
{
  const auto message = error_of(R"(<ParameterList><ParameterList name="Geometry">
      <Parameter name="l_q" type="double" value="1"/></ParameterList></ParameterList>)");
  expect_contains(message, "unknown parameter 'Geometry/l_q'");
  expect_contains(message, "l_p");
}

TEST(ParameterValidation, OutOfRangeNamesValueAndRange)
{
  const auto message = error_of(R"(<ParameterList><ParameterList name="Geometry">
      <Parameter name="l_p" type="double" value="-5"/></ParameterList></ParameterList>)");
  expect_contains(message, "'Geometry/l_p' = -5");
  expect_contains(message, "(0, inf)");
  expect_contains(error_of(R"(<ParameterList><ParameterList name="Mesh">
      <Parameter name="refinement factor" type="int" value="0"/></ParameterList></ParameterList>)"),
                  "[1, 64]");
}

TEST(ParameterValidation, WrongTypeNamesExpectedType)
{
  const auto message = error_of(R"(<ParameterList><ParameterList name="Geometry">
      <Parameter name="l_p" type="string" value="long"/></ParameterList></ParameterList>)");
  expect_contains(message, "'Geometry/l_p': expected double");
  expect_contains(message, "long");
}

TEST(ParameterValidation, StringOutsideAllowedListNamesChoices)
{
  const auto message = error_of(R"(<ParameterList><ParameterList name="Mesh">
      <Parameter name="level" type="string" value="ultra"/></ParameterList></ParameterList>)");
  expect_contains(message, "'Mesh/level' = 'ultra'");
  expect_contains(message, "coarse, medium, fine");
}

TEST(ParameterValidation, ValueWhereSublistExpected)
{
  expect_contains(error_of(R"(<ParameterList><Parameter name="Geometry" type="int" value="1"/></ParameterList>)"),
                  "'Geometry' must be a sublist");
}

TEST(ParameterValidation, MalformedXmlAndUnparsableNumbers)
{
  expect_contains(error_of("<ParameterList><ParameterList name=\"Mesh\">"), "cannot read parameter list");
  expect_contains(error_of(R"(<ParameterList><ParameterList name="Geometry">
      <Parameter name="l_p" type="double" value="abc"/></ParameterList></ParameterList>)"),
                  "'Geometry/l_p': value 'abc' is not a valid double");
}

TEST(ParameterValidation, RepeatedKeysAndSublistsAreErrorsNotOverrides)
{
  expect_contains(error_of(R"(<ParameterList><ParameterList name="Geometry">
      <Parameter name="l_p" type="double" value="300"/>
      <Parameter name="l_p" type="double" value="200"/></ParameterList></ParameterList>)"),
                  "parameter 'Geometry/l_p' is given twice (lines 2, 3)");
  expect_contains(error_of(R"(<ParameterList><ParameterList name="Mesh"></ParameterList>
      <ParameterList name="Mesh"></ParameterList></ParameterList>)"),
                  "sublist 'Mesh' is given twice");
}

TEST(ParameterValidation, IntegersBeyondIntAreNotWrapped)
{
  auto mesh = [](const std::string& value) {
    return error_of(R"(<ParameterList><ParameterList name="Mesh"><Parameter name="refinement factor" type="int" value=")" +
                    value + R"("/></ParameterList></ParameterList>)");
  };
  expect_contains(mesh("4294967298"), "'Mesh/refinement factor': value '4294967298' is outside the range of int");
  expect_contains(mesh("2147483648"), "is outside the range of int");
  expect_contains(mesh("-2147483649"), "is outside the range of int");
  expect_contains(mesh("2147483647"), "'Mesh/refinement factor' = 2147483647 is out of range");   // an int, too big
  expect_contains(mesh("1.5"), "is not a valid int");
}

TEST(ParameterValidation, MissingValuesAndNonFiniteNumbersNameTheKey)
{
  auto geometry = [](const std::string& attributes) {
    return error_of(R"(<ParameterList><ParameterList name="Geometry"><Parameter name="l_p" )" + attributes +
                    R"(/></ParameterList></ParameterList>)");
  };
  expect_contains(geometry(R"(type="double")"), "parameter 'Geometry/l_p' has no value attribute");
  expect_contains(geometry(R"(value="3")"), "parameter 'Geometry/l_p' has no type attribute");
  for (const char* value : {"nan", "NaN", "inf", "-inf"})
    expect_contains(geometry(std::string(R"(type="double" value=")") + value + "\""), "is not a finite number");
  expect_contains(geometry(R"(type="double" value="1e999")"), "'Geometry/l_p': value '1e999' is not a valid double");
  expect_contains(geometry(R"(type="double" value="")"), "'Geometry/l_p': value '' is not a valid double");
  const std::string huge(4000, 'x');   // within the bound on a value's length (xml_bounds.hpp)
  const auto message = error_of(R"(<ParameterList><ParameterList name="Mesh"><Parameter name="level" type="string" value=")" +
                                huge + R"("/></ParameterList></ParameterList>)");
  expect_contains(message, "'Mesh/level' = 'xxx");
  EXPECT_LT(message.size(), 400u);   // the value is shortened in the message
}

TEST(ParameterValidation, MissingFileIsNamed)
{
  try {
    read_xml_file("/nonexistent/scene.xml");
    FAIL() << "no error";
  } catch (const InputError& error) {
    expect_contains(error.what(), "/nonexistent/scene.xml");
  }
}

TEST(ParameterValidation, RangeDescriptions)
{
  EXPECT_EQ(Range::positive().describe(), "(0, inf)");
  EXPECT_EQ(Range::closed(1, 64).describe(), "[1, 64]");
  EXPECT_FALSE(Range::positive().contains(0.0));
  EXPECT_TRUE(Range::non_negative().contains(0.0));
}
