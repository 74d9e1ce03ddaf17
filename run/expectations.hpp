// Checks a run against its scenario's expectations (scenarios/SCHEMA.md,
// section `expect`): parameter errors, cost, kmrmse, the ratio to the
// Cramer-Rao bound, and the accuracy after compensation.
#pragma once

#include <vector>

namespace gpm::scenario {

struct RunOutcome;
struct Check;

// One Check per expectation set in outcome.spec.expect.
std::vector<Check> evaluate_expectations(const RunOutcome& outcome);

}  // namespace gpm::scenario
