#include "campo/scene_loader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include <openssl/evp.h>

#include "scene/generator_fields.hpp"
#include "scene/dem_source.hpp"
#include "scene/generators.hpp"
#include "scene/geodesy.hpp"
#include "scene/heightfield_sources.hpp"
#include "scene/mesh_sources.hpp"
#include "scene/sensor_fields.hpp"
#include "scene/world_config.hpp"

namespace campo {

namespace {

// Every length, size and spacing of a scene (positions are in [-1e6, 1e6] m):
// beyond these, geometry, physics and figures lose their meaning in doubles.
const Range kLength{0.0, 1e6, true, false};
// Terrain heights, however they are given (expression, CSV, PNG).
const Range kTerrainHeight = Range::closed(-1e5, 1e5);

constexpr std::string_view kTypes[] = {
    "cuboid", "cylinder", "sphere", "cone", "plane", "heightfield", "mesh", "dummy",
    "rolling_terrain", "trees", "vineyard", "grid_obstacles", "mover", "quadrotor", "rover"};

bool valid_alias(const std::string& alias) {
  for (char c : alias) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return !alias.empty() && alias.size() <= 64;
}

Color read_color(const JsonNode& node) {
  const Eigen::Vector3d c = node.as_vector3(Range::closed(0.0, 1.0));
  return {c.x(), c.y(), c.z()};
}

// A rate or step as a reader would write it: up to 12 significant digits (80, 26.6666666667).
std::string format_rate(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", value);
  return text;
}

// What a rate must be at this physics step, with the valid rates nearest `rate_hz`:
// "a rate that divides the physics rate 240 Hz (1 / physics_step_s) into a whole number of
// steps, such as 240, 120, 80 or 60" (for 100 Hz).
std::string dividing_rate_expectation(double rate_hz, double physics_step_s) {
  const std::vector<double> rates = dividing_rates_near(rate_hz, physics_step_s);
  std::string list;
  for (std::size_t i = 0; i < rates.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == rates.size() ? " or " : ", ") + format_rate(rates[i]);
  }
  return "a rate that divides the physics rate " + format_rate(1.0 / physics_step_s) +
         " Hz (1 / physics_step_s) into a whole number of steps, such as " + list;
}

// A rate read at `node` must be a whole number of physics steps per period (no silent rounding).
void check_rate(const JsonNode& node, double rate_hz, double physics_step_s) {
  if (steps_per_period(rate_hz, physics_step_s) == 0) node.fail(dividing_rate_expectation(rate_hz, physics_step_s));
}

SensorDef read_sensor(const JsonNode& node, const SceneLimits& limits, InputErrors* errors);

// Runs a generator; its complaints about the config become input errors at `at`.
template <class Generate>
auto generated(const JsonNode& at, Generate generate) -> decltype(generate()) {
  try {
    return generate();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(at.file(), at.pointer(), e.what());
  }
}

class Loader {
 public:
  Loader(const SceneLimits& limits, std::filesystem::path base_dir, const SceneChecks& checks)
      : limits_(limits), base_dir_(std::move(base_dir)), checks_(checks) {}

  // Every error of the scene that can be found is collected (each top-level
  // key, object, field and waypoint checked on its own) and thrown at the end
  // as one InputError; what makes the rest meaningless (another format
  // version, a document that is not an object) is thrown at once.
  Scene load(const JsonNode& root) {
    ObjectReader r(root, &errors_);
    if (auto v = r.optional("campo_scene")) {
      if (v->as_int(1, 1000) != 1) v->fail("format version 1");
    }
    r.read("name", scene_.name);
    std::string description;
    r.read("description", description);
    if (auto world = r.optional("world")) r.check([&] { read_world(*world); });
    if (auto end = r.optional("end")) {
      r.check([&] { scene_.end = end->as_choice({"all", "first_failure"}) == 0 ? EndRule::all : EndRule::first_failure; });
    }
    r.check([&] { read_objects(r.required("objects"), Eigen::Isometry3d::Identity(), 0); });
    r.finish();
    // Missions last: they may name frames and grids declared anywhere.
    for (const auto& pending : pending_missions_) {
      VehicleDef& vehicle = scene_.vehicles[pending.first];
      const auto& mission = pending.second;
      errors_.check([&] { vehicle.mission = read_mission(mission, vehicle.mission_area_m, vehicle.gates); });
    }
    errors_.throw_if_any();
    return std::move(scene_);
  }

 private:
  void read_world(const JsonNode& node) {
    WorldConfig& w = scene_.world;
    ObjectReader r(node, &errors_);
    geo_reference_given_ = r.has("geo_reference");  // else a DEM may fill it (read_dem)
    world_config_fields().read_fields(r, w);
    r.finish();
    // The rates against the step, once both are known to be valid.
    if (!r.ok()) return;
    r.check([&] { check_world_rate(r, "control_rate_hz", w.control_rate_hz); });
    r.check([&] { check_world_rate(r, "sensor_rate_hz", w.sensor_rate_hz); });
  }

  // A world rate, set or default, at the physics step, set or default: the
  // error points at the rate when the file sets it, else at the step.
  void check_world_rate(ObjectReader& r, std::string_view key, double rate_hz) {
    const double dt = scene_.world.physics_step_s;
    if (auto rate = r.optional(key)) return check_rate(*rate, rate_hz, dt);
    if (steps_per_period(rate_hz, dt) > 0) return;
    const JsonNode step = *r.optional("physics_step_s");  // present: the defaults agree with each other
    step.fail("a step that divides the period of the default " + std::string(key) + " " + format_rate(rate_hz) +
              " Hz, or else /world/" + std::string(key) + " set to " + dividing_rate_expectation(rate_hz, dt));
  }

