// Adhesion in the assembled system: the undeformed spatula stores -A_c w_adh (Q1C1 and Q1C2), a stiff block
// lifted off the substrate feels area x traction with its maximum at r_min, the global tangent with contact and
// enrichment against finite differences, the residual as the energy's gradient, 1 vs 2 ranks, the same assembly on
// any Kokkos backend and thread count as the Serial build's (stored values), and the law registry open to new laws.
#include "contact/adhesion.hpp"
#include "contact/contact_kernel.hpp"
#include "discretization/system_fields.hpp"
#include "mesh/box_mesh.hpp"
#include "contact/contact_registry.hpp"
#include "analysis/load_stepping.hpp"
#include "parameters/parameter_validation.hpp"
#include "same_fields.hpp"
#include "mesh/spatula_mesher.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <tuple>

using namespace spatula;
using discretization::DiscreteSystem;
using discretization::Master;
using discretization::MasterControl;

namespace {

contact::AdhesionSettings settings(discretization::Enrichment enrichment, const std::string& law = "frictionless")
{
  contact::AdhesionSettings s;
  s.law = law;
  s.enrichment = enrichment;
  s.quadrature = 4;
  s.lennard_jones.r_reg = 0.8 * s.lennard_jones.equilibrium_gap();
  s.lennard_jones.r_cut = 10.0;
  s.substrate_height = -s.lennard_jones.equilibrium_gap();
  return s;
}

mesh::MeshParameters level(const std::string& name)
{
  mesh::MeshParameters p;
  p.level = name;
  return p;
}

struct Spatula {
  explicit Spatula(const std::string& level_name = "coarse") : mesh(mesh::mesh_spatula(shape, level(level_name))) {}
  geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  mesh::HexMesh mesh;
  discretization::Constraints constraints() const
  {
    const auto p1 = shape.point(1);
    return discretization::spatula_constraints(mesh, {p1.x, p1.y, p1.z}, false);
  }
  std::unique_ptr<DiscreteSystem> system(const contact::AdhesionSettings& s,
                                         Teuchos::RCP<const Teuchos::Comm<int>> comm) const
  {
    const auto partition = mesh::partition_mesh(mesh, comm->getSize());
    discretization::SystemOptions options{s.enrichment, contact::make_contact_model(s)};
    return std::make_unique<DiscreteSystem>(mesh, partition, constraints(), discretization::SolidParameters{}, comm,
                                            options);
  }
  // A state with part of the pad lifted (gaps across the Lennard-Jones range) and the end face rotated by 0.01 rad.
  Teuchos::RCP<discretization::Vector> partly_lifted_pad(DiscreteSystem& system) const
  {
    auto x = system.create_vector();
    std::vector<double> u(3 * mesh.node_count());
    for (std::int64_t n = 0; n < mesh.node_count(); ++n) {
      const auto& X = mesh.coordinates[n];
      u[3 * n + 0] = 0.05 * std::sin(0.02 * X[0]);
      u[3 * n + 1] = 0.02 * X[1] / 100.0;
      u[3 * n + 2] = 0.3 * std::max(0.0, std::sin(0.01 * X[0] + 0.02 * X[1])) + 0.02;
    }
    discretization::set_displacements(system, *x, u);
    system.set_master(*x, Master::rotation, 0.01);
    return x;
  }
};

}  // namespace

