#include "scene/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "campo/scene.hpp"

namespace campo {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A closed interval of the line parameter; empty when lo > hi.
struct Interval {
  double lo = -kInf;
  double hi = kInf;
  bool empty() const { return lo > hi; }
  Interval meet(const Interval& other) const { return {std::max(lo, other.lo), std::min(hi, other.hi)}; }
};
constexpr Interval kEmpty{kInf, -kInf};

/// Parameters t where p + t d stays in lo <= coordinate <= hi (one slab).
Interval slab(double p, double d, double lo, double hi) {
  if (std::abs(d) < 1e-12) return (p >= lo && p <= hi) ? Interval{} : kEmpty;
  const double t0 = (lo - p) / d;
  const double t1 = (hi - p) / d;
  return {std::min(t0, t1), std::max(t0, t1)};
}

/// Solutions of a t^2 + b t + c <= 0 as up to two intervals (the second used
/// when a < 0, where the set is everything outside the roots).
std::pair<Interval, Interval> quadratic_below_zero(double a, double b, double c) {
  if (std::abs(a) < 1e-12) {
    if (std::abs(b) < 1e-12) return {c <= 0.0 ? Interval{} : kEmpty, kEmpty};
    return {b > 0.0 ? Interval{-kInf, -c / b} : Interval{-c / b, kInf}, kEmpty};
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return {a > 0.0 ? kEmpty : Interval{}, kEmpty};
  const double s = std::sqrt(disc);
  const double r0 = std::min((-b - s) / (2.0 * a), (-b + s) / (2.0 * a));
  const double r1 = std::max((-b - s) / (2.0 * a), (-b + s) / (2.0 * a));
  if (a > 0.0) return {{r0, r1}, kEmpty};
  return {{-kInf, r0}, {r1, kInf}};
}

/// Shapes shrink by this much before testing a point, so a point on a
/// shape's surface (a box side on a cell edge) counts as outside despite rounding.
constexpr double kSurfaceTolerance_m = 1e-9;

/// Where the vertical line through world (x, y) meets a convex shape, shrunk
/// by kSurfaceTolerance_m: the range of world z, or an empty interval. Exact
/// for any orientation. The line z -> (x, y, z) is p + z d in the shape's
/// frame (d = the world's up).
Interval vertical_extent(const Shape& shape, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  switch (shape.type) {
    case ShapeType::cuboid: {
      const Eigen::Vector3d h = (0.5 * shape.size_m).array() - kSurfaceTolerance_m;
      return slab(p.x(), d.x(), -h.x(), h.x()).meet(slab(p.y(), d.y(), -h.y(), h.y())).meet(
          slab(p.z(), d.z(), -h.z(), h.z()));
    }
    case ShapeType::sphere: {
      const double r = shape.radius_m - kSurfaceTolerance_m;
      return quadratic_below_zero(d.squaredNorm(), 2.0 * p.dot(d), p.squaredNorm() - r * r).first;
    }
    case ShapeType::cylinder: {
      const double r = shape.radius_m - kSurfaceTolerance_m;
      const double half = 0.5 * shape.height_m - kSurfaceTolerance_m;
      const Interval radial = quadratic_below_zero(d.x() * d.x() + d.y() * d.y(), 2.0 * (p.x() * d.x() + p.y() * d.y()),
                                                   p.x() * p.x() + p.y() * p.y() - r * r)
                                  .first;
      return radial.meet(slab(p.z(), d.z(), -half, half));
    }
    case ShapeType::cone: {
      // Radius k (apex_z - z) shrinking to 0 at the apex (+h/2); the slab keeps
      // the one nappe between base and apex, where the double cone is convex.
      const double half = 0.5 * shape.height_m - kSurfaceTolerance_m;
      const double k = (shape.radius_m - kSurfaceTolerance_m) / shape.height_m;
      const double qz = half - p.z();  // apex_z - z at t = 0; decreases by d.z per unit t
      const auto [first, second] = quadratic_below_zero(
          d.x() * d.x() + d.y() * d.y() - k * k * d.z() * d.z(),
          2.0 * (p.x() * d.x() + p.y() * d.y() + k * k * qz * d.z()),
          p.x() * p.x() + p.y() * p.y() - k * k * qz * qz);
      const Interval height = slab(p.z(), d.z(), -half, half);
      const Interval a = first.meet(height);
      const Interval b = second.meet(height);
      if (a.empty()) return b;
      if (b.empty()) return a;
      return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
    }
    case ShapeType::plane:
    case ShapeType::heightfield:
    case ShapeType::mesh:  // mark_mesh
      break;
  }
  return kEmpty;
}

/// World axis-aligned bounding box of a shape (cuboid, sphere, cylinder, cone).
Eigen::AlignedBox3d world_box(const Shape& shape) {
  const Eigen::Matrix3d& R = shape.pose.linear();
  Eigen::Vector3d half;
  switch (shape.type) {
    case ShapeType::cuboid:
      half = R.cwiseAbs() * (0.5 * shape.size_m);
      break;
    case ShapeType::sphere:
      half = Eigen::Vector3d::Constant(shape.radius_m);
      break;
    case ShapeType::mesh: {
      Eigen::AlignedBox3d box;
      const Eigen::AlignedBox3d& local = shape.mesh->bounds_m;
      for (int corner = 0; corner < 8; ++corner) {
        box.extend(shape.pose * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
      }
      return box;
    }
    default: {
      // A disc of radius r at each end of the axis a spans r sqrt(1 - a_i^2) along axis i.
      const Eigen::Vector3d a = R.col(2);
      for (int i = 0; i < 3; ++i) {
        half[i] = std::abs(a[i]) * 0.5 * shape.height_m + shape.radius_m * std::sqrt(std::max(0.0, 1.0 - a[i] * a[i]));
      }
    }
  }
  const Eigen::Vector3d c = shape.pose.translation();
  return {c - half, c + half};
}

// A static mesh on the grid's half-cell lattice (see build_occupancy_grid):
// where the vertical line through a lattice point crosses the surface within
// the height band, or (a closed mesh) runs inside the solid across the band.
// Each triangle visits the lattice points under it (its edges included); a
// vertical triangle of an open mesh, which no vertical line crosses, is walked
// along its footprint.
template <class Mark, class Ground>
void mark_mesh(const Shape& shape, const Eigen::Vector2d& lo, double half, int lattice_cols, int lattice_rows,
               const OccupancyConfig& config, Ground&& ground_at, Mark&& mark) {
  const TriangleMesh& mesh = *shape.mesh;
  std::vector<Eigen::Vector3d> world;
  world.reserve(mesh.vertices_m.size());
  for (const Eigen::Vector3d& v : mesh.vertices_m) world.push_back(shape.pose * v);
  const auto in_band = [&](double z_lo, double z_hi, double ground) {
    return z_hi > ground + config.ground_clearance_m && z_lo < ground + config.vehicle_height_m;
  };
  const auto lattice_index = [&](int j, int i) { return static_cast<std::int64_t>(i) * (lattice_cols + 1) + j; };
  std::vector<std::pair<std::int64_t, double>> crossings;  // (lattice point, z) where a vertical line meets a face
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = world[t[0]];
    const Eigen::Vector3d& b = world[t[1]];
    const Eigen::Vector3d& c = world[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double x0 = std::min({a.x(), b.x(), c.x()}), x1 = std::max({a.x(), b.x(), c.x()});
    const double y0 = std::min({a.y(), b.y(), c.y()}), y1 = std::max({a.y(), b.y(), c.y()});
    const int j0 = std::max(0, static_cast<int>(std::ceil((x0 - lo.x()) / half)));
    const int j1 = std::min(lattice_cols, static_cast<int>(std::floor((x1 - lo.x()) / half)));
    const int i0 = std::max(0, static_cast<int>(std::ceil((y0 - lo.y()) / half)));
    const int i1 = std::min(lattice_rows, static_cast<int>(std::floor((y1 - lo.y()) / half)));
    if (std::abs(n.z()) > 1e-9 * n.norm()) {
      // Lattice points inside the triangle's footprint (barycentric, edges included).
      const double area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
      for (int i = i0; i <= i1; ++i) {
        for (int j = j0; j <= j1; ++j) {
          const Eigen::Vector2d p = lo + half * Eigen::Vector2d(j, i);
          const double u = ((b.x() - p.x()) * (c.y() - p.y()) - (c.x() - p.x()) * (b.y() - p.y())) / area;
          const double v = ((c.x() - p.x()) * (a.y() - p.y()) - (a.x() - p.x()) * (c.y() - p.y())) / area;
          const double w = 1.0 - u - v;
          if (u < 0.0 || v < 0.0 || w < 0.0) continue;
          crossings.emplace_back(lattice_index(j, i), u * a.z() + v * b.z() + w * c.z());
        }
      }
      continue;
    }
    // Vertical: in a closed mesh, the faces around it bound the solid already.
    // In an open one, along its footprint (a segment), the z range of the
    // triangle above each step, at the lattice point nearest the step (so a
    // wall may cover the lattice points beside it: conservative).
    if (mesh.closed) continue;
    // The footprint is the longest of the edges' footprints.
    const Eigen::Vector2d fa(a.x(), a.y()), fb(b.x(), b.y()), fc(c.x(), c.y());
    Eigen::Vector2d from = fa, to = fb;
    if ((fc - fa).norm() > (to - from).norm()) to = fc;
    if ((fc - fb).norm() > (to - from).norm()) {
      from = fb;
      to = fc;
    }
    const double length = (to - from).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.5 * half))));
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d q = from + (to - from) * (static_cast<double>(k) / steps);
      double z_lo = kInf, z_hi = -kInf;
      const Eigen::Vector3d* corners[3] = {&a, &b, &c};
      for (int e = 0; e < 3; ++e) {
        const Eigen::Vector3d& p0 = *corners[e];
        const Eigen::Vector3d& p1 = *corners[(e + 1) % 3];
        const Eigen::Vector2d d = p1.head<2>() - p0.head<2>();
        // Where this edge is above q (its footprint through q), if anywhere.
        const double dd = d.squaredNorm();
        const double s = dd > 0.0 ? std::clamp((q - p0.head<2>()).dot(d) / dd, 0.0, 1.0) : 0.0;
        if ((p0.head<2>() + s * d - q).norm() > 1e-9 + 1e-9 * length) continue;
        const double z = dd > 0.0 ? p0.z() + s * (p1.z() - p0.z()) : std::min(p0.z(), p1.z());
        z_lo = std::min({z_lo, z, dd > 0.0 ? z : std::min(p0.z(), p1.z())});
        z_hi = std::max({z_hi, z, dd > 0.0 ? z : std::max(p0.z(), p1.z())});
      }
      if (z_lo > z_hi) continue;
      const int j = static_cast<int>(std::lround((q.x() - lo.x()) / half));
      const int i = static_cast<int>(std::lround((q.y() - lo.y()) / half));
      if (j < 0 || i < 0 || j > lattice_cols || i > lattice_rows) continue;
      if (in_band(z_lo, z_hi, ground_at(q.x(), q.y()))) mark(j, i);
    }
  }
  // Per lattice point, its crossings in height order: each within the band
  // marks it, and so does a stretch inside a closed mesh across the band.
  std::sort(crossings.begin(), crossings.end());
  // A line through an edge shared by two faces meets the surface once, not twice.
  crossings.erase(std::unique(crossings.begin(), crossings.end(),
                              [](const auto& x, const auto& y) { return x.first == y.first && std::abs(x.second - y.second) <= 1e-9; }),
                  crossings.end());
  for (std::size_t k = 0; k < crossings.size();) {
    std::size_t end = k;
    while (end < crossings.size() && crossings[end].first == crossings[k].first) ++end;
    const int i = static_cast<int>(crossings[k].first / (lattice_cols + 1));
    const int j = static_cast<int>(crossings[k].first % (lattice_cols + 1));
    const Eigen::Vector2d p = lo + half * Eigen::Vector2d(j, i);
    const double ground = ground_at(p.x(), p.y());
    bool marked = false;
    for (std::size_t m = k; m < end && !marked; ++m) marked = in_band(crossings[m].second, crossings[m].second, ground);
    if (mesh.closed) {
      for (std::size_t m = k; m + 1 < end && !marked; m += 2) marked = in_band(crossings[m].second, crossings[m + 1].second, ground);
    }
    if (marked) mark(j, i);
    k = end;
  }
}

