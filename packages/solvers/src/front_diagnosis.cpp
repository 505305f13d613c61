#include "solvers/front_diagnosis.hpp"

#include <iomanip>
#include <sstream>

namespace spatula::solvers {

FrontDiagnosis diagnose_front(const SpatulaModel& model, const discretization::Vector& from,
                              const discretization::Vector& full, double fraction)
{
  auto& system = model.system();
  FrontDiagnosis diagnosis;
  diagnosis.gaps = system.contact_gap_changes(from, full, fraction);
  const double start = system.evaluate(from, nullptr, false).energy();
  discretization::Vector x(from.getMap());
  for (std::size_t k = 0; k < FrontDiagnosis::fractions.size(); ++k) {
    const double t = FrontDiagnosis::fractions[k];
    x.update(1.0 - t, from, t, full, 0.0);
    const auto evaluation = system.evaluate(x, nullptr, false);
    diagnosis.energy_change[k] = evaluation.admissible ? evaluation.energy() - start : 1e300;
  }
  return diagnosis;
}

std::string front_line(const FrontDiagnosis& diagnosis, double fraction)
{
  const auto& gaps = diagnosis.gaps;
  std::ostringstream line;
  line << "      full step: " << gaps.crossing << " contact points cross the law's inflection";
  if (gaps.crossing > 0)
    line << std::fixed << std::setprecision(1) << " (at X = " << gaps.mean[0] << " +- " << gaps.spread[0]
         << ", Y = " << gaps.mean[1] << " +- " << gaps.spread[1] << " nm)";
  line << std::defaultfloat << std::setprecision(4) << "; Pi - Pi_0 at t = ";
  for (std::size_t k = 0; k < FrontDiagnosis::fractions.size(); ++k)
    line << (k ? ", " : "") << FrontDiagnosis::fractions[k] << ": " << diagnosis.energy_change[k];
  line << " nN nm, of which their Pi_c ";
  for (std::size_t k = 0; k < FrontDiagnosis::fractions.size(); ++k) line << (k ? ", " : "") << gaps.energy_change[k];
  line << "; " << gaps.large << " points' gaps change by more than " << fraction << " r0\n";
  return line.str();
}

}  // namespace spatula::solvers
