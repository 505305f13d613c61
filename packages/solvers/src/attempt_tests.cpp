#include "solvers/attempt_tests.hpp"

#include <NOX_Abstract_Group.H>
#include <NOX_Solver_Generic.H>
#include <NOX_Solver_LineSearchBased.H>

#include <ostream>

namespace spatula::solvers {

namespace {

// Gives up on a Newton attempt once `limit` iterations in a row met its rule while |f| was still above `far` times
// the residual the attempt started from. Two rules: hopeless (|f| left above `contraction` times its value before)
// and short steps (the line search cut the step to at most `short step`: Newton's direction does not lower |f|).
// The far condition spares the slow last iterations of a converging attempt (a nearly singular tangent at a peel
// front converges linearly, many orders below where it began); near a fold a hopeless attempt stays near its start.
class GiveUp : public NOX::StatusTest::Generic {
public:
  using Rule = GiveUpRule;
  // An iteration counts while |f| >= far |f_0| and |f| >= floor.
  GiveUp(std::string description, int limit, double far, double floor, Rule rule)
      : description_(std::move(description)), limit_(limit), far_(far), floor_(floor), rule_(std::move(rule))
  {
  }

  NOX::StatusTest::StatusType checkStatus(const NOX::Solver::Generic& solver, NOX::StatusTest::CheckType) override
  {
    const int iteration = solver.getNumIterations();
    if (iteration == 0) {   // a new attempt
      start_ = solver.getSolutionGroup().getNormF();
      count_ = last_ = 0;
      status_ = NOX::StatusTest::Unconverged;
      return status_;
    }
    if (iteration == last_) return status_;   // asked twice in one iteration
    last_ = iteration;
    const double now = solver.getSolutionGroup().getNormF(), before = solver.getPreviousSolutionGroup().getNormF();
    const auto* line_search = dynamic_cast<const NOX::Solver::LineSearchBased*>(&solver);
    const double step = line_search ? line_search->getStepSize() : 1.0;
    count_ = now >= far_ * start_ && now >= floor_ && rule_(now, before, step) ? count_ + 1 : 0;
    status_ = count_ >= limit_ ? NOX::StatusTest::Failed : NOX::StatusTest::Unconverged;
    return status_;
  }
  NOX::StatusTest::StatusType getStatus() const override { return status_; }
  std::ostream& print(std::ostream& stream, int indent) const override
  {
    return stream << std::string(indent, ' ') << status_ << " " << description_ << ": " << count_ << " of " << limit_
                  << " iterations in a row\n";
  }

private:
  std::string description_;
  int limit_;
  double far_, floor_;
  Rule rule_;
  double start_ = 0.0;
  int count_ = 0, last_ = 0;
  NOX::StatusTest::StatusType status_ = NOX::StatusTest::Unconverged;
};

// The iteration limit of an attempt, spared while it converges: at `limit` iterations an attempt fails unless each of
// its last two iterations cut |f| to `contraction` of its value before or less; such an attempt goes on, at most
// `extension` iterations more. At the medium peel front an attempt often needs 13-14 iterations, the last few
// converging fast: failing it at 12 threw its iterations away and the cut increments that followed bisected towards a
// load that was no limit point (docs/performance.md, "The peel front").
class IterationLimit : public NOX::StatusTest::Generic {
public:
  IterationLimit(int limit, int extension, double contraction)
      : limit_(limit), extension_(extension), contraction_(contraction)
  {
  }
  NOX::StatusTest::StatusType checkStatus(const NOX::Solver::Generic& solver, NOX::StatusTest::CheckType) override
  {
    const int iteration = solver.getNumIterations();
    if (iteration == 0) {
      older_ratio_ = 1.0;
      last_ = 0;
      status_ = NOX::StatusTest::Unconverged;
      return status_;
    }
    if (iteration == last_) return status_;   // asked twice in one iteration
    last_ = iteration;
    const double before = solver.getPreviousSolutionGroup().getNormF();
    const double ratio = before > 0.0 ? solver.getSolutionGroup().getNormF() / before : 1.0;
    const bool converging = ratio <= contraction_ && older_ratio_ <= contraction_;
    older_ratio_ = ratio;
    const bool spent = iteration >= limit_ + extension_ || (iteration >= limit_ && !converging);
    status_ = spent ? NOX::StatusTest::Failed : NOX::StatusTest::Unconverged;
    return status_;
  }
  NOX::StatusTest::StatusType getStatus() const override { return status_; }
  std::ostream& print(std::ostream& stream, int indent) const override
  {
    return stream << std::string(indent, ' ') << status_ << " iteration limit " << limit_ << " (+" << extension_
                  << " while converging)\n";
  }

private:
  int limit_, extension_;
  double contraction_;
  double older_ratio_ = 1.0;
  int last_ = 0;
  NOX::StatusTest::StatusType status_ = NOX::StatusTest::Unconverged;
};

}  // namespace

Teuchos::RCP<NOX::StatusTest::Generic> give_up_test(std::string description, int limit, double far, double floor,
                                                    GiveUpRule rule)
{
  return Teuchos::rcp(new GiveUp(std::move(description), limit, far, floor, std::move(rule)));
}

Teuchos::RCP<NOX::StatusTest::Generic> iteration_limit_test(int limit, int extension, double contraction)
{
  return Teuchos::rcp(new IterationLimit(limit, extension, contraction));
}

}  // namespace spatula::solvers