TEST(Adhesion, UndeformedSpatulaStoresMinusContactAreaTimesWorkOfAdhesion)
{
  Spatula spatula;
  auto comm = Teuchos::DefaultComm<int>::getComm();
  for (auto enrichment : {discretization::Enrichment::q1c1, discretization::Enrichment::q1c2}) {
    const auto s = settings(enrichment);
    auto system = spatula.system(s, comm);
    auto x = system->create_vector(), f = system->create_vector();
    const auto evaluation = system->evaluate(*x, f.get(), true);
    const double w_adh = s.lennard_jones.work_of_adhesion();
    const double area = 2.0 * system->contact_area();   // full spatula
    EXPECT_NEAR(2.0 * evaluation.contact_energy, -area * w_adh, 1e-9 * area * w_adh);
    EXPECT_NEAR(f->normInf(), 0.0, 1e-12);   // traction-free start
    EXPECT_EQ(evaluation.skipped_contact_faces, 0);
    if (comm->getRank() == 0 && enrichment == discretization::Enrichment::q1c2)
      std::cout << "Pi_c0 = A_c w_adh = " << area << " nm^2 x " << w_adh << " nN/nm = " << area * w_adh / 2.0
                << " E R0^3 (paper: 759.3 exact law with A_c = 49,524 nm^2, 761.5 with its regularization)\n";
  }
}

TEST(Adhesion, StiffBlockLiftedFeelsAreaTimesTractionMaximalAtRmin)
{
  mesh::BoxParameters box;
  box.lengths = {20.0, 5.0, 10.0};
  box.elements = {4, 1, 2};
  const auto mesh = mesh::box_mesh(box);
  discretization::Constraints constraints;
  constraints.fixed.push_back({mesh.nodes(mesh::Boundary::symmetry), 1});
  for (std::int64_t n = 0; n < mesh.node_count(); ++n)
    if (mesh.coordinates[n][2] == 10.0) constraints.rigid_nodes.push_back(n);
  constraints.rigid_centre = {10.0, 0.0, 10.0};
  auto comm = Teuchos::DefaultComm<int>::getComm();
  const auto partition = mesh::partition_mesh(mesh, comm->getSize());
  auto s = settings(discretization::Enrichment::q1c1);
  discretization::SolidParameters stiff;
  stiff.young = 2e4;   // so stiff that the bottom follows the top
  auto system = Teuchos::rcp(new DiscreteSystem(mesh, partition, constraints, stiff, comm,
                                                {s.enrichment, contact::make_contact_model(s)}));
  solvers::LinearSolverFactory linear(solvers::LinearSolverParameters{});
  auto model = Teuchos::rcp(new solvers::SpatulaModel(system, linear.lows_factory()));
  solvers::NewtonSolver newton(model, solvers::NewtonParameters{}, linear);
  analysis::LoadPath path(*model, newton, nullptr, false);
  analysis::StepParameters steps;
  steps.initial = steps.maximum = 0.01;
  ASSERT_FALSE(path.advance(Master::lift, 0.3, MasterControl::moving(Master::lift), steps, 1.0, {}).has_value());
  const auto& lj = s.lennard_jones;
  const double area = 20.0 * 5.0;
  double strongest = 0.0, at = 0.0;
  for (const auto& point : path.points()) {
    double phi, dphi, d2phi;
    lj.evaluate(lj.equilibrium_gap() + point.lift, phi, dphi, d2phi);
    const double expected = area * dphi;   // the pull that holds the block: area x attraction (-T = phi')
    EXPECT_NEAR(point.force, expected, 2e-3 * area * lj.max_traction()) << "lift " << point.lift;
    if (point.force > strongest) {
      strongest = point.force;
      at = point.lift;
    }
  }
  EXPECT_NEAR(strongest, area * lj.max_traction(), 0.01 * area * lj.max_traction());
  EXPECT_NEAR(lj.equilibrium_gap() + at, lj.strongest_attraction_gap(), 0.0101);
}

TEST(Adhesion, GlobalTangentWithContactAndEnrichmentIsTheResidualDerivative)
{
  Spatula spatula;
  auto comm = Teuchos::DefaultComm<int>::getComm();
  for (const std::string law : {"frictionless", "stiction"}) {
    auto system = spatula.system(settings(discretization::Enrichment::q1c2, law), comm);
    system->set_control({{false, false, false}});
    auto x = spatula.partly_lifted_pad(*system);
    auto f = system->create_vector(), jv = system->create_vector(), direction = system->create_vector();
    ASSERT_TRUE(system->evaluate(*x, f.get(), true).admissible);
    direction->randomize(-1.0, 1.0);
    system->jacobian()->apply(*direction, *jv);
    const double h = 1e-7;
    auto plus = system->create_vector(), minus = system->create_vector(), fp = system->create_vector(),
         fm = system->create_vector();
    plus->update(1.0, *x, h, *direction, 0.0);
    minus->update(1.0, *x, -h, *direction, 0.0);
    system->evaluate(*plus, fp.get(), false);
    system->evaluate(*minus, fm.get(), false);
    fp->update(-0.5 / h, *fm, 0.5 / h);
    fp->update(-1.0, *jv, 1.0);
    EXPECT_LT(fp->norm2() / jv->norm2(), 1e-6) << law;
  }
}

