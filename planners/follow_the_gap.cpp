#include "planners/follow_the_gap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "planners/pure_pursuit.hpp"

namespace campo {

int bubble_half_width(double radius_m, double nearest_range_m, double increment_rad) {
  // Touching (or a reading below zero): every sector; callers clip to the scan.
  constexpr int kAll = std::numeric_limits<int>::max() / 2;
  if (!(nearest_range_m > 0.0)) return kAll;
  const double sectors = radius_m / (nearest_range_m * std::abs(increment_rad));
  if (!(sectors < kAll)) return kAll;
  // A hair of tolerance so an exact quotient is not pushed up by rounding.
  return static_cast<int>(std::ceil(sectors - 1e-9));
}

namespace {

// free_distance() from the offset's cosine and sine (a table in the scan loop).
double free_distance_cs(double range_m, double cos_offset, double sin_offset, double radius_m) {
  const double along = range_m * cos_offset;
  const double lateral = range_m * sin_offset;
  if (std::abs(lateral) > radius_m || (along < 0.0 && range_m > radius_m)) return std::numeric_limits<double>::infinity();
  return std::max(0.0, along - std::sqrt(radius_m * radius_m - lateral * lateral));
}

}  // namespace

double free_distance(double range_m, double offset_rad, double radius_m) {
  return free_distance_cs(range_m, std::cos(offset_rad), std::sin(offset_rad), radius_m);
}

FollowTheGapStep follow_the_gap_step(const FollowTheGapConfig& config, FollowTheGapState& state,
                                     const PlanarScanView& scan, double goal_bearing_rad, double robot_heading_rad) {
  FollowTheGapStep step;
  step.heading_rad = goal_bearing_rad;
  const int beams = static_cast<int>(scan.ranges_m.size());
  const auto saturated = static_cast<float>(config.max_range_m + 1.0);

  // Saturate no-returns so they stand apart from readings just inside the range.
  std::vector<float> ranges(scan.ranges_m.begin(), scan.ranges_m.end());
  for (float& r : ranges) {
    if (!std::isfinite(r) || r >= config.max_range_m) r = saturated;
  }
  if (beams == 0) return step;
  const auto nearest = std::min_element(ranges.begin(), ranges.end());
  step.nearest_beam = static_cast<int>(nearest - ranges.begin());
  step.nearest_range_m = *nearest;
  step.active = step.nearest_range_m < config.activation_range_m;
  if (!step.active) {
    state.has_previous = false;
    return step;
  }

  // Safety bubble: the rover as a point, the nearest obstacle grown by R.
  const std::vector<float> saturated_ranges = ranges;
  const double d_min = step.nearest_range_m;
  step.bubble_half_width = bubble_half_width(config.bubble_radius_m, d_min, scan.increment_rad);
  step.bubble_first_beam = std::max(0, step.nearest_beam - step.bubble_half_width);
  step.bubble_last_beam = std::min(beams - 1, step.nearest_beam + step.bubble_half_width);
  std::fill(ranges.begin() + step.bubble_first_beam, ranges.begin() + step.bubble_last_beam + 1, 0.0f);

  // Free space: the bubble grows only the nearest reading by R, so other
  // near readings (a wall beside, the far side of a passage) would still
  // leave rays a point could take but the rover could not.
  const bool free_space = config.free_range_m > 0.0;
  const double dalpha = std::abs(scan.increment_rad);
  if (free_space) {
    std::vector<float> free = ranges;
    const double radius = config.bubble_radius_m;
    // Beams are evenly spaced, so the offsets' cosines and sines are shared by every reading.
    const int max_reach = std::min(beams - 1, static_cast<int>(std::ceil(M_PI / 2.0 / dalpha)));
    std::vector<double> cos_offset(max_reach + 1), sin_offset(max_reach + 1);
    for (int m = 0; m <= max_reach; ++m) {
      cos_offset[m] = std::cos(m * dalpha);
      sin_offset[m] = std::sin(m * dalpha);
    }
    for (int j = 0; j < beams; ++j) {
      const double d = saturated_ranges[j];
      if (!(d < config.free_range_m + radius)) continue;  // farther ones cannot shorten a beam below free_range_m
      const double half = d <= radius ? M_PI / 2.0 : std::asin(radius / d);
      const int reach = std::min(max_reach, static_cast<int>(std::ceil(half / dalpha)));
      for (int k = std::max(0, j - reach); k <= std::min(beams - 1, j + reach); ++k) {
        const int m = std::abs(k - j);
        const double t = free_distance_cs(d, cos_offset[m], sin_offset[m], radius);
        if (t < free[k]) free[k] = static_cast<float>(t);
      }
    }
    // A beam is free when the rover can drive past free_range_m along it; the rest blocks.
    for (float& r : free) {
      if (!(r > config.free_range_m)) r = 0.0f;
    }
    ranges = std::move(free);
  }

  // Gaps: maximal runs of unblocked beams, split (003 only) at range steps above the threshold.
  const double w = config.alpha_m / d_min;
  for (int i = 0; i < beams;) {
    if (ranges[i] <= 0.0f) {
      ++i;
      continue;
    }
    ScanGap g;
    g.first_beam = i;
    double sum = ranges[i];
    while (i + 1 < beams && ranges[i + 1] > 0.0f &&
           (free_space || std::abs(ranges[i + 1] - ranges[i]) <= config.gap_jump_m)) {
      sum += ranges[++i];
    }
    g.last_beam = i++;
    const double r1 = ranges[g.first_beam];
    const double r2 = ranges[g.last_beam];
    const double spread = scan.angle(g.last_beam) - scan.angle(g.first_beam);
    g.width_m = std::sqrt(std::max(0.0, r1 * r1 + r2 * r2 - 2.0 * r1 * r2 * std::cos(spread)));
    g.mean_range = sum / (g.last_beam - g.first_beam + 1) / config.max_range_m;
    g.center_rad = 0.5 * (scan.angle(g.first_beam) + scan.angle(g.last_beam));
    // Near obstacles (large a / d_min) pull the heading toward the gap's centre, far ones toward the goal.
    g.heading_rad = (w * g.center_rad + goal_bearing_rad) / (w + 1.0);
    double a1 = scan.angle(g.first_beam), a2 = scan.angle(g.last_beam);
    if (!free_space && !config.grow_gap_edges) {
      // As 003 §3.6 prints it: the blend is the heading, inside the gap or not.
    } else if (!free_space) {
      // 003's point-robot approach (§2.4.2): the obstacles bounding the gap
      // are grown by R too, not only the nearest one (the bubble). At a range
      // step the nearer reading is the obstacle's edge; the gap loses the
      // angle asin(R / d) that edge's growth covers. A bubble or the end of
      // the field of view bounds it as it is. Without this, the opening past
      // a box's edge that only a point fits is a gap, straight at the box.
      const auto edge_growth = [&](int inside, int outside) {
        if (outside < 0 || outside >= beams || ranges[outside] <= 0.0f) return 0.0;
        const double d = std::min(ranges[outside], ranges[inside]);
        return d <= config.bubble_radius_m ? M_PI / 2.0 : std::asin(config.bubble_radius_m / d);
      };
      const double step_sign = scan.increment_rad < 0.0 ? -1.0 : 1.0;
      a1 += step_sign * edge_growth(g.first_beam, g.first_beam - 1);
      a2 -= step_sign * edge_growth(g.last_beam, g.last_beam + 1);
      // Grown edges that cross leave no room for the rover: no gap.
      if (step_sign * (a2 - a1) < 0.0) continue;
    }
    // A goal behind an obstacle would otherwise pull the heading out of the gap, onto the obstacle.
    if (free_space || config.grow_gap_edges) {
      g.heading_rad = std::clamp(g.heading_rad, std::min(a1, a2), std::max(a1, a2));
    }
    g.score = config.k_width * g.width_m * g.mean_range +
              config.k_heading * (M_PI - std::abs(g.heading_rad - goal_bearing_rad));
    step.gaps.push_back(g);
  }

  // Hysteresis: the gap sharing most of the previous choice's sectors (at
  // least half a beam, compared in angle) gets the bonus.
  const auto half_width = [&](const ScanGap& g) { return 0.5 * (g.last_beam - g.first_beam + 1) * dalpha; };
  if (state.has_previous) {
    const double previous_center = wrap_to_pi(state.previous_center_world_rad - robot_heading_rad);
    double best_overlap = 0.5 * dalpha;
    ScanGap* favoured = nullptr;
    for (ScanGap& g : step.gaps) {
      const double overlap = std::min(
          {half_width(g) + state.previous_half_width_rad - std::abs(wrap_to_pi(g.center_rad - previous_center)),
           2.0 * half_width(g), 2.0 * state.previous_half_width_rad});
      if (overlap > best_overlap) {
        best_overlap = overlap;
        favoured = &g;
      }
    }
    if (favoured != nullptr) {
      favoured->score += config.hysteresis_bonus;
      favoured->previous = true;
    }
  }

  const auto best = std::max_element(step.gaps.begin(), step.gaps.end(),
                                     [](const ScanGap& a, const ScanGap& b) { return a.score < b.score; });
  if (best == step.gaps.end()) {
    state.has_previous = false;
  } else {
    step.chosen = static_cast<int>(best - step.gaps.begin());
    step.heading_rad = best->heading_rad;
    state.has_previous = true;
    state.previous_center_world_rad = wrap_to_pi(best->center_rad + robot_heading_rad);
    state.previous_half_width_rad = half_width(*best);
  }
  step.ranges_m = std::move(ranges);
  return step;
}

}  // namespace campo
