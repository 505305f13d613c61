#pragma once
// The XML "Adhesion" sublist turned into a contact model: law (a registry name), substrate, enrichment, contact
// quadrature, and the adhesion constants, given either physically (A_H, r0) or normalized (gamma_W, gamma_L with
// R0 = 1 nm and W0 = E; paper Sec. 3, eqs. 19-21):
//
//   gamma_L = R0 / r0,  gamma_W = E / w0,  w0 = A_H / (2 pi^2 r0^3)   =>  r0 = R0 / gamma_L, A_H = 2 pi^2 r0^3 E / gamma_W.
//
// New laws are added by registering them (contact_registry.hpp); the solver and the assembly never change.
#include "contact/adhesive_friction.hpp"
#include "discretization/contact_model.hpp"
#include "discretization/node_space.hpp"

#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <string>

namespace spatula::contact {

enum class SubstrateKind { flat, rough };   // in the order of substrate_names()

struct AdhesionSettings {
  std::string law = "frictionless";
  SubstrateKind substrate = SubstrateKind::flat;
  discretization::Enrichment enrichment = discretization::Enrichment::q1c2;
  int quadrature = 6;                  // Gauss points per direction on each contact face
  contact::LennardJones lennard_jones;    // A_H [nN nm], r0, r_reg, r_cut [nm]
  contact::RoughSubstrate rough;          // z0, h, lambda (base set from r_eq: asperity tops at -r_eq)
  contact::AdhesiveFriction friction;     // 'law' = adhesive friction: its sliding limit and stick
  double substrate_height = 0.0;       // flat: the plane z = -r_eq, so the undeformed pad is traction-free
  bool conform = true;                 // rough: start from the pad pressed onto the asperities
  bool skip_distant_faces = true;      // integrate only faces with a point within the cut-off
  bool anchor_at_restart = false;      // stiction: travel measured from the restart state (else the undeformed one)

  double gamma_W(double young) const;
  double gamma_L() const { return 1.0 / lennard_jones.r0; }
};

// The scene's adhesion: off by default (law "none"); the settings' defaults are those of every key declared (a law's
// regularization ratio 0.8 and cut-off 10 nm are scene choices, declared in the list only).
struct AdhesionParameters {
  bool enabled = false;
  AdhesionSettings settings;
  std::shared_ptr<const discretization::ContactModel> model;   // the law the settings select (null: none)

  static void declare(Teuchos::ParameterList& adhesion);
  // Reads a validated sublist; E [GPa] is needed for the normalized form.
  static AdhesionParameters from(const Teuchos::ParameterList& adhesion, double young);
};

// The contact model the settings select (through the registry). Throws InputError for unknown names and
// invalid combinations.
std::shared_ptr<const discretization::ContactModel> make_contact_model(const AdhesionSettings& settings);

}  // namespace spatula::contact