// The residual is the gradient of the energy Pi_int + Pi_c, which the energy line search of the Newton solver
// (solvers/energy_line_search.hpp) and the jumps' descents rely on: its slope along a direction d against central
// differences of the energy, for both laws on a partly lifted pad (gaps across the Lennard-Jones range).
TEST(Adhesion, TheResidualIsTheEnergyGradient)
{
  Spatula spatula;
  auto comm = Teuchos::DefaultComm<int>::getComm();
  for (const std::string law : {"frictionless", "stiction"}) {
    auto system = spatula.system(settings(discretization::Enrichment::q1c2, law), comm);
    system->set_control({{true, false, true}});   // rotation prescribed, lift free, slide held
    const auto x = spatula.partly_lifted_pad(*system);
    auto f = system->create_vector(), direction = system->create_vector();
    ASSERT_TRUE(system->evaluate(*x, f.get(), false).admissible);
    direction->randomize(-1.0, 1.0);
    direction->elementWiseMultiply(1.0, *f, *direction, 0.0);   // zero on the prescribed rows, where f is 0
    const double h = 1e-5 / direction->normInf();   // displacements of 1e-5 nm at most
    auto shifted = system->create_vector();
    const auto energy = [&](double step) {
      shifted->update(1.0, *x, step, *direction, 0.0);
      const auto evaluation = system->evaluate(*shifted, nullptr, false);
      return evaluation.energy();
    };
    const double slope = f->dot(*direction), difference = (energy(h) - energy(-h)) / (2.0 * h);
    EXPECT_NEAR(difference, slope, 1e-5 * std::abs(slope)) << law;
  }
}

TEST(Adhesion, SameOnAllRanksAndOnOne)
{
  Spatula spatula;
  auto world = Teuchos::DefaultComm<int>::getComm();
  auto self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  const auto s = settings(discretization::Enrichment::q1c2);
  auto a = spatula.system(s, world), b = spatula.system(s, self);
  std::vector<double> u(3 * spatula.mesh.node_count());
  for (std::int64_t n = 0; n < spatula.mesh.node_count(); ++n) u[3 * n + 2] = 0.001 * spatula.mesh.coordinates[n][0];
  auto xa = a->create_vector(), xb = b->create_vector();
  discretization::set_displacements(*a, *xa, u);
  discretization::set_displacements(*b, *xb, u);
  auto fa = a->create_vector(), fb = b->create_vector();
  const auto ea = a->evaluate(*xa, fa.get(), true), eb = b->evaluate(*xb, fb.get(), true);
  EXPECT_NEAR(ea.contact_energy, eb.contact_energy, 1e-12 * std::abs(eb.contact_energy));
  EXPECT_NEAR(ea.internal_energy, eb.internal_energy, 1e-12 * eb.internal_energy);
  EXPECT_NEAR(fa->norm2(), fb->norm2(), 1e-12 * fb->norm2());
  EXPECT_EQ(ea.active_contact_faces + ea.skipped_contact_faces, eb.active_contact_faces + eb.skipped_contact_faces);
}

