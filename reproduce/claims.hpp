#pragma once
/// The claims of each seed thesis, measured: each function runs its
/// experiments on the workbench and returns the claims with their verdicts.
#include <vector>

#include "reproduce/report.hpp"
#include "reproduce/workbench.hpp"

namespace campo {

/// Seed 000: Table 5.1, Fig. 5.6, Fig. 5.5 (terrain following), the field-of-view and range sweep.
std::vector<Claim> seed_000_claims(const Workbench& bench);

}  // namespace campo
