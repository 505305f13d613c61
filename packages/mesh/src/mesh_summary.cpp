#include "mesh/mesh_summary.hpp"

#include "mesh/hexahedron.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>

namespace spatula::mesh {

namespace {

void element_coordinates(const HexMesh& mesh, std::int64_t element, double x[8][3])
{
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) x[a][i] = mesh.coordinates[mesh.elements[element][a]][i];
}

const double gauss = 1.0 / std::sqrt(3.0);

}  // namespace

std::array<double, 8> gauss_point_jacobians(const HexMesh& mesh, std::int64_t element)
{
  double x[8][3], jacobian[3][3];
  element_coordinates(mesh, element, x);
  std::array<double, 8> values{};
  for (int a = 0; a < 8; ++a) {
    const double xi[3] = {gauss * hex_node_coordinate(a, 0), gauss * hex_node_coordinate(a, 1),
                          gauss * hex_node_coordinate(a, 2)};
    values[a] = hex_jacobian(x, xi, jacobian);
  }
  return values;
}

double scaled_jacobian(const HexMesh& mesh, std::int64_t element)
{
  double x[8][3];
  element_coordinates(mesh, element, x);
  // Neighbours of each corner along +xi, +eta, +zeta in the right-handed order of the reference cube.
  constexpr int neighbours[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                    {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  double smallest = std::numeric_limits<double>::max();
  for (int a = 0; a < 8; ++a) {
    double e[3][3];
    for (int d = 0; d < 3; ++d) {
      double length = 0.0;
      for (int i = 0; i < 3; ++i) {
        e[d][i] = x[neighbours[a][d]][i] - x[a][i];
        length += e[d][i] * e[d][i];
      }
      length = std::sqrt(length);
      for (int i = 0; i < 3; ++i) e[d][i] /= length;
    }
    const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                       e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                       e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    smallest = std::min(smallest, det);
  }
  return smallest;
}

double side_area(const HexMesh& mesh, const Side& side)
{
  const auto nodes = mesh.side_nodes(side);
  double area = 0.0;
  for (int q = 0; q < 4; ++q) {
    const double s = (q == 0 || q == 3) ? -gauss : gauss, t = q < 2 ? -gauss : gauss;
    const double ds[4] = {-(1 - t) / 4, (1 - t) / 4, (1 + t) / 4, -(1 + t) / 4};
    const double dt[4] = {-(1 - s) / 4, -(1 + s) / 4, (1 + s) / 4, (1 - s) / 4};
    double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
    for (int c = 0; c < 4; ++c)
      for (int i = 0; i < 3; ++i) {
        a[i] += ds[c] * mesh.coordinates[nodes[c]][i];
        b[i] += dt[c] * mesh.coordinates[nodes[c]][i];
      }
    area += std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
  }
  return area;
}

std::optional<ElementDefect> find_defective_element(const HexMesh& mesh)
{
  std::optional<ElementDefect> worst;
  std::int64_t count = 0;
  for (std::int64_t e = 0; e < mesh.element_count(); ++e) {
    const auto jacobians = gauss_point_jacobians(mesh, e);
    const double gauss = *std::min_element(jacobians.begin(), jacobians.end());
    const double scaled = scaled_jacobian(mesh, e);
    if (gauss > 0.0 && scaled >= smallest_scaled_jacobian && std::isfinite(gauss) && std::isfinite(scaled)) continue;
    ++count;
    if (!worst || !(scaled >= worst->scaled_jacobian)) worst = ElementDefect{e, mesh.parts[e], gauss, scaled, 0};
  }
  if (worst) worst->defective_elements = count;
  return worst;
}

MeshSummary summarize(const HexMesh& mesh, const std::string& level)
{
  MeshSummary summary;
  summary.level = level;
  summary.nodes = mesh.node_count();
  summary.elements = mesh.element_count();
  summary.min_scaled_jacobian = std::numeric_limits<double>::max();
  summary.min_scaled_jacobian_per_part.fill(std::numeric_limits<double>::max());
  summary.min_gauss_jacobian = std::numeric_limits<double>::max();
  double half_volume = 0.0;
  for (std::int64_t e = 0; e < mesh.element_count(); ++e) {
    ++summary.elements_per_part[static_cast<int>(mesh.parts[e])];
    const auto jacobians = gauss_point_jacobians(mesh, e);
    for (double j : jacobians) {
      half_volume += j;   // Gauss weights are 1
      summary.min_gauss_jacobian = std::min(summary.min_gauss_jacobian, j);
    }
    const double scaled = scaled_jacobian(mesh, e);
    summary.min_scaled_jacobian = std::min(summary.min_scaled_jacobian, scaled);
    auto& in_part = summary.min_scaled_jacobian_per_part[static_cast<int>(mesh.parts[e])];
    in_part = std::min(in_part, scaled);
  }
  summary.volume = 2.0 * half_volume;
  const auto& contact = mesh.sides(Boundary::contact);
  summary.contact_elements = static_cast<std::int64_t>(contact.size());
  double half_area = 0.0;
  for (const Side& side : contact) {
    half_area += side_area(mesh, side);
    const auto n = mesh.side_nodes(side);
    auto distance = [&](std::int64_t a, std::int64_t b) {
      const auto &x = mesh.coordinates[a], &y = mesh.coordinates[b];
      return std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
    };
    const double diameter = std::max(distance(n[0], n[2]), distance(n[1], n[3]));
    summary.largest_contact_diameter = std::max(summary.largest_contact_diameter, diameter);
    auto& per_part = summary.largest_contact_diameter_per_part[static_cast<int>(mesh.parts[side.element])];
    per_part = std::max(per_part, diameter);
  }
  summary.contact_area = 2.0 * half_area;
  return summary;
}

void print(std::ostream& out, const MeshSummary& s)
{
  auto line = [&](const std::string& name, const auto& value) {
    out << "  " << std::left << std::setw(36) << name << value << "\n";
  };
  out << "mesh summary (level " << s.level << "; elements for the half spatula, area and volume full):\n";
  for (int p = 0; p < part_count; ++p) line(std::string("solid elements ") + part_name(Part(p)), s.elements_per_part[p]);
  line("solid elements total", s.elements);
  line("nodes", s.nodes);
  line("contact elements", s.contact_elements);
  line("largest contact diameter [nm]", s.largest_contact_diameter);
  for (int p = 1; p < part_count; ++p)
    line(std::string("  in ") + part_name(Part(p)), s.largest_contact_diameter_per_part[p]);
  line("contact area A_c [nm^2]", s.contact_area);
  line("volume [nm^3]", s.volume);
  line("min scaled Jacobian", s.min_scaled_jacobian);
  line("min det J at Gauss points [nm^3]", s.min_gauss_jacobian);
}

void write_csv(std::ostream& out, const MeshSummary& s)
{
  out << "quantity,value\nlevel," << s.level << "\n";
  constexpr const char* keys[part_count] = {"elements_P_I", "elements_P_II", "elements_P_III", "elements_P_IV"};
  for (int p = 0; p < part_count; ++p) out << keys[p] << "," << s.elements_per_part[p] << "\n";
  constexpr const char* diameters[part_count] = {"", "largest_contact_diameter_P_II_nm",
                                                 "largest_contact_diameter_P_III_nm", "largest_contact_diameter_P_IV_nm"};
  for (int p = 1; p < part_count; ++p) out << diameters[p] << "," << s.largest_contact_diameter_per_part[p] << "\n";
  out << "elements_total," << s.elements << "\nnodes," << s.nodes << "\ncontact_elements," << s.contact_elements
      << "\nlargest_contact_diameter_nm," << s.largest_contact_diameter << "\ncontact_area_nm2," << s.contact_area
      << "\nvolume_nm3," << s.volume << "\nmin_scaled_jacobian," << s.min_scaled_jacobian
      << "\nmin_gauss_jacobian_nm3," << s.min_gauss_jacobian << "\n";
}

}  // namespace spatula::mesh
