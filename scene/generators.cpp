#include "scene/generators.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <Eigen/Geometry>

#include "campo/random.hpp"
#include "scene/generators_grid.hpp"

namespace campo {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Rolling terrain: each wave's wavelength is the nominal one times [1 - j, 1 + j).
constexpr double kWavelengthJitter = 0.3;
/// Trees: trunks reach this far below the ground so they never float on a slope.
constexpr double kTrunkFooting_m = 0.2;
/// Trees: attempts per requested tree before dart throwing gives up.
constexpr int kAttemptsPerTree = 1000;
/// Vineyard: free space kept between an obstacle's footprint and a row side.
constexpr double kObstacleRowClearance_m = 0.3;
/// Grid obstacles: boxes reach this far below the lowest ground under them.
constexpr double kGridBoxFooting_m = 1.0;

std::string generator_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument(message);
}

bool finite_positive(double value) { return std::isfinite(value) && value > 0.0; }

/// A (min, max) interval with 0 < min <= max.
bool valid_range(const Eigen::Vector2d& range) {
  return range.allFinite() && range[0] > 0.0 && range[0] <= range[1];
}

double ground_at(const GroundFunction& ground, double x, double y) {
  const double z = ground(x, y);
  if (!std::isfinite(z)) {
    throw std::runtime_error("ground height at (" + generator_number(x) + ", " + generator_number(y) + ") is not finite");
  }
  return z;
}

Eigen::Isometry3d translation(double x, double y, double z) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

/// A colour near `base`: each component shifted by up to +-spread, kept in [0, 1].
Color jittered(const Color& base, double spread, Rng& rng) {
  const auto shift = [&](double c) { return std::clamp(c + rng.uniform(-spread, spread), 0.0, 1.0); };
  const double r = shift(base.r);
  const double g = shift(base.g);
  const double b = shift(base.b);
  return {r, g, b};
}

/// Integer cell of a point on a uniform lattice, for neighbour lookups.
struct Cell {
  std::int64_t ix = 0;
  std::int64_t iy = 0;
  bool operator==(const Cell&) const = default;
};
struct CellHash {
  std::size_t operator()(const Cell& cell) const {
    return std::hash<std::uint64_t>{}(static_cast<std::uint64_t>(cell.ix) * 0x9e3779b97f4a7c15ULL ^
                                      static_cast<std::uint64_t>(cell.iy));
  }
};

/// Points with a minimum pairwise distance; lookups only visit the 3 x 3
/// lattice cells (of side min_distance) around a candidate.
class SpacedPoints {
 public:
  explicit SpacedPoints(double min_distance_m) : min_distance_m_(min_distance_m) {}

  bool has_neighbour_closer_than_min(const Eigen::Vector2d& p) const {
    if (min_distance_m_ <= 0.0) return false;
    const Cell centre = cell_of(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find({centre.ix + dx, centre.iy + dy});
        if (it == cells_.end()) continue;
        for (const int i : it->second) {
          if ((points_[i] - p).norm() < min_distance_m_) return true;
        }
      }
    }
    return false;
  }

  void add(const Eigen::Vector2d& p) {
    if (min_distance_m_ > 0.0) cells_[cell_of(p)].push_back(static_cast<int>(points_.size()));
    points_.push_back(p);
  }

  const std::vector<Eigen::Vector2d>& points() const { return points_; }

 private:
  Cell cell_of(const Eigen::Vector2d& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / min_distance_m_)),
            static_cast<std::int64_t>(std::floor(p.y() / min_distance_m_))};
  }

  double min_distance_m_;
  std::vector<Eigen::Vector2d> points_;
  std::unordered_map<Cell, std::vector<int>, CellHash> cells_;
};

void validate(const TreesConfig& c) {
  require(c.area_min_m.allFinite() && c.area_max_m.allFinite() &&
              (c.area_max_m - c.area_min_m).minCoeff() > 0.0,
          "trees: area_max must be greater than area_min in x and y");
  require(c.count >= 0 && c.count <= 10000, "trees: count must be in [0, 10000], got " + std::to_string(c.count));
  require(std::isfinite(c.min_spacing_m) && c.min_spacing_m >= 0.0, "trees: min_spacing must be finite and >= 0");
  require(valid_range(c.trunk_radius_m), "trees: trunk_radius must be a range 0 < min <= max");
  require(valid_range(c.trunk_height_m), "trees: trunk_height must be a range 0 < min <= max");
  require(valid_range(c.crown_radius_m), "trees: crown_radius must be a range 0 < min <= max");
  require(finite_positive(c.crown_height_ratio), "trees: crown_height_ratio must be finite and > 0");
  for (const auto& circle : c.keep_out) {
    require(circle.allFinite() && circle.z() >= 0.0, "trees: keep_out circles need finite x, y and radius >= 0");
  }
}