  void read_objects(const JsonNode& node, const Eigen::Isometry3d& parent, int depth) {
    if (depth > limits_.max_child_depth) {
      node.fail("children nested at most " + std::to_string(limits_.max_child_depth) + " deep");
    }
    for (const JsonNode& object : node.as_array(0, static_cast<std::size_t>(limits_.max_objects))) {
      if (++object_count_ > limits_.max_objects) {
        object.fail("at most " + std::to_string(limits_.max_objects) + " objects in a scene");
      }
      // Each object on its own: an error in one leaves the next to be checked.
      const std::size_t before = errors_.count();
      errors_.check([&] { read_object(object, parent, depth); });
      if (errors_.count() > before) note_failed(object);
    }
  }

  // An object with errors is not in the scene: what later refers to it (a
  // mission's grid or frame, ground under a point) must not be blamed on the reference.
  void note_failed(const JsonNode& object) {
    const nlohmann::json& value = object.value();
    if (!value.is_object()) return;
    const auto alias = value.find("alias");
    if (alias != value.end() && alias->is_string()) failed_aliases_.insert(alias->get<std::string>());
    const auto type = value.find("type");
    const bool ground = type != value.end() && type->is_string() &&
                        (*type == "heightfield" || *type == "plane" || *type == "rolling_terrain");
    if (ground && failed_ground_.empty()) failed_ground_ = object.pointer();
  }

  // Why there is no ground below world (x, y), for "expected ..." messages: no terrain
  // declared before, a terrain that did not load, or a point outside the terrain's extent.
  std::string no_ground_reason(double x, double y) const {
    const std::string point = "(" + format_rate(x) + ", " + format_rate(y) + ")";
    std::string extents;
    int terrains = 0;
    for (const Shape& shape : scene_.shapes) {
      if (shape.type != ShapeType::heightfield || !shape.terrain) continue;
      if (++terrains > 4) continue;  // a few are enough to see where the ground is
      // The grid is centred on its pose; its corners in the world (yaw only).
      const double hx = 0.5 * shape.terrain->size_x_m(), hy = 0.5 * shape.terrain->size_y_m();
      Eigen::AlignedBox2d box;
      for (const double cx : {-hx, hx}) {
        for (const double cy : {-hy, hy}) box.extend((shape.pose * Eigen::Vector3d(cx, cy, 0.0)).head<2>());
      }
      extents += (extents.empty() ? "" : "; ") + ("\"" + shape.alias + "\" covers x in [") +
                 format_rate(box.min().x()) + ", " + format_rate(box.max().x()) + "] m, y in [" +
                 format_rate(box.min().y()) + ", " + format_rate(box.max().y()) + "] m";
    }
    if (terrains > 4) extents += "; and " + std::to_string(terrains - 4) + " more";
    if (!extents.empty()) return point + " is outside the terrain declared before this object (" + extents + ")";
    if (!failed_ground_.empty()) {
      return "no terrain below " + point + ": the terrain at " + failed_ground_ + " has errors (reported with these)";
    }
    return "no terrain below " + point + "; declare the terrain (heightfield, plane or rolling_terrain) before this object";
  }

  std::string claim_alias(ObjectReader& r) {
    const JsonNode node = r.required("alias");
    const std::string alias = node.as_string();
    if (!valid_alias(alias)) node.fail("an alias of 1-64 letters, digits, '_', '-' or '.'");
    const auto [it, inserted] = alias_pointers_.emplace(alias, node.pointer());
    if (!inserted) {
      throw InputError(node.file(), node.pointer(),
                       "duplicate alias \"" + alias + "\" (first used at " + it->second + ")");
    }
    return alias;
  }

  // World pose of an object: parent * local, with z optionally measured from the ground.
  Eigen::Isometry3d read_pose(ObjectReader& r, const Eigen::Isometry3d& parent) {
    auto node = r.optional("pose");
    if (!node) return parent;
    ObjectReader p(*node, r.errors());
    Pose pose;
    p.read("position_m", pose.position_m, Range::closed(-1e6, 1e6));
    p.read("rpy_deg", pose.rpy_deg, Range::closed(-360.0, 360.0));
    bool above_ground = false;
    p.read("above_ground", above_ground);
    p.finish();
    if (!p.ok()) return parent;
    Eigen::Isometry3d world = parent * to_isometry(pose);
    if (above_ground) {
      const Eigen::Vector3d t = world.translation();
      const auto ground = scene_.ground_height(t.x(), t.y());
      if (!ground) {
        throw InputError(node->file(), node->pointer() + "/above_ground",
                         "expected ground below the object: " + no_ground_reason(t.x(), t.y()));
      }
      world.translation().z() = *ground + pose.position_m.z();
    }
    return world;
  }

  // Keys shared by every shape: static, mass, colour, friction.
  void read_shape_properties(ObjectReader& r, Shape& shape) {
    r.read("static", shape.is_static);
    r.read("mass_kg", shape.mass_kg, Range{0.0, 1e9, true, false});
    r.read("friction", shape.friction, Range::closed(0.0, 10.0));
    if (auto c = r.optional("color")) r.check([&] { shape.color = read_color(*c); });
    if (r.ok() && !shape.is_static && shape.mass_kg <= 0.0) {
      throw InputError(r.node().file(), r.node().pointer(),
                       "a non-static shape needs \"mass_kg\" > 0");
    }
  }

  // Geometry keys of a primitive shape type.
  void read_primitive(ObjectReader& r, Shape& shape) {
    switch (shape.type) {
      case ShapeType::cuboid:
        r.check([&] { shape.size_m = r.required("size_m").as_vector3(kLength); });
        break;
      case ShapeType::cylinder:
      case ShapeType::cone:
        r.check([&] { shape.radius_m = r.required("radius_m").as_number(kLength); });
        r.check([&] { shape.height_m = r.required("height_m").as_number(kLength); });
        break;
      case ShapeType::sphere:
        r.check([&] { shape.radius_m = r.required("radius_m").as_number(kLength); });
        break;
      case ShapeType::plane:
      case ShapeType::heightfield:
      case ShapeType::mesh:
        break;
    }
  }

