// The discrete system: construction, evaluation, the masters and the switch to the contact law's descent law (the
// assembly itself in discrete_system_assembly.hpp, the contact faces' state in discrete_system_contact.cpp).
#include "discretization/discrete_system_assembly.hpp"

namespace spatula::discretization {

DiscreteSystem::DiscreteSystem(const mesh::HexMesh& mesh, const mesh::Partition& partition,
                               const Constraints& constraints, const SolidParameters& solid,
                               Teuchos::RCP<const Teuchos::Comm<int>> comm, const SystemOptions& options)
    : implementation_(std::make_unique<Implementation>(mesh, partition, constraints, solid, std::move(comm), options))
{
}

DiscreteSystem::~DiscreteSystem() = default;

Teuchos::RCP<const Map> DiscreteSystem::owned_map() const { return implementation_->owned; }
Teuchos::RCP<Vector> DiscreteSystem::create_vector() const { return Teuchos::rcp(new Vector(implementation_->owned)); }
Teuchos::RCP<CrsMatrix> DiscreteSystem::jacobian() const { return implementation_->matrix; }
const DofLayout& DiscreteSystem::layout() const { return implementation_->layout; }
const NodeSpace& DiscreteSystem::nodes() const { return implementation_->space; }
const MultiVector& DiscreteSystem::load_derivatives() const { return *implementation_->coupling; }

double DiscreteSystem::mean_diagonal() const
{
  const auto& matrix = *implementation_->matrix;
  Vector diagonal(matrix.getRowMap());
  matrix.getLocalDiagCopy(diagonal);
  return diagonal.norm1() / static_cast<double>(diagonal.getGlobalLength());
}
double DiscreteSystem::contact_area() const { return implementation_->half_contact_area; }
void DiscreteSystem::set_control(const MasterControl& control) { implementation_->control = control; }
const MasterControl& DiscreteSystem::control() const { return implementation_->control; }

double DiscreteSystem::master(const Vector& x, Master which) const { return implementation_->master_value(x, which); }

void DiscreteSystem::set_master(Vector& x, Master which, double value) const
{
  const auto id = implementation_->layout.masters[static_cast<int>(which)];
  if (x.getMap()->isNodeGlobalElement(id)) x.replaceGlobalValue(id, value);
}

Evaluation DiscreteSystem::evaluate(const Vector& x, Vector* residual, bool with_jacobian)
{
  return implementation_->evaluate(x, residual, with_jacobian);
}

const SystemTopology& DiscreteSystem::topology() const { return *implementation_; }
const SolidParameters& DiscreteSystem::solid() const { return implementation_->solid; }
const SolidModel& DiscreteSystem::solid_model() const { return *implementation_->solid_model; }
const ContactModel* DiscreteSystem::contact_model() const { return implementation_->options.contact.get(); }

bool DiscreteSystem::has_descent_law() const { return implementation_->descent_law != nullptr; }

void DiscreteSystem::use_descent_law(bool on)
{
  auto& impl = *implementation_;
  if (!impl.law) return;
  impl.options.contact = on && impl.descent_law ? impl.descent_law : impl.law;
}

}  // namespace spatula::discretization
