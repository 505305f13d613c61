// The default parameters reproduce the paper's Table 1 and derived values; the relations between Table 1's points
// and Table 2's radii hold (docs/geometry.md).
#include "parameters/parameter_validation.hpp"
#include "geometry/spatula_shape.hpp"

#include <gtest/gtest.h>

using namespace spatula::geometry;

namespace {

constexpr double pi = 3.14159265358979323846;

double distance(Vec3 a, Vec3 b) { return std::hypot(a.x - b.x, a.y - b.y); }   // in the X-Y plane

struct TablePoint {
  int index;
  double x, y, z;   // NaN where Table 1 gives no value
};
constexpr double none = std::numeric_limits<double>::quiet_NaN();
const TablePoint table1[] = {
    {1, -647.6, 0.0, 80.6}, {2, 0.0, 0.0, 25.0},   {3, 83.8, 36.2, 18.7},  {4, 117.0, 50.5, 16.6},
    {5, 280.2, 120.9, 10.6}, {6, 350.0, 75.0, 10.0}, {7, 350.0, 0.0, 20.0},  {8, 330.0, 0.0, 10.0},
    {9, 288.1, 102.5, 10.0}, {10, 128.9, 23.0, 10.0}, {11, 113.8, 0.0, 10.0}, {12, 83.8, 0.0, 37.3},
    {13, 300.0, 75.0, none}, {14, 138.8, 0.0, none}, {15, 350.0, none, 4091.0}};

}  // namespace

TEST(SpatulaShape, DefaultsReproduceTable1ToATenthOfANanometre)
{
  const SpatulaShape shape(ShapeParameters{});
  for (const auto& expected : table1) {
    const Vec3 p = shape.point(expected.index);
    SCOPED_TRACE("P" + std::to_string(expected.index));
    EXPECT_NEAR(p.x, expected.x, 0.05 + 1e-9);
    if (!std::isnan(expected.y)) {
      EXPECT_NEAR(p.y, expected.y, 0.05 + 1e-9);
    }
    // P15's Z is r5 + h_r/2: Table 1 rounds it with the paper's r5 = 4081 (see docs/geometry.md).
    if (!std::isnan(expected.z) && expected.index != 15) {
      EXPECT_NEAR(p.z, expected.z, 0.05 + 1e-9);
    }
  }
}

TEST(SpatulaShape, DerivedRadiusAndShaftInclination)
{
  const SpatulaShape shape(ShapeParameters{});
  EXPECT_NEAR(shape.r5(), 4081.0, 0.003 * 4081.0);
  EXPECT_NEAR(shape.r5(), 122725.0 / 30.0, 1e-9);   // (l_p^2 + (a_s - h_r/2)^2) / (2 (a_s - h_r/2))
  EXPECT_NEAR(shape.theta_s() * 180.0 / pi, 4.91, 0.005);
  EXPECT_NEAR(shape.point(15).z, 4091.0, 10.0);
}

TEST(SpatulaShape, ConsistencyRelationsOfModelSection1)
{
  const ShapeParameters p;
  const SpatulaShape shape(p);
  auto P = [&](int i) { return shape.point(i); };
  EXPECT_NEAR(distance(P(13), P(5)), p.r1, 1e-9);
  EXPECT_NEAR(distance(P(13), P(6)), p.r1, 1e-9);
  EXPECT_NEAR(distance(P(13), P(9)), p.r2, 1e-9);
  EXPECT_NEAR(distance(P(14), P(4)), p.r3, 1e-9);
  EXPECT_NEAR(distance(P(14), P(10)), p.r4, 1e-9);
  EXPECT_NEAR(distance(P(14), P(11)), p.r4, 1e-9);
  // P2..P5 on one straight line in X-Y.
  for (int i : {3, 4}) {
    const double cross = P(i).x * P(5).y - P(i).y * P(5).x;
    EXPECT_NEAR(cross / (std::hypot(P(i).x, P(i).y) * std::hypot(P(5).x, P(5).y)), 0.0, 1e-12);
  }
  // a(X) at the points of the rim axis.
  EXPECT_NEAR(shape.rim_half_height(0.0), p.a_s, 1e-9);
  EXPECT_NEAR(shape.rim_half_height(P(3).x), 18.7, 0.05);
  EXPECT_NEAR(shape.rim_half_height(P(4).x), 16.6, 0.05);
  EXPECT_NEAR(shape.rim_half_height(P(5).x), 10.6, 0.05);
  EXPECT_NEAR(shape.rim_half_height(p.l_p), 0.5 * p.h_r, 1e-9);
  // tan(theta_s) = (Z1 - Z2) / (X2 - X1), and the shaft axis is l_s long.
  EXPECT_NEAR(std::tan(shape.theta_s()), (P(1).z - P(2).z) / (P(2).x - P(1).x), 1e-12);
  EXPECT_NEAR(std::hypot(P(1).x - P(2).x, P(1).z - P(2).z), p.l_s, 1e-9);
  // P12 is the top of the rim/shaft junction on the symmetry plane: Z = 2a.
  EXPECT_NEAR(P(12).z, 2.0 * shape.rim_half_height(P(12).x), 1e-12);
}