/// Vineyard rows: x of row i's centre line, the rows centred on the origin.
double row_x(const VineyardConfig& c, int row) { return (row - 0.5 * (c.row_count - 1)) * c.row_spacing_m; }

/// Half width of a row's solid part (canopy, or posts if they are wider).
double row_half_width(const VineyardConfig& c) { return std::max(0.5 * c.canopy_width_m, c.post_radius_m); }

void validate(const VineyardConfig& c) {
  require(c.field_size_m.allFinite() && c.field_size_m.minCoeff() > 0.0, "vineyard: field_size must be finite and > 0");
  require(c.row_count >= 1 && c.row_count <= 500,
          "vineyard: row_count must be in [1, 500], got " + std::to_string(c.row_count));
  require(finite_positive(c.row_spacing_m), "vineyard: row_spacing must be finite and > 0");
  require(std::isfinite(c.headland_m) && c.headland_m >= 0.0, "vineyard: headland must be finite and >= 0");
  require(finite_positive(c.post_spacing_m), "vineyard: post_spacing must be finite and > 0");
  require(finite_positive(c.post_radius_m), "vineyard: post_radius must be finite and > 0");
  require(finite_positive(c.post_height_m), "vineyard: post_height must be finite and > 0");
  require(finite_positive(c.canopy_width_m), "vineyard: canopy_width must be finite and > 0");
  require(std::isfinite(c.canopy_bottom_m) && std::isfinite(c.canopy_top_m) && c.canopy_bottom_m >= 0.0 &&
              c.canopy_bottom_m < c.canopy_top_m,
          "vineyard: canopy needs 0 <= canopy_bottom < canopy_top, got " + generator_number(c.canopy_bottom_m) + " and " +
              generator_number(c.canopy_top_m));
  require(finite_positive(c.fence_height_m), "vineyard: fence_height must be finite and > 0");
  require(finite_positive(c.fence_thickness_m), "vineyard: fence_thickness must be finite and > 0");
  require(c.obstacle_count >= 0 && c.obstacle_count <= 10000,
          "vineyard: obstacle_count must be in [0, 10000], got " + std::to_string(c.obstacle_count));
  require(valid_range(c.obstacle_size_m), "vineyard: obstacle_size must be a range 0 < min <= max");

  const double row_length = c.field_size_m.y() - 2.0 * c.headland_m;
  require(row_length > 0.0, "vineyard: headlands of " + generator_number(c.headland_m) + " m leave no room for rows in a field " +
                                generator_number(c.field_size_m.y()) + " m long (y)");
  // Keeps the post count far inside int; the scene loader caps the total.
  require(row_length / c.post_spacing_m <= 1e6, "vineyard: post_spacing gives more than 1e6 posts per row");
  const double half_width = row_half_width(c);
  require(c.row_count == 1 || 2.0 * half_width < c.row_spacing_m,
          "vineyard: rows " + generator_number(2.0 * half_width) + " m wide (canopy or posts) must be narrower than the row spacing " +
              generator_number(c.row_spacing_m) + " m");
  const double rows_span = (c.row_count - 1) * c.row_spacing_m + 2.0 * half_width;
  const double available = c.field_size_m.x() - 2.0 * c.headland_m;
  require(rows_span <= available, "vineyard: " + std::to_string(c.row_count) + " rows at " + generator_number(c.row_spacing_m) +
                                      " m spacing span " + generator_number(rows_span) + " m but the field " +
                                      generator_number(c.field_size_m.x()) + " m wide leaves " + generator_number(available) +
                                      " m inside the headland margins");
  if (c.obstacle_count > 0) {
    require(c.row_count >= 2, "vineyard: obstacles go between rows, so they need at least 2 rows");
    // The widest footprint of a yawed box of edge e is its diagonal, sqrt(2) e.
    const double widest = std::sqrt(2.0) * c.obstacle_size_m[1];
    const double gap = c.row_spacing_m - 2.0 * half_width;
    const double needed = widest + kObstacleRowClearance_m + std::max(kObstacleRowClearance_m, c.obstacle_passage_m);
    require(gap >= needed,
            "vineyard: the " + generator_number(gap) + " m between rows cannot hold obstacles up to " + generator_number(c.obstacle_size_m[1]) +
                " m with " + generator_number(kObstacleRowClearance_m) + " m clearance on one side and a passage of " +
                generator_number(std::max(kObstacleRowClearance_m, c.obstacle_passage_m)) + " m on the other (needs " + generator_number(needed) +
                " m)");
    require(row_length >= widest, "vineyard: rows of " + generator_number(row_length) + " m are shorter than obstacles up to " +
                                      generator_number(widest) + " m across");
  }
}

}  // namespace