  void add_shape(Shape shape, const JsonNode& at) {
    if (static_cast<long>(scene_.shapes.size()) >= limits_.max_shapes) {
      at.fail("a scene of at most " + std::to_string(limits_.max_shapes) + " shapes");
    }
    if (shape.source.empty()) shape.source = at.pointer();
    scene_.shapes.push_back(std::move(shape));
  }

  void add_generated(std::vector<Shape> shapes, const JsonNode& at,
                     const Eigen::Isometry3d& placement = Eigen::Isometry3d::Identity()) {
    if (static_cast<long>(scene_.shapes.size() + shapes.size()) > limits_.max_shapes) {
      at.fail("a scene of at most " + std::to_string(limits_.max_shapes) + " shapes");
    }
    for (Shape& s : shapes) {
      s.pose = placement * s.pose;
      s.source = at.pointer();
      scene_.shapes.push_back(std::move(s));
    }
  }

  // The ground so far, for generators that stand things on it: the highest
  // ground shape (heightfield, plane) at each (x, y). Only the ground shapes
  // are visited per query (a scene may hold 200000 shapes), and level planes
  // fold into one height, so a flat ground visits none. The function is used
  // before the generated shapes are added.
  struct Ground {
    GroundFunction height;
    std::size_t shapes_per_query = 0;  // the ground shapes each query visits
  };
  Ground ground() {
    // Only the shapes added since the last call are looked at: linear in the shapes however many generators ask.
    for (; ground_scanned_ < scene_.shapes.size(); ++ground_scanned_) {
      const Shape& shape = scene_.shapes[ground_scanned_];
      const Eigen::Vector3d n = shape.pose.linear().col(2);
      if (shape.type == ShapeType::plane && n.x() == 0.0 && n.y() == 0.0) {
        const double z = shape.pose.translation().z();  // ground_height_of() of a level plane, everywhere
        level_ground_m_ = level_ground_m_ ? std::max(*level_ground_m_, z) : z;
      } else if (shape.type == ShapeType::heightfield || shape.type == ShapeType::plane) {
        ground_shapes_.push_back(ground_scanned_);
      }
    }
    std::vector<const Shape*> shapes;
    for (const std::size_t i : ground_shapes_) shapes.push_back(&scene_.shapes[i]);
    const std::size_t count = shapes.size();
    return {[shapes = std::move(shapes), level = level_ground_m_](double x, double y) {
              std::optional<double> best = level;
              for (const Shape* shape : shapes) {
                const auto h = ground_height_of(*shape, x, y);
                if (h && (!best || *h > *best)) best = h;
              }
              return best.value_or(0.0);
            },
            count};
  }

  // The keys of an object are checked on their own where they can be (an
  // error in one leaves the others to be checked), and nothing of an object
  // with errors is added to the scene; its type decides which keys it has,
  // so an error in the type ends the object.
  void read_object(const JsonNode& node, const Eigen::Isometry3d& parent, int depth) {
    ObjectReader r(node, &errors_);
    std::string alias;
    r.check([&] { alias = claim_alias(r); });
    const JsonNode type_node = r.required("type");
    const std::string type(kTypes[type_node.as_choice({std::begin(kTypes), std::end(kTypes)})]);

    if (const auto shape_type = shape_type_from_string(type)) {
      Shape shape;
      shape.alias = alias;
      shape.type = *shape_type;
      r.check([&] { shape.pose = read_pose(r, parent); });
      read_shape_properties(r, shape);
      if (shape.type == ShapeType::heightfield) {
        r.check([&] { read_heightfield(r, shape); });
      } else if (shape.type == ShapeType::mesh) {
        r.check([&] { read_mesh(r, shape); });
      } else {
        read_primitive(r, shape);
      }
      r.check([&] {
        if (!shape.is_static && (shape.type == ShapeType::plane || shape.type == ShapeType::heightfield)) {
          throw InputError(node.file(), child_pointer(node.pointer(), "static"),
                           "expected true: planes and heightfields are always static");
        }
      });
      const Eigen::Isometry3d frame = shape.pose;
      if (r.ok()) add_shape(std::move(shape), node);
      if (auto children = r.optional("children")) r.check([&] { read_objects(*children, frame, depth + 1); });
    } else if (type == "dummy") {
      Frame frame{alias, parent};
      r.check([&] { frame.pose = read_pose(r, parent); });
      if (r.ok()) scene_.frames.push_back(frame);
      if (auto children = r.optional("children")) r.check([&] { read_objects(*children, frame.pose, depth + 1); });
    } else if (type == "rolling_terrain") {
      read_rolling_terrain(r, alias, parent);
    } else if (type == "trees") {
      read_trees(r, alias);
    } else if (type == "vineyard") {
      read_vineyard(r, alias, parent);
    } else if (type == "grid_obstacles") {
      read_grid_obstacles(r, alias);
    } else if (type == "mover") {
      read_mover(r, alias, parent);
    } else {
      read_vehicle(r, alias, *vehicle_type_from_string(type), parent);
    }
    r.finish();
  }

  void check_vertex_count(const JsonNode& at, const Eigen::Vector2d& size_m, double spacing_m) {
    const double vertices = (std::round(size_m.x() / spacing_m) + 1) * (std::round(size_m.y() / spacing_m) + 1);
    if (vertices > static_cast<double>(kMaxHeightfieldVertices)) {
      at.fail("a grid of at most " + std::to_string(kMaxHeightfieldVertices) +
              " vertices (size / spacing too fine)");
    }
  }

