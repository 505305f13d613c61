#include "mesh/mesh_choice.hpp"

#include <algorithm>
#include <cstdio>

namespace spatula::mesh {

namespace {

MeshParameters mesh(const char* level, int refinement_factor, SectionShape section)
{
  MeshParameters parameters;
  parameters.level = level;
  parameters.refinement_factor = refinement_factor;
  parameters.section = section;
  return parameters;
}

constexpr auto inscribed = SectionShape::inscribed;
constexpr auto equal_area = SectionShape::equal_area;

}  // namespace

// Errors against the fine level's pull-off at 60 deg (P_max 6.627 nN, Delta u_z 174.7 nm, Delta Pi_ext 682.5e-18 J),
// each the largest of the three quantities' relative differences; the hexahedra are checked against the mesher by
// mesh_test (MeshChoice.TheTableCountsTheMeshersHexahedra).
const std::vector<MeshCandidate>& mesh_candidates()
{
  static const std::vector<MeshCandidate> candidates = {
      {"coarse", mesh("coarse", 1, inscribed), 760, 65.62, "results/coarse/pull-off-60"},
      {"coarse with the equal-area section", mesh("coarse", 1, equal_area), 760, 65.95,
       "results/variants/mesh-choice/coarse-equal-area"},
      {"coarse refined 2 x 2 with the equal-area section", mesh("coarse", 2, equal_area), 2584, 10.79,
       "results/variants/mesh-choice/coarse-x2-equal-area"},
      {"coarse refined 2 x 2", mesh("coarse", 2, inscribed), 2584, 12.98,
       "results/variants/mesh-choice/coarse-x2"},
      {"coarse refined 3 x 3 with the equal-area section", mesh("coarse", 3, equal_area), 5472, 2.49,
       "results/variants/mesh-choice/coarse-x3-equal-area"},
      {"medium with the equal-area section", mesh("medium", 1, equal_area), 9424, 0.94,
       "results/variants/medium-equal-area-pull-off-60"},
      {"medium", mesh("medium", 1, inscribed), 9424, 9.75, "results/medium/pull-off-60"},
      {"fine", mesh("fine", 1, inscribed), 97888, 0.0, "results/fine/pull-off-60"},
  };
  return candidates;
}

MeshChoice choose_mesh(double target_percent)
{
  const auto& candidates = mesh_candidates();
  const MeshCandidate* picked = nullptr;
  for (const auto& candidate : candidates) {
    if (candidate.error_percent > target_percent || &candidate == &candidates.back()) continue;
    if (!picked || candidate.hexahedra < picked->hexahedra ||
        (candidate.hexahedra == picked->hexahedra && candidate.error_percent < picked->error_percent))
      picked = &candidate;
  }
  char reason[512];
  if (picked) {
    std::snprintf(reason, sizeof reason,
                  "'Mesh/level' = auto picked %s (%lld hexahedra; the fine level has %lld): its largest error "
                  "against the fine level on the pull-off at 60 deg is %.3g %% (target %.3g %%; %s, "
                  "docs/mesh-choice.md)",
                  picked->label, static_cast<long long>(picked->hexahedra),
                  static_cast<long long>(candidates.back().hexahedra), picked->error_percent, target_percent,
                  picked->measured);
    return {picked->parameters, reason};
  }
  const auto best = std::min_element(candidates.begin(), candidates.end() - 1, [](const auto& a, const auto& b) {
    return a.error_percent < b.error_percent;
  });
  std::snprintf(reason, sizeof reason,
                "'Mesh/level' = auto picked the fine level (%lld hexahedra): the target %.3g %% is below every coarser "
                "mesh measured (the best, %s, is within %.3g %%); the fine level is the table's reference, its own "
                "error is not measured",
                static_cast<long long>(candidates.back().hexahedra), target_percent, best->label, best->error_percent);
  return {candidates.back().parameters, reason};
}

}  // namespace spatula::mesh
