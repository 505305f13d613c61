// The assembled system: the tangent (with the rigid end face's chain rule) against finite differences of the
// residual, identity rows of prescribed masters with their reactions, and identical results on 1 and 2 ranks; the
// solid's law chosen by name ('Material/law'), a law added by name used by the assembly and the tr(sigma) field.
#include "discretization/discrete_system.hpp"
#include "discretization/system_fields.hpp"
#include "mesh/spatula_mesher.hpp"
#include "parameters/parameter_validation.hpp"

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace spatula;
using discretization::DiscreteSystem;
using discretization::Master;
using discretization::Vector;

namespace {

struct Fixture {
  geometry::SpatulaShape shape{geometry::ShapeParameters{}};
  mesh::HexMesh mesh = mesh::mesh_spatula(shape, mesh::MeshParameters{});
  std::array<double, 3> centre() const { return {shape.point(1).x, shape.point(1).y, shape.point(1).z}; }

  std::unique_ptr<DiscreteSystem> system(Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                         const discretization::SolidParameters& solid = {}) const
  {
    const auto partition = mesh::partition_mesh(mesh, comm->getSize());
    return std::make_unique<DiscreteSystem>(mesh, partition,
                                            discretization::spatula_constraints(mesh, centre(), false), solid, comm);
  }

  // A smooth, non-trivial displacement field (bending of the shaft plus a wave in the pad) [nm].
  std::vector<double> field() const
  {
    std::vector<double> u(3 * mesh.node_count());
    for (std::int64_t n = 0; n < mesh.node_count(); ++n) {
      const auto& x = mesh.coordinates[n];
      u[3 * n + 0] = 0.3 * std::sin(0.01 * x[0] + 0.02 * x[2]);
      u[3 * n + 1] = 0.2 * std::cos(0.013 * x[1] + 0.005 * x[0]) * x[1] / 100.0;
      u[3 * n + 2] = 0.4 * std::sin(0.008 * x[0]) + 0.01 * x[2];
    }
    return u;
  }
};

}  // namespace

TEST(DiscreteSystem, TangentIsTheResidualDerivative)
{
  Fixture fixture;
  auto comm = Teuchos::DefaultComm<int>::getComm();
  auto system = fixture.system(comm);
  system->set_control({{false, false, false}});   // all masters free: their rows and couplings are tested too
  auto x = system->create_vector();
  discretization::set_displacements(*system, *x, fixture.field());
  system->set_master(*x, Master::rotation, 0.05);
  system->set_master(*x, Master::lift, 1.5);
  auto f = system->create_vector();
  ASSERT_TRUE(system->evaluate(*x, f.get(), true).admissible);
  auto direction = system->create_vector();
  direction->randomize(-1.0, 1.0);
  system->set_master(*direction, Master::rotation, 0.7);   // exercise the rotation column strongly
  auto jv = system->create_vector();
  system->jacobian()->apply(*direction, *jv);

  const double h = 1e-6;
  auto plus = system->create_vector(), minus = system->create_vector(), fp = system->create_vector(),
       fm = system->create_vector();
  plus->update(1.0, *x, h, *direction, 0.0);
  minus->update(1.0, *x, -h, *direction, 0.0);
  system->evaluate(*plus, fp.get(), false);
  system->evaluate(*minus, fm.get(), false);
  auto difference = system->create_vector();
  difference->update(0.5 / h, *fp, -0.5 / h, *fm, 0.0);
  difference->update(-1.0, *jv, 1.0);
  EXPECT_LT(difference->norm2() / jv->norm2(), 1e-6);
}

TEST(DiscreteSystem, PrescribedMastersGiveIdentityRowsAndReactions)
{
  Fixture fixture;
  auto comm = Teuchos::DefaultComm<int>::getComm();
  auto system = fixture.system(comm);
  auto x = system->create_vector();
  discretization::set_displacements(*system, *x, fixture.field());
  system->set_master(*x, Master::rotation, 0.03);
  auto f = system->create_vector();
  const auto evaluation = system->evaluate(*x, f.get(), true);
  // The prescribed rows are zero in f, and J e_m = e_m.
  for (int m = 0; m < discretization::master_count; ++m) {
    auto unit = system->create_vector(), image = system->create_vector();
    system->set_master(*unit, Master(m), 1.0);
    system->jacobian()->apply(*unit, *image);
    EXPECT_NEAR(system->master(*image, Master(m)), 1.0, 1e-14);
    image->update(-1.0, *unit, 1.0);
    EXPECT_NEAR(image->normInf(), 0.0, 1e-14);
    EXPECT_EQ(system->master(*f, Master(m)), 0.0);
    EXPECT_NE(evaluation.master_residual[m], 0.0);   // the reaction is kept
  }
  // The reactions equal the free system's master residuals.
  system->set_control({{false, false, false}});
  const auto free = system->evaluate(*x, f.get(), false);
  EXPECT_DOUBLE_EQ(system->master(*f, Master::rotation), evaluation.master_residual[0]);
  EXPECT_NEAR(free.master_residual[1], evaluation.master_residual[1], 1e-12 * std::abs(free.master_residual[1]));
}

