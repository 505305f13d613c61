#pragma once
// The parametric gecko spatula of Sauer & Holl (paper Sec. 2, Appendix A, Tables 1-2; docs/geometry.md).
//
// Twelve parameters (Table 2) fix the reference points P1..P15 (Table 1) and four parts: P_I the shaft and rim
// (a half elliptic cylinder swept along the axis P1..P7), P_II the outer pad band, P_III the prism {P2, P3, P12}
// and P_IV the thin pad. Only the half Y >= 0 is described. The construction rules the paper leaves open are
// stated here and in docs/geometry.md; lengths are in nanometres.
#include <Teuchos_ParameterList.hpp>

#include <array>
#include <cmath>

namespace spatula::geometry {

struct Vec2 {
  double x = 0.0, y = 0.0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }
inline Vec2 lerp(Vec2 a, Vec2 b, double t) { return a + t * (b - a); }

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

// The twelve geometric parameters of Table 2 (nm).
struct ShapeParameters {
  double a_s = 25.0, b_s = 45.0, c_s = 60.0, l_s = 650.0;   // shaft
  double l_p = 350.0, h_p = 10.0, h_r = 20.0, w_p = 250.0;  // pad
  double r1 = 50.0, r2 = 30.0, r3 = 55.0, r4 = 25.0;        // corner radii

  // Declares the twelve keys (Table 2 defaults, all positive) into the "Geometry" sublist.
  static void declare(Teuchos::ParameterList& geometry);
  // Reads a validated "Geometry" sublist.
  static ShapeParameters from(const Teuchos::ParameterList& geometry);
};

// One of the five pieces of the rim axis from P2 to P7, shared by P_I (its sweep) and by the pad parts that
// meet it, so both sides of an interface use the very same points.
enum class RimPiece { p2_p3 = 0, p3_p4, p4_p5, arc_p5_p6, p6_p7 };
constexpr int rim_piece_count = 5;

// The elliptic cross-section of P_I at one point of its axis: it lies in the vertical plane spanned by e_z and
// the horizontal unit vector `b_direction` (perpendicular to the axis, pointing away from the pad interior).
struct CrossSection {
  Vec3 centre;
  double a = 0.0;   // vertical half-width
  double b = 0.0;   // horizontal half-width
  Vec2 b_direction;
};

class SpatulaShape {
public:
  // Derives r5, theta_s and P1..P15; throws parameters::InputError naming the keys if the parameters do not
  // describe a spatula (e.g. radii that do not fit, h_r < h_p).
  explicit SpatulaShape(const ShapeParameters& parameters);

  const ShapeParameters& parameters() const { return parameters_; }
  double r5() const { return r5_; }            // radius of the rim's top curve in the X-Z plane
  double theta_s() const { return theta_s_; }  // shaft inclination [rad]

  // Reference point P1..P15 (1-based as in Table 1). P13, P14 have z = 0 (the paper gives none); P15 y = 0.
  Vec3 point(int index) const;

  // Rim half-height a(X) = z15 - sqrt(r5^2 - (X - l_p)^2) for 0 <= X <= l_p (a(0) = a_s, a(l_p) = h_r/2).
  double rim_half_height(double x) const;

  // Rim axis in the X-Y plane: piece, and sigma in [0, 1] along it (arc-length uniform on every piece).
  Vec2 rim_axis(RimPiece piece, double sigma) const;
  // P_I cross-section along the shaft (sigma in [0,1] from P1 to P2) and along the rim pieces.
  CrossSection shaft_section(double sigma) const;
  CrossSection rim_section(RimPiece piece, double sigma) const;

  // The outer pad band P_II, parametrized by a piece (p3_p4 .. p6_p7, plus p2_p3 standing for its edge
  // P12 -> P3 against P_III), sigma along it and t across it: t = 0 on the outer edge (P12-P3, then the rim
  // axis), t = 1 on the inner boundary P11..P8 with P_IV. Transverse lines are rays from P14 (first two
  // pieces), straight (P4P5 to P10P9), rays from P13 (arc) and lines of constant Y (tip).
  Vec2 band_point(RimPiece piece, double sigma, double t) const;
  // Top height of P_II there: h_p + (2 a(X) - h_p) (1 + cos(pi s)) / 2, where s = t, except in the corner
  // pieces, where s = clamp((r3 - |x - P14|) / (r3 - r4)) so the corner {P3, P4, P12} keeps the rim height 2a.
  double band_height(RimPiece piece, double sigma, double t) const;

  // Top height of the prism P_III (2a(X)) and of the thin pad P_IV (h_p).
  double prism_height(double x) const { return 2.0 * rim_half_height(x); }
  double thin_pad_height() const { return parameters_.h_p; }

  // Exact area of the pad's contact surface (bottom of P_II, P_III, P_IV) of the half spatula.
  double half_contact_area() const;

private:
  Vec2 band_inner(RimPiece piece, double sigma) const;
  double rim_b_angle(RimPiece piece, double sigma) const;

  ShapeParameters parameters_;
  double r5_ = 0.0, z15_ = 0.0, theta_s_ = 0.0;
  double psi_ = 0.0;   // angle of the straight rim line P2-P5 with the X axis
  Vec2 p2_, p3_, p4_, p5_, p6_, p7_, p8_, p9_, p10_, p11_, p12_, p13_, p14_, p6_inner_;
  Vec3 p1_;
  double phi5_ = 0.0;   // angle of P5 about P13
};

}  // namespace spatula::geometry
