#include "reproduce/seed_003_criteria.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "reproduce/trajectory_checks.hpp"

namespace campo {

OutcomeCounts count_outcomes(const std::vector<RunOutcome>& runs) {
  OutcomeCounts c;
  for (const RunOutcome& r : runs) {
    ++c.runs;
    c.reached += r.reached;
    c.collision_free += r.collisions == 0;
    const bool clean = r.reached && r.collisions == 0;
    c.reached_clean += clean;
    c.with_avoidance += r.avoiding_s > 0.0;
    c.avoided += clean && r.avoiding_s > 0.0;
  }
  return c;
}

std::optional<bool> every_run_reaches_without_collision(const std::vector<RunOutcome>& runs) {
  if (runs.empty()) return std::nullopt;
  const OutcomeCounts c = count_outcomes(runs);
  return c.reached_clean == c.runs;
}

std::optional<bool> never_trapped(const std::vector<RunOutcome>& runs) {
  if (runs.empty()) return std::nullopt;
  return std::none_of(runs.begin(), runs.end(), [](const RunOutcome& r) { return r.timed_out; });
}

double longest_standstill_s(const std::vector<double>& time_s, const std::vector<double>& speed_mps, double still_mps) {
  const std::size_t n = std::min(time_s.size(), speed_mps.size());
  double longest = 0.0;
  std::optional<double> since;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(speed_mps[i]) < still_mps) {
      if (!since) since = time_s[i];
      longest = std::max(longest, time_s[i] - *since);
    } else {
      since.reset();
    }
  }
  return longest;
}

std::vector<int> gap_sides(const std::vector<double>& chosen_centre_deg) {
  std::vector<int> sides;
  for (double c : chosen_centre_deg) {
    if (c == 0.0 || !std::isfinite(c)) continue;
    const int side = c > 0.0 ? 1 : -1;
    if (sides.empty() || sides.back() != side) sides.push_back(side);
  }
  return sides;
}

bool switches_right_then_left(const std::vector<double>& chosen_centre_deg) {
  const std::vector<int> sides = gap_sides(chosen_centre_deg);
  return sides.size() >= 2 && sides[0] < 0 && sides[1] > 0;
}

int fig46_switches(const std::vector<CrossingRun>& runs) {
  int n = 0;
  for (const CrossingRun& r : runs) n += switches_right_then_left(r.chosen_centre_deg);
  return n;
}

std::optional<bool> fig46_holds(const std::vector<CrossingRun>& runs) {
  if (runs.empty()) return std::nullopt;
  std::vector<RunOutcome> outcomes;
  for (const CrossingRun& r : runs) outcomes.push_back(r.outcome);
  return fig46_switches(runs) > 0 && *every_run_reaches_without_collision(outcomes);
}

int steering_reversals(const std::vector<double>& heading_deg, double deadband_deg) {
  int reversals = 0, last = 0;
  for (double h : heading_deg) {
    if (!std::isfinite(h) || std::abs(h) <= deadband_deg) continue;
    const int sign = h > 0.0 ? 1 : -1;
    if (last != 0 && sign != last) ++reversals;
    last = sign;
  }
  return reversals;
}

int gap_flips(const std::vector<double>& chosen_centre_deg, double jump_deg) {
  std::vector<std::pair<double, double>> stretches;  // first and last value of each stretch
  for (double c : chosen_centre_deg) {
    if (!std::isfinite(c)) continue;
    if (!stretches.empty() && std::abs(c - stretches.back().second) <= jump_deg) stretches.back().second = c;
    else stretches.push_back({c, c});
  }
  int flips = 0;
  for (std::size_t k = 2; k < stretches.size(); ++k) {
    flips += std::abs(stretches[k].first - stretches[k - 2].second) <= jump_deg;
  }
  return flips;
}

std::optional<bool> hysteresis_holds(const std::vector<int>& flips_without_bonus,
                                     const std::vector<int>& flips_with_bonus, int indecisive) {
  if (flips_without_bonus.empty() || flips_with_bonus.empty()) return std::nullopt;
  const auto undecided = [&](int r) { return r >= indecisive; };
  return std::any_of(flips_without_bonus.begin(), flips_without_bonus.end(), undecided) &&
         std::none_of(flips_with_bonus.begin(), flips_with_bonus.end(), undecided);
}

double signed_cross_track(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& route) {
  if (route.empty()) return std::numeric_limits<double>::infinity();
  if (route.size() == 1) return (point - route.front()).norm();
  double best = std::numeric_limits<double>::infinity(), signed_best = best;
  for (std::size_t i = 1; i < route.size(); ++i) {
    const Eigen::Vector2d a = route[i - 1], ab = route[i] - a;
    const double length2 = ab.squaredNorm();
    if (length2 <= 0.0) continue;
    const double t = std::clamp((point - a).dot(ab) / length2, 0.0, 1.0);
    const Eigen::Vector2d d = point - (a + t * ab);
    const double distance = d.norm();
    if (distance < best) {
      best = distance;
      const double cross = ab.x() * (point - a).y() - ab.y() * (point - a).x();
      signed_best = cross >= 0.0 ? distance : -distance;
    }
  }
  return signed_best;
}

std::vector<double> route_curvature(const std::vector<Eigen::Vector2d>& route) {
  std::vector<double> k(route.size(), 0.0);
  for (std::size_t i = 1; i + 1 < route.size(); ++i) {
    const Eigen::Vector2d u = route[i] - route[i - 1], v = route[i + 1] - route[i];
    const double mean_length = 0.5 * (u.norm() + v.norm());
    if (mean_length <= 0.0) continue;
    k[i] = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)) / mean_length;
  }
  return k;
}