  // An "imu" or "rgb_camera" sensor block of vehicle `vehicle`.
  void read_other_sensor(const JsonNode& node, const std::string& type, const std::string& alias,
                         VehicleDef& vehicle) {
    ObjectReader r(node, &errors_);
    r.required("alias");
    r.required("type");
    if (type == "imu") {
      ImuDef imu{alias, {}};
      imu_config_fields().read_fields(r, imu.imu);
      r.finish();
      if (!r.ok()) return;
      if (imu.imu.rate_hz > 0.0) check_rate(*r.optional("rate_hz"), imu.imu.rate_hz, scene_.world.physics_step_s);
      vehicle.imus.push_back(std::move(imu));
    } else {
      RgbCameraDef camera{alias, {}};
      rgb_camera_config_fields().read_fields(r, camera.camera);
      r.finish();
      if (!r.ok()) return;
      if (camera.camera.rate_hz > 0.0) {
        check_rate(*r.optional("rate_hz"), camera.camera.rate_hz, scene_.world.physics_step_s);
      }
      vehicle.rgb_cameras.push_back(std::move(camera));
    }
  }

  void read_heightfield(ObjectReader& r, Shape& shape) {
    const JsonNode& node = r.node();
    const auto expression = r.optional("expression");
    const auto csv = r.optional("csv");
    const auto png = r.optional("png");
    const auto dem = r.optional("dem");
    // After the sources are read, so that an error here does not leave them unread (reported as unknown).
    r.check([&] {
      const Eigen::Vector3d rpy = rpy_deg_from_rotation(shape.pose.linear());
      if (std::abs(rpy.x()) > 1e-9 || std::abs(rpy.y()) > 1e-9) {
        throw InputError(node.file(), child_pointer(node.pointer(), "pose"),
                         "expected a heightfield pose without roll or pitch");
      }
    });
    if (static_cast<int>(expression.has_value()) + csv.has_value() + png.has_value() + dem.has_value() != 1) {
      // Which other keys belong depends on the source: none is reported unknown.
      for (const std::string_view key : {"size_m", "spacing_m", "height_scale_m", "min_height_m"}) r.accept(key);
      for (const std::string& key : dem_fields().keys()) r.accept(key);
      throw InputError(node.file(), node.pointer(),
                       "expected exactly one height source: \"expression\", \"csv\", \"png\" or \"dem\"");
    }
    Eigen::Vector2d size_m(100.0, 100.0);
    double spacing_m = 1.0;
    double height_scale_m = 1.0;
    double min_height_m = 0.0;
    const JsonNode& source = expression ? *expression : csv ? *csv : png ? *png : *dem;
    if (expression) {
      r.read("size_m", size_m, kLength);
      r.read("spacing_m", spacing_m, kLength);
      if (!r.ok()) return;
      check_vertex_count(node, size_m, spacing_m);
      shape.terrain = std::make_shared<HeightGrid>(generated(source, [&] {
        return heightgrid_from_expression(expression->as_string(), size_m, spacing_m, shape.pose);
      }));
    } else if (csv) {
      r.read("spacing_m", spacing_m, kLength);
      const auto path = resolve_path(*csv);
      if (!r.ok()) return;
      shape.terrain = std::make_shared<HeightGrid>(
          generated(source, [&] { return heightgrid_from_csv(path, spacing_m); }));
    } else if (dem) {
      read_dem(r, *dem, shape);
      if (!shape.terrain) return;
    } else {
      r.read("size_m", size_m, kLength);
      r.read("height_scale_m", height_scale_m, kLength);
      r.read("min_height_m", min_height_m, Range::closed(-1e4, 1e4));
      const auto path = resolve_path(*png);
      if (!r.ok()) return;
      shape.terrain = std::make_shared<HeightGrid>(generated(
          source, [&] { return heightgrid_from_png(path, size_m, height_scale_m, min_height_m); }));
    }
    check_heights(source, *shape.terrain);
  }

  // A "dem" heightfield (docs/scene-format.md, "heightfield"): the grid from
  // the file; one with a CRS is placed by the world's geo_reference, or,
  // when the scene gives none, fills it with its centre at the pose, so
  // geodetic waypoints (read after every object) land on the terrain.
  void read_dem(ObjectReader& r, const JsonNode& source, Shape& shape) {
    DemOptions options;
    dem_fields().read_fields(r, options);
    const auto path = resolve_path(source);
    if (!r.ok()) return;
    DemTerrain dem = generated(source, [&] { return heightgrid_from_dem(path, options); });
    const JsonNode& node = r.node();
    if (dem.centre_lat_lon_deg) {
      const double latitude = dem.centre_lat_lon_deg->x(), longitude = dem.centre_lat_lon_deg->y();
      GeoReference& reference = scene_.world.geo_reference;
      const std::string by = geo_reference_filled_by_.empty()
                                 ? std::string("the world's geo_reference")
                                 : "the geo_reference filled from the DEM at " + geo_reference_filled_by_;
      if (geo_reference_given_) {
        if (r.has("pose")) {
          throw InputError(node.file(), child_pointer(node.pointer(), "pose"),
                           "expected no pose: " + by + " places a DEM with a coordinate reference system (its centre at its "
                           "latitude and longitude)");
        }
        if (reference.projection != GeoProjection::wgs84_enu) {
          source.fail("a geo_reference with projection \"wgs84_enu\" to place a DEM: \"sphere_no_coslat\" "
                      "stretches east-west distances, so the terrain would not lie under geodetic waypoints");
        }
        const Eigen::Vector3d at = geodetic_to_local(reference, latitude, longitude, 0.0);
        if (!(std::abs(at.x()) <= 1e6 && std::abs(at.y()) <= 1e6 && std::abs(at.z()) <= 1e6)) {
          source.fail("a DEM within 1000 km of the geo_reference; its centre (" + format_rate(latitude) + ", " +
                      format_rate(longitude) + ") lies at (" + format_rate(at.x()) + ", " + format_rate(at.y()) +
                      ") m");
        }
        shape.pose = Eigen::Translation3d(at) * Eigen::Isometry3d::Identity();
      } else {
        const Eigen::Vector3d t = shape.pose.translation();
        if (std::abs(rpy_deg_from_rotation(shape.pose.linear()).z()) > 1e-9) {
          throw InputError(node.file(), child_pointer(node.pointer(), "pose"),
                           "expected a pose without yaw: this DEM fills the world's geo_reference, whose x is east");
        }
        const double altitude = -t.z();
        if (!Range::closed(-1e4, 1e5).contains(altitude)) {
          throw InputError(node.file(), child_pointer(node.pointer(), "pose"),
                           "expected a pose z in [-1e5, 1e4] m: this DEM fills the geo_reference with altitude_m = -z");
        }
        reference = GeoReference{latitude, longitude, altitude, GeoProjection::wgs84_enu, t.head<2>()};
        geo_reference_given_ = true;
        geo_reference_filled_by_ = node.pointer();
      }
    }
    shape.terrain = std::make_shared<HeightGrid>(std::move(dem.grid));
  }

