#include "mesh/hex_mesh.hpp"

#include "mesh/hexahedron.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace spatula::mesh {

const char* part_name(Part part)
{
  constexpr const char* names[part_count] = {"P_I shaft and rim", "P_II outer pad", "P_III prism", "P_IV thin pad"};
  return names[static_cast<int>(part)];
}

const char* boundary_name(Boundary boundary)
{
  constexpr const char* names[boundary_count] = {"symmetry", "end_face", "contact"};
  return names[static_cast<int>(boundary)];
}

std::array<std::int64_t, 4> HexMesh::side_nodes(const Side& side) const
{
  const auto& element = elements[side.element];
  return {element[hex_face_node(side.face, 0)], element[hex_face_node(side.face, 1)],
          element[hex_face_node(side.face, 2)], element[hex_face_node(side.face, 3)]};
}

std::int64_t HexMeshBuilder::add_node(const Point& x, Flags flags)
{
  coordinates_.push_back(x);
  flags_.push_back(flags);
  return static_cast<std::int64_t>(coordinates_.size()) - 1;
}

void HexMeshBuilder::add_element(const Hexahedron& nodes, Part part)
{
  elements_.push_back(nodes);
  parts_.push_back(part);
}

namespace {

struct CellKey {
  std::int64_t i, j, k;
  bool operator==(const CellKey& other) const { return i == other.i && j == other.j && k == other.k; }
};
struct CellHash {
  std::size_t operator()(const CellKey& key) const
  {
    return std::hash<std::int64_t>()(key.i * 73856093 ^ key.j * 19349663 ^ key.k * 83492791);
  }
};

double element_centre_jacobian(const HexMesh& mesh, const Hexahedron& element)
{
  double x[8][3], jacobian[3][3];
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) x[a][i] = mesh.coordinates[element[a]][i];
  const double centre[3] = {0.0, 0.0, 0.0};
  return hex_jacobian(x, centre, jacobian);
}

}  // namespace

HexMesh HexMeshBuilder::finish(double tolerance)
{
  HexMesh mesh;
  // 1. Merge coincident nodes: a hash grid of cell size `tolerance`, searching the 27 neighbouring cells.
  std::unordered_map<CellKey, std::vector<std::int64_t>, CellHash> grid;
  std::vector<std::int64_t> merged(coordinates_.size());
  std::vector<Flags> merged_flags;
  for (std::size_t n = 0; n < coordinates_.size(); ++n) {
    const Point& x = coordinates_[n];
    const CellKey cell{static_cast<std::int64_t>(std::floor(x[0] / tolerance)),
                       static_cast<std::int64_t>(std::floor(x[1] / tolerance)),
                       static_cast<std::int64_t>(std::floor(x[2] / tolerance))};
    std::int64_t found = -1;
    for (int di = -1; di <= 1 && found < 0; ++di)
      for (int dj = -1; dj <= 1 && found < 0; ++dj)
        for (int dk = -1; dk <= 1 && found < 0; ++dk) {
          auto it = grid.find({cell.i + di, cell.j + dj, cell.k + dk});
          if (it == grid.end()) continue;
          for (std::int64_t candidate : it->second) {
            const Point& y = mesh.coordinates[candidate];
            if (std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]) <= tolerance) {
              found = candidate;
              break;
            }
          }
        }
    if (found < 0) {
      found = mesh.node_count();
      mesh.coordinates.push_back(x);
      merged_flags.push_back(0);
      grid[cell].push_back(found);
    }
    merged[n] = found;
    merged_flags[found] |= flags_[n];
  }

  // 2. Elements on merged nodes, positively oriented (mirror in the reference xi-eta plane if needed, which
  //    keeps the bottom face at the bottom).
  mesh.parts = parts_;
  mesh.elements.reserve(elements_.size());
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const auto& original = elements_[e];
    Hexahedron element;
    for (int a = 0; a < 8; ++a) element[a] = merged[original[a]];
    auto sorted = element;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw MeshingError(parts_[e], "an element collapsed onto itself (two of its corners merged)");
    if (element_centre_jacobian(mesh, element) < 0.0) {
      std::swap(element[1], element[3]);
      std::swap(element[5], element[7]);
    }
    mesh.elements.push_back(element);
  }

  // 3. Node sets and side sets from the flags.
  for (int b = 0; b < boundary_count; ++b) {
    const Flags bit = flag(Boundary(b));
    for (std::int64_t n = 0; n < mesh.node_count(); ++n)
      if (merged_flags[n] & bit) mesh.node_sets[b].push_back(n);
  }
  for (const Side& side : boundary_sides(mesh)) {
    const auto nodes = mesh.side_nodes(side);
    for (int b = 0; b < boundary_count; ++b) {
      const Flags bit = flag(Boundary(b));
      if (std::all_of(nodes.begin(), nodes.end(), [&](std::int64_t n) { return merged_flags[n] & bit; }))
        mesh.side_sets[b].push_back(side);
    }
  }
  return mesh;
}

std::vector<Side> boundary_sides(const HexMesh& mesh)
{
  struct FaceRecord {
    std::array<std::int64_t, 4> key;
    Side side;
  };
  std::vector<FaceRecord> faces;
  faces.reserve(6 * mesh.elements.size());
  for (std::int64_t e = 0; e < mesh.element_count(); ++e)
    for (int f = 0; f < hex_face_count; ++f) {
      FaceRecord record{mesh.side_nodes({e, f}), {e, f}};
      std::sort(record.key.begin(), record.key.end());
      faces.push_back(record);
    }
  std::sort(faces.begin(), faces.end(), [](const FaceRecord& a, const FaceRecord& b) { return a.key < b.key; });
  std::vector<Side> boundary;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) throw MeshingError(mesh.parts[faces[i].side.element], "a face is shared by more than two elements (parts overlap)");
    if (j - i == 1) boundary.push_back(faces[i].side);
    i = j;
  }
  std::sort(boundary.begin(), boundary.end(), [](const Side& a, const Side& b) {
    return a.element != b.element ? a.element < b.element : a.face < b.face;
  });
  return boundary;
}

}  // namespace spatula::mesh