bool is_obstacle_candidate(const Shape& shape) {
  return shape.is_static && shape.type != ShapeType::plane && shape.type != ShapeType::heightfield;
}

// Origin on a multiple of the resolution, so cell edges fall on round coordinates.
// (The 1e-9 keeps -3.5 / 0.1 = -34.999... from adding a cell.)
Eigen::Vector2d grid_origin(const Eigen::AlignedBox2d& bounds, const OccupancyConfig& config) {
  const double r = config.resolution_m;
  return ((bounds.min().array() - config.margin_m) / r + 1e-9).floor() * r;
}

}  // namespace

Eigen::AlignedBox2d occupancy_bounds(const Scene& scene, bool with_missions) {
  // The obstacles plus the places the vehicles start at and go to, so a
  // planner always finds its start and goal inside the grid.
  Eigen::AlignedBox2d bounds;
  for (const Shape& shape : scene.shapes) {
    if (!is_obstacle_candidate(shape)) continue;
    const Eigen::AlignedBox3d box = world_box(shape);
    bounds.extend(Eigen::Vector2d(box.min().head<2>()));
    bounds.extend(Eigen::Vector2d(box.max().head<2>()));
  }
  for (const VehicleDef& vehicle : scene.vehicles) {
    bounds.extend(Eigen::Vector2d(vehicle.pose.translation().head<2>()));
    if (!with_missions) continue;
    for (const Waypoint& waypoint : vehicle.mission) bounds.extend(Eigen::Vector2d(waypoint.position_m.head<2>()));
  }
  return bounds;
}