HeightGrid make_rolling_terrain(const RollingTerrainConfig& config) {
  require(config.waves >= 1 && config.waves <= 32,
          "rolling terrain: waves must be in [1, 32], got " + std::to_string(config.waves));
  require(std::isfinite(config.amplitude_m) && config.amplitude_m >= 0.0,
          "rolling terrain: amplitude must be finite and >= 0");
  require(finite_positive(config.wavelength_m), "rolling terrain: wavelength must be finite and > 0");
  const GridLayout layout = grid_layout<std::invalid_argument>(config.size_m, config.spacing_m);

  // sin(kx x + ky y + phase) = sin(kx x) cos(ky y + phase) + cos(kx x) sin(ky y + phase):
  // factors per column and per row (index [vertex * waves + wave]) need
  // (cols + rows) * waves sines instead of cols * rows * waves.
  const int cols = layout.cols;
  const int rows = layout.rows;
  const auto count = static_cast<std::size_t>(config.waves);
  std::vector<double> sin_x(cols * count), cos_x(cols * count), sin_y(rows * count), cos_y(rows * count);
  Rng rng(config.seed);
  for (std::size_t w = 0; w < count; ++w) {
    const double direction = rng.uniform(0.0, kTwoPi);
    const double wavelength = config.wavelength_m * rng.uniform(1.0 - kWavelengthJitter, 1.0 + kWavelengthJitter);
    const double phase = rng.uniform(0.0, kTwoPi);
    const double k = kTwoPi / wavelength;
    for (int c = 0; c < cols; ++c) {
      const double angle = k * std::cos(direction) * grid_vertex_coordinate(c, cols, layout.spacing_x_m);
      sin_x[c * count + w] = std::sin(angle);
      cos_x[c * count + w] = std::cos(angle);
    }
    for (int r = 0; r < rows; ++r) {
      const double angle = k * std::sin(direction) * grid_vertex_coordinate(r, rows, layout.spacing_y_m) + phase;
      sin_y[r * count + w] = std::sin(angle);
      cos_y[r * count + w] = std::cos(angle);
    }
  }

  HeightGrid grid;
  grid.cols = cols;
  grid.rows = rows;
  grid.spacing_x_m = layout.spacing_x_m;
  grid.spacing_y_m = layout.spacing_y_m;
  grid.heights_m.resize(static_cast<std::size_t>(cols) * rows);
  double peak = 0.0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      double z = 0.0;
      for (std::size_t w = 0; w < count; ++w) {
        z += sin_x[c * count + w] * cos_y[r * count + w] + cos_x[c * count + w] * sin_y[r * count + w];
      }
      grid.heights_m[static_cast<std::size_t>(r) * cols + c] = z;
      peak = std::max(peak, std::abs(z));
    }
  }
  // amplitude * (z / peak) rather than z * (amplitude / peak): the peak vertex
  // then lands on exactly +-amplitude. A flat sum (peak 0) stays flat.
  if (peak > 0.0) {
    for (double& z : grid.heights_m) z = config.amplitude_m * (z / peak);
  }
  return grid;
}

