#pragma once
// Meshes the parametric spatula into trilinear hexahedra, the four parts conforming at their interfaces.
//
// Topology (per in-plane factor k; the paper's Table 3 levels are k = 1, 4, 8):
//  - the rim axis P2..P7 is split into 2k, 2k, 9k, 4k, 3k segments (P2P3, P3P4, P4P5, arc, P6P7);
//  - P_III: the triangle {P2, P3, P12} as three quads (split k x k), height 2a(X);
//  - P_II: a structured band along the rim axis, 2k elements across, cosine top profile;
//  - P_IV: a C-grid, a core block and three ring blocks (2k thick) following its curved outline;
//  - P_I: a half-disc cross-section mesh swept along the axis (18k segments on the shaft), its flat face
//    coinciding with the symmetry plane (shaft), then with the P_III and P_II interfaces.
// The pad parts are extruded in `layers` equal layers; P_I's half-disc has `layers` segments on its diameter and
// equal chords on its arc (4 with 4 layers, 8 with 6, 12 with 10). Inscribed in the disc, such a polygon holds 90.0 % of
// its area with 4 chords (98.9 % with 12) and 81 % (97.7 %) of its second moment about the horizontal axis: the
// 4-layer levels' shaft is 10 % thinner and about 19 % softer in bending than the spatula's. `section` = equal area
// moves the arc's inner nodes outward so that the polygon has the disc's area (second moment 94.9 %, 99.8 %).
#include "mesh/hex_mesh.hpp"
#include "geometry/spatula_shape.hpp"

#include <Teuchos_ParameterList.hpp>

#include <string>

namespace spatula::mesh {

// How P_I's half-disc section polygon meets the curved section: nodes on the curve, or moved out to keep its area.
enum class SectionShape { inscribed, equal_area };

struct MeshParameters {
  std::string level = "coarse";   // a name in mesh_levels(); 'auto' in a scene is resolved by from()
  int refinement_factor = 1;      // multiplies the level's in-plane subdivision
  int layers = 0;                 // elements through the pad thickness; 0: the level's value
  SectionShape section = SectionShape::equal_area;   // inscribed: the paper's Table 3 polygon
  double target_error_percent = 2.0;   // level = auto: the largest measured error allowed (mesh_choice.hpp)
  std::string choice;                  // level = auto: what was picked and why (empty otherwise)

  static const std::vector<std::string>& section_names();

  int in_plane_factor() const;    // k
  int layer_count() const;

  static void declare(Teuchos::ParameterList& mesh);
  static MeshParameters from(const Teuchos::ParameterList& mesh);
};

// The registry of named mesh levels (the paper's Table 3 densities).
struct MeshLevel {
  const char* name;
  int in_plane_factor;
  int layers;
};
const std::vector<MeshLevel>& mesh_levels();

HexMesh mesh_spatula(const geometry::SpatulaShape& shape, const MeshParameters& parameters);

}  // namespace spatula::mesh
