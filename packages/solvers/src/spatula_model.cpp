#include "solvers/spatula_model.hpp"

#include <Thyra_DetachedVectorView.hpp>
#include <Thyra_TpetraLinearOp.hpp>
#include <Thyra_VectorStdOps.hpp>

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
      space_(Thyra::tpetraVectorSpace<double>(system_->owned_map())),
      parameter_space_(Thyra::tpetraVectorSpace<double>(
          Tpetra::createLocalMapWithNode<LocalOrdinal, GlobalOrdinal, Node>(1, system_->owned_map()->getComm())))
{
}

Teuchos::RCP<const Thyra::VectorSpaceBase<double>> SpatulaModel::get_p_space(int index) const
{
  if (!parameter_ || index != 0) throw std::logic_error("SpatulaModel: no parameter " + std::to_string(index));
  return parameter_space_;
}

Teuchos::RCP<const Teuchos::Array<std::string>> SpatulaModel::get_p_names(int index) const
{
  if (!parameter_ || index != 0) throw std::logic_error("SpatulaModel: no parameter " + std::to_string(index));
  return Teuchos::rcp(new Teuchos::Array<std::string>(1, "load"));
}

Teuchos::RCP<const Thyra::VectorSpaceBase<double>> SpatulaModel::get_x_space() const { return space_; }
Teuchos::RCP<const Thyra::VectorSpaceBase<double>> SpatulaModel::get_f_space() const { return space_; }

Base::InArgs<double> SpatulaModel::createInArgs() const
{
  Base::InArgsSetup<double> in;
  in.setModelEvalDescription("spatula adhesion model");
  in.set_Np(parameter_ ? 1 : 0);
  in.setSupports(Base::IN_ARG_x);
  return std::move(in);
}

Base::InArgs<double> SpatulaModel::getNominalValues() const
{
  auto nominal = createInArgs();
  nominal.set_x(Thyra::createVector(system_->create_vector(), space_));
  if (parameter_) {
    auto p = Thyra::createMember(parameter_space_);
    Thyra::assign(p.ptr(), 0.0);
    nominal.set_p(0, p);
  }
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
  out.set_Np_Ng(parameter_ ? 1 : 0, 0);
  out.setSupports(Base::OUT_ARG_f);
  out.setSupports(Base::OUT_ARG_W_op);
  if (parameter_) out.setSupports(Base::OUT_ARG_DfDp, 0, Base::DerivativeSupport(Base::DERIV_MV_BY_COL));
  return std::move(out);
}

const discretization::Evaluation& SpatulaModel::evaluate(const discretization::Vector& x,
                                                         discretization::Vector* residual, bool with_jacobian) const
{
  ++(with_jacobian ? counters_.jacobians : counters_.residuals);
  // A state with non-finite entries (a failed linear solve upstream) is inadmissible as it stands.
  if (!std::isfinite(x.norm1())) {
    last_ = discretization::Evaluation{};
    last_.admissible = false;
  } else {
    last_ = system_->evaluate(x, residual, with_jacobian);
  }
  if (!last_.admissible) {
    // An inverted element: no residual exists. A huge one makes NOX's line search step back.
    ++counters_.inadmissible;
    if (residual) residual->putScalar(1e100);
  }
  return last_;
}

void SpatulaModel::evalModelImpl(const Base::InArgs<double>& in, const Base::OutArgs<double>& out) const
{
  Teuchos::RCP<const discretization::Vector> x = Extract::getConstTpetraVector(in.get_x());
  const auto f_out = out.get_f();
  const auto W_out = out.get_W_op();
  const auto f = f_out.is_null() ? Teuchos::null : Extract::getTpetraVector(f_out);
  Teuchos::RCP<Thyra::MultiVectorBase<double>> dfdp;
  if (parameter_ && !out.get_DfDp(0).isEmpty()) dfdp = out.get_DfDp(0).getMultiVector();
  if (parameter_ && !in.get_p(0).is_null()) {   // the controlled master's value comes from p
    auto shifted = Teuchos::rcp(new discretization::Vector(*x, Teuchos::Copy));
    system_->set_master(*shifted, *parameter_, Thyra::get_ele(*in.get_p(0), 0));
    x = shifted;
  }
  const bool with_jacobian = !W_out.is_null() || !dfdp.is_null();
  if (!evaluate(*x, f.get(), with_jacobian).admissible) {
    if (with_jacobian)
      throw std::runtime_error("tangent asked at an inadmissible state (inverted element " +
                               std::to_string(last_.inverted_element) + " or non-finite displacements)");
    return;
  }
  if (!dfdp.is_null()) {
    auto target = Extract::getTpetraMultiVector(dfdp);
    target->getVectorNonConst(0)->assign(*system_->load_derivatives().getVector(static_cast<int>(*parameter_)));
  }
}

}  // namespace spatula::solvers
