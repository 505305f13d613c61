#pragma once
// What the project's Thyra preconditioner factories share (MUMPS, the algebraic multigrid): the tangent is a Tpetra
// CrsMatrix, the preconditioner a DefaultPreconditioner holding one Tpetra operator that approximates its inverse,
// and the factory takes no parameters through Stratimikos. A subclass says how the operator is made for a tangent.
#include "discretization/tpetra_types.hpp"

#include <Thyra_DefaultPreconditioner.hpp>
#include <Thyra_PreconditionerFactoryBase.hpp>
#include <Thyra_TpetraLinearOp.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>

#include <string>

namespace spatula::solvers {

class InversePreconditionerFactory : public Thyra::PreconditionerFactoryBase<double> {
public:
  explicit InversePreconditionerFactory(std::string name) : name_(std::move(name)) {}

  bool isCompatible(const Thyra::LinearOpSourceBase<double>& source) const override
  {
    return !matrix_of(source).is_null();
  }
  Teuchos::RCP<Thyra::PreconditionerBase<double>> createPrec() const override
  {
    return Teuchos::rcp(new Thyra::DefaultPreconditioner<double>);
  }
  void uninitializePrec(Thyra::PreconditionerBase<double>* preconditioner,
                        Teuchos::RCP<const Thyra::LinearOpSourceBase<double>>* source,
                        Thyra::ESupportSolveUse* use) const override
  {
    if (source) *source = Teuchos::null;
    if (use) *use = Thyra::SUPPORT_SOLVE_UNSPECIFIED;
    dynamic_cast<Thyra::DefaultPreconditioner<double>&>(*preconditioner).uninitialize();
  }

  void setParameterList(const Teuchos::RCP<Teuchos::ParameterList>& list) override { list_ = list; }
  Teuchos::RCP<Teuchos::ParameterList> getNonconstParameterList() override { return list_; }
  Teuchos::RCP<Teuchos::ParameterList> unsetParameterList() override
  {
    auto old = list_;
    list_ = Teuchos::null;
    return old;
  }
  Teuchos::RCP<const Teuchos::ParameterList> getValidParameters() const override
  {
    return Teuchos::rcp(new Teuchos::ParameterList(name_));
  }

protected:
  // The tangent behind a Thyra operator source (null if it is not a Tpetra CrsMatrix).
  static Teuchos::RCP<const discretization::CrsMatrix> matrix_of(const Thyra::LinearOpSourceBase<double>& source)
  {
    using ThyraOperator = Thyra::TpetraLinearOp<double, discretization::LocalOrdinal, discretization::GlobalOrdinal,
                                                discretization::Node>;
    const auto op = Teuchos::rcp_dynamic_cast<const ThyraOperator>(source.getOp());
    if (op.is_null()) return Teuchos::null;
    return Teuchos::rcp_dynamic_cast<const discretization::CrsMatrix>(op->getConstTpetraOperator());
  }
  // Makes `inverse` (an operator on `map`) the preconditioner's.
  static void hold(Thyra::PreconditionerBase<double>& preconditioner,
                   const Teuchos::RCP<const discretization::Map>& map,
                   const Teuchos::RCP<discretization::Operator>& inverse)
  {
    const auto space = Thyra::tpetraVectorSpace<double>(map);
    const Teuchos::RCP<const Thyra::LinearOpBase<double>> op =
        Thyra::tpetraLinearOp<double, discretization::LocalOrdinal, discretization::GlobalOrdinal,
                              discretization::Node>(space, space, inverse);
    dynamic_cast<Thyra::DefaultPreconditioner<double>&>(preconditioner).initializeUnspecified(op);
  }

private:
  std::string name_;
  Teuchos::RCP<Teuchos::ParameterList> list_;
};

}  // namespace spatula::solvers
