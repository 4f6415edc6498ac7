#pragma once
/// The claims of each seed thesis, measured: each function runs its
/// experiments on the workbench and returns the claims with their verdicts.
#include <vector>

#include "reproduce/report.hpp"
#include "reproduce/workbench.hpp"

namespace campo {

/// Seed 000: Table 5.1, Fig. 5.6, Fig. 5.5 (terrain following), the field-of-view and range sweep.
std::vector<Claim> seed_000_claims(const Workbench& bench);

/// Seed 001: the obstacles and routes of Tabelle 5.1-5.6, the three behaviours (the slot, the weave, the wall),
/// the bridge with column and OctoMap mapping, Figures 5.4-5.13.
std::vector<Claim> seed_001_claims(const Workbench& bench);

/// Seed 003: Fig. 45 (random obstacles), no local minimum (§2.4.2), Fig. 46 (a crossing walker), Fig. 44
/// (hysteresis), tracking and slowing in curves, Fig. 35 (lookahead), Fig. 33 (Dubins route), a start off the route.
std::vector<Claim> seed_003_claims(const Workbench& bench);

}  // namespace campo
