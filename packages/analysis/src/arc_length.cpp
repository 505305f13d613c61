// LoadPath::arc_length: LOCA's arc-length continuation over the Thyra model, with the controlled end-face master
// exposed as the continuation parameter (SpatulaModel::set_continuation_parameter) and df/dp from the assembly.
#include "analysis/load_stepping.hpp"

#include <LOCA.H>
#include <LOCA_Thyra.H>
#include <LOCA_Thyra_Group.H>
#include <LOCA_Thyra_SaveDataStrategy.H>
#include <NOX_StatusTest_Combo.H>
#include <NOX_StatusTest_MaxIters.H>
#include <NOX_StatusTest_NormF.H>
#include <NOX_Thyra_Vector.H>
#include <Teuchos_TimeMonitor.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>

#include <cstdlib>
#include <sstream>

namespace spatula::analysis {

namespace {

using discretization::GlobalOrdinal;
using discretization::LocalOrdinal;
using discretization::Node;
using Extract = Thyra::TpetraOperatorVectorExtraction<double, LocalOrdinal, GlobalOrdinal, Node>;

// Hands every converged continuation point back to the load path.
class Recorder : public LOCA::Thyra::SaveDataStrategy {
public:
  Recorder(std::function<void(const discretization::Vector&, double)> save) : save_(std::move(save)) {}
  void saveSolution(const NOX::Abstract::Vector& x, double p) override
  {
    const auto& thyra = dynamic_cast<const NOX::Thyra::Vector&>(x);
    save_(*Extract::getConstTpetraVector(thyra.getThyraRCPVector()), p);
  }

private:
  std::function<void(const discretization::Vector&, double)> save_;
};

// Scoped exposure of the continuation parameter (the model goes back to x -> f afterwards).
struct ContinuationParameter {
  solvers::SpatulaModel& model;
  ContinuationParameter(solvers::SpatulaModel& m, Master master) : model(m) { model.set_continuation_parameter(master); }
  ~ContinuationParameter() { model.set_continuation_parameter(std::nullopt); }
};

}  // namespace

std::optional<Failure> LoadPath::arc_length(Master controlled, double resume_above,
                                            discretization::MasterControl control,
                                            const ArcLengthParameters& parameters, double unit,
                                            const Callback& on_point)
{
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewTimer("spatula: arc-length continuation"));
  auto& system = model_.system();
  control.prescribed[static_cast<int>(controlled)] = true;
  set_control(control);
  const double start = system.master(*x_, controlled);
  ContinuationParameter exposed(model_, controlled);

  auto list = Teuchos::rcp(new Teuchos::ParameterList("continuation"));
  auto& loca = list->sublist("LOCA");
  auto& stepper = loca.sublist("Stepper");
  stepper.set("Continuation Method", "Arc Length");
  stepper.set("Continuation Parameter", "load");
  stepper.set("Initial Value", start);
  stepper.set("Max Value", resume_above);
  stepper.set("Min Value", start - 1e6);   // must not exceed the initial value (else LOCA stops at once)
  stepper.set("Max Steps", parameters.maximum_steps);
  stepper.set("Max Nonlinear Iterations", 25);
  stepper.set("Compute Eigenvalues", false);
  stepper.set("Enable Arc Length Scaling", true);
  stepper.set("Goal Arc Length Parameter Contribution", 0.5);
  loca.sublist("Bifurcation").set("Type", "None");
  loca.sublist("Predictor").set("Method", "Secant");
  loca.sublist("Predictor").sublist("First Step Predictor").set("Method", "Tangent");
  auto& step = loca.sublist("Step Size");
  step.set("Method", "Adaptive");
  step.set("Initial Step Size", parameters.initial);
  step.set("Min Step Size", parameters.minimum);
  step.set("Max Step Size", parameters.maximum);
  step.set("Aggressiveness", 0.5);
  auto& nox = list->sublist("NOX");
  nox.set("Nonlinear Solver", "Line Search Based");
  nox.sublist("Line Search").set("Method", "Full Step");
  nox.sublist("Direction").set("Method", "Newton");
  nox.sublist("Direction").sublist("Newton").sublist("Linear Solver").set("Tolerance", 1e-10);
  nox.sublist("Printing").set("Output Information", std::getenv("SPATULA_LOCA_DEBUG") ? 0x3 : 0);
  loca.sublist("Utilities").set("Output Information", std::getenv("SPATULA_LOCA_DEBUG") ? 0x7f : 0);

  auto global = LOCA::createGlobalData(list);
  LOCA::ParameterVector parameter_vector;
  parameter_vector.addParameter("load", start);
  auto working = Teuchos::rcp(new discretization::Vector(*x_, Teuchos::Copy));
  NOX::Thyra::Vector guess(Thyra::createVector(working, model_.get_x_space()));
  auto group = Teuchos::rcp(new LOCA::Thyra::Group(global, guess, Teuchos::rcpFromRef(model_), parameter_vector, 0,
                                                   true));
  int recorded = 0;
  double reached = start;
  group->setSaveDataStrategy(Teuchos::rcp(new Recorder([&](const discretization::Vector& x, double p) {
    auto state = Teuchos::rcp(new discretization::Vector(x, Teuchos::Copy));
    system.set_master(*state, controlled, p);
    reached = p;
    if (recorded++ == 0) return;   // LOCA saves the starting point too: it is already ours
    accept(*state, 0, -1, on_point);
  })));

  using namespace NOX::StatusTest;
  auto tests = Teuchos::rcp(new Combo(Combo::OR));
  tests->addStatusTest(Teuchos::rcp(new NormF(1e-8)));
  tests->addStatusTest(Teuchos::rcp(new MaxIters(25)));
  LOCA::Stepper loca_stepper(global, group, tests, list);
  LOCA::Abstract::Iterator::IteratorStatus status = LOCA::Abstract::Iterator::Failed;
  std::string what;
  try {
    status = loca_stepper.run();
  } catch (const std::bad_alloc&) {
    LOCA::destroyGlobalData(global);
    throw;   // not a stop of the continuation: see solvers/out_of_memory.hpp
  } catch (const std::exception& error) {
    what = error.what();
  }
  LOCA::destroyGlobalData(global);
  if (reached > resume_above) return std::nullopt;
  Failure failure;
  failure.step = next_step();
  failure.load = reached / unit;
  failure.smallest_increment = parameters.minimum;
  std::ostringstream reason;
  reason << "arc-length continuation stopped at " << reached / unit << " before passing " << resume_above / unit
         << " (LOCA status " << static_cast<int>(status) << ", " << recorded - 1 << " points)";
  if (!what.empty()) reason << " (" << what << ")";
  failure.reason = reason.str();
  return failure;
}

}  // namespace spatula::analysis
