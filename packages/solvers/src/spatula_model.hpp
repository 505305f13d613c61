#pragma once
// The spatula's nonlinear system as a Thyra model evaluator over Tpetra (NOX reaches Tpetra only through Thyra
// in Trilinos 13.2): x -> f(x) (the residual) and W = df/dx (the tangent, the system's FE matrix), with the linear
// solver factory that NOX uses for the Newton steps. For continuation (LOCA) one prescribed end-face master can
// be exposed as the parameter p ("load"): its value is then taken from p instead of x, and df/dp is the load
// vector the assembly sets aside (DiscreteSystem::load_derivatives).
#include "discretization/discrete_system.hpp"

#include <Thyra_LinearOpWithSolveFactoryBase.hpp>
#include <Thyra_StateFuncModelEvaluatorBase.hpp>

#include <optional>

namespace spatula::solvers {

struct ModelCounters {
  int residuals = 0;        // evaluations of f alone
  int jacobians = 0;        // evaluations with W
  int inadmissible = 0;     // evaluations at states with an inverted element (f set to a huge value)
};

class SpatulaModel : public Thyra::StateFuncModelEvaluatorBase<double> {
public:
  SpatulaModel(Teuchos::RCP<discretization::DiscreteSystem> system,
               Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> linear_solver);

  Teuchos::RCP<const Thyra::VectorSpaceBase<double>> get_x_space() const override;
  Teuchos::RCP<const Thyra::VectorSpaceBase<double>> get_f_space() const override;
  Thyra::ModelEvaluatorBase::InArgs<double> createInArgs() const override;
  Thyra::ModelEvaluatorBase::InArgs<double> getNominalValues() const override;
  Teuchos::RCP<Thyra::LinearOpBase<double>> create_W_op() const override;
  Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> get_W_factory() const override;

  // Exposes (or, with nullopt, hides) a master as the continuation parameter p.
  void set_continuation_parameter(std::optional<discretization::Master> master) { parameter_ = master; }

  Teuchos::RCP<const Thyra::VectorSpaceBase<double>> get_p_space(int index) const override;
  Teuchos::RCP<const Teuchos::Array<std::string>> get_p_names(int index) const override;

  discretization::DiscreteSystem& system() const { return *system_; }
  const ModelCounters& counters() const { return counters_; }
  // The last evaluation (reactions, energy, admissibility).
  const discretization::Evaluation& last_evaluation() const { return last_; }
  // Evaluates f at x (into `residual`, if non-null) and with `with_jacobian` the tangent into system().jacobian(),
  // counted as NOX's evaluations are; an inadmissible state returns admissible = false and fills f with 1e100.
  const discretization::Evaluation& evaluate(const discretization::Vector& x, discretization::Vector* residual,
                                             bool with_jacobian) const;

private:
  Thyra::ModelEvaluatorBase::OutArgs<double> createOutArgsImpl() const override;
  void evalModelImpl(const Thyra::ModelEvaluatorBase::InArgs<double>& in,
                     const Thyra::ModelEvaluatorBase::OutArgs<double>& out) const override;

  Teuchos::RCP<discretization::DiscreteSystem> system_;
  Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> linear_solver_;
  Teuchos::RCP<const Thyra::VectorSpaceBase<double>> space_, parameter_space_;
  std::optional<discretization::Master> parameter_;
  mutable ModelCounters counters_;
  mutable discretization::Evaluation last_;
};

}  // namespace spatula::solvers