// What the Serial build assembles for the partly lifted pad (Q1C2, coarse and medium meshes), stored beside this file
// by SPATULA_WRITE_ASSEMBLY_REFERENCE=1: energies, end-face reactions, the residual and the tangent applied to a fixed
// vector. A threaded backend (an OpenMP Trilinos, KOKKOS_NUM_THREADS=2 in the tests) adds the element contributions
// in another order through its atomics and reductions, so it must agree to rounding, not bit for bit.
std::vector<std::pair<std::string, double>> assembly_fingerprint(const std::string& level_name,
                                                                 Teuchos::RCP<const Teuchos::Comm<int>> comm)
{
  Spatula spatula(level_name);
  auto system = spatula.system(settings(discretization::Enrichment::q1c2), comm);
  auto x = spatula.partly_lifted_pad(*system);
  auto f = system->create_vector(), w = system->create_vector(), kw = system->create_vector();
  const auto evaluation = system->evaluate(*x, f.get(), true);
  EXPECT_TRUE(evaluation.admissible);
  // w by node of the node space (mesh and enrichment nodes), not by unknown id, which depends on the partition.
  std::vector<double> nodal(discretization::space_displacements(*system, *x).size());
  for (std::size_t i = 0; i < nodal.size(); ++i) nodal[i] = std::sin(0.37 * double(i) + 0.1);
  discretization::set_space_displacements(*system, *w, nodal);
  system->jacobian()->apply(*w, *kw);
  return {{"internal energy", evaluation.internal_energy}, {"contact energy", evaluation.contact_energy},
          {"moment", evaluation.master_residual[0]}, {"lift force", evaluation.master_residual[1]},
          {"residual norm", f->norm2()}, {"residual . w", f->dot(*w)}, {"w . K w", w->dot(*kw)},
          {"K w norm", kw->norm2()}, {"tangent Frobenius norm", system->jacobian()->getFrobeniusNorm()}};
}

TEST(Adhesion, AssemblyOnThisBackendAgreesWithTheSerialBuildsToRounding)
{
  const std::string directory = std::string(__FILE__).substr(0, std::string(__FILE__).rfind('/') + 1);
  const std::string reference = directory + "assembly_reference.csv";
  auto comm = Teuchos::DefaultComm<int>::getComm();
  std::cout << "Kokkos backend " << Kokkos::DefaultExecutionSpace::name() << ", "
            << Kokkos::DefaultExecutionSpace::concurrency() << " thread(s) per rank, " << comm->getSize()
            << " rank(s)\n";
  std::vector<std::tuple<std::string, std::string, double>> computed;
  for (const std::string level_name : {"coarse", "medium"})
    for (const auto& [quantity, value] : assembly_fingerprint(level_name, comm))
      computed.emplace_back(level_name, quantity, value);
  if (std::getenv("SPATULA_WRITE_ASSEMBLY_REFERENCE")) {
    if (comm->getRank() == 0) {
      std::ofstream out(reference);
      out << "level,quantity,value\n" << std::setprecision(17);
      for (const auto& [level_name, quantity, value] : computed) out << level_name << ',' << quantity << ',' << value << '\n';
    }
    GTEST_SKIP() << "wrote " << reference;
  }
  std::ifstream in(reference);
  ASSERT_TRUE(in) << reference << " is missing: run this test once with SPATULA_WRITE_ASSEMBLY_REFERENCE=1 on a "
                               "Serial build";
  std::map<std::pair<std::string, std::string>, double> stored;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const auto first = line.find(','), last = line.rfind(',');
    stored[{line.substr(0, first), line.substr(first + 1, last - first - 1)}] = std::stod(line.substr(last + 1));
  }
  double largest = 0.0;
  for (const auto& [level_name, quantity, value] : computed) {
    const auto found = stored.find({level_name, quantity});
    ASSERT_NE(found, stored.end()) << level_name << ' ' << quantity << " not in " << reference;
    EXPECT_NEAR(value, found->second, 1e-10 * std::abs(found->second)) << level_name << ' ' << quantity;
    largest = std::max(largest, std::abs(value / found->second - 1.0));
  }
  std::cout << "largest relative difference from the Serial build's values: " << largest << '\n';
}

