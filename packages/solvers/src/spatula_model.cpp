#include "spatula_model.hpp"

#include <Thyra_TpetraLinearOp.hpp>

#include <cmath>
#include <Thyra_TpetraThyraWrappers.hpp>

namespace spatula::solvers {

using discretization::GlobalOrdinal;
using discretization::LocalOrdinal;
using discretization::Node;
using Extract = Thyra::TpetraOperatorVectorExtraction<double, LocalOrdinal, GlobalOrdinal, Node>;
using Base = Thyra::ModelEvaluatorBase;

SpatulaModel::SpatulaModel(Teuchos::RCP<discretization::DiscreteSystem> system,
                           Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> linear_solver)
    : system_(std::move(system)), linear_solver_(std::move(linear_solver)),
      space_(Thyra::tpetraVectorSpace<double>(system_->owned_map()))
{
}

Teuchos::RCP<const Thyra::VectorSpaceBase<double>> SpatulaModel::get_x_space() const { return space_; }
Teuchos::RCP<const Thyra::VectorSpaceBase<double>> SpatulaModel::get_f_space() const { return space_; }

Base::InArgs<double> SpatulaModel::createInArgs() const
{
  Base::InArgsSetup<double> in;
  in.setModelEvalDescription("spatula adhesion model");
  in.setSupports(Base::IN_ARG_x);
  return std::move(in);
}

Base::InArgs<double> SpatulaModel::getNominalValues() const
{
  auto nominal = createInArgs();
  nominal.set_x(Thyra::createVector(system_->create_vector(), space_));
  return nominal;
}

Teuchos::RCP<Thyra::LinearOpBase<double>> SpatulaModel::create_W_op() const
{
  return Thyra::tpetraLinearOp<double, LocalOrdinal, GlobalOrdinal, Node>(space_, space_, system_->jacobian());
}

Teuchos::RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> SpatulaModel::get_W_factory() const
{
  return linear_solver_;
}

Base::OutArgs<double> SpatulaModel::createOutArgsImpl() const
{
  Base::OutArgsSetup<double> out;
  out.setModelEvalDescription("spatula adhesion model");
  out.setSupports(Base::OUT_ARG_f);
  out.setSupports(Base::OUT_ARG_W_op);
  return std::move(out);
}

void SpatulaModel::evalModelImpl(const Base::InArgs<double>& in, const Base::OutArgs<double>& out) const
{
  const auto x = Extract::getConstTpetraVector(in.get_x());
  const auto f_out = out.get_f();
  const auto W_out = out.get_W_op();
  const auto f = f_out.is_null() ? Teuchos::null : Extract::getTpetraVector(f_out);
  const bool with_jacobian = !W_out.is_null();
  ++(with_jacobian ? counters_.jacobians : counters_.residuals);
  // A state with non-finite entries (a failed linear solve upstream) is inadmissible as it stands.
  if (!std::isfinite(x->norm1())) {
    last_ = discretization::Evaluation{};
    last_.admissible = false;
  } else {
    last_ = system_->evaluate(*x, f.get(), with_jacobian);
  }
  if (!last_.admissible && with_jacobian)
    throw std::runtime_error("tangent asked at an inadmissible state (inverted element " +
                             std::to_string(last_.inverted_element) + " or non-finite displacements)");
  if (!last_.admissible) {
    // An inverted element: no residual exists. A huge one makes NOX's line search step back.
    ++counters_.inadmissible;
    if (!f.is_null()) f->putScalar(1e100);
  }
}

}  // namespace spatula::solvers
