#include "python/bindings/observation.hpp"

#include <cstdint>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "campo/pose.hpp"
#include "sensors/lidar.hpp"

namespace campo::python {

namespace py = pybind11;

namespace {

py::array_t<double> vector3(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  auto r = out.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < 3; ++i) r(i) = v[i];
  return out;
}

// The scan's shape as an image: rows x cols for a grid sensor, one row of beams otherwise.
std::pair<py::ssize_t, py::ssize_t> image_shape(const RangeScan& scan) {
  const auto beams = static_cast<py::ssize_t>(scan.ranges_m.size());
  if (scan.rows > 0 && scan.cols > 0 && static_cast<py::ssize_t>(scan.rows) * scan.cols == beams) {
    return {scan.rows, scan.cols};
  }
  return {1, beams};
}

// A read-only C-ordered array of `shape` over `data` without a copy; its base keeps `owner`
// (the owner of `data`) alive.
template <class T, class Owner>
py::array_t<T> shared_array(const std::shared_ptr<const Owner>& owner, const T* data, std::vector<py::ssize_t> shape) {
  auto* kept = new std::shared_ptr<const Owner>(owner);
  py::capsule base(kept, [](void* p) { delete static_cast<std::shared_ptr<const Owner>*>(p); });
  py::array_t<T> array(std::move(shape), data, base);
  // A view of the sensor's own buffer: writing to it would change what the next reader sees.
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

// A 2-D array over `data` (rows x cols) without a copy; it keeps `scan` (the owner of `data`) alive.
template <class T>
py::array_t<T> shared_view(const std::shared_ptr<const RangeScan>& scan, const T* data) {
  const auto [rows, cols] = image_shape(*scan);
  return shared_array(scan, data, {rows, cols});
}

const RangeScan& scan_of(const SensorView& s) {
  if (!s.scan) throw std::runtime_error("sensor \"" + s.alias + "\" has not scanned yet");
  return *s.scan;
}

}  // namespace

ObservationView view_of(const Observation& o, std::shared_ptr<const std::vector<Eigen::Vector3d>> mission_m) {
  ObservationView v;
  v.time_s = o.time_s;
  v.vehicle = o.vehicle;
  v.state = o.state;
  v.stable = o.stable;
  v.sensors.reserve(o.sensors.size());
  for (const SensorReading& r : o.sensors) {
    v.sensors.push_back({std::string(r.alias), r.scan, r.config ? r.config->min_range_m : 0.0,
                         r.config ? r.config->max_range_m : 0.0, r.fresh});
  }
  v.images.reserve(o.images.size());
  for (const ImageReading& r : o.images) v.images.push_back({std::string(r.alias), r.image, r.fresh});
  v.imus.reserve(o.imus.size());
  for (const ImuReading& r : o.imus) {
    v.imus.push_back({std::string(r.alias), r.time_s, r.specific_force_mps2, r.angular_rate_radps, r.valid, r.fresh});
  }
  v.mission_m = std::move(mission_m);
  return v;
}

std::shared_ptr<const std::vector<Eigen::Vector3d>> mission_positions(std::span<const Waypoint> mission) {
  auto positions = std::make_shared<std::vector<Eigen::Vector3d>>();
  for (const Waypoint& w : mission) positions->push_back(w.position_m);
  return positions;
}

void bind_observation(py::module_& m) {
  py::class_<VehicleState>(m, "State", "A vehicle's state, world frame (numpy arrays are copies).")
      .def_property_readonly("position_m", [](const VehicleState& s) { return vector3(s.position_m); })
      .def_property_readonly("velocity_mps", [](const VehicleState& s) { return vector3(s.linear_velocity_mps); })
      .def_property_readonly("angular_velocity_radps",
                             [](const VehicleState& s) { return vector3(s.angular_velocity_radps); })
      .def_property_readonly("rpy_deg",
                             [](const VehicleState& s) { return vector3(rpy_deg_from_rotation(s.orientation.toRotationMatrix())); })
      .def_property_readonly("yaw_rad", &VehicleState::yaw_rad, "heading of the body x axis, from +x (east), CCW")
      .def_property_readonly("orientation_xyzw",
                             [](const VehicleState& s) {
                               py::array_t<double> q(4);
                               auto r = q.mutable_unchecked<1>();
                               r(0) = s.orientation.x();
                               r(1) = s.orientation.y();
                               r(2) = s.orientation.z();
                               r(3) = s.orientation.w();
                               return q;
                             })
      .def("__repr__", [](const VehicleState& s) {
        return "State(position_m=[" + std::to_string(s.position_m.x()) + ", " + std::to_string(s.position_m.y()) +
               ", " + std::to_string(s.position_m.z()) + "])";
      });

  py::class_<SensorView>(m, "SensorReading",
                         "A sensor's latest scan. ranges_m and hits are read-only views of the sensor's buffer, "
                         "not copies: the sensor's next scan overwrites them (numpy.copy to keep one).")
      .def_readonly("alias", &SensorView::alias)
      .def_readonly("fresh", &SensorView::fresh, "taken since the previous observation")
      .def_property_readonly("time_s", [](const SensorView& s) { return scan_of(s).time_s; })
      .def_property_readonly("ranges_m",
                             [](const SensorView& s) {
                               scan_of(s);
                               return shared_view<float>(s.scan, s.scan->ranges_m.data());
                             },
                             "2-D float32 (rows x cols; one row for a list of beams), max range where no return")
      .def_property_readonly("hits",
                             [](const SensorView& s) {
                               scan_of(s);
                               return shared_view<std::uint8_t>(s.scan, s.scan->hits.data());
                             },
                             "2-D uint8, 1 where the beam hit something")
      .def_property_readonly("points_m",
                             [](const SensorView& s) {
                               const RangeScan& scan = scan_of(s);
                               py::array_t<float> out({static_cast<py::ssize_t>(scan.points.size()), py::ssize_t{3}});
                               auto r = out.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < scan.points.size(); ++i) {
                                 for (py::ssize_t j = 0; j < 3; ++j) r(static_cast<py::ssize_t>(i), j) = scan.points[i][j];
                               }
                               return out;
                             },
                             "N x 3 float32 world-frame hit points (hits only, beam order), a copy")
      .def_property_readonly("depth",
                             [](const SensorView& s) {
                               const RangeScan& scan = scan_of(s);
                               RangeSensorConfig config;
                               config.min_range_m = s.min_range_m;
                               config.max_range_m = s.max_range_m;
                               const cv::Mat depth = depth_map(scan, config);
                               const auto [rows, cols] = image_shape(scan);
                               py::array_t<float> out({rows, cols});
                               std::memcpy(out.mutable_data(), depth.ptr<float>(), sizeof(float) * rows * cols);
                               return out;
                             },
                             "the normalised depth map of SPEC §6 (range / max range in [0, 1], 0 below the "
                             "minimum range, 1 where nothing was hit), float32, a copy")
      .def_property_readonly("sensor_pose",
                             [](const SensorView& s) {
                               const Eigen::Matrix4d t = scan_of(s).sensor_pose.matrix();
                               py::array_t<double> out({4, 4});
                               auto r = out.mutable_unchecked<2>();
                               for (py::ssize_t i = 0; i < 4; ++i) {
                                 for (py::ssize_t j = 0; j < 4; ++j) r(i, j) = t(i, j);
                               }
                               return out;
                             },
                             "4 x 4 world-from-sensor transform of the scan");