std::vector<Shape> make_trees(const TreesConfig& config, const std::string& alias, const GroundFunction& ground) {
  validate(config);
  Rng rng(config.seed);

  // Dart throwing: uniform candidates, rejected near a trunk or in a keep-out circle.
  SpacedPoints trunks(config.min_spacing_m);
  const long max_attempts = static_cast<long>(kAttemptsPerTree) * config.count;
  for (long attempt = 0; attempt < max_attempts && static_cast<int>(trunks.points().size()) < config.count;
       ++attempt) {
    // One draw per statement: the order of a call's arguments is the compiler's (GCC, which
    // made the recorded scenes, drew y first; clang draws x first). Likewise below.
    const double y = rng.uniform(config.area_min_m.y(), config.area_max_m.y());
    const double x = rng.uniform(config.area_min_m.x(), config.area_max_m.x());
    const Eigen::Vector2d p(x, y);
    const bool kept_out = std::any_of(config.keep_out.begin(), config.keep_out.end(), [&](const Eigen::Vector3d& k) {
      return (p - k.head<2>()).norm() < k.z();
    });
    if (kept_out || trunks.has_neighbour_closer_than_min(p)) continue;
    trunks.add(p);
  }
  if (static_cast<int>(trunks.points().size()) < config.count) {
    throw std::runtime_error("could not place " + std::to_string(config.count) + " trees with min spacing " +
                             generator_number(config.min_spacing_m) + " m in area [" + generator_number(config.area_min_m.x()) + ", " +
                             generator_number(config.area_max_m.x()) + "] x [" + generator_number(config.area_min_m.y()) + ", " +
                             generator_number(config.area_max_m.y()) + "] m; placed " + std::to_string(trunks.points().size()));
  }

  const Color bark{0.40, 0.26, 0.13};
  const Color leaves{0.20, 0.45, 0.15};
  std::vector<Shape> shapes;
  shapes.reserve(2 * trunks.points().size());
  for (std::size_t i = 0; i < trunks.points().size(); ++i) {
    const Eigen::Vector2d& p = trunks.points()[i];
    const double trunk_radius = rng.uniform(config.trunk_radius_m[0], config.trunk_radius_m[1]);
    const double trunk_height = rng.uniform(config.trunk_height_m[0], config.trunk_height_m[1]);
    const double crown_radius = rng.uniform(config.crown_radius_m[0], config.crown_radius_m[1]);
    const double g = ground_at(ground, p.x(), p.y());
    const std::string name = alias + "/tree" + std::to_string(i);

    Shape trunk;
    trunk.alias = name + "/trunk";
    trunk.type = ShapeType::cylinder;
    trunk.radius_m = trunk_radius;
    trunk.height_m = trunk_height + kTrunkFooting_m;
    trunk.pose = translation(p.x(), p.y(), g - kTrunkFooting_m + 0.5 * trunk.height_m);
    trunk.color = jittered(bark, 0.05, rng);

    Shape crown;
    crown.alias = name + "/crown";
    crown.radius_m = crown_radius;
    if (config.crown == CrownShape::sphere) {
      crown.type = ShapeType::sphere;
      crown.pose = translation(p.x(), p.y(), g + trunk_height + 0.6 * crown_radius);
    } else {
      crown.type = ShapeType::cone;
      crown.height_m = config.crown_height_ratio * crown_radius;
      crown.pose = translation(p.x(), p.y(), g + 0.7 * trunk_height + 0.5 * crown.height_m);
    }
    crown.color = jittered(leaves, 0.05, rng);

    shapes.push_back(std::move(trunk));
    shapes.push_back(std::move(crown));
  }
  return shapes;
}