Eigen::Vector2d occupancy_grid_cells(const Eigen::AlignedBox2d& bounds, const OccupancyConfig& config) {
  if (bounds.isEmpty()) return Eigen::Vector2d::Zero();
  const double r = config.resolution_m;
  const Eigen::Vector2d lo = grid_origin(bounds, config);
  const Eigen::Vector2d hi = bounds.max().array() + config.margin_m;
  return ((hi - lo).array() / r - 1e-9).ceil().max(1.0);
}

Eigen::Vector2i OccupancyGrid::cell_of(const Eigen::Vector2d& point_m) const {
  const Eigen::Vector2d u = (point_m - origin_m) / resolution_m;
  // Clamped so far-away points stay representable; they are outside either way.
  const auto to_int = [](double v) {
    return static_cast<int>(std::clamp(std::floor(v), -1e9, 1e9));
  };
  return {to_int(u.x()), to_int(u.y())};
}

Eigen::Vector2d OccupancyGrid::centre_of(int col, int row) const {
  return origin_m + resolution_m * Eigen::Vector2d(col + 0.5, row + 0.5);
}

bool OccupancyGrid::segment_free(const Eigen::Vector2d& a_m, const Eigen::Vector2d& b_m,
                                 std::int64_t* cells_checked) const {
  if (!a_m.allFinite() || !b_m.allFinite()) return false;
  // Every cell look-up of the walk, counted for callers that bound their work.
  const auto blocked = [&](int col, int row) {
    if (cells_checked) ++*cells_checked;
    return is_occupied(col, row);
  };
  // Amanatides-Woo traversal in cell units; t in [0, 1] along a -> b.
  const Eigen::Vector2d u0 = (a_m - origin_m) / resolution_m;
  const Eigen::Vector2d u1 = (b_m - origin_m) / resolution_m;
  Eigen::Vector2i cell = cell_of(a_m);
  const Eigen::Vector2i end = cell_of(b_m);
  if (blocked(cell.x(), cell.y())) return false;
  const Eigen::Vector2d d = u1 - u0;
  const int step_x = d.x() > 0.0 ? 1 : -1;
  const int step_y = d.y() > 0.0 ? 1 : -1;
  const double delta_x = d.x() != 0.0 ? 1.0 / std::abs(d.x()) : kInf;
  const double delta_y = d.y() != 0.0 ? 1.0 / std::abs(d.y()) : kInf;
  double next_x = d.x() > 0.0 ? (cell.x() + 1 - u0.x()) * delta_x : d.x() < 0.0 ? (u0.x() - cell.x()) * delta_x : kInf;
  double next_y = d.y() > 0.0 ? (cell.y() + 1 - u0.y()) * delta_y : d.y() < 0.0 ? (u0.y() - cell.y()) * delta_y : kInf;
  // Step counts come from the end cell, so rounding in next_x / next_y can
  // never make the walk overshoot or loop.
  int left_x = std::abs(end.x() - cell.x());
  int left_y = std::abs(end.y() - cell.y());
  constexpr double kCornerTolerance = 1e-9;
  while (left_x > 0 || left_y > 0) {
    const bool corner = left_x > 0 && left_y > 0 && std::abs(next_x - next_y) <= kCornerTolerance;
    if (corner) {
      // Through a cell corner: the segment touches both cells beside it.
      if (blocked(cell.x() + step_x, cell.y()) || blocked(cell.x(), cell.y() + step_y)) return false;
      cell += Eigen::Vector2i(step_x, step_y);
      next_x += delta_x;
      next_y += delta_y;
      --left_x;
      --left_y;
    } else if (left_y == 0 || (left_x > 0 && next_x < next_y)) {
      cell.x() += step_x;
      next_x += delta_x;
      --left_x;
    } else {
      cell.y() += step_y;
      next_y += delta_y;
      --left_y;
    }
    if (blocked(cell.x(), cell.y())) return false;
  }
  return true;
}

