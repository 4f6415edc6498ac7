#include "sensors/ray_fan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace campo {

namespace {

// Bins per side of a face at most, and the fewest rays a bin should hold on
// average: finer bins fit small surfaces better, but each bin a surface
// covers costs a lookup and a partly filled vector of eight rays.
constexpr int kMaxGrid = 64;
constexpr double kRaysPerBin = 6.0;

}  // namespace

int RayFan::face_of(const Eigen::Vector3f& d) {
  const float ax = std::fabs(d.x()), ay = std::fabs(d.y()), az = std::fabs(d.z());
  const int axis = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
  return 2 * axis + (d[axis] < 0.0f ? 1 : 0);
}

Eigen::Vector2f RayFan::face_coordinates(const Eigen::Vector3f& d, int face) {
  const int m = face / 2;
  const float w = face % 2 ? -d[m] : d[m];
  return {d[(m + 1) % 3] / w, d[(m + 2) % 3] / w};
}

RayFan::RayFan(std::span<const Eigen::Vector3f> directions) {
  const std::size_t n = directions.size();
  std::vector<int> face(n);
  std::vector<Eigen::Vector2f> uv(n);
  std::array<std::size_t, fan::kFaces> on_face{};
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& d = directions[i];
    // Unit length: the kernels take the ray parameter for the distance.
    if (!d.allFinite() || std::abs(d.squaredNorm() - 1.0f) > 1e-4f) {
      throw std::invalid_argument("RayFan: direction " + std::to_string(i) + " is not a unit vector");
    }
    face[i] = face_of(d);
    uv[i] = face_coordinates(d, face[i]);
    ++on_face[static_cast<std::size_t>(face[i])];
  }
  // The cone around every ray: about their mean direction, as wide as the
  // furthest ray plus 1 mrad (what rounding does to the culling tests is far
  // smaller). Past a half-turn every surface may be seen.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& d : directions) sum += d.cast<double>();
  if (sum.norm() > 1e-3 * static_cast<double>(n)) {
    const Eigen::Vector3d axis = sum.normalized();
    double nearest = 1.0;
    for (const Eigen::Vector3f& d : directions) nearest = std::min(nearest, axis.dot(d.cast<double>()) / d.cast<double>().norm());
    const double half_angle = std::acos(std::clamp(nearest, -1.0, 1.0)) + 1e-3;
    if (half_angle < 3.1) {
      for (int i = 0; i < 3; ++i) cone_axis_[i] = static_cast<float>(axis[i]);
      cone_cos_ = static_cast<float>(std::cos(half_angle));
      cone_sin_ = static_cast<float>(std::sin(half_angle));
    }
  }
  // Per face, the finest grid whose occupied bins hold kRaysPerBin rays on
  // average: a 2D scan gets about that many per bin, a planar one a row of
  // bins along its line.
  std::vector<std::uint8_t> occupied;
  std::uint32_t bins = 0;
  for (int f = 0; f < fan::kFaces; ++f) {
    if (on_face[static_cast<std::size_t>(f)] == 0) continue;
    int grid = kMaxGrid;
    for (; grid > 1; grid /= 2) {
      occupied.assign(static_cast<std::size_t>(grid) * grid, 0);
      std::size_t used = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (face[i] != f) continue;
        auto& cell = occupied[static_cast<std::size_t>(fan::bin_of(uv[i].y(), grid) * grid + fan::bin_of(uv[i].x(), grid))];
        used += cell == 0;
        cell = 1;
      }
      if (static_cast<double>(on_face[static_cast<std::size_t>(f)]) >= kRaysPerBin * static_cast<double>(used)) break;
    }
    grid_[f] = grid;
    first_bin_[f] = bins;
    bins += static_cast<std::uint32_t>(grid * grid);
  }
  // Counting sort by bin, stable: within a bin, beam order.
  std::vector<std::uint32_t> bin(n);
  bin_start_.assign(bins + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const int f = face[i], grid = grid_[f];
    bin[i] = first_bin_[f] + static_cast<std::uint32_t>(fan::bin_of(uv[i].y(), grid) * grid + fan::bin_of(uv[i].x(), grid));
    ++bin_start_[bin[i] + 1];
  }
  for (std::uint32_t b = 0; b < bins; ++b) bin_start_[b + 1] += bin_start_[b];
  std::vector<std::uint32_t> next(bin_start_.begin(), bin_start_.end() - 1);
  order_.resize(n);
  x_.assign(n + 8, 0.0f);
  y_.assign(n + 8, 0.0f);
  z_.assign(n + 8, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t slot = next[bin[i]]++;
    order_[slot] = static_cast<std::uint32_t>(i);
    x_[slot] = directions[i].x();
    y_[slot] = directions[i].y();
    z_[slot] = directions[i].z();
  }
}

fan::Rays RayFan::rays() const {
  fan::Rays r;
  r.x = x_.data();
  r.y = y_.data();
  r.z = z_.data();
  r.size = static_cast<std::uint32_t>(order_.size());
  for (int f = 0; f < fan::kFaces; ++f) {
    r.grid[f] = grid_[f];
    r.first_bin[f] = first_bin_[f];
  }
  r.bin_start = bin_start_.data();
  for (int i = 0; i < 3; ++i) r.cone_axis[i] = cone_axis_[i];
  r.cone_cos = cone_cos_;
  r.cone_sin = cone_sin_;
  return r;
}

}  // namespace campo