std::vector<Shape> make_vineyard(const VineyardConfig& config, const std::string& alias) {
  validate(config);
  const double row_length = config.field_size_m.y() - 2.0 * config.headland_m;
  // Equal post gaps no longer than post_spacing, with a post at each row end;
  // a ratio a rounding error above a whole number counts as that number.
  const int post_gaps = std::max(1, static_cast<int>(std::ceil(row_length / config.post_spacing_m - 1e-9)));
  const double post_gap = row_length / post_gaps;

  std::vector<Shape> shapes;
  for (int i = 0; i < config.row_count; ++i) {
    const double x = row_x(config, i);
    const std::string row = alias + "/row" + std::to_string(i);
    for (int j = 0; j <= post_gaps; ++j) {
      Shape post;
      post.alias = row + "/post" + std::to_string(j);
      post.type = ShapeType::cylinder;
      post.radius_m = config.post_radius_m;
      post.height_m = config.post_height_m;
      post.pose = translation(x, -0.5 * row_length + j * post_gap, 0.5 * config.post_height_m);
      post.color = {0.45, 0.35, 0.25};
      shapes.push_back(std::move(post));
    }
    Shape canopy;
    canopy.alias = row + "/canopy";
    canopy.type = ShapeType::cuboid;
    canopy.size_m = {config.canopy_width_m, row_length, config.canopy_top_m - config.canopy_bottom_m};
    canopy.pose = translation(x, 0.0, 0.5 * (config.canopy_bottom_m + config.canopy_top_m));
    canopy.color = {0.20, 0.50, 0.15};
    shapes.push_back(std::move(canopy));
  }

  // Fence walls centred on the field boundary; the x walls overlap the y walls at the corners.
  const double fx = config.field_size_m.x();
  const double fy = config.field_size_m.y();
  const double t = config.fence_thickness_m;
  const double h = config.fence_height_m;
  const struct {
    const char* side;
    Eigen::Vector3d centre;
    Eigen::Vector3d size;
  } walls[] = {
      {"north", {0.0, 0.5 * fy, 0.5 * h}, {fx + t, t, h}},
      {"south", {0.0, -0.5 * fy, 0.5 * h}, {fx + t, t, h}},
      {"east", {0.5 * fx, 0.0, 0.5 * h}, {t, fy + t, h}},
      {"west", {-0.5 * fx, 0.0, 0.5 * h}, {t, fy + t, h}},
  };
  for (const auto& wall : walls) {
    Shape fence;
    fence.alias = alias + "/fence/" + wall.side;
    fence.type = ShapeType::cuboid;
    fence.size_m = wall.size;
    fence.pose = translation(wall.centre.x(), wall.centre.y(), wall.centre.z());
    fence.color = {0.50, 0.50, 0.50};
    shapes.push_back(std::move(fence));
  }

  // Obstacles: a random gap between rows, then a centre that keeps the yawed
  // footprint clear of both row sides and within the row length.
  Rng rng(config.seed);
  const double half_width = row_half_width(config);
  for (int k = 0; k < config.obstacle_count; ++k) {
    const auto gap = static_cast<int>(rng.uniform_int(0, config.row_count - 2));
    Eigen::Vector3d size;
    for (int axis = 2; axis >= 0; --axis) size[axis] = rng.uniform(config.obstacle_size_m[0], config.obstacle_size_m[1]);
    const double yaw = rng.uniform(0.0, std::numbers::pi);
    const double c = std::abs(std::cos(yaw));
    const double s = std::abs(std::sin(yaw));
    const double half_x = 0.5 * (c * size.x() + s * size.y());
    const double half_y = 0.5 * (s * size.x() + c * size.y());
    const double margin_x = half_width + kObstacleRowClearance_m + half_x;
    double lo = row_x(config, gap) + margin_x, hi = row_x(config, gap + 1) - margin_x;
    if (config.obstacle_passage_m > kObstacleRowClearance_m) {
      // Against one row or the other, leaving the passage on the far side.
      const double shrink = config.obstacle_passage_m - kObstacleRowClearance_m;
      if (rng.bernoulli(0.5)) {
        hi -= shrink;
      } else {
        lo += shrink;
      }
    }
    const double x = rng.uniform(lo, hi);
    const double y = rng.uniform(-0.5 * row_length + half_y, 0.5 * row_length - half_y);

    Shape obstacle;
    obstacle.alias = alias + "/obstacle" + std::to_string(k);
    obstacle.type = ShapeType::cuboid;
    obstacle.size_m = size;
    obstacle.pose = translation(x, y, 0.5 * size.z());
    obstacle.pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    obstacle.color = {0.80, 0.40, 0.10};
    shapes.push_back(std::move(obstacle));
  }
  return shapes;
}

Eigen::Vector2d grid_cell_center(const GridObstaclesConfig& config, int row, int col) {
  if (row < 1 || row > config.rows || col < 1 || col > config.cols) {
    throw std::invalid_argument("cell (" + std::to_string(row) + ", " + std::to_string(col) + ") is outside the " +
                                std::to_string(config.rows) + " x " + std::to_string(config.cols) + " grid");
  }
  return config.origin_m + config.cell_size_m * Eigen::Vector2d(col - 0.5, row - 0.5);
}

