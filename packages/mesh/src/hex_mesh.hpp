#pragma once
// A conforming mesh of trilinear hexahedra with element blocks (the spatula's parts), node sets and side sets.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace spatula::mesh {

using Point = std::array<double, 3>;
using Hexahedron = std::array<std::int64_t, 8>;   // node ids, Hex8 order (see hexahedron.hpp)

// Element blocks: the four parts of the spatula (paper Fig. 2).
enum class Part : int { shaft_and_rim = 0, outer_pad = 1, prism = 2, thin_pad = 3 };
constexpr int part_count = 4;
const char* part_name(Part part);   // "P_I shaft and rim", ...

// Named boundaries, each with a node set and a side set.
enum class Boundary : int { symmetry = 0, end_face = 1, contact = 2 };
constexpr int boundary_count = 3;
const char* boundary_name(Boundary boundary);   // "symmetry", "end_face", "contact"

struct Side {
  std::int64_t element = 0;
  int face = 0;   // local face, see hex_face_node
};

struct HexMesh {
  std::vector<Point> coordinates;
  std::vector<Hexahedron> elements;
  std::vector<Part> parts;                                       // per element
  std::array<std::vector<std::int64_t>, boundary_count> node_sets;   // sorted node ids
  std::array<std::vector<Side>, boundary_count> side_sets;

  std::int64_t node_count() const { return static_cast<std::int64_t>(coordinates.size()); }
  std::int64_t element_count() const { return static_cast<std::int64_t>(elements.size()); }
  const std::vector<std::int64_t>& nodes(Boundary b) const { return node_sets[static_cast<int>(b)]; }
  const std::vector<Side>& sides(Boundary b) const { return side_sets[static_cast<int>(b)]; }
  // The four node ids of a side, outward ordered.
  std::array<std::int64_t, 4> side_nodes(const Side& side) const;
};

// The geometry cannot be meshed conformingly (parts that do not fit together); `part` is where it was found.
class MeshingError : public std::runtime_error {
public:
  MeshingError(Part part, const std::string& what) : std::runtime_error(what), part(part) {}
  Part part;
};

// Assembles a HexMesh from parts that each create their own nodes: coincident nodes (within a tolerance) are
// merged, so parts conform wherever they place identical points; element orientation is made positive; side
// sets are the boundary faces whose four nodes all carry the boundary's flag.
class HexMeshBuilder {
public:
  using Flags = unsigned;   // bit b set: node lies on Boundary b
  static constexpr Flags flag(Boundary b) { return 1u << static_cast<int>(b); }

  std::int64_t add_node(const Point& x, Flags flags = 0);
  void add_element(const Hexahedron& nodes, Part part);
  // Merges nodes closer than `tolerance`, fixes orientation and builds the sets.
  HexMesh finish(double tolerance);

private:
  std::vector<Point> coordinates_;
  std::vector<Flags> flags_;
  std::vector<Hexahedron> elements_;
  std::vector<Part> parts_;
};

// All faces that belong to exactly one element, as sides; throws std::logic_error if a face is shared by more
// than two elements (a non-manifold mesh).
std::vector<Side> boundary_sides(const HexMesh& mesh);

}  // namespace spatula::mesh