  // Heights far beyond any terrain would overflow sizes derived from them
  // (boxes standing on the ground, figure axes), so they are refused here.
  static void check_heights(const JsonNode& source, const HeightGrid& grid) {
    for (int row = 0; row < grid.rows; ++row) {
      for (int col = 0; col < grid.cols; ++col) {
        const double h = grid.at(col, row);
        if (!kTerrainHeight.contains(h)) {
          std::ostringstream got;
          got << h;
          throw InputError(source.file(), source.pointer(),
                           "expected terrain heights that are " + kTerrainHeight.describe() + " m, got " +
                               got.str() + " at vertex (column " + std::to_string(col) + ", row " +
                               std::to_string(row) + ")");
        }
      }
    }
  }

  // A "mesh" object: its file read (within what is left of the scene's triangle budget) and placed.
  void read_mesh(ObjectReader& r, Shape& shape) {
    MeshSourceConfig c;
    mesh_source_fields().read_fields(r, c);
    const JsonNode file = r.required("file");
    if (!r.ok()) return;
    const auto path = resolve_path(file);
    MeshLimits limits;
    limits.max_file_bytes = limits_.max_mesh_file_bytes;
    limits.max_triangles = static_cast<std::size_t>(std::max(0L, limits_.max_mesh_triangles));
    const std::size_t left = limits.max_triangles - std::min(limits.max_triangles, mesh_triangles_);
    if (left == 0) {
      file.fail("at most " + std::to_string(limits.max_triangles) + " triangles in all meshes of a scene, used up before this one");
    }
    MeshReadResult read = generated(file, [&] { return read_triangle_mesh(path, c.scale, c.up_axis, limits, left); });
    mesh_triangles_ += read.mesh.triangles.size();
    shape.mesh = std::make_shared<const TriangleMesh>(std::move(read.mesh));
  }

  std::filesystem::path resolve_path(const JsonNode& node) {
    std::filesystem::path p = node.as_string();
    if (p.is_relative()) p = base_dir_ / p;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) {
      throw InputError(node.file(), node.pointer(),
                       "expected a readable file, but \"" + p.string() + "\" does not exist");
    }
    return p;
  }

  void read_rolling_terrain(ObjectReader& r, const std::string& alias,
                            const Eigen::Isometry3d& parent) {
    RollingTerrainConfig c;
    rolling_terrain_fields().read_fields(r, c);
    Shape shape;
    shape.alias = alias;
    shape.type = ShapeType::heightfield;
    r.check([&] { shape.pose = read_pose(r, parent); });
    shape.color = {0.45, 0.6, 0.3};
    if (auto col = r.optional("color")) r.check([&] { shape.color = read_color(*col); });
    r.read("friction", shape.friction, Range::closed(0.0, 10.0));
    if (!r.ok()) return;
    check_vertex_count(r.node(), c.size_m, c.spacing_m);
    const Eigen::Vector3d rpy = rpy_deg_from_rotation(shape.pose.linear());
    if (std::abs(rpy.x()) > 1e-9 || std::abs(rpy.y()) > 1e-9) {
      throw InputError(r.node().file(), child_pointer(r.node().pointer(), "pose"),
                       "expected a terrain pose without roll or pitch");
    }
    shape.terrain = std::make_shared<HeightGrid>(generated(r.node(), [&] { return make_rolling_terrain(c); }));
    add_shape(std::move(shape), r.node());
  }

  void read_trees(ObjectReader& r, const std::string& alias) {
    TreesConfig c;
    trees_fields(limits_).read_fields(r, c);
    if (!r.ok()) return;
    if ((c.area_max_m.array() <= c.area_min_m.array()).any()) {
      r.fail("\"area_max_m\" greater than \"area_min_m\" in x and y");
    }
    add_generated(generated(r.node(), [&] { return make_trees(c, alias, ground().height); }), r.node());
  }

  void read_vineyard(ObjectReader& r, const std::string& alias, const Eigen::Isometry3d& parent) {
    VineyardConfig c;
    vineyard_fields(limits_).read_fields(r, c);
    Eigen::Isometry3d placement = parent;
    r.check([&] { placement = read_pose(r, parent); });
    if (!r.ok()) return;
    const double posts_per_row = std::floor(c.field_size_m.y() / c.post_spacing_m) + 2;
    if (posts_per_row * c.row_count > static_cast<double>(limits_.max_vineyard_posts)) {
      r.fail("at most " + std::to_string(limits_.max_vineyard_posts) +
             " posts (row_count x row length / post_spacing_m)");
    }
    add_generated(generated(r.node(), [&] { return make_vineyard(c, alias); }), r.node(), placement);
  }

