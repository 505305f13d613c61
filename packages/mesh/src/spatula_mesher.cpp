#include "mesh/spatula_mesher.hpp"

#include "mesh/mesh_choice.hpp"
#include "parameters/parameter_validation.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace spatula::mesh {

using geometry::CrossSection;
using geometry::RimPiece;
using geometry::SpatulaShape;
using geometry::Vec2;
using Flags = HexMeshBuilder::Flags;

const std::vector<MeshLevel>& mesh_levels()
{
  static const std::vector<MeshLevel> levels = {{"coarse", 1, 4}, {"medium", 4, 4}, {"fine", 8, 10}};
  return levels;
}

namespace {

const MeshLevel& find_level(const std::string& name)
{
  for (const auto& level : mesh_levels())
    if (name == level.name) return level;
  throw parameters::InputError("mesh level '" + name + "' is not one of coarse, medium, fine");
}

}  // namespace

int MeshParameters::in_plane_factor() const { return find_level(level).in_plane_factor * refinement_factor; }
int MeshParameters::layer_count() const { return layers > 0 ? layers : find_level(level).layers; }

const std::vector<std::string>& MeshParameters::section_names()
{
  static const std::vector<std::string> names = {"inscribed", "equal area"};
  return names;
}

void MeshParameters::declare(Teuchos::ParameterList& mesh)
{
  const MeshParameters d;   // the defaults
  std::vector<std::string> names;
  for (const auto& level : mesh_levels()) names.push_back(level.name);
  names.push_back("auto");
  parameters::declare_string(mesh, "level", d.level,
                             "mesh density as in the paper's Table 3 (in-plane factor 1, 4, 8), or auto: the mesh with "
                             "the fewest hexahedra whose measured error is within 'target error' (it then sets "
                             "refinement factor, layers and section itself)", names);
  parameters::declare_int(mesh, "refinement factor", d.refinement_factor,
                          "multiplies the level's in-plane factor k: every pad element split k x k more, the shaft "
                          "and rim's axis segments k times more (the coarse level refined 4 times is the medium one)",
                          parameters::Range::closed(1, 16));
  parameters::declare_int(mesh, "layers", d.layers, "elements through the pad thickness (0: the level's 4, 4, 10)",
                          parameters::Range::closed(0, 32));
  parameters::declare_string(mesh, "section", parameters::name_of(d.section, section_names()),
                             "the shaft and rim's half-disc section polygon: its arc's inner nodes moved outward to "
                             "keep the curve's area (equal area: within 1 % of the fine level at 60 deg on the medium "
                             "mesh, docs/mesh-choice.md), or every node on the curve as in the paper's Table 3 "
                             "(inscribed: 10 % of the area lost with 4 layers, 1.1 % with 10)", section_names());
  parameters::declare_double(mesh, "target error", d.target_error_percent,
                             "level = auto only: the largest relative error [%] of P_max, Delta u_z and Delta Pi_ext "
                             "allowed, as measured against the fine level on the pull-off at 60 deg (other scenes "
                             "may differ; docs/mesh-choice.md)",
                             parameters::Range{0.0, 100.0, true, false});
}

MeshParameters MeshParameters::from(const Teuchos::ParameterList& mesh)
{
  MeshParameters p;
  p.level = mesh.get<std::string>("level");
  p.refinement_factor = mesh.get<int>("refinement factor");
  p.layers = mesh.get<int>("layers");
  p.section = parameters::choice<SectionShape>(mesh, "section", section_names());
  p.target_error_percent = mesh.get<double>("target error");
  if (p.layers != 0 && p.layers < 3)
    parameters::fail("Mesh/layers", p.layers, "allowed: 0 (the level's value) or 3..32");
  if (p.level != "auto") return p;
  const MeshParameters defaults;
  if (p.refinement_factor != defaults.refinement_factor || p.layers != defaults.layers ||
      p.section != defaults.section)
    throw parameters::InputError("parameter 'Mesh/level' = 'auto' chooses 'refinement factor', 'layers' and "
                                 "'section' itself: leave them at their defaults (1, 0, '" +
                                 parameters::name_of(defaults.section, section_names()) + "'; got " +
                                 std::to_string(p.refinement_factor) + ", " + std::to_string(p.layers) + ", '" +
                                 parameters::name_of(p.section, section_names()) + "') or name a level");
  auto choice = choose_mesh(p.target_error_percent);
  choice.parameters.target_error_percent = p.target_error_percent;
  choice.parameters.choice = choice.reason;
  return choice.parameters;
}

