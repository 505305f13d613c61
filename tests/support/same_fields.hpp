#pragma once
// expect_same_fields(a, b, &Struct::first, &Struct::second, ...): EXPECT_EQ on each named field of two structs,
// failures numbered by the field's place in the list (the defaults tests: a parameter list read back against a
// default-constructed struct).
#include <gtest/gtest.h>

template <class Struct, class... Fields>
void expect_same_fields(const Struct& a, const Struct& b, Fields... fields)
{
  auto check = [&](auto field, int place) { EXPECT_EQ(a.*field, b.*field) << "field " << place << " of the list"; };
  int place = 0;
  (check(fields, ++place), ...);
}
