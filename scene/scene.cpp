#include "campo/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "scene/geodesy.hpp"

namespace campo {

namespace {

constexpr std::array<std::pair<ShapeType, std::string_view>, 7> kShapeNames{{
    {ShapeType::cuboid, "cuboid"},
    {ShapeType::cylinder, "cylinder"},
    {ShapeType::sphere, "sphere"},
    {ShapeType::cone, "cone"},
    {ShapeType::plane, "plane"},
    {ShapeType::heightfield, "heightfield"},
    {ShapeType::mesh, "mesh"},
}};

constexpr std::array<std::pair<VehicleType, std::string_view>, 2> kVehicleNames{{
    {VehicleType::quadrotor, "quadrotor"},
    {VehicleType::rover, "rover"},
}};

template <class Enum, std::size_t N>
std::string_view name_of(const std::array<std::pair<Enum, std::string_view>, N>& table, Enum e) {
  for (const auto& [value, name] : table) {
    if (value == e) return name;
  }
  return "?";
}

template <class Enum, std::size_t N>
std::optional<Enum> value_of(const std::array<std::pair<Enum, std::string_view>, N>& table,
                             std::string_view name) {
  for (const auto& [value, n] : table) {
    if (n == name) return value;
  }
  return std::nullopt;
}

template <class T>
const T* find_by_alias(const std::vector<T>& items, std::string_view alias) {
  for (const auto& item : items) {
    if (item.alias == alias) return &item;
  }
  return nullptr;
}

}  // namespace

std::string_view to_string(ShapeType type) { return name_of(kShapeNames, type); }
std::optional<ShapeType> shape_type_from_string(std::string_view name) {
  return value_of(kShapeNames, name);
}
std::string_view to_string(VehicleType type) { return name_of(kVehicleNames, type); }
std::string_view to_string(GustModel model) {
  switch (model) {
    case GustModel::none: return "none";
    case GustModel::one_minus_cos: return "one_minus_cos";
    case GustModel::dryden: return "dryden";
  }
  return "?";
}
Eigen::Vector3d WindConfig::steady_velocity_mps() const {
  const double a = direction_deg * (std::numbers::pi / 180.0);
  return {speed_mps * std::cos(a), speed_mps * std::sin(a), vertical_mps};
}
std::string_view to_string(EndRule rule) { return rule == EndRule::first_failure ? "first_failure" : "all"; }
std::optional<VehicleType> vehicle_type_from_string(std::string_view name) {
  return value_of(kVehicleNames, name);
}

double HeightGrid::min_height_m() const {
  return *std::min_element(heights_m.begin(), heights_m.end());
}

double HeightGrid::max_height_m() const {
  return *std::max_element(heights_m.begin(), heights_m.end());
}

std::optional<double> HeightGrid::height_at(double x, double y) const {
  // Continuous vertex coordinates, origin at vertex (0, 0).
  const double u = x / spacing_x_m + 0.5 * (cols - 1);
  const double v = y / spacing_y_m + 0.5 * (rows - 1);
  if (!(u >= 0.0 && v >= 0.0 && u <= cols - 1 && v <= rows - 1)) return std::nullopt;
  const int c = std::min(static_cast<int>(u), cols - 2);
  const int r = std::min(static_cast<int>(v), rows - 2);
  const double fu = u - c;
  const double fv = v - r;
  const double h00 = at(c, r), h10 = at(c + 1, r), h01 = at(c, r + 1), h11 = at(c + 1, r + 1);
  // Split along the diagonal (c+1, r)-(c, r+1), as Bullet does.
  if (fu + fv <= 1.0) return h00 + fu * (h10 - h00) + fv * (h01 - h00);
  return h11 + (1.0 - fu) * (h01 - h11) + (1.0 - fv) * (h10 - h11);
}

Eigen::Vector3d Mover::position_at(double t_s) const {
  double travelled = std::max(0.0, t_s - start_time_s) * speed_mps;
  double total = 0.0;
  for (std::size_t i = 1; i < path_m.size(); ++i) total += (path_m[i] - path_m[i - 1]).norm();
  if (total <= 0.0) return path_m.front();
  if (loop) {
    travelled = std::fmod(travelled, total);
  } else if (travelled >= total) {
    return path_m.back();
  }
  for (std::size_t i = 1; i < path_m.size(); ++i) {
    const double segment = (path_m[i] - path_m[i - 1]).norm();
    if (travelled <= segment && segment > 0.0) {
      return path_m[i - 1] + (path_m[i] - path_m[i - 1]) * (travelled / segment);
    }
    travelled -= segment;
  }
  return path_m.back();
}

std::int64_t steps_per_period(double rate_hz, double physics_step_s) {
  const double steps = 1.0 / (rate_hz * physics_step_s);
  if (!std::isfinite(steps) || steps > 1e15) return 0;
  const double whole = std::round(steps);
  if (whole < 1.0 || std::abs(steps - whole) > kRatePeriodTolerance * whole) return 0;
  return static_cast<std::int64_t>(whole);
}

std::vector<double> dividing_rates_near(double rate_hz, double physics_step_s, int each_side) {
  // The rates are (1/physics_step_s) / n for whole n; rate_hz sits at n = steps.
  const double physics_rate_hz = 1.0 / physics_step_s;
  // Past 2^52 a double no longer counts n one by one: a slower rate (or none, NaN) is listed from there.
  constexpr double kMaxSteps = 4503599627370496.0;  // 2^52
  double steps = physics_rate_hz / rate_hz;
  if (!(steps <= kMaxSteps)) steps = kMaxSteps;
  const auto exact = steps_per_period(rate_hz, physics_step_s);
  // Largest n whose rate is at or above rate_hz, smallest n whose rate is below it.
  const double above = exact > 0 ? static_cast<double>(exact) : std::floor(steps);
  const double below = std::max(exact > 0 ? static_cast<double>(exact) + 1.0 : std::ceil(steps), 1.0);
  // Counted loops: each_side rates on each side at most, whatever the numbers.
  std::vector<double> rates;
  for (int i = each_side - 1; i >= 0; --i) {
    if (const double n = above - i; n >= 1.0) rates.push_back(physics_rate_hz / n);
  }
  for (int i = 0; i < each_side; ++i) {
    if (const double n = below + i; n > above) rates.push_back(physics_rate_hz / n);
  }
  return rates;
}

const Shape* Scene::find_shape(std::string_view alias) const { return find_by_alias(shapes, alias); }
const Frame* Scene::find_frame(std::string_view alias) const { return find_by_alias(frames, alias); }
const VehicleDef* Scene::find_vehicle(std::string_view alias) const {
  return find_by_alias(vehicles, alias);
}

std::optional<double> ground_height_of(const Shape& shape, double x, double y) {
  if (shape.type == ShapeType::heightfield) {
    const Eigen::Vector3d local = shape.pose.inverse() * Eigen::Vector3d(x, y, 0.0);
    if (auto h = shape.terrain->height_at(local.x(), local.y())) return *h + shape.pose.translation().z();
  } else if (shape.type == ShapeType::plane) {
    // z where the vertical line through (x, y) meets the plane, if it is not vertical.
    const Eigen::Vector3d n = shape.pose.linear().col(2);
    if (std::abs(n.z()) > 1e-9) {
      const Eigen::Vector3d p = shape.pose.translation();
      return p.z() - (n.x() * (x - p.x()) + n.y() * (y - p.y())) / n.z();
    }
  }
  return std::nullopt;
}

std::optional<double> Scene::ground_height(double x, double y) const {
  std::optional<double> best;
  for (const auto& shape : shapes) {
    const auto h = ground_height_of(shape, x, y);
    if (h && (!best || *h > *best)) best = h;
  }
  return best;
}

std::vector<MovingBody> moving_bodies(const Scene& scene) {
  std::vector<MovingBody> bodies;
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    if (!scene.shapes[i].is_static) bodies.push_back({&scene.shapes[i], static_cast<std::int32_t>(i)});
  }
  for (std::size_t i = 0; i < scene.movers.size(); ++i) {
    bodies.push_back({&scene.movers[i].shape, -1 - static_cast<std::int32_t>(i)});
  }
  return bodies;
}

std::vector<Eigen::Isometry3d> scripted_poses(const Scene& scene, double t_s) {
  std::vector<Eigen::Isometry3d> poses;
  for (const MovingBody& body : moving_bodies(scene)) {
    Eigen::Isometry3d pose = body.shape->pose;
    if (body.id < 0) pose.translation() = scene.movers[static_cast<std::size_t>(-1 - body.id)].position_at(t_s);
    poses.push_back(pose);
  }
  return poses;
}

std::string_view to_string(GeoProjection projection) {
  return projection == GeoProjection::wgs84_enu ? "wgs84_enu" : "sphere_no_coslat";
}

Eigen::Vector3d geodetic_to_local(const GeoReference& reference, double latitude_deg, double longitude_deg,
                                  double altitude_m) {
  const Geodetic point{latitude_deg, longitude_deg, altitude_m};
  const Geodetic origin{reference.latitude_deg, reference.longitude_deg, reference.altitude_m};
  Eigen::Vector3d local = reference.projection == GeoProjection::wgs84_enu ? geodetic_to_enu(point, origin)
                                                                         : geodetic_to_sphere_no_coslat(point, origin);
  local.head<2>() += reference.position_m;
  return local;
}

}  // namespace campo
