#pragma once
/// Dubins paths (SPEC §7.3, 003 §2.2.1 and §3.3): the shortest way for a
/// vehicle that only drives forward, with a minimum turning radius, from one
/// pose in the plane to another is one of six words of at most three pieces,
/// each a left arc (L), a right arc (R) or a straight (S) [Dubins 1957]. The
/// rover's global planner threads them through the operator's waypoints:
/// straights along the vineyard rows, arcs to switch rows. Pure functions.
#include <array>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace campo::dubins {

/// A pose in the plane.
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_rad = 0.0;  ///< direction of travel, counter-clockwise from +x
};

/// The six candidate words; to_string gives their letters ("LSL" ...), one
/// per segment, so to_string(word)[i] says what segment i is.
enum class Word { LSL, RSR, LSR, RSL, RLR, LRL };
inline constexpr std::array<Word, 6> kWords = {Word::LSL, Word::RSR, Word::LSR,
                                               Word::RSL, Word::RLR, Word::LRL};
std::string_view to_string(Word word);

/// One Dubins path: from `start`, drive the three segments of `word` in turn.
struct Path {
  Pose2 start;
  Word word = Word::LSL;
  double radius_m = 1.0;  ///< turning radius of the arcs, > 0
  /// Length of each segment in metres: arc length for L and R, straight
  /// length for S; zero when the segment is not needed.
  std::array<double, 3> segment_lengths_m{};

  double length_m() const;
  /// The pose `s_m` metres along the path (s_m clamped to [0, length_m()]);
  /// heading wrapped to [-pi, pi).
  Pose2 pose_at(double s_m) const;
};

/// The path of the given word from `from` to `to` with turning radius
/// `radius_m`; nullopt when that word cannot join them (LSR and RSL need the
/// two turning circles apart, RLR and LRL need them close). Of the two CCC
/// solutions, the one with the middle arc longer than a half turn (the only
/// one that can be shortest). Throws std::invalid_argument for a radius <= 0
/// or a non-finite input.
std::optional<Path> path(const Pose2& from, const Pose2& to, double radius_m, Word word);

/// The shortest of the six words (LSL and RSR always exist). Words
/// whose lengths agree to 1e-12 (relative) tie, and the first in kWords wins,
/// so a straight run comes out as LSL with zero arcs. Throws like path().
Path shortest_path(const Pose2& from, const Pose2& to, double radius_m);

/// Poses along the path at equal spacing of at most `step_m`, the first at
/// s = 0 and the last at s = length_m() (a zero-length path gives one pose).
/// Throws std::invalid_argument unless step_m is positive and finite.
std::vector<Pose2> sample(const Path& path, double step_m);

/// One shortest path per consecutive pair of operator waypoints (empty for
/// fewer than two). Throws like path().
std::vector<Path> route(std::span<const Pose2> waypoints, double radius_m);

/// The paths sampled one after the other; the junction pose shared by the end
/// of a path and the start of the next appears once. Throws like sample().
std::vector<Pose2> sample_route(std::span<const Path> paths, double step_m);

}  // namespace campo::dubins