OccupancyGrid build_occupancy_grid(const Scene& scene, const OccupancyConfig& config) {
  if (!(config.resolution_m > 0.0) || !std::isfinite(config.resolution_m)) {
    throw std::invalid_argument("occupancy grid: resolution must be finite and > 0");
  }
  if (!(config.ground_clearance_m < config.vehicle_height_m) || !std::isfinite(config.vehicle_height_m) ||
      !std::isfinite(config.ground_clearance_m)) {
    throw std::invalid_argument("occupancy grid: need finite ground_clearance < vehicle_height");
  }
  if (!(config.margin_m >= 0.0) || !std::isfinite(config.margin_m)) {
    throw std::invalid_argument("occupancy grid: margin must be finite and >= 0");
  }

  OccupancyGrid grid;
  grid.resolution_m = config.resolution_m;
  const Eigen::AlignedBox2d bounds = occupancy_bounds(scene);
  if (bounds.isEmpty()) return grid;
  const Eigen::Vector2d extent = occupancy_grid_cells(bounds, config);
  if (extent.x() * extent.y() > static_cast<double>(config.max_cells)) {
    throw std::invalid_argument("occupancy grid: " + std::to_string(extent.x()) + " x " + std::to_string(extent.y()) +
                                " cells exceed the limit of " + std::to_string(config.max_cells));
  }
  const double r = config.resolution_m;
  const Eigen::Vector2d lo = grid_origin(bounds, config);
  grid.origin_m = lo;
  grid.cols = static_cast<int>(extent.x());
  grid.rows = static_cast<int>(extent.y());
  grid.occupied.assign(static_cast<std::size_t>(grid.cols) * grid.rows, 0);

  // Ground from the terrain shapes alone: Scene::ground_height walks every
  // shape, which would dominate the cost on scenes with many obstacles.
  Scene terrain;
  for (const Shape& shape : scene.shapes) {
    if (shape.type == ShapeType::plane || shape.type == ShapeType::heightfield) terrain.shapes.push_back(shape);
  }

  // Each shape over its own bounding box only, tested at the points of a
  // half-cell lattice (corners, edge midpoints and centres of the cells); a
  // point marks every cell it belongs to.
  const double half = 0.5 * r;
  const int lattice_cols = 2 * grid.cols;
  const int lattice_rows = 2 * grid.rows;
  const auto mark = [&](int j, int i) {
    for (int row = (i - 1) / 2; row <= i / 2; ++row) {
      for (int col = (j - 1) / 2; col <= j / 2; ++col) {
        if (grid.contains(col, row)) grid.occupied[static_cast<std::size_t>(row) * grid.cols + col] = 1;
      }
    }
  };
  for (const Shape& shape : scene.shapes) {
    if (!is_obstacle_candidate(shape)) continue;
    if (shape.type == ShapeType::mesh) {
      mark_mesh(shape, lo, half, lattice_cols, lattice_rows, config,
                [&terrain](double x, double y) { return terrain.ground_height(x, y).value_or(0.0); }, mark);
      continue;
    }
    const Eigen::AlignedBox3d box = world_box(shape);
    const Eigen::Isometry3d to_local = shape.pose.inverse();
    const Eigen::Vector3d up_local = shape.pose.linear().transpose() * Eigen::Vector3d::UnitZ();
    const auto lattice = [&](double v, double o) { return (v - o) / half; };
    const int j0 = std::max(0, static_cast<int>(std::floor(lattice(box.min().x(), lo.x()))));
    const int j1 = std::min(lattice_cols, static_cast<int>(std::ceil(lattice(box.max().x(), lo.x()))));
    const int i0 = std::max(0, static_cast<int>(std::floor(lattice(box.min().y(), lo.y()))));
    const int i1 = std::min(lattice_rows, static_cast<int>(std::ceil(lattice(box.max().y(), lo.y()))));
    for (int i = i0; i <= i1; ++i) {
      for (int j = j0; j <= j1; ++j) {
        const Eigen::Vector2d point = lo + half * Eigen::Vector2d(j, i);
        const Interval z = vertical_extent(shape, to_local * Eigen::Vector3d(point.x(), point.y(), 0.0), up_local);
        if (z.empty()) continue;
        const double ground = terrain.ground_height(point.x(), point.y()).value_or(0.0);
        if (z.hi > ground + config.ground_clearance_m && z.lo < ground + config.vehicle_height_m) mark(j, i);
      }
    }
  }
  return grid;
}

OccupancyGrid inflate(const OccupancyGrid& grid, double radius_m) {
  if (!(radius_m >= 0.0) || !std::isfinite(radius_m)) {
    throw std::invalid_argument("inflate: radius must be finite and >= 0");
  }
  OccupancyGrid out = grid;
  if (radius_m == 0.0 || grid.occupied.empty() ||
      std::none_of(grid.occupied.begin(), grid.occupied.end(), [](std::uint8_t v) { return v != 0; })) {
    return out;
  }
  // distanceTransform measures from each non-zero pixel to the nearest zero
  // one, so obstacles are the zeros. DIST_MASK_PRECISE: exact Euclidean.
  cv::Mat free(grid.rows, grid.cols, CV_8U);
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      free.at<std::uint8_t>(row, col) = grid.occupied[static_cast<std::size_t>(row) * grid.cols + col] ? 0 : 255;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(free, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  // The tolerance absorbs float rounding, so a radius of exactly sqrt(k)
  // cells includes the cells at that distance.
  const double limit = radius_m / grid.resolution_m + 1e-4;
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      if (distance.at<float>(row, col) <= limit) out.occupied[static_cast<std::size_t>(row) * grid.cols + col] = 1;
    }
  }
  return out;
}

}  // namespace campo
