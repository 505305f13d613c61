#pragma once
// 'Mesh/level' = auto: the cheapest mesh whose measured discretization error is within a target.
//
// The table in mesh_choice.cpp is measured, not modelled: each candidate ran the frictionless Q1C2 pull-off at 60 deg
// (the paper's Table 6 scene, xml/studies/pull-off-60.xml) to detachment, and its error is the largest relative difference of
// P_max, Delta u_z and Delta Pi_ext (to the main snap) from those of the fine level, the paper's own resolution
// (docs/mesh-choice.md, written by benchmarks/mesh_choice.py, lists each run and how to repeat it). The fine level is the
// reference, so its own error is not in the table. The candidates share the solver and its settings, so cost is
// counted in hexahedra (the measured run times are in the doc). Contact enrichment and quadrature are not chosen:
// on the coarse mesh Q1C1 added 50-97 % to P_max, and 3 x 3 or 4 x 4 points per face took more time than 6 x 6, not
// less (docs/error-vs-time.md, "What each option saves and changes").
#include "mesh/spatula_mesher.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace spatula::mesh {

struct MeshCandidate {
  const char* label;
  MeshParameters parameters;
  std::int64_t hexahedra;   // of the default spatula (half model)
  double error_percent;     // the largest of the three errors against the fine level; 0: the fine level itself
  const char* measured;     // where the run that gave the error is kept
};

// Ordered by hexahedra, the fine level last.
const std::vector<MeshCandidate>& mesh_candidates();

struct MeshChoice {
  MeshParameters parameters;
  std::string reason;   // one line: what was picked, its measured error and what it costs
};

// The candidate with the fewest hexahedra (then the smallest error) whose error is at most `target_percent`; the fine
// level, with a reason that says the target is below every measured coarser mesh, when none is.
MeshChoice choose_mesh(double target_percent);

}  // namespace spatula::mesh