namespace {

std::size_t nearest_index(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& route) {
  std::size_t best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < route.size(); ++i) {
    const double d2 = (route[i] - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = i;
  }
  return best;
}

}  // namespace

SpeedByCurvature speed_by_curvature(const std::vector<Eigen::Vector2d>& track, const std::vector<double>& speed_mps,
                                    const std::vector<Eigen::Vector2d>& route, double straight_max, double curve_min) {
  SpeedByCurvature out;
  if (route.empty()) return out;
  const std::vector<double> k = route_curvature(route);
  double straight_sum = 0.0, curve_sum = 0.0;
  for (std::size_t i = 0; i < std::min(track.size(), speed_mps.size()); ++i) {
    const std::size_t j = nearest_index(track[i], route);
    // Curvature over the neighbours too: a point at a junction of straight and arc belongs to neither.
    double kmin = std::abs(k[j]), kmax = kmin;
    for (std::size_t m = j > 0 ? j - 1 : 0; m <= std::min(j + 1, k.size() - 1); ++m) {
      if (m == 0 || m + 1 == k.size()) continue;
      kmin = std::min(kmin, std::abs(k[m]));
      kmax = std::max(kmax, std::abs(k[m]));
    }
    const double cross = distance_to_polyline(track[i], route);
    if (kmax <= straight_max) {
      ++out.straight_samples;
      straight_sum += speed_mps[i];
      out.straight_cross_track_max_m = std::max(out.straight_cross_track_max_m, cross);
    } else if (kmin >= curve_min) {
      ++out.curve_samples;
      curve_sum += speed_mps[i];
      out.curve_cross_track_max_m = std::max(out.curve_cross_track_max_m, cross);
    }
  }
  if (out.straight_samples) out.straight_mps = straight_sum / out.straight_samples;
  if (out.curve_samples) out.curve_mps = curve_sum / out.curve_samples;
  return out;
}

std::optional<bool> tracking_holds(double cross_track_max_m, double free_half_width_m, const SpeedByCurvature& s) {
  if (s.straight_samples == 0 || s.curve_samples == 0) return std::nullopt;
  return cross_track_max_m < free_half_width_m && s.curve_mps < s.straight_mps;
}

std::optional<double> distance_to_rejoin_m(const std::vector<Eigen::Vector2d>& track,
                                           const std::vector<Eigen::Vector2d>& route, double within_m) {
  double travelled = 0.0;
  for (std::size_t i = 0; i < track.size(); ++i) {
    if (i > 0) travelled += (track[i] - track[i - 1]).norm();
    if (distance_to_polyline(track[i], route) <= within_m) return travelled;
  }
  return std::nullopt;
}

std::optional<bool> every_run_rejoins(const std::vector<std::optional<double>>& rejoin_m,
                                      const std::vector<RunOutcome>& runs) {
  if (runs.empty() || rejoin_m.size() != runs.size()) return std::nullopt;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!rejoin_m[i] || !runs[i].reached || runs[i].collisions != 0) return false;
  }
  return true;
}

int oscillations(const std::vector<double>& signed_offset_m, double band_m) {
  int swings = 0, last = 0;
  for (double o : signed_offset_m) {
    if (!std::isfinite(o)) continue;
    const int side = o > band_m ? 1 : o < -band_m ? -1 : 0;
    if (side == 0) continue;
    if (last != 0 && side != last) ++swings;
    last = side;
  }
  return swings;
}

std::optional<bool> lookahead_holds(const std::vector<LookaheadRun>& runs, double reference_m) {
  const LookaheadRun* reference = nullptr;
  const LookaheadRun* smallest = nullptr;
  const LookaheadRun* largest = nullptr;
  for (const LookaheadRun& r : runs) {
    if (r.lookahead_m == reference_m) reference = &r;
    if (!smallest || r.lookahead_m < smallest->lookahead_m) smallest = &r;
    if (!largest || r.lookahead_m > largest->lookahead_m) largest = &r;
  }
  if (!reference || smallest->lookahead_m >= reference_m || largest->lookahead_m <= reference_m) return std::nullopt;
  return smallest->straight_oscillations > reference->straight_oscillations &&
         largest->curve_miss_m > reference->curve_miss_m;
}

double curve_miss_m(const std::vector<Eigen::Vector2d>& route, const std::vector<Eigen::Vector2d>& track,
                    double curve_min) {
  const std::vector<double> k = route_curvature(route);
  double worst = 0.0;
  for (std::size_t i = 0; i < route.size(); ++i) {
    if (std::abs(k[i]) < curve_min) continue;
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& p : track) best = std::min(best, (p - route[i]).squaredNorm());
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}

double max_distance_to_geometry(const std::vector<Eigen::Vector2d>& points, const std::vector<Segment2>& segments,
                                const std::vector<Circle2>& circles) {
  double worst = 0.0;
  for (const Eigen::Vector2d& p : points) {
    double best = std::numeric_limits<double>::infinity();
    for (const Segment2& s : segments) best = std::min(best, distance_to_polyline(p, {s.a, s.b}));
    for (const Circle2& c : circles) best = std::min(best, std::abs((p - c.centre).norm() - c.radius_m));
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace campo