  void read_grid_obstacles(ObjectReader& r, const std::string& alias) {
    GridObstaclesConfig c;
    grid_obstacles_fields(limits_).read_fields(r, c);
    if (!r.ok()) return;
    // Ground samples per block within one budget for the generator (generators.hpp).
    add_generated(generated(r.node(),
                            [&] {
                              const Ground g = ground();
                              return make_grid_obstacles(c, alias, g.height,
                                                         grid_box_samples_per_side(c, g.shapes_per_query));
                            }),
                  r.node());
    grids_.emplace(alias, c);
  }

  void read_mover(ObjectReader& r, const std::string& alias, const Eigen::Isometry3d& parent) {
    Mover mover;
    mover.shape.alias = alias;
    r.check([&] { mover.shape.pose = read_pose(r, parent); });
    r.check([&] {
      const JsonNode shape_node = r.required("shape");
      ObjectReader s(shape_node, r.errors());
      const auto type = s.required("type").as_choice({"cuboid", "cylinder", "sphere", "cone"});
      mover.shape.type = *shape_type_from_string(std::array{"cuboid", "cylinder", "sphere", "cone"}[type]);
      read_primitive(s, mover.shape);
      if (auto c = s.optional("color")) s.check([&] { mover.shape.color = read_color(*c); });
      s.finish();
    });
    r.check([&] {
      for (const JsonNode& point : r.required("path_m").as_array(2, static_cast<std::size_t>(limits_.max_waypoints))) {
        r.check([&] { mover.path_m.push_back(parent * point.as_vector3(Range::closed(-1e6, 1e6))); });
      }
    });
    r.read("speed_mps", mover.speed_mps, Range::closed(1e-3, 100.0));
    r.read("start_time_s", mover.start_time_s, Range::non_negative());
    r.read("loop", mover.loop);
    if (!r.ok()) return;
    mover.shape.source = r.node().pointer();
    mover.shape.pose.translation() = mover.path_m.front();
    scene_.movers.push_back(std::move(mover));
  }

  void read_vehicle(ObjectReader& r, const std::string& alias, VehicleType type,
                    const Eigen::Isometry3d& parent) {
    if (static_cast<int>(scene_.vehicles.size()) >= limits_.max_vehicles) {
      r.fail("at most " + std::to_string(limits_.max_vehicles) + " vehicles");
    }
    VehicleDef vehicle;
    vehicle.alias = alias;
    vehicle.type = type;
    r.check([&] { vehicle.pose = read_pose(r, parent); });
    if (auto sensors = r.optional("sensors")) {
      std::map<std::string, std::string> sensor_aliases;
      r.check([&] {
        for (const JsonNode& s : sensors->as_array(0, static_cast<std::size_t>(limits_.max_sensors))) {
          // Each sensor on its own.
          r.check([&] {
            ObjectReader sr(s);
            const JsonNode alias_node = sr.required("alias");
            const std::string sensor_alias = alias_node.as_string();
            if (!valid_alias(sensor_alias)) alias_node.fail("an alias of 1-64 letters, digits, '_', '-' or '.'");
            if (!sensor_aliases.emplace(sensor_alias, alias_node.pointer()).second) {
              throw InputError(alias_node.file(), alias_node.pointer(),
                               "duplicate sensor alias \"" + sensor_alias + "\" on vehicle \"" + alias + "\"");
            }
            const std::size_t before = errors_.count();
            // IMUs and colour cameras are kept apart from the range sensors.
            const JsonNode type_node = sr.required("type");
            const std::string type = type_node.value().is_string() ? type_node.as_string() : std::string();
            if (type == "imu" || type == "rgb_camera") {
              read_other_sensor(s, type, sensor_alias, vehicle);
              return;
            }
            SensorDef sensor = read_sensor(s, limits_, &errors_);
            if (errors_.count() > before) return;
            // 0 = world.sensor_rate_hz, checked with the world.
            const double rate_hz = sensor.range.rate_hz;
            if (rate_hz > 0.0) check_rate(*sr.optional("rate_hz"), rate_hz, scene_.world.physics_step_s);
            vehicle.sensors.push_back(std::move(sensor));
          });
        }
      });
    }
    vehicle.planner.params = {nlohmann::json::object(), r.node().file(),
                              child_pointer(child_pointer(r.node().pointer(), "planner"), "params")};
    bool planner_read = true;
    if (auto planner = r.optional("planner")) {
      const std::size_t before = errors_.count();
      r.check([&] {
        ObjectReader p(*planner, r.errors());
        p.check([&] {
          const JsonNode name = p.required("name");
          vehicle.planner.name = name.as_string();
          vehicle.planner.name_pointer = name.pointer();
        });
        if (auto params = p.optional("params")) p.check([&] { vehicle.planner.params = read_params_block(*params); });
        p.finish();
      });
      planner_read = errors_.count() == before;
    }
    // The planner's and the vehicle's parameters, checked here (by planners/ and vehicles/) when
    // their blocks read well, so that their errors come with this object's others.
    if (planner_read && checks_.planner) r.check([&] { checks_.planner(vehicle); });
    vehicle.params = {nlohmann::json::object(), r.node().file(), child_pointer(r.node().pointer(), "params")};
    bool params_read = true;
    if (auto params = r.optional("params")) {
      params_read = r.check([&] { vehicle.params = read_params_block(*params); });
    }
    if (params_read && checks_.vehicle_params) r.check([&] { checks_.vehicle_params(vehicle); });
    if (auto noise = r.optional("state_noise")) {
      r.check([&] {
        ObjectReader n(*noise, r.errors());
        state_noise_fields().read_fields(n, vehicle.state_noise);
        n.finish();
      });
    }
    const auto mission = r.optional("mission");
    if (!r.ok()) return;
    if (mission) pending_missions_.emplace_back(scene_.vehicles.size(), *mission);
    scene_.vehicles.push_back(std::move(vehicle));
  }

