#include "planners/dubins.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace campo::dubins {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// A turn this close below a full turn is rounding noise of "no turn": read
/// as 0 so a straight run does not come out as a full circle plus a line.
constexpr double kFullTurnSnapRad = 1e-10;
/// Turning circles nearer than this (in radii) coincide: the path is one arc.
constexpr double kCoincidentCircles = 1e-10;
/// Slack (in radii) on the tangency limits of LSR/RSL (apart by 2) and
/// RLR/LRL (apart by 4), so touching circles are not lost to rounding.
constexpr double kTangencySlack = 1e-12;
/// Relative length difference below which two words tie.
constexpr double kTieTolerance = 1e-12;

/// The name and segment turns of each word, in enum order: +1 left, 0
/// straight, -1 right.
struct WordInfo {
  std::string_view name;
  std::array<int, 3> turn;
};
constexpr std::array<WordInfo, 6> kWordInfo = {{{"LSL", {1, 0, 1}},
                                                {"RSR", {-1, 0, -1}},
                                                {"LSR", {1, 0, -1}},
                                                {"RSL", {-1, 0, 1}},
                                                {"RLR", {-1, 1, -1}},
                                                {"LRL", {1, -1, 1}}}};

const WordInfo& info(Word word) { return kWordInfo[static_cast<std::size_t>(word)]; }

/// Angle in [0, 2 pi), with near-full turns snapped to 0.
double mod2pi(double angle) {
  double a = std::fmod(angle, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return a >= kTwoPi - kFullTurnSnapRad ? 0.0 : a;
}

double wrap_pi(double angle) { return angle - kTwoPi * std::floor((angle + kPi) / kTwoPi); }

/// The problem in the normalized frame: radius 1, start at the origin, goal
/// on the +x axis at distance d (the distance in radii); alpha and beta are
/// the start and goal headings measured from the start->goal direction.
/// Sines and cosines are shared by all six words.
struct Normalized {
  double d, alpha, beta;
  double sa, ca, sb, cb;
};

Normalized normalize(const Pose2& from, const Pose2& to, double radius_m) {
  const double dx = to.x_m - from.x_m;
  const double dy = to.y_m - from.y_m;
  const double direction = std::atan2(dy, dx);
  // Not reduced: they only enter sines, cosines and angles reduced later.
  const double alpha = from.heading_rad - direction;
  const double beta = to.heading_rad - direction;
  return {std::hypot(dx, dy) / radius_m, alpha, beta, std::sin(alpha), std::cos(alpha), std::sin(beta),
          std::cos(beta)};
}

/// Segment lengths in radii (arc angles, straight length / radius).
using Segments = std::array<double, 3>;

// In the normalized frame the left turning circle of a pose (x, y, h) is
// centred at (x - sin h, y + cos h) and the right one at (x + sin h, y - cos h).
// Every word is solved from the vector v between the start and goal circles
// of its first and last letters.

// Outer tangent of two equal circles: the straight runs parallel to v.
Segments solve_lsl(const Normalized& n) {
  const double vx = n.d - n.sb + n.sa;
  const double vy = n.cb - n.ca;
  const double p = std::hypot(vx, vy);
  const double heading = p < kCoincidentCircles ? n.beta : std::atan2(vy, vx);
  return {mod2pi(heading - n.alpha), p, mod2pi(n.beta - heading)};
}

Segments solve_rsr(const Normalized& n) {
  const double vx = n.d + n.sb - n.sa;
  const double vy = n.ca - n.cb;
  const double p = std::hypot(vx, vy);
  const double heading = p < kCoincidentCircles ? n.beta : std::atan2(vy, vx);
  return {mod2pi(n.alpha - heading), p, mod2pi(heading - n.beta)};
}

// Inner tangent: the straight crosses v at the angle whose tangent is 2 / p,
// turned towards the second circle; the circles must be at least 2 apart.
std::optional<Segments> solve_lsr(const Normalized& n) {
  const double vx = n.d + n.sb + n.sa;
  const double vy = -n.cb - n.ca;
  const double p_squared = vx * vx + vy * vy - 4.0;
  if (p_squared < -kTangencySlack) return std::nullopt;
  const double p = std::sqrt(std::max(0.0, p_squared));
  const double heading = std::atan2(vy, vx) + std::atan2(2.0, p);
  return Segments{mod2pi(heading - n.alpha), p, mod2pi(heading - n.beta)};
}

std::optional<Segments> solve_rsl(const Normalized& n) {
  const double vx = n.d - n.sb - n.sa;
  const double vy = n.cb + n.ca;
  const double p_squared = vx * vx + vy * vy - 4.0;
  if (p_squared < -kTangencySlack) return std::nullopt;
  const double p = std::sqrt(std::max(0.0, p_squared));
  const double heading = std::atan2(vy, vx) - std::atan2(2.0, p);
  return Segments{mod2pi(n.alpha - heading), p, mod2pi(n.beta - heading)};
}

// Three arcs: the middle circle touches both end circles, so its centre is 2
// from each, at angle acos(|v| / 4) off v; its arc is a half turn plus twice
// that angle. The circles must be at most 4 apart.
std::optional<Segments> solve_rlr(const Normalized& n) {
  const double vx = n.d + n.sb - n.sa;
  const double vy = n.ca - n.cb;
  const double half_distance = std::hypot(vx, vy) / 4.0;
  if (half_distance > 1.0 + kTangencySlack) return std::nullopt;
  const double p = kPi + 2.0 * std::acos(std::min(1.0, half_distance));
  const double t = mod2pi(n.alpha - std::atan2(vy, vx) + p / 2.0);
  return Segments{t, p, mod2pi(n.alpha - t + p - n.beta)};
}

std::optional<Segments> solve_lrl(const Normalized& n) {
  const double vx = n.d - n.sb + n.sa;
  const double vy = n.cb - n.ca;
  const double half_distance = std::hypot(vx, vy) / 4.0;
  if (half_distance > 1.0 + kTangencySlack) return std::nullopt;
  const double p = kPi + 2.0 * std::acos(std::min(1.0, half_distance));
  const double t = mod2pi(std::atan2(vy, vx) + p / 2.0 - n.alpha);
  return Segments{t, p, mod2pi(n.beta - n.alpha - t + p)};
}

std::optional<Segments> solve(Word word, const Normalized& n) {
  switch (word) {
    case Word::LSL: return solve_lsl(n);
    case Word::RSR: return solve_rsr(n);
    case Word::LSR: return solve_lsr(n);
    case Word::RSL: return solve_rsl(n);
    case Word::RLR: return solve_rlr(n);
    case Word::LRL: return solve_lrl(n);
  }
  return std::nullopt;
}

bool finite(const Pose2& pose) {
  return std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.heading_rad);
}