TEST(DiscreteSystem, SameResultsOnAllRanksAndOnOne)
{
  Fixture fixture;
  auto world = Teuchos::DefaultComm<int>::getComm();
  auto self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  auto distributed = fixture.system(world);
  auto serial = fixture.system(self);
  const auto u = fixture.field();
  auto x_world = distributed->create_vector(), x_self = serial->create_vector();
  discretization::set_displacements(*distributed, *x_world, u);
  discretization::set_displacements(*serial, *x_self, u);
  for (auto* s : {distributed.get(), serial.get()}) s->set_control({{false, false, false}});
  distributed->set_master(*x_world, Master::rotation, 0.04);
  serial->set_master(*x_self, Master::rotation, 0.04);
  auto f_world = distributed->create_vector(), f_self = serial->create_vector();
  const auto a = distributed->evaluate(*x_world, f_world.get(), true);
  const auto b = serial->evaluate(*x_self, f_self.get(), true);
  EXPECT_NEAR(a.internal_energy, b.internal_energy, 1e-12 * b.internal_energy);
  for (int m = 0; m < 2; ++m) EXPECT_NEAR(a.master_residual[m], b.master_residual[m], 1e-10 * std::abs(b.master_residual[m]));
  EXPECT_NEAR(f_world->norm2(), f_self->norm2(), 1e-12 * f_self->norm2());
  EXPECT_NEAR(distributed->jacobian()->getFrobeniusNorm(), serial->jacobian()->getFrobeniusNorm(),
              1e-12 * serial->jacobian()->getFrobeniusNorm());
  // Full nodal fields agree too.
  const auto ua = discretization::node_displacements(*distributed, *x_world);
  const auto ub = discretization::node_displacements(*serial, *x_self);
  for (std::size_t i = 0; i < ua.size(); ++i) ASSERT_NEAR(ua[i], ub[i], 1e-13);
}

TEST(DiscreteSystem, InvertedElementIsReportedNotNaN)
{
  Fixture fixture;
  auto system = fixture.system(Teuchos::DefaultComm<int>::getComm());
  auto x = system->create_vector();
  std::vector<double> u(3 * fixture.mesh.node_count(), 0.0);
  for (std::int64_t n = 0; n < fixture.mesh.node_count(); ++n)
    if (fixture.mesh.coordinates[n][2] > 5.0 && fixture.mesh.coordinates[n][0] > 200.0) u[3 * n + 2] = -200.0;
  discretization::set_displacements(*system, *x, u);
  auto f = system->create_vector();
  const auto evaluation = system->evaluate(*x, f.get(), true);
  EXPECT_FALSE(evaluation.admissible);
  EXPECT_GE(evaluation.inverted_element, 0);
  EXPECT_LT(evaluation.inverted_element, fixture.mesh.element_count());
}

// A law added to the registry by name is what the assembly and the tr(sigma) field use, with no other change: the
// Neo-Hookean law with E doubled at the same nu (its energy is linear in the Lame constants) gives exactly twice the
// energy, residual and stress field of the registered 'neo-hookean' at the same state. An unknown name is refused
// naming the key and the laws there are.
TEST(SolidLaws, ALawAddedByNameIsUsedByTheAssemblyAndTheStressField)
{
  discretization::SolidLawRegistry::instance().add("twice neo-hookean", [](const discretization::SolidParameters& p) {
    return std::make_shared<discretization::LawSolidModel<laws::NeoHookean>>(
        "twice neo-hookean", laws::NeoHookean::from_young(2.0 * p.young, p.poisson), p);
  });
  auto comm = Teuchos::DefaultComm<int>::getComm();
  Fixture fixture;
  discretization::SolidParameters twice;
  twice.law = "twice neo-hookean";
  auto plain = fixture.system(comm), doubled = fixture.system(comm, twice);
  EXPECT_EQ(plain->solid_model().name(), "neo-hookean");
  EXPECT_EQ(doubled->solid_model().name(), "twice neo-hookean");
  auto x = plain->create_vector();
  discretization::set_displacements(*plain, *x, fixture.field());
  auto f_plain = plain->create_vector(), f_doubled = doubled->create_vector();
  const auto a = plain->evaluate(*x, f_plain.get(), false), b = doubled->evaluate(*x, f_doubled.get(), false);
  ASSERT_GT(a.internal_energy, 0.0);
  EXPECT_NEAR(b.internal_energy, 2.0 * a.internal_energy, 1e-12 * a.internal_energy);
  f_doubled->update(-2.0, *f_plain, 1.0);
  EXPECT_LT(f_doubled->normInf(), 1e-12 * f_plain->normInf());
  const auto trace_plain = discretization::element_cauchy_trace(*plain, *x);
  const auto trace_doubled = discretization::element_cauchy_trace(*doubled, *x);
  double largest = 0.0;
  for (std::size_t e = 0; e < trace_plain.size(); ++e) {
    EXPECT_NEAR(trace_doubled[e], 2.0 * trace_plain[e], 1e-12 * std::abs(trace_plain[e]) + 1e-15) << "element " << e;
    largest = std::max(largest, std::abs(trace_plain[e]));
  }
  EXPECT_GT(largest, 0.0);

  discretization::SolidParameters unknown;
  unknown.law = "rubber";
  try {
    fixture.system(comm, unknown);
    ADD_FAILURE() << "an unknown law was accepted";
  } catch (const parameters::InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'Material/law' = 'rubber'"), std::string::npos) << message;
    EXPECT_NE(message.find("'neo-hookean'"), std::string::npos) << message;
  }
}