  static ParamsBlock read_params_block(const JsonNode& node) {
    if (!node.value().is_object()) node.fail("an object");
    return {node.value(), node.file(), node.pointer()};
  }

  // The waypoints; `area` becomes the extent of the mission's grid, if any.
  std::vector<Waypoint> read_mission(const JsonNode& node, std::optional<Eigen::AlignedBox2d>& area,
                                     std::vector<MissionGate>& gates) {
    ObjectReader r(node, &errors_);
    const GridObstaclesConfig* grid = nullptr;
    if (auto g = r.optional("grid")) {
      const std::string name = g->as_string();
      const auto it = grids_.find(name);
      if (it == grids_.end() && failed_aliases_.contains(name)) {
        // Reported where the grid is; the mission, which depends on it, is not checked.
        g->fail("a grid_obstacles object without errors (\"" + name + "\" has errors, reported with these)");
      }
      if (it == grids_.end()) g->fail("the alias of a grid_obstacles object");
      grid = &it->second;
      area = Eigen::AlignedBox2d(grid->origin_m, grid->origin_m + grid->cell_size_m * Eigen::Vector2d(grid->cols, grid->rows));
    }
    std::vector<Waypoint> waypoints;
    r.check([&] {
      for (const JsonNode& wp :
           r.required("waypoints").as_array(1, static_cast<std::size_t>(limits_.max_waypoints))) {
        r.check([&] { waypoints.push_back(read_waypoint(wp, grid)); });  // each waypoint on its own
      }
    });
    if (auto list = r.optional("gates")) {
      r.check([&] {
        if (!grid) list->fail("a mission with \"grid\" naming a grid_obstacles object");
        for (const JsonNode& gate : list->as_array(1, 16)) {
          r.check([&] { gates.push_back(read_gate(gate, *grid, gates)); });
        }
      });
    }
    r.finish();
    return waypoints;
  }

  // A gate: a named block of cells of the mission's grid, optionally only
  // below a height above ground.
  MissionGate read_gate(const JsonNode& node, const GridObstaclesConfig& grid, const std::vector<MissionGate>& before) {
    ObjectReader r(node);
    MissionGate gate;
    const JsonNode name = r.required("name");
    gate.name = name.as_string();
    const bool valid = !gate.name.empty() && gate.name.size() <= 32 && std::islower(static_cast<unsigned char>(gate.name[0])) &&
                       std::all_of(gate.name.begin(), gate.name.end(), [](char c) {
                         return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_';
                       });
    if (!valid) name.fail("a name of lower-case letters, digits and '_', starting with a letter (up to 32)");
    for (const MissionGate& other : before) {
      if (other.name == gate.name) name.fail("a gate name not used before in this mission");
    }
    const auto range = [&](std::string_view key, int count) {
      const JsonNode node = r.required(key);
      const auto items = node.as_array(2, 2);
      const int lo = static_cast<int>(items[0].as_int(1, count));
      const int hi = static_cast<int>(items[1].as_int(lo, count));
      return std::pair{lo, hi};
    };
    const auto [row_lo, row_hi] = range("rows", grid.rows);
    const auto [col_lo, col_hi] = range("cols", grid.cols);
    const double c = grid.cell_size_m;
    gate.area_m = Eigen::AlignedBox2d(grid.origin_m + c * Eigen::Vector2d(col_lo - 1, row_lo - 1),
                                      grid.origin_m + c * Eigen::Vector2d(col_hi, row_hi));
    if (auto agl = r.optional("max_agl_m")) gate.max_agl_m = agl->as_number(Range::closed(-1e4, 1e5));
    r.finish();
    return gate;
  }

