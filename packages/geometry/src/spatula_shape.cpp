#include "geometry/spatula_shape.hpp"

#include "parameters/parameter_validation.hpp"

#include <algorithm>
#include <sstream>

namespace spatula::geometry {

namespace {

constexpr double pi = 3.14159265358979323846;

std::string number(double value)
{
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

}  // namespace

void ShapeParameters::declare(Teuchos::ParameterList& geometry)
{
  using parameters::declare_double;
  using parameters::Range;
  const ShapeParameters d;
  declare_double(geometry, "a_s", d.a_s, "vertical half-width of the shaft at P2 [nm]", Range::positive());
  declare_double(geometry, "b_s", d.b_s, "horizontal half-width of the shaft at P2 [nm]", Range::positive());
  declare_double(geometry, "c_s", d.c_s, "radius of the shaft end face at P1 [nm]", Range::positive());
  declare_double(geometry, "l_s", d.l_s, "shaft length along its axis, P1 to P2 [nm]", Range::positive());
  declare_double(geometry, "l_p", d.l_p, "pad length, X distance P2 to P7 [nm]", Range::positive());
  declare_double(geometry, "h_p", d.h_p, "pad thickness [nm]", Range::positive());
  declare_double(geometry, "h_r", d.h_r, "rim thickness at the tip, >= h_p [nm]", Range::positive());
  declare_double(geometry, "w_p", d.w_p, "pad width (Y diameter at P13) [nm]", Range::positive());
  declare_double(geometry, "r1", d.r1, "outer corner radius of the rim about P13 [nm]", Range::positive());
  declare_double(geometry, "r2", d.r2, "inner corner radius about P13, < r1 [nm]", Range::positive());
  declare_double(geometry, "r3", d.r3, "radius about P14 bounding the rim corner {P3,P4,P12} [nm]",
                 Range::positive());
  declare_double(geometry, "r4", d.r4, "radius about P14 of the thin pad's inner corner, < r3 [nm]",
                 Range::positive());
}

ShapeParameters ShapeParameters::from(const Teuchos::ParameterList& geometry)
{
  ShapeParameters p;
  p.a_s = geometry.get<double>("a_s");
  p.b_s = geometry.get<double>("b_s");
  p.c_s = geometry.get<double>("c_s");
  p.l_s = geometry.get<double>("l_s");
  p.l_p = geometry.get<double>("l_p");
  p.h_p = geometry.get<double>("h_p");
  p.h_r = geometry.get<double>("h_r");
  p.w_p = geometry.get<double>("w_p");
  p.r1 = geometry.get<double>("r1");
  p.r2 = geometry.get<double>("r2");
  p.r3 = geometry.get<double>("r3");
  p.r4 = geometry.get<double>("r4");
  return p;
}

SpatulaShape::SpatulaShape(const ShapeParameters& parameters) : parameters_(parameters)
{
  using parameters::fail;
  const auto& p = parameters_;

  if (p.h_r < p.h_p) fail("Geometry/h_r", p.h_r, "the rim must be at least as thick as the pad, h_p = " + number(p.h_p));
  // r5: the rim's top curve is a circle in the X-Z plane with a(0) = a_s, a(l_p) = h_r/2 and a horizontal
  // tangent at the tip (centre P15 above P7).
  const double drop = p.a_s - 0.5 * p.h_r;
  if (drop <= 0.0)
    fail("Geometry/a_s", p.a_s, "must exceed h_r/2 = " + number(0.5 * p.h_r) + " (the rim tapers from P2 to P7)");
  if (drop >= p.l_p) fail("Geometry/a_s", p.a_s, "a_s - h_r/2 must be smaller than l_p = " + number(p.l_p));
  r5_ = (p.l_p * p.l_p + drop * drop) / (2.0 * drop);
  z15_ = 0.5 * p.h_r + r5_;
  // theta_s: the shaft axis continues the rim's top curve with a continuous slope at P2.
  theta_s_ = std::asin(p.l_p / r5_);

  if (p.r1 >= p.l_p) fail("Geometry/r1", p.r1, "must be smaller than l_p = " + number(p.l_p));
  if (p.r1 >= 0.5 * p.w_p) fail("Geometry/r1", p.r1, "must be smaller than w_p/2 = " + number(0.5 * p.w_p));
  if (p.r2 >= p.r1) fail("Geometry/r2", p.r2, "must be smaller than r1 = " + number(p.r1));
  if (p.r4 >= p.r3) fail("Geometry/r4", p.r4, "must be smaller than r3 = " + number(p.r3));

  p2_ = {0.0, 0.0};
  p13_ = {p.l_p - p.r1, 0.5 * p.w_p - p.r1};
  p6_ = {p.l_p, p13_.y};
  p7_ = {p.l_p, 0.0};
  // The straight rim line from P2 is tangent to the corner arc r1 about P13 at P5.
  const double centre_distance = norm(p13_);
  psi_ = std::atan2(p13_.y, p13_.x) + std::asin(p.r1 / centre_distance);
  const Vec2 along{std::cos(psi_), std::sin(psi_)};
  const Vec2 outward{-std::sin(psi_), std::cos(psi_)};
  p5_ = std::sqrt(centre_distance * centre_distance - p.r1 * p.r1) * along;
  phi5_ = std::atan2(p5_.y - p13_.y, p5_.x - p13_.x);
  // P14 on the symmetry line, at distance r3 from the rim line; P4 is the touching point.
  p14_ = {p.r3 / std::sin(psi_), 0.0};
  p4_ = p14_ + p.r3 * outward;
  p12_ = {p14_.x - p.r3, 0.0};
  p3_ = {p12_.x, p12_.x * std::tan(psi_)};
  if (!(dot(p4_, along) < norm(p5_)))
    fail("Geometry/r3", p.r3, "the corner arc about P14 must touch the rim line before P5; make r3 smaller");
  // Inner boundary of the outer pad band (the thin pad's outline).
  p11_ = {p14_.x - p.r4, 0.0};
  p10_ = p14_ + p.r4 * outward;
  p9_ = p13_ + (p.r2 / p.r1) * (p5_ - p13_);
  p6_inner_ = {p.l_p - (p.r1 - p.r2), p13_.y};
  p8_ = {p6_inner_.x, 0.0};
  if (!(p10_.x < p9_.x && p11_.x < p8_.x))
    fail("Geometry/r4", p.r4, "the thin pad P8-P9-P10-P11 is empty or folded; check r2, r3, r4 against l_p and w_p");

  p1_ = {-p.l_s * std::cos(theta_s_), 0.0, p.a_s + p.l_s * std::sin(theta_s_)};
  if (p1_.z - p.c_s < 0.0)
    fail("Geometry/c_s", p.c_s,
         "the shaft end face would reach below the substrate (centre P1 at Z = " + number(p1_.z) + ")");
}

Vec3 SpatulaShape::point(int index) const
{
  auto flat = [](Vec2 q, double z) { return Vec3{q.x, q.y, z}; };
  switch (index) {
    case 1: return p1_;
    case 2: return flat(p2_, rim_half_height(p2_.x));
    case 3: return flat(p3_, rim_half_height(p3_.x));
    case 4: return flat(p4_, rim_half_height(p4_.x));
    case 5: return flat(p5_, rim_half_height(p5_.x));
    case 6: return flat(p6_, rim_half_height(p6_.x));
    case 7: return flat(p7_, 2.0 * rim_half_height(p7_.x));
    case 8: return flat(p8_, parameters_.h_p);
    case 9: return flat(p9_, parameters_.h_p);
    case 10: return flat(p10_, parameters_.h_p);
    case 11: return flat(p11_, parameters_.h_p);
    case 12: return flat(p12_, 2.0 * rim_half_height(p12_.x));
    case 13: return flat(p13_, 0.0);
    case 14: return flat(p14_, 0.0);
    case 15: return {parameters_.l_p, 0.0, z15_};
    default: throw std::out_of_range("spatula points are P1..P15, asked for P" + std::to_string(index));
  }
}

double SpatulaShape::rim_half_height(double x) const
{
  const double dx = x - parameters_.l_p;
  return z15_ - std::sqrt(r5_ * r5_ - dx * dx);
}

Vec2 SpatulaShape::rim_axis(RimPiece piece, double sigma) const
{
  switch (piece) {
    case RimPiece::p2_p3: return lerp(p2_, p3_, sigma);
    case RimPiece::p3_p4: return lerp(p3_, p4_, sigma);
    case RimPiece::p4_p5: return lerp(p4_, p5_, sigma);
    case RimPiece::arc_p5_p6: {
      const double phi = (1.0 - sigma) * phi5_;
      return p13_ + parameters_.r1 * Vec2{std::cos(phi), std::sin(phi)};
    }
    case RimPiece::p6_p7: return lerp(p6_, p7_, sigma);
  }
  return {};
}

// Angle beta of b_direction = (-sin beta, cos beta): 0 at P1, half the kink at P2, psi at P3, linear between.
double SpatulaShape::rim_b_angle(RimPiece piece, double sigma) const
{
  switch (piece) {
    case RimPiece::p2_p3: return 0.5 * psi_ * (1.0 + sigma);
    case RimPiece::p3_p4:
    case RimPiece::p4_p5: return psi_;
    case RimPiece::arc_p5_p6: return (1.0 - sigma) * phi5_ - 0.5 * pi;
    case RimPiece::p6_p7: return -0.5 * pi;
  }
  return 0.0;
}

CrossSection SpatulaShape::shaft_section(double sigma) const
{
  const auto& p = parameters_;
  const Vec3 p2{p2_.x, p2_.y, p.a_s};
  CrossSection section;
  section.centre = {p1_.x + sigma * (p2.x - p1_.x), 0.0, p1_.z + sigma * (p2.z - p1_.z)};
  section.a = p.c_s + sigma * (p.a_s - p.c_s);
  section.b = p.c_s + sigma * (p.b_s - p.c_s);
  const double beta = 0.5 * psi_ * sigma;
  section.b_direction = {-std::sin(beta), std::cos(beta)};
  return section;
}

CrossSection SpatulaShape::rim_section(RimPiece piece, double sigma) const
{
  const Vec2 axis = rim_axis(piece, sigma);
  CrossSection section;
  section.a = rim_half_height(axis.x);
  section.centre = {axis.x, axis.y, section.a};
  section.b = piece == RimPiece::p2_p3
                  ? parameters_.b_s + sigma * (rim_half_height(p3_.x) - parameters_.b_s)
                  : section.a;
  const double beta = rim_b_angle(piece, sigma);
  section.b_direction = {-std::sin(beta), std::cos(beta)};
  return section;
}

Vec2 SpatulaShape::band_inner(RimPiece piece, double sigma) const
{
  switch (piece) {
    case RimPiece::p2_p3:
    case RimPiece::p3_p4: {
      const Vec2 ray = band_point(piece, sigma, 0.0) - p14_;
      return p14_ + (parameters_.r4 / norm(ray)) * ray;
    }
    case RimPiece::p4_p5: return lerp(p10_, p9_, sigma);
    case RimPiece::arc_p5_p6: {
      const double phi = (1.0 - sigma) * phi5_;
      return p13_ + parameters_.r2 * Vec2{std::cos(phi), std::sin(phi)};
    }
    case RimPiece::p6_p7: return lerp(p6_inner_, p8_, sigma);
  }
  return {};
}

Vec2 SpatulaShape::band_point(RimPiece piece, double sigma, double t) const
{
  const Vec2 outer = piece == RimPiece::p2_p3 ? lerp(p12_, p3_, sigma) : rim_axis(piece, sigma);
  if (t == 0.0) return outer;
  return lerp(outer, band_inner(piece, sigma), t);
}

double SpatulaShape::band_height(RimPiece piece, double sigma, double t) const
{
  const auto& p = parameters_;
  const Vec2 x = band_point(piece, sigma, t);
  double s = t;
  if (piece == RimPiece::p2_p3 || piece == RimPiece::p3_p4)
    s = std::clamp((p.r3 - norm(x - p14_)) / (p.r3 - p.r4), 0.0, 1.0);
  return p.h_p + (2.0 * rim_half_height(x.x) - p.h_p) * 0.5 * (1.0 + std::cos(pi * s));
}

double SpatulaShape::half_contact_area() const
{
  // Polygon P2, P5, P6, P7 (shoelace) plus the circular segment between chord P5-P6 and the arc r1.
  const Vec2 polygon[] = {p2_, p5_, p6_, p7_};
  double twice_area = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % 4];
    twice_area += a.x * b.y - b.x * a.y;
  }
  const double r = parameters_.r1;
  const double segment = 0.5 * r * r * (phi5_ - std::sin(phi5_));
  return 0.5 * std::abs(twice_area) + segment;
}

}  // namespace spatula::geometry