  py::class_<ImuView>(m, "ImuReading",
                      "An IMU's latest sample, in the IMU's own frame (x forward, y left, z up as mounted); "
                      "numpy arrays are copies.")
      .def_readonly("alias", &ImuView::alias)
      .def_readonly("time_s", &ImuView::time_s, "when it was taken, s")
      .def_readonly("valid", &ImuView::valid, "false before the first sample")
      .def_readonly("fresh", &ImuView::fresh, "taken since the previous observation")
      .def_property_readonly("specific_force_mps2",
                             [](const ImuView& v) { return vector3(v.specific_force_mps2); },
                             "accelerometer, m/s²: acceleration minus gravity (+9.81 up at rest)")
      .def_property_readonly("angular_rate_radps", [](const ImuView& v) { return vector3(v.angular_rate_radps); },
                             "gyroscope, rad/s")
      .def("__repr__", [](const ImuView& v) {
        return "ImuReading(alias='" + v.alias + "', time_s=" + std::to_string(v.time_s) + ")";
      });

  py::class_<ObservationView>(m, "Observation", "What a planner sees at a control tick.")
      .def_readonly("time_s", &ObservationView::time_s)
      .def_readonly("state", &ObservationView::state, "as the planner is told it (estimated with state noise)")
      .def_readonly("stable", &ObservationView::stable, "speeds below the vehicle's thresholds")
      .def_property_readonly("vehicle", [](const ObservationView& o) { return std::string(to_string(o.vehicle)); })
      .def_property_readonly("sensors",
                             [](const ObservationView& o) {
                               py::dict sensors;
                               for (const SensorView& s : o.sensors) sensors[py::str(s.alias)] = py::cast(s);
                               return sensors;
                             },
                             "alias -> SensorReading")
      .def_property_readonly("images",
                             [](const ObservationView& o) {
                               py::dict images;
                               for (const ImageView& v : o.images) {
                                 if (!v.image) {
                                   images[py::str(v.alias)] = py::none();
                                   continue;
                                 }
                                 const RgbImage& image = *v.image;
                                 images[py::str(v.alias)] = shared_array(v.image, image.rgb.data(), {image.rows, image.cols, 3});
                               }
                               return images;
                             },
                             "alias -> the colour camera's latest image, a read-only uint8 array (rows, cols, 3) "
                             "of RGB, row 0 at the top: a view of the camera's buffer, not a copy (the camera's "
                             "next image overwrites it; numpy.copy to keep one); None before its first image")
      .def_property_readonly("imus",
                             [](const ObservationView& o) {
                               py::dict imus;
                               for (const ImuView& v : o.imus) imus[py::str(v.alias)] = py::cast(v);
                               return imus;
                             },
                             "alias -> ImuReading, the vehicle's IMUs in scene order")
      .def_property_readonly("mission_m",
                             [](const ObservationView& o) {
                               const std::vector<Eigen::Vector3d>& w = *o.mission_m;
                               py::array_t<double> out({static_cast<py::ssize_t>(w.size()), py::ssize_t{3}});
                               auto r = out.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < w.size(); ++i) {
                                 for (py::ssize_t j = 0; j < 3; ++j) r(static_cast<py::ssize_t>(i), j) = w[i][j];
                               }
                               return out;
                             },
                             "the mission's waypoints, N x 3, world frame");
}

}  // namespace campo::python
