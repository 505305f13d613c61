#pragma once
// The state vector as fields over the mesh, and back: nodal displacements complete on every rank (for output,
// checkpoints and diagnostics) and the element field tr(sigma). Each is collective where it gathers.
#include "discretization/discrete_system.hpp"

#include <vector>

namespace spatula::discretization {

// Writes nodal displacements u (N x 3, row-major, all mesh nodes) into the free unknowns of x that this rank owns
// (fixed and rigid components are not unknowns and are ignored; an enrichment node takes its corners' mean).
void set_displacements(const DiscreteSystem& system, Vector& x, const std::vector<double>& u);

// Nodal displacements (N x 3, row-major, every node of the mesh including fixed and rigid ones), complete on every
// rank. Collective.
std::vector<double> node_displacements(const DiscreteSystem& system, const Vector& x);

// The same over every node of the node space (mesh and enrichment nodes): what a checkpoint stores, and its inverse
// (the masters are set separately). Collective.
std::vector<double> space_displacements(const DiscreteSystem& system, const Vector& x);
void set_space_displacements(const DiscreteSystem& system, Vector& x, const std::vector<double>& u);

// The element field tr(sigma) [GPa] (mean over the element's Gauss points), complete on every rank. Collective.
std::vector<double> element_cauchy_trace(const DiscreteSystem& system, const Vector& x);

// The energy a contact law with state (adhesive friction) has dissipated per unit undeformed area up to the committed
// state [nN/nm = J/m^2], each contact face's mean over its undeformed area, on the element the face belongs to
// (zero on the others): where the pad has slid. Empty for a law that records none. Collective.
std::vector<double> element_contact_dissipation(const DiscreteSystem& system);

}  // namespace spatula::discretization