TEST(Adhesion, FacesBeyondTheCutOffAreSkippedButKeepTheirEnergy)
{
  Spatula spatula;
  auto s = settings(discretization::Enrichment::q1c2);
  auto system = spatula.system(s, Teuchos::DefaultComm<int>::getComm());
  std::vector<double> u(3 * spatula.mesh.node_count(), 0.0);
  for (std::int64_t n = 0; n < spatula.mesh.node_count(); ++n)   // the pad beyond X = 200 nm lifted by 20 nm
    if (spatula.mesh.coordinates[n][0] > 200.0) u[3 * n + 2] = 20.0;
  auto x = system->create_vector(), f = system->create_vector();
  discretization::set_displacements(*system, *x, u);
  const auto evaluation = system->evaluate(*x, f.get(), false);
  EXPECT_GT(evaluation.skipped_contact_faces, 0);
  EXPECT_GT(evaluation.active_contact_faces, 0);
  // Lifting everything: every face skipped, energy phi(r_cut) per unit area, no adhesion force at all.
  for (std::int64_t n = 0; n < spatula.mesh.node_count(); ++n) u[3 * n + 2] = 20.0;
  discretization::set_displacements(*system, *x, u);
  const auto far = system->evaluate(*x, f.get(), false);
  EXPECT_EQ(far.active_contact_faces, 0);
  double phi_cut, unused1, unused2;
  s.lennard_jones.exact(s.lennard_jones.r_cut, phi_cut, unused1, unused2);
  EXPECT_NEAR(far.contact_energy, phi_cut * system->contact_area(), 1e-12);
}

TEST(Adhesion, SkippingDistantFacesChangesNothingButTheWork)
{
  Spatula spatula;
  auto s = settings(discretization::Enrichment::q1c2);
  auto skipping = spatula.system(s, Teuchos::DefaultComm<int>::getComm());
  s.skip_distant_faces = false;
  auto every = spatula.system(s, Teuchos::DefaultComm<int>::getComm());
  std::vector<double> u(3 * spatula.mesh.node_count(), 0.0);
  for (std::int64_t n = 0; n < spatula.mesh.node_count(); ++n)   // a peel: the pad beyond X = 150 nm rises
    u[3 * n + 2] = std::max(0.0, 0.2 * (spatula.mesh.coordinates[n][0] - 150.0));
  auto xa = skipping->create_vector(), xb = every->create_vector();
  discretization::set_displacements(*skipping, *xa, u);
  discretization::set_displacements(*every, *xb, u);
  auto fa = skipping->create_vector(), fb = every->create_vector();
  const auto a = skipping->evaluate(*xa, fa.get(), true), b = every->evaluate(*xb, fb.get(), true);
  EXPECT_GT(a.skipped_contact_faces, 0);
  EXPECT_EQ(b.skipped_contact_faces, 0);
  EXPECT_NEAR(a.contact_energy, b.contact_energy, 1e-12 * std::abs(b.contact_energy));
  fa->update(-1.0, *fb, 1.0);
  EXPECT_LE(fa->norm2(), 1e-12 * fb->norm2());
}

namespace {

// A test-only law: a linear spring holding each surface point at the equilibrium gap, phi = k/2 (d - r_eq)^2.
struct SpringIntegrand {
  double stiffness = 1.0, height = 0.0, rest = 0.25;
  KOKKOS_INLINE_FUNCTION double far_bound(const double x[3]) const { return x[2] - height; }
  KOKKOS_INLINE_FUNCTION double cut_off() const { return 1e30; }
  KOKKOS_INLINE_FUNCTION double gap(const double x[3]) const { return x[2] - height; }
  KOKKOS_INLINE_FUNCTION double inflection() const { return -1e30; }   // a spring has none
  KOKKOS_INLINE_FUNCTION double range() const { return rest; }
  KOKKOS_INLINE_FUNCTION bool evaluate(const double[3], const double x[3], double& phi, double g[3],
                                       double (*H)[3]) const
  {
    const double d = x[2] - height - rest;
    phi = 0.5 * stiffness * d * d;
    g[0] = g[1] = 0.0;
    g[2] = stiffness * d;
    if (H)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) H[i][j] = i == 2 && j == 2 ? stiffness : 0.0;
    return true;
  }
};

}  // namespace