void check_inputs(const Pose2& from, const Pose2& to, double radius_m) {
  if (!(std::isfinite(radius_m) && radius_m > 0.0)) {
    throw std::invalid_argument("dubins: turning radius must be positive and finite, got " +
                                std::to_string(radius_m));
  }
  if (!finite(from) || !finite(to)) throw std::invalid_argument("dubins: poses must be finite");
}

Path make_path(const Pose2& from, Word word, double radius_m, const Segments& segments) {
  return {from, word, radius_m, {segments[0] * radius_m, segments[1] * radius_m, segments[2] * radius_m}};
}

/// Drive `length_m` from `pose`: straight (turn 0) or along a circle of
/// `radius_m` to the left (+1) or right (-1). Heading not wrapped.
Pose2 advance(const Pose2& pose, int turn, double length_m, double radius_m) {
  if (turn == 0) {
    return {pose.x_m + length_m * std::cos(pose.heading_rad), pose.y_m + length_m * std::sin(pose.heading_rad),
            pose.heading_rad};
  }
  const double heading = pose.heading_rad + turn * length_m / radius_m;
  return {pose.x_m + turn * radius_m * (std::sin(heading) - std::sin(pose.heading_rad)),
          pose.y_m - turn * radius_m * (std::cos(heading) - std::cos(pose.heading_rad)), heading};
}

}  // namespace

std::string_view to_string(Word word) { return info(word).name; }

double Path::length_m() const { return segment_lengths_m[0] + segment_lengths_m[1] + segment_lengths_m[2]; }

Pose2 Path::pose_at(double s_m) const {
  double remaining = std::clamp(s_m, 0.0, length_m());
  Pose2 pose = start;
  for (std::size_t i = 0; i < 3 && remaining > 0.0; ++i) {
    const double run = std::min(remaining, segment_lengths_m[i]);
    pose = advance(pose, info(word).turn[i], run, radius_m);
    remaining -= run;
  }
  pose.heading_rad = wrap_pi(pose.heading_rad);
  return pose;
}

std::optional<Path> path(const Pose2& from, const Pose2& to, double radius_m, Word word) {
  check_inputs(from, to, radius_m);
  const std::optional<Segments> segments = solve(word, normalize(from, to, radius_m));
  if (!segments) return std::nullopt;
  return make_path(from, word, radius_m, *segments);
}

Path shortest_path(const Pose2& from, const Pose2& to, double radius_m) {
  check_inputs(from, to, radius_m);
  const Normalized n = normalize(from, to, radius_m);
  Word best_word = Word::LSL;
  Segments best = solve_lsl(n);
  double best_length = best[0] + best[1] + best[2];
  for (Word word : std::span(kWords).subspan(1)) {
    const std::optional<Segments> segments = solve(word, n);
    if (!segments) continue;
    const double length = (*segments)[0] + (*segments)[1] + (*segments)[2];
    if (length < best_length - kTieTolerance * std::max(1.0, best_length)) {
      best_word = word;
      best = *segments;
      best_length = length;
    }
  }
  return make_path(from, best_word, radius_m, best);
}

std::vector<Pose2> sample(const Path& path, double step_m) {
  if (!(std::isfinite(step_m) && step_m > 0.0)) {
    throw std::invalid_argument("dubins: sampling step must be positive and finite, got " + std::to_string(step_m));
  }
  const double length = path.length_m();
  const auto intervals = static_cast<std::size_t>(std::ceil(length / step_m));
  std::vector<Pose2> poses;
  poses.reserve(intervals + 1);
  poses.push_back(path.pose_at(0.0));
  for (std::size_t i = 1; i <= intervals; ++i) {
    poses.push_back(path.pose_at(i == intervals ? length : length * static_cast<double>(i) / static_cast<double>(intervals)));
  }
  return poses;
}

std::vector<Path> route(std::span<const Pose2> waypoints, double radius_m) {
  std::vector<Path> paths;
  for (std::size_t i = 1; i < waypoints.size(); ++i) paths.push_back(shortest_path(waypoints[i - 1], waypoints[i], radius_m));
  return paths;
}

std::vector<Pose2> sample_route(std::span<const Path> paths, double step_m) {
  std::vector<Pose2> poses;
  for (const Path& path : paths) {
    const std::vector<Pose2> part = sample(path, step_m);
    // The first pose of every path after the first is the junction already added.
    poses.insert(poses.end(), part.begin() + (poses.empty() ? 0 : 1), part.end());
  }
  return poses;
}

}  // namespace campo::dubins