  // A waypoint is exactly one of: position_m [x,y,z] | [x,y] with agl_m,
  // frame (dummy alias), geodetic [lat, lon, alt] | [lat, lon] with agl_m,
  // cell [row, col] with agl_m.
  Waypoint read_waypoint(const JsonNode& node, const GridObstaclesConfig* grid) {
    ObjectReader r(node);
    Waypoint wp;
    const auto position = r.optional("position_m");
    const auto frame = r.optional("frame");
    const auto geodetic = r.optional("geodetic");
    const auto cell = r.optional("cell");
    const auto agl = r.optional("agl_m");
    if (static_cast<int>(position.has_value()) + frame.has_value() + geodetic.has_value() +
            cell.has_value() != 1) {
      r.fail("a waypoint with exactly one of \"position_m\", \"frame\", \"geodetic\", \"cell\"");
    }
    Eigen::Vector2d xy;
    if (position) {
      const auto items = position->as_array(2, 3);
      if (items.size() == 3 && agl) agl->fail("no \"agl_m\" with a 3D position_m");
      if (items.size() == 2 && !agl) position->fail("[x, y, z], or [x, y] with \"agl_m\"");
      const Range coordinate = Range::closed(-1e6, 1e6);
      wp.position_m = {items[0].as_number(coordinate), items[1].as_number(coordinate),
                       items.size() == 3 ? items[2].as_number(coordinate) : 0.0};
      xy = wp.position_m.head<2>();
    } else if (frame) {
      const std::string name = frame->as_string();
      const Frame* f = scene_.find_frame(name);
      if (!f && failed_aliases_.contains(name)) {
        frame->fail("a dummy object without errors (\"" + name + "\" has errors, reported with these)");
      }
      if (!f) frame->fail("the alias of a dummy object");
      wp.position_m = f->pose.translation();
      xy = wp.position_m.head<2>();
    } else if (geodetic) {
      const auto g = geodetic->as_array(2, 3);
      if (g.size() == 3 && agl) agl->fail("no \"agl_m\" with a geodetic [lat, lon, alt]");
      if (g.size() == 2 && !agl) geodetic->fail("[lat, lon, alt], or [lat, lon] with \"agl_m\"");
      wp.position_m = geodetic_to_local(scene_.world.geo_reference, g[0].as_number(Range::closed(-90.0, 90.0)),
                                        g[1].as_number(Range::closed(-180.0, 180.0)),
                                        g.size() == 3 ? g[2].as_number(Range::closed(-1e4, 1e5)) : 0.0);
      xy = wp.position_m.head<2>();
    } else {
      if (!grid) cell->fail("a mission with \"grid\" naming a grid_obstacles object");
      const auto rc = cell->as_array(2, 2);
      xy = grid_cell_center(*grid, static_cast<int>(rc[0].as_int(1, grid->rows)),
                            static_cast<int>(rc[1].as_int(1, grid->cols)));
      if (!agl) cell->fail("a cell waypoint with \"agl_m\"");
      wp.position_m.head<2>() = xy;
    }
    if (agl) {
      if (frame) agl->fail("no \"agl_m\" with a frame waypoint");
      const auto ground = scene_.ground_height(xy.x(), xy.y());
      if (!ground) {
        throw InputError(agl->file(), agl->pointer(), "expected a waypoint above terrain: " + no_ground_reason(xy.x(), xy.y()));
      }
      wp.position_m.z() = *ground + agl->as_number(Range::closed(-1e4, 1e5));
    }
    if (auto heading = r.optional("heading_deg")) {
      wp.heading_deg = heading->as_number(Range::closed(-360.0, 360.0));
    }
    r.finish();
    return wp;
  }

  const SceneLimits& limits_;
  std::filesystem::path base_dir_;
  const SceneChecks& checks_;
  Scene scene_;
  std::map<std::string, std::string> alias_pointers_;
  std::map<std::string, GridObstaclesConfig> grids_;
  // The world's geo_reference: given by the scene or filled by a DEM (read_dem), and which DEM filled it.
  bool geo_reference_given_ = false;
  std::string geo_reference_filled_by_;
  // ground(): shapes looked at so far, the non-level ground shapes among them, the highest level plane.
  std::size_t ground_scanned_ = 0;
  std::vector<std::size_t> ground_shapes_;
  std::optional<double> level_ground_m_;
  std::vector<std::pair<std::size_t, JsonNode>> pending_missions_;
  int object_count_ = 0;
  std::size_t mesh_triangles_ = 0;  // in the meshes read so far
  InputErrors errors_;
  std::set<std::string> failed_aliases_;  // objects with errors, not in the scene
  std::string failed_ground_;             // pointer of the first terrain with errors
};

}  // namespace

namespace {

// parse_sensor, going on past errors into `errors` if given.
SensorDef read_sensor(const JsonNode& node, const SceneLimits& limits, InputErrors* errors) {
  ObjectReader r(node, errors);
  SensorDef sensor;
  if (auto alias = r.optional("alias")) sensor.alias = alias->as_string();
  RangeSensorConfig& c = sensor.range;
  // The kind first: the fields' requirements depend on it.
  c.kind = r.required("type").as_choice({"lidar", "depth_camera"}) == 0 ? RangeSensorKind::lidar
                                                                        : RangeSensorKind::depth_camera;
  if (r.has("beams") && (r.has("fov_deg") || r.has("resolution"))) {
    r.fail("either \"beams\" or a grid (\"fov_deg\", \"resolution\"), not both");
  }
  range_sensor_config_fields(limits).read_fields(r, c);
  r.finish();
  return sensor;
}

}  // namespace

SensorDef parse_sensor(const JsonNode& node, const SceneLimits& limits) { return read_sensor(node, limits, nullptr); }

std::string sha256_hex(const std::string& bytes) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  EVP_Digest(bytes.data(), bytes.size(), digest.data(), &length, EVP_sha256(), nullptr);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < length; ++i) {
    out += kHex[digest[i] >> 4];
    out += kHex[digest[i] & 0xf];
  }
  return out;
}

Scene parse_scene(const nlohmann::json& document, const std::string& source,
                  const std::filesystem::path& base_dir, const std::string& source_sha256,
                  const SceneLimits& limits, const SceneChecks& checks) {
  Loader loader(limits, base_dir, checks);
  Scene scene;
  try {
    scene = loader.load(JsonNode(document, source, ""));
  } catch (const InputError& e) {
    // Beside each index pointer, the objects it goes through as the file names them.
    throw with_aliases(e, source, document);
  }
  if (scene.name.empty()) scene.name = std::filesystem::path(source).stem().string();
  scene.source_path = source;
  scene.source_sha256 = source_sha256;
  return scene;
}

Scene load_scene(const std::filesystem::path& path, const SceneLimits& limits) {
  return load_scene_text(read_text_file(path, limits.json), path, limits);
}

Scene load_scene_text(const std::string& text, const std::filesystem::path& path, const SceneLimits& limits,
                      const SceneChecks& checks) {
  const nlohmann::json document = parse_json_text(text, path.string(), limits.json);
  try {
    return parse_scene(document, path.string(), path.parent_path(), sha256_hex(text), limits, checks);
  } catch (const InputError& e) {
    throw with_locations(e, path.string(), text);  // each error's line and column in the file
  }
}

}  // namespace campo
