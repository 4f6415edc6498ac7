#pragma once
/// `straight`: head for each mission waypoint in turn in a straight line.
/// The simplest closed-loop planner, and the baseline the others are compared to.
#include <memory>

#include "campo/config_fields.hpp"
#include "campo/planner.hpp"

namespace campo {

struct StraightConfig {
  double speed_mps = 0.6;    ///< cruise speed (seed 000 flew at 0.6 m/s)
  double tolerance_m = 0.3;  ///< a waypoint counts as reached within this distance
  bool horizontal = false;   ///< measure distance in x, y only (default true for the rover)
};

/// The fields of `params` (parameters() writes them back). The table's
/// defaults are the quadrotor's; the rover's differ (make_straight_planner).
const ConfigFields<StraightConfig>& straight_config_fields();

std::unique_ptr<Planner> make_straight_planner(const ParamsBlock& params, const PlannerContext& context);

}  // namespace campo