namespace {

constexpr Flags symmetry_flag = HexMeshBuilder::flag(Boundary::symmetry);
constexpr Flags end_face_flag = HexMeshBuilder::flag(Boundary::end_face);
constexpr Flags contact_flag = HexMeshBuilder::flag(Boundary::contact);
constexpr Flags diameter_flag = 1u << 8;   // unit half-disc: node on the flat diameter (u = 0)
constexpr double pi = 3.14159265358979323846;

// Points along one side of a structured block, and the boundary flags its points carry.
struct Edge {
  std::vector<Vec2> points;
  Flags flags = 0;
  int segments() const { return static_cast<int>(points.size()) - 1; }
};

Edge straight(Vec2 a, Vec2 b, int segments, Flags flags = 0)
{
  Edge edge{{}, flags};
  for (int i = 0; i <= segments; ++i) edge.points.push_back(geometry::lerp(a, b, double(i) / segments));
  return edge;
}

Edge chain_part(const std::vector<Vec2>& chain, int begin, int end)
{
  Edge edge;
  const int step = end >= begin ? 1 : -1;
  for (int i = begin; i != end + step; i += step) edge.points.push_back(chain[i]);
  return edge;
}

// A structured block of (ni + 1) x (nj + 1) points.
struct Block {
  int ni = 0, nj = 0;
  std::vector<Vec2> points;
  std::vector<Flags> flags;
  std::vector<double> heights;   // pad blocks: top height at each point
  int index(int i, int j) const { return j * (ni + 1) + i; }
};

// Transfinite (Coons) interpolation from four edges: bottom/top run along i, left/right along j, with
// bottom[0] = left[0], bottom[ni] = right[0], top[0] = left[nj], top[ni] = right[nj].
Block transfinite(const Edge& bottom, const Edge& top, const Edge& left, const Edge& right)
{
  Block block;
  block.ni = bottom.segments();
  block.nj = left.segments();
  if (top.segments() != block.ni || right.segments() != block.nj)
    throw std::logic_error("transfinite block: opposite edges differ in segment count");
  const Vec2 c00 = bottom.points.front(), c10 = bottom.points.back();
  const Vec2 c01 = top.points.front(), c11 = top.points.back();
  for (int j = 0; j <= block.nj; ++j)
    for (int i = 0; i <= block.ni; ++i) {
      const double u = double(i) / block.ni, v = double(j) / block.nj;
      Vec2 p = (1 - v) * bottom.points[i] + v * top.points[i] + (1 - u) * left.points[j] + u * right.points[j];
      p = p - ((1 - u) * (1 - v) * c00 + u * (1 - v) * c10 + (1 - u) * v * c01 + u * v * c11);
      // Edge points exactly as given, so neighbouring blocks share them bit for bit.
      if (j == 0) p = bottom.points[i];
      if (j == block.nj) p = top.points[i];
      if (i == 0) p = left.points[j];
      if (i == block.ni) p = right.points[j];
      Flags f = 0;
      if (j == 0) f |= bottom.flags;
      if (j == block.nj) f |= top.flags;
      if (i == 0) f |= left.flags;
      if (i == block.ni) f |= right.flags;
      block.points.push_back(p);
      block.flags.push_back(f);
    }
  return block;
}

// Extrudes a pad block through its height in equal layers; the bottom layer is the contact surface.
void extrude(HexMeshBuilder& builder, const Block& block, int layers, Part part)
{
  std::vector<std::int64_t> ids(block.points.size() * (layers + 1));
  for (std::size_t n = 0; n < block.points.size(); ++n)
    for (int m = 0; m <= layers; ++m) {
      const double z = block.heights[n] * m / layers;
      ids[n * (layers + 1) + m] =
          builder.add_node({block.points[n].x, block.points[n].y, z}, block.flags[n] | (m == 0 ? contact_flag : 0));
    }
  auto id = [&](int i, int j, int m) { return ids[block.index(i, j) * (layers + 1) + m]; };
  for (int j = 0; j < block.nj; ++j)
    for (int i = 0; i < block.ni; ++i)
      for (int m = 0; m < layers; ++m)
        builder.add_element({id(i, j, m), id(i + 1, j, m), id(i + 1, j + 1, m), id(i, j + 1, m),
                             id(i, j, m + 1), id(i + 1, j, m + 1), id(i + 1, j + 1, m + 1), id(i, j + 1, m + 1)},
                            part);
}

void set_heights(Block& block, const std::function<double(Vec2)>& height)
{
  block.heights.clear();
  for (const Vec2& p : block.points) block.heights.push_back(height(p));
}

// Segments of the five rim pieces per in-plane factor k: P2P3, P3P4, P4P5, arc P5P6, P6P7.
constexpr int piece_segments[geometry::rim_piece_count] = {2, 2, 9, 4, 3};

struct RimStation {
  RimPiece piece;
  double sigma;
};

// Stations along the rim axis from P2 (column 0) to P7; the band P_II uses the same columns, its piece p2_p3
// standing for the edge P12-P3.
std::vector<RimStation> rim_stations(int k)
{
  std::vector<RimStation> stations{{RimPiece::p2_p3, 0.0}};
  for (int piece = 0; piece < geometry::rim_piece_count; ++piece) {
    const int n = piece_segments[piece] * k;
    for (int i = 1; i <= n; ++i) stations.push_back({RimPiece(piece), double(i) / n});
  }
  return stations;
}

// --- P_II: the band between the rim axis and the thin pad, 2k elements across -------------------------------
Block outer_pad_band(const SpatulaShape& shape, int k)
{
  const auto stations = rim_stations(k);
  Block band;
  band.ni = static_cast<int>(stations.size()) - 1;
  band.nj = 2 * k;
  for (int j = 0; j <= band.nj; ++j)
    for (int i = 0; i <= band.ni; ++i) {
      // Column 0 is P12 (start of the edge P12-P3), not P2.
      const auto& station = stations[i];
      const double t = double(j) / band.nj;
      band.points.push_back(shape.band_point(station.piece, station.sigma, t));
      band.heights.push_back(shape.band_height(station.piece, station.sigma, t));
      band.flags.push_back(i == 0 || i == band.ni ? symmetry_flag : 0);
    }
  return band;
}

// --- P_III: the triangle {P2, P3, P12} as three quads around its centroid, each k x k ------------------------
std::vector<Block> prism_blocks(const SpatulaShape& shape, int k)
{
  auto flat = [&](int index) { return Vec2{shape.point(index).x, shape.point(index).y}; };
  const Vec2 p2 = flat(2), p3 = flat(3), p12 = flat(12);
  const Vec2 centroid = (1.0 / 3.0) * (p2 + p3 + p12);
  auto rim_edge = [&](double from, double to) {   // along P2 -> P3, sigma from..to, k segments
    Edge edge;
    for (int i = 0; i <= k; ++i) edge.points.push_back(shape.rim_axis(RimPiece::p2_p3, from + (to - from) * i / k));
    return edge;
  };
  auto band_edge = [&](double from, double to) {   // along P12 -> P3
    Edge edge;
    for (int i = 0; i <= k; ++i)
      edge.points.push_back(shape.band_point(RimPiece::p2_p3, from + (to - from) * i / k, 0.0));
    return edge;
  };
  const Vec2 mid23 = shape.rim_axis(RimPiece::p2_p3, 0.5);
  const Vec2 mid312 = shape.band_point(RimPiece::p2_p3, 0.5, 0.0);
  const Vec2 mid122 = geometry::lerp(p12, p2, 0.5);
  std::vector<Block> blocks;
  // At P2: P2 -> mid23 (bottom), mid122 -> centroid (top), P2 -> mid122 (left), mid23 -> centroid (right).
  blocks.push_back(transfinite(rim_edge(0.0, 0.5), straight(mid122, centroid, k),
                               straight(p2, mid122, k, symmetry_flag), straight(mid23, centroid, k)));
  // At P3: mid23 -> P3 (bottom), centroid -> mid312 (top), mid23 -> centroid (left), P3 -> mid312 (right).
  blocks.push_back(transfinite(rim_edge(0.5, 1.0), straight(centroid, mid312, k), straight(mid23, centroid, k),
                               band_edge(1.0, 0.5)));
  // At P12: P12 -> mid312 (bottom), mid122 -> centroid (top), P12 -> mid122 (left), mid312 -> centroid (right).
  blocks.push_back(transfinite(band_edge(0.0, 0.5), straight(mid122, centroid, k),
                               straight(p12, mid122, k, symmetry_flag), straight(mid312, centroid, k)));
  for (auto& block : blocks) set_heights(block, [&](Vec2 p) { return shape.prism_height(p.x); });
  return blocks;
}

// --- P_IV: a C-grid inside the thin pad's outline ------------------------------------------------------------
// The outline (the band's inner edge, P11 .. P8, 20k segments) is split at X1 = node 5k (on P10-P9) and X2 =
// node 15k (halfway round the arc r2); a core block sits on the symmetry line and three ring blocks (left, top,
// right), 2k elements thick, join it to the outline. The core's top edge is the outline X1..X2 moved inward; its
// slanted sides bisect the free angle at the core corners (so the three blocks meeting there share it fairly),
// as far as the outline leaves room.
Vec2 bisector_foot(Vec2 corner, Vec2 towards_a, Vec2 towards_b)
{
  const Vec2 a = (1.0 / geometry::norm(towards_a - corner)) * (towards_a - corner);
  const Vec2 b = (1.0 / geometry::norm(towards_b - corner)) * (towards_b - corner);
  const Vec2 down = -1.0 * (a + b);   // bisects the reflex angle between a and b
  return corner + (-corner.y / down.y) * down;
}

std::vector<Block> thin_pad_blocks(const Block& band, double pad_height, int k)
{
  std::vector<Vec2> outline;
  for (int i = 0; i <= band.ni; ++i) outline.push_back(band.points[band.index(i, band.nj)]);
  const int last = band.ni, x1 = 5 * k, x2 = last - 5 * k, rings = 2 * k;
  auto inward_normal = [&](int i) {   // outline runs clockwise around P_IV: inward is to the right
    const Vec2 tangent = outline[i + 1] - outline[i - 1];
    return (1.0 / geometry::norm(tangent)) * Vec2{tangent.y, -tangent.x};
  };
  const double width = 0.45 * outline[x1].y;
  std::vector<Vec2> core_top;
  for (int i = x1; i <= x2; ++i) core_top.push_back(outline[i] + width * inward_normal(i));
  const Vec2 k1 = core_top.front(), k2 = core_top.back();
  const Vec2 p11 = outline.front(), p8 = outline.back();
  // Feet of the core's sides on the symmetry line, kept at least halfway between the corner and the outline.
  const Vec2 c1{std::max(bisector_foot(k1, outline[x1], core_top[1]).x, 0.5 * (p11.x + k1.x)), 0.0};
  const Vec2 c2{std::min(bisector_foot(k2, outline[x2], core_top[core_top.size() - 2]).x, 0.5 * (k2.x + p8.x)), 0.0};
  if (!(p11.x < c1.x && c1.x < c2.x && c2.x < p8.x))
    throw MeshingError(Part::thin_pad, "the thin pad's grid does not fit inside its outline");

  std::vector<Block> blocks;
  blocks.push_back(transfinite(straight(c1, c2, x2 - x1, symmetry_flag), Edge{core_top}, straight(c1, k1, x1),
                               straight(c2, k2, x1)));
  blocks.push_back(transfinite(straight(p11, c1, rings, symmetry_flag), straight(outline[x1], k1, rings),
                               chain_part(outline, 0, x1), straight(c1, k1, x1)));
  blocks.push_back(transfinite(Edge{core_top}, chain_part(outline, x1, x2), straight(k1, outline[x1], rings),
                               straight(k2, outline[x2], rings)));
  blocks.push_back(transfinite(straight(c2, p8, rings, symmetry_flag), straight(k2, outline[x2], rings),
                               straight(c2, k2, x1), chain_part(outline, last, x2)));
  for (auto& block : blocks) set_heights(block, [&](Vec2) { return pad_height; });
  return blocks;
}

// --- P_I: the unit half-disc (u >= 0, u^2 + v^2 <= 1) meshed with a core and three ring blocks -----------------
struct UnitSection {
  std::vector<Vec2> nodes;
  std::vector<Flags> flags;
  std::vector<std::array<int, 4>> quads;
};

// The radius of the arc's inner nodes that gives the polygon of m equal chords (its ends (0, -1) and (0, 1) fixed on
// the diameter) the half disc's area pi/2: 1/2 sin(pi/m) (2 s + (m - 2) s^2) = pi/2.
double equal_area_radius(int chords)
{
  const double a = chords - 2.0, c = -pi / std::sin(pi / chords);
  return (-2.0 + std::sqrt(4.0 - 4.0 * a * c)) / (2.0 * a);
}

UnitSection unit_half_disc(int diameter_segments, SectionShape shape)
{
  const int n = diameter_segments;
  const int ring = std::max(1, n / 4), core_height = n - 2 * ring, core_width = std::max(1, core_height / 2);
  const double beta = double(core_height) / n, alpha = 0.5;
  const int chords = 2 * core_width + core_height;   // equal chords on the arc
  const double corner_angle = -0.5 * pi + pi * core_width / chords;
  const double radius = shape == SectionShape::equal_area ? equal_area_radius(chords) : 1.0;
  auto on_arc = [&](double angle) {   // the diameter's ends stay where the diameter is
    const double r = std::abs(std::abs(angle) - 0.5 * pi) < 1e-12 ? 1.0 : radius;
    return Vec2{r * std::cos(angle), r * std::sin(angle)};
  };
  auto arc = [&](double from, double to, int segments) {
    Edge edge;
    for (int i = 0; i <= segments; ++i) edge.points.push_back(on_arc(from + (to - from) * i / segments));
    return edge;
  };
  const Vec2 lower{alpha, -beta}, upper{alpha, beta};
  const Vec2 arc_lower = on_arc(corner_angle);
  const Vec2 arc_upper{arc_lower.x, -arc_lower.y};
  std::vector<Block> blocks;
  blocks.push_back(transfinite(straight({0, -beta}, lower, core_width), straight({0, beta}, upper, core_width),
                               straight({0, -beta}, {0, beta}, core_height, diameter_flag),
                               straight(lower, upper, core_height)));
  blocks.push_back(transfinite(arc(-0.5 * pi, corner_angle, core_width), straight({0, -beta}, lower, core_width),
                               straight({0, -1}, {0, -beta}, ring, diameter_flag), straight(arc_lower, lower, ring)));
  blocks.push_back(transfinite(straight(lower, arc_lower, ring), straight(upper, arc_upper, ring),
                               straight(lower, upper, core_height), arc(corner_angle, -corner_angle, core_height)));
  blocks.push_back(transfinite(straight({0, beta}, upper, core_width), arc(0.5 * pi, -corner_angle, core_width),
                               straight({0, beta}, {0, 1}, ring, diameter_flag), straight(upper, arc_upper, ring)));
  // Merge the blocks' shared points (a few dozen nodes: a linear search is fine).
  UnitSection section;
  auto node_of = [&](Vec2 p, Flags f) {
    for (std::size_t q = 0; q < section.nodes.size(); ++q)
      if (geometry::norm(section.nodes[q] - p) < 1e-12) {
        section.flags[q] |= f;
        return static_cast<int>(q);
      }
    section.nodes.push_back(p);
    section.flags.push_back(f);
    return static_cast<int>(section.nodes.size()) - 1;
  };
  for (const auto& block : blocks) {
    std::vector<int> ids;
    for (std::size_t q = 0; q < block.points.size(); ++q) ids.push_back(node_of(block.points[q], block.flags[q]));
    for (int j = 0; j < block.nj; ++j)
      for (int i = 0; i < block.ni; ++i)
        section.quads.push_back({ids[block.index(i, j)], ids[block.index(i + 1, j)], ids[block.index(i + 1, j + 1)],
                                 ids[block.index(i, j + 1)]});
  }
  return section;
}

void shaft_and_rim(HexMeshBuilder& builder, const SpatulaShape& shape, int k, int layers, SectionShape section)
{
  const UnitSection unit = unit_half_disc(layers, section);
  const int shaft_segments = 18 * k;
  std::vector<CrossSection> sections;
  for (int i = 0; i <= shaft_segments; ++i) sections.push_back(shape.shaft_section(double(i) / shaft_segments));
  const auto stations = rim_stations(k);
  for (std::size_t s = 1; s < stations.size(); ++s)
    sections.push_back(shape.rim_section(stations[s].piece, stations[s].sigma));

  const int per_section = static_cast<int>(unit.nodes.size());
  std::vector<std::int64_t> ids;
  for (std::size_t s = 0; s < sections.size(); ++s) {
    const auto& section = sections[s];
    for (int q = 0; q < per_section; ++q) {
      const Vec2 uv = unit.nodes[q];
      Flags flags = 0;
      if (s == 0) flags |= end_face_flag;
      if (s <= std::size_t(shaft_segments) && (unit.flags[q] & diameter_flag)) flags |= symmetry_flag;
      if (s + 1 == sections.size()) flags |= symmetry_flag;   // the tip section P7 lies in Y = 0
      const double horizontal = uv.x * section.b;
      ids.push_back(builder.add_node({section.centre.x + horizontal * section.b_direction.x,
                                      section.centre.y + horizontal * section.b_direction.y,
                                      section.centre.z + uv.y * section.a},
                                     flags));
    }
  }
  for (std::size_t s = 0; s + 1 < sections.size(); ++s)
    for (const auto& quad : unit.quads) {
      Hexahedron element;
      for (int c = 0; c < 4; ++c) {
        element[c] = ids[s * per_section + quad[c]];
        element[c + 4] = ids[(s + 1) * per_section + quad[c]];
      }
      builder.add_element(element, Part::shaft_and_rim);
    }
}

}  // namespace

HexMesh mesh_spatula(const SpatulaShape& shape, const MeshParameters& parameters)
{
  const int k = parameters.in_plane_factor();
  const int layers = parameters.layer_count();
  HexMeshBuilder builder;
  shaft_and_rim(builder, shape, k, layers, parameters.section);
  const Block band = outer_pad_band(shape, k);
  extrude(builder, band, layers, Part::outer_pad);
  for (const auto& block : prism_blocks(shape, k)) extrude(builder, block, layers, Part::prism);
  for (const auto& block : thin_pad_blocks(band, shape.thin_pad_height(), k)) extrude(builder, block, layers, Part::thin_pad);
  return builder.finish(1e-6);
}

}  // namespace spatula::mesh
