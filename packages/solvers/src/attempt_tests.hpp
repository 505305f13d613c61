#pragma once
// When a Newton attempt stops short of convergence: NOX status tests on the iterations of one attempt (the
// rules are described in attempt_tests.cpp).
#include <NOX_StatusTest_Generic.H>
#include <Teuchos_RCP.hpp>

#include <functional>
#include <string>

namespace spatula::solvers {

// Whether an iteration counts towards giving up, from |f| now, |f| before and the line-search step (1 without one).
using GiveUpRule = std::function<bool(double now, double before, double step)>;

// Fails once `limit` iterations in a row met `rule` while |f| was still above `far` times the attempt's first |f|
// and above `floor`.
Teuchos::RCP<NOX::StatusTest::Generic> give_up_test(std::string description, int limit, double far, double floor,
                                                    GiveUpRule rule);

// Fails at `limit` iterations unless the attempt is converging (its last two iterations each cut |f| to
// `contraction` or less), and at `limit` + `extension` in any case.
Teuchos::RCP<NOX::StatusTest::Generic> iteration_limit_test(int limit, int extension, double contraction);

}  // namespace spatula::solvers