TEST(SpatulaShape, RimSectionsAreContinuousAlongTheAxis)
{
  const SpatulaShape shape(ShapeParameters{});
  for (int piece = 0; piece + 1 < rim_piece_count; ++piece) {
    const auto end = shape.rim_section(RimPiece(piece), 1.0);
    const auto start = shape.rim_section(RimPiece(piece + 1), 0.0);
    EXPECT_NEAR(end.centre.x, start.centre.x, 1e-9);
    EXPECT_NEAR(end.centre.y, start.centre.y, 1e-9);
    EXPECT_NEAR(end.b, start.b, 1e-9);
    EXPECT_NEAR(end.b_direction.x, start.b_direction.x, 1e-12);
    EXPECT_NEAR(end.b_direction.y, start.b_direction.y, 1e-12);
  }
  const auto shaft_end = shape.shaft_section(1.0);
  const auto rim_start = shape.rim_section(RimPiece::p2_p3, 0.0);
  EXPECT_NEAR(shaft_end.centre.z, rim_start.centre.z, 1e-9);
  EXPECT_NEAR(shaft_end.b, rim_start.b, 1e-9);
  EXPECT_NEAR(shaft_end.b_direction.x, rim_start.b_direction.x, 1e-12);
  // b is perpendicular to the axis on the rim (here P4-P5).
  const auto section = shape.rim_section(RimPiece::p4_p5, 0.5);
  const Vec2 along = shape.rim_axis(RimPiece::p4_p5, 1.0) - shape.rim_axis(RimPiece::p4_p5, 0.0);
  EXPECT_NEAR(dot(section.b_direction, along), 0.0, 1e-9);
  // The end face is the disc of radius c_s about P1.
  const auto face = shape.shaft_section(0.0);
  EXPECT_DOUBLE_EQ(face.a, 60.0);
  EXPECT_DOUBLE_EQ(face.b, 60.0);
}

TEST(SpatulaShape, BandHeightFallsFromRimToPadWithZeroSlopeAtTheInnerBoundary)
{
  const SpatulaShape shape(ShapeParameters{});
  for (int piece = 1; piece < rim_piece_count; ++piece) {
    const auto rim_piece = RimPiece(piece);
    const Vec2 outer = shape.band_point(rim_piece, 0.4, 0.0);
    EXPECT_NEAR(shape.band_height(rim_piece, 0.4, 0.0), 2.0 * shape.rim_half_height(outer.x), 1e-9);
    EXPECT_NEAR(shape.band_height(rim_piece, 0.4, 1.0), 10.0, 1e-9);
    const double slope = (shape.band_height(rim_piece, 0.4, 1.0) - shape.band_height(rim_piece, 0.4, 1.0 - 1e-4));
    EXPECT_LT(std::abs(slope), 1e-5);
  }
  // The corner {P3, P4, P12} keeps the rim height: at P3 (outer end of the P12-P3 edge) height is 2a.
  EXPECT_NEAR(shape.band_height(RimPiece::p2_p3, 1.0, 0.0), 2.0 * shape.rim_half_height(shape.point(3).x), 1e-9);
}

TEST(SpatulaShape, ExactContactArea)
{
  const SpatulaShape shape(ShapeParameters{});
  const double full = 2.0 * shape.half_contact_area();
  EXPECT_NEAR(full, 49524.0, 0.015 * 49524.0);
}

TEST(SpatulaShape, InvalidCombinationsNameTheKey)
{
  auto message_of = [](ShapeParameters p) {
    try {
      SpatulaShape shape(p);
    } catch (const spatula::parameters::InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  ShapeParameters p;
  p.h_r = 5.0;   // thinner rim than pad
  EXPECT_NE(message_of(p).find("Geometry/h_r"), std::string::npos) << message_of(p);
  p = {};
  p.r2 = 60.0;
  EXPECT_NE(message_of(p).find("Geometry/r2"), std::string::npos);
  p = {};
  p.r1 = 130.0;
  EXPECT_NE(message_of(p).find("Geometry/r1"), std::string::npos);
  p = {};
  p.r4 = 70.0;
  EXPECT_NE(message_of(p).find("Geometry/r4"), std::string::npos);
  p = {};
  p.a_s = 9.0;
  EXPECT_NE(message_of(p).find("Geometry/a_s"), std::string::npos);
  p = {};
  p.c_s = 100.0;
  EXPECT_NE(message_of(p).find("Geometry/c_s"), std::string::npos);
}
