#pragma once
// Measures of a spatula mesh, reported in the form of the paper's Table 3 (half spatula) plus the full-spatula
// contact area and volume and the element quality.
#include "mesh/hex_mesh.hpp"

#include <array>
#include <iosfwd>
#include <optional>
#include <string>

namespace spatula::mesh {

struct MeshSummary {
  std::string level;
  std::int64_t nodes = 0;
  std::array<std::int64_t, part_count> elements_per_part{};
  std::int64_t elements = 0;
  std::int64_t contact_elements = 0;
  double largest_contact_diameter = 0.0;   // longest diagonal of a contact face [nm]
  std::array<double, part_count> largest_contact_diameter_per_part{};
  double contact_area = 0.0;               // full spatula [nm^2]
  double volume = 0.0;                     // full spatula [nm^3]
  double min_scaled_jacobian = 0.0;        // over all element corners, 1 for a cube
  std::array<double, part_count> min_scaled_jacobian_per_part{};
  double min_gauss_jacobian = 0.0;         // smallest det J over 2x2x2 Gauss points [nm^3]
};

MeshSummary summarize(const HexMesh& mesh, const std::string& level);

// det J at the 2x2x2 Gauss points of element e (8 values).
std::array<double, 8> gauss_point_jacobians(const HexMesh& mesh, std::int64_t element);
// Minimum over the 8 corners of det[e1 e2 e3] with e_i the unit edge vectors leaving the corner.
double scaled_jacobian(const HexMesh& mesh, std::int64_t element);
// An element the solid cannot use: det J <= 0 at a Gauss point (inverted or tangled), or a corner's scaled
// Jacobian below `smallest_scaled_jacobian` (degenerate, flattened to almost no volume).
struct ElementDefect {
  std::int64_t element = 0;
  Part part = Part::shaft_and_rim;
  double gauss_jacobian = 0.0;     // smallest det J at its Gauss points [nm^3]
  double scaled_jacobian = 0.0;    // smallest at its corners
  std::int64_t defective_elements = 0;   // how many elements of the mesh are like it
};
constexpr double smallest_scaled_jacobian = 1e-3;
// The worst defective element of the mesh (the smallest scaled Jacobian), or nothing if every element is usable.
std::optional<ElementDefect> find_defective_element(const HexMesh& mesh);
// Area of a side (bilinear quadrilateral), by 2x2 Gauss quadrature.
double side_area(const HexMesh& mesh, const Side& side);

// Prints the summary as an aligned table of "quantity  value" lines.
void print(std::ostream& out, const MeshSummary& summary);
// Writes "quantity,value" lines (with a header) for scripts and docs.
void write_csv(std::ostream& out, const MeshSummary& summary);

}  // namespace spatula::mesh