int grid_box_samples_per_side(const GridObstaclesConfig& config, std::size_t shapes_per_sample) {
  if (shapes_per_sample == 0) return 1;
  // Shape visits at n samples per side, in doubles (no overflow, whatever the blocks say).
  const auto visits = [&](int n) {
    double points = 0.0;
    for (const GridBox& box : config.boxes) {
      const double cols = std::max(1.0, static_cast<double>(box.col_last) - box.col_first + 1.0);
      const double rows = std::max(1.0, static_cast<double>(box.row_last) - box.row_first + 1.0);
      points += (std::min(2.0 * cols, static_cast<double>(n)) + 1.0) * (std::min(2.0 * rows, static_cast<double>(n)) + 1.0);
    }
    return points * static_cast<double>(shapes_per_sample);
  };
  // Visits grow with n: the largest n within the budget, by bisection.
  if (visits(kGridBoxGroundSamples) <= kGridBoxGroundVisits) return kGridBoxGroundSamples;
  int lo = 1, hi = kGridBoxGroundSamples;  // visits(hi) > budget; lo is the answer if nothing larger fits
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (visits(mid) <= kGridBoxGroundVisits ? lo : hi) = mid;
  }
  return lo;
}

std::vector<Shape> make_grid_obstacles(const GridObstaclesConfig& config, const std::string& alias,
                                       const GroundFunction& ground, int samples_per_side) {
  require(samples_per_side >= 1 && samples_per_side <= kGridBoxGroundSamples,
          "grid obstacles: samples per side must be in [1, " + std::to_string(kGridBoxGroundSamples) + "]");
  require(config.origin_m.allFinite(), "grid obstacles: origin must be finite");
  require(finite_positive(config.cell_size_m), "grid obstacles: cell_size must be finite and > 0");
  require(config.rows >= 1 && config.cols >= 1, "grid obstacles: rows and cols must be >= 1");
  const double s = config.cell_size_m;
  std::vector<Shape> shapes;
  shapes.reserve(config.boxes.size());
  for (std::size_t k = 0; k < config.boxes.size(); ++k) {
    const GridBox& box = config.boxes[k];
    const std::string which = "grid obstacles: box " + std::to_string(k) + ": ";
    require(1 <= box.row_first && box.row_first <= box.row_last && box.row_last <= config.rows,
            which + "rows " + std::to_string(box.row_first) + "-" + std::to_string(box.row_last) +
                " must be an ascending range within 1-" + std::to_string(config.rows));
    require(1 <= box.col_first && box.col_first <= box.col_last && box.col_last <= config.cols,
            which + "cols " + std::to_string(box.col_first) + "-" + std::to_string(box.col_last) +
                " must be an ascending range within 1-" + std::to_string(config.cols));
    require(finite_positive(box.height_m), which + "height must be finite and > 0");

    const double x0 = config.origin_m.x() + (box.col_first - 1) * s;
    const double y0 = config.origin_m.y() + (box.row_first - 1) * s;
    const int cols = box.col_last - box.col_first + 1;
    const int rows = box.row_last - box.row_first + 1;
    // Ground extremes sampled at every cell corner and centre under the block,
    // but at most samples_per_side per side: a block over a whole 10000 x 10000
    // grid would otherwise cost 4e8 ground queries, and 10000 such blocks 256^2 each.
    const int samples_x = std::min(2 * cols, samples_per_side);
    const int samples_y = std::min(2 * rows, samples_per_side);
    double lowest = std::numeric_limits<double>::infinity();
    double highest = -std::numeric_limits<double>::infinity();
    for (int j = 0; j <= samples_y; ++j) {
      for (int i = 0; i <= samples_x; ++i) {
        const double g = ground_at(ground, x0 + cols * s * i / samples_x, y0 + rows * s * j / samples_y);
        lowest = std::min(lowest, g);
        highest = std::max(highest, g);
      }
    }
    const double bottom = lowest - kGridBoxFooting_m;
    const double top = highest + box.height_m;

    Shape shape;
    shape.alias = alias + "/box" + std::to_string(k);
    shape.type = ShapeType::cuboid;
    shape.size_m = {cols * s, rows * s, top - bottom};
    shape.pose = translation(x0 + 0.5 * cols * s, y0 + 0.5 * rows * s, 0.5 * (bottom + top));
    shape.color = {0.55, 0.55, 0.60};
    shapes.push_back(std::move(shape));
  }
  return shapes;
}

}  // namespace campo