TEST(ContactRegistry, ANewLawIsUsedByNameWithoutTouchingTheSolver)
{
  contact::ContactLawRegistry::instance().add("test spring", [](const contact::AdhesionSettings& s) {
    SpringIntegrand spring{3.0, s.substrate_height, s.lennard_jones.equilibrium_gap()};
    return std::make_shared<contact::IntegrandContactModel<SpringIntegrand>>(spring, s.quadrature,
                                                                                   "test spring", 0.0);
  });
  auto s = settings(discretization::Enrichment::q1c1, "test spring");
  Spatula spatula;
  auto system = spatula.system(s, Teuchos::DefaultComm<int>::getComm());
  auto x = system->create_vector(), f = system->create_vector();
  std::vector<double> u(3 * spatula.mesh.node_count(), 0.0);
  for (auto& value : u) value = 0.0;
  for (std::int64_t n = 0; n < spatula.mesh.node_count(); ++n) u[3 * n + 2] = 0.1;   // everything lifted 0.1 nm
  discretization::set_displacements(*system, *x, u);
  const auto evaluation = system->evaluate(*x, f.get(), false);
  // phi = k/2 0.1^2 over the contact area (the spring's energy, nothing else of the adhesion).
  EXPECT_NEAR(evaluation.contact_energy, 0.5 * 3.0 * 0.01 * system->contact_area(), 1e-9);
  const auto names = contact::ContactLawRegistry::instance().names();
  EXPECT_NE(std::find(names.begin(), names.end(), "test spring"), names.end());
  s.law = "no such law";
  try {
    contact::make_contact_model(s);
    FAIL() << "unknown law accepted";
  } catch (const parameters::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("'Adhesion/law' = 'no such law'"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("frictionless"), std::string::npos);
  }
}

TEST(ContactRegistry, StictionOnARoughSubstrateIsAClearError)
{
  auto s = settings(discretization::Enrichment::q1c2, "stiction");
  s.substrate = contact::SubstrateKind::rough;
  try {
    contact::make_contact_model(s);
    FAIL() << "accepted";
  } catch (const parameters::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("needs 'Adhesion/substrate' = 'flat'"), std::string::npos);
  }
}

// One source for every default: the Adhesion list declares the typed settings' own defaults (adhesion off; when on,
// the law's constants, substrate, enrichment and quadrature as a default AdhesionSettings), and its normalized
// constants are the physical ones at the default Young's modulus.
TEST(Adhesion, AnEmptyListReadsBackAsTheTypedDefaults)
{
  Teuchos::ParameterList list;
  contact::AdhesionParameters::declare(list);
  const double young = discretization::SolidParameters{}.young;
  const auto read = contact::AdhesionParameters::from(list, young);
  const contact::AdhesionParameters d;
  EXPECT_EQ(read.enabled, d.enabled);
  using Settings = contact::AdhesionSettings;
  const auto& t = d.settings;
  expect_same_fields(read.settings, t, &Settings::substrate, &Settings::enrichment, &Settings::quadrature,
                     &Settings::skip_distant_faces, &Settings::anchor_at_restart, &Settings::conform);
  using Law = contact::LennardJones;
  expect_same_fields(read.settings.lennard_jones, t.lennard_jones, &Law::hamaker, &Law::r0);
  using Rough = contact::RoughSubstrate;
  expect_same_fields(read.settings.rough, t.rough, &Rough::z0, &Rough::width, &Rough::spacing);
  list.set("specification", std::string("normalized"));
  const auto normalized = contact::AdhesionParameters::from(list, young).settings.lennard_jones;
  EXPECT_NEAR(normalized.hamaker, t.lennard_jones.hamaker, 1e-4 * t.lennard_jones.hamaker);   // gamma_W to 5 digits
  EXPECT_DOUBLE_EQ(normalized.r0, t.lennard_jones.r0);
}
