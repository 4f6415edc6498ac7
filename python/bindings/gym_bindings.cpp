// campo._campo's half of campo.gym (docs/python.md, "Gymnasium environments"):
// one NavigationEnv stepped from Python, and a batch of them stepped in C++
// worker threads with the interpreter released, writing straight into the
// batched numpy arrays a vector environment returns.
#include "python/bindings/gym_bindings.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/bindings/navigation_env.hpp"
#include "python/bindings/python_planner.hpp"
#include "python/bindings/worker_pool.hpp"
#include "render/snapshot.hpp"
#include "render/video_encoder.hpp"
#include "scene/scene_mesh.hpp"
#include "scene/scene_overrides.hpp"

namespace campo::python {

namespace py = pybind11;
using gym::NavigationEnv;
using gym::NavigationOptions;
using gym::ObservationBuffers;
using gym::StepOutcome;

namespace {

using FloatArray = py::array_t<float, py::array::c_style>;
using ByteArray = py::array_t<std::uint8_t, py::array::c_style>;

// An override's value as JSON; numpy's scalars and arrays (a seed drawn by np.random) as the numbers and lists they hold.
nlohmann::json override_value(const py::handle& value) {
  const py::cpp_function numpy_values([](const py::handle& o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error("an override's value must be JSON: numbers, strings, booleans, lists or dicts, got " +
                         py::repr(o).cast<std::string>());
  });
  const std::string text = py::module_::import("json")
                               .attr("dumps")(value, py::arg("allow_nan") = false, py::arg("default") = numpy_values)
                               .cast<std::string>();
  return nlohmann::json::parse(text);
}

std::vector<SceneOverride> overrides_of(const py::handle& overrides, const std::string& name) {
  std::vector<SceneOverride> list;
  if (overrides.is_none()) return list;
  if (!py::isinstance<py::dict>(overrides)) {
    throw InputError(name, "", "a dict {JSON pointer: value}, e.g. {\"/world/time_limit_s\": 60}");
  }
  for (const auto& item : overrides.cast<py::dict>()) {
    list.push_back(make_override(py::str(item.first).cast<std::string>(), override_value(item.second)));
  }
  return list;
}

// The keyword arguments of campo.gym's environments, as NavigationOptions.
NavigationOptions options_of(const py::dict& kwargs) {
  NavigationOptions o;
  for (const auto& item : kwargs) {
    const std::string key = py::str(item.first).cast<std::string>();
    const py::handle value = item.second;
    auto number = [&]() {
      if ((!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value)) ||
          !std::isfinite(value.cast<double>())) {
        throw InputError(key, "", "a finite number, got " + py::repr(value).cast<std::string>());
      }
      return value.cast<double>();
    };
    if (key == "vehicle") o.vehicle = value.cast<std::string>();
    else if (key == "action_mode") {
      try {
        o.action_mode = gym::action_mode(value.cast<std::string>());
      } catch (const std::invalid_argument& e) {
        throw InputError("action_mode", "", e.what());
      }
    } else if (key == "ticks_per_step") o.ticks_per_step = value.cast<int>();
    else if (key == "goal_radius_m") o.goal_radius_m = number();
    else if (key == "waypoint_range_m") o.waypoint_range_m = number();
    else if (key == "waypoint_speed_mps") o.waypoint_speed_mps = number();
    else if (key == "max_speed_mps") o.max_speed_mps = number();
    else if (key == "max_yaw_rate_radps") o.max_yaw_rate_radps = number();
    else if (key == "progress_weight") o.reward.progress_weight = number();
    else if (key == "goal_reward") o.reward.goal_reward = number();
    else if (key == "collision_penalty") o.reward.collision_penalty = number();
    else if (key == "time_penalty_per_s") o.reward.time_penalty_per_s = number();
    else throw InputError(key, "", "an option of campo.gym's environments (docs/python.md)");
  }
  return o;
}

// The arrays of one observation, or of a batch of `batch` (0: one, no leading dimension).
class ObservationArrays {
 public:
  ObservationArrays(const NavigationEnv& env, std::size_t batch) : batch_(batch) {
    auto add = [&](const std::string& key, std::vector<py::ssize_t> shape) {
      if (batch > 0) shape.insert(shape.begin(), static_cast<py::ssize_t>(batch));
      keys_.push_back(key);
      arrays_.emplace_back(shape);
    };
    for (const auto& [key, size] : gym::kStateKeys) add(std::string(key), {size});
    for (const gym::SensorLayout& s : env.sensors()) add(s.key, {s.rows, s.cols});
    for (const gym::CameraLayout& c : env.cameras()) {
      std::vector<py::ssize_t> shape{c.rows, c.cols, 3};
      if (batch > 0) shape.insert(shape.begin(), static_cast<py::ssize_t>(batch));
      camera_keys_.push_back(c.key);
      camera_arrays_.emplace_back(shape);
    }
    for (const gym::ImuLayout& imu : env.imus()) {
      std::vector<py::ssize_t> shape{6};
      if (batch > 0) shape.insert(shape.begin(), static_cast<py::ssize_t>(batch));
      imu_keys_.push_back(imu.key);
      imu_arrays_.emplace_back(shape);
    }
  }

  // Where observation `i` of the batch goes (i = 0 without a batch). Taken with the interpreter held.
  ObservationBuffers buffers(std::size_t i) {
    ObservationBuffers b;
    for (std::size_t k = 0; k < arrays_.size(); ++k) {
      const std::size_t per = static_cast<std::size_t>(arrays_[k].size()) / std::max<std::size_t>(1, batch_);
      float* base = arrays_[k].mutable_data() + i * per;
      if (k < gym::kStateKeys.size()) b.state[k] = base;
      else b.sensors.push_back(base);
    }
    for (ByteArray& images : camera_arrays_) {
      const std::size_t per = static_cast<std::size_t>(images.size()) / std::max<std::size_t>(1, batch_);
      b.cameras.push_back(images.mutable_data() + i * per);
    }
    for (FloatArray& samples : imu_arrays_) b.imus.push_back(samples.mutable_data() + i * 6);
    return b;
  }

  py::dict dict() const {
    py::dict d;
    for (std::size_t k = 0; k < arrays_.size(); ++k) d[py::str(keys_[k])] = arrays_[k];
    for (std::size_t k = 0; k < camera_arrays_.size(); ++k) d[py::str(camera_keys_[k])] = camera_arrays_[k];
    for (std::size_t k = 0; k < imu_arrays_.size(); ++k) d[py::str(imu_keys_[k])] = imu_arrays_[k];
    return d;
  }

 private:
  std::size_t batch_;
  std::vector<FloatArray> arrays_;  // kStateKeys, then the sensors
  std::vector<std::string> keys_;
  std::vector<ByteArray> camera_arrays_;  // one RGB image per colour camera
  std::vector<std::string> camera_keys_;
  std::vector<FloatArray> imu_arrays_;  // 6 floats per IMU (gym::ImuLayout)
  std::vector<std::string> imu_keys_;
};

py::dict info_of(const StepOutcome& s) {
  py::dict info;
  info["progress_m"] = s.terms.progress_m;
  info["reached"] = s.terms.reached;
  info["collided"] = s.terms.collided;
  info["dt_s"] = s.terms.dt_s;
  info["time_s"] = s.time_s;
  info["waypoint"] = s.waypoint;
  info["outcome"] = s.outcome ? py::object(py::str(std::string(to_string(*s.outcome)))) : py::none();
  return info;
}

const float* action_data(const FloatArray& action, std::size_t rows, int size) {
  const bool shaped = rows == 0 ? action.ndim() == 1 && action.shape(0) == size
                                : action.ndim() == 2 && static_cast<std::size_t>(action.shape(0)) == rows &&
                                      action.shape(1) == size;
  if (!shaped) {
    throw std::invalid_argument("action: expected shape " +
                                (rows == 0 ? "(" + std::to_string(size) + ",)"
                                           : "(" + std::to_string(rows) + ", " + std::to_string(size) + ")"));
  }
  return action.data();
}

// One environment as campo.gym.NavigationEnv steps it.
class SingleEnv {
 public:
  SingleEnv(const std::string& scene, const py::object& overrides, const py::kwargs& kwargs)
      : env_(scene, overrides_of(overrides, "overrides"), options_of(kwargs)) {}

  py::dict reset(std::optional<std::uint64_t> seed, const py::object& overrides) {
    const std::vector<SceneOverride> list = overrides_of(overrides, "options[\"overrides\"]");
    {
      py::gil_scoped_release release;
      env_.reset(seed, list);
    }
    mesh_.reset();
    return observation();
  }

  py::tuple step(const FloatArray& action) {
    const float* data = action_data(action, 0, env_.action_size());
    StepOutcome s;
    {
      py::gil_scoped_release release;
      s = env_.step(data);
    }
    return py::make_tuple(observation(), s.reward, s.terminated, s.truncated, info_of(s));
  }

  py::dict observation() const {
    ObservationArrays arrays(env_, 0);
    env_.write_observation(arrays.buffers(0));
    return arrays.dict();
  }

  // An RGB frame of the scene, the track so far and the vehicle: from behind and above it ("chase"), or
  // straight down from `height_m` above it, its heading up the frame ("above", for forests whose crowns
  // hide the vehicle from behind).
  py::array_t<std::uint8_t> render(int width_px, int height_px, const std::string& view, double distance_m) {
    if (view != "chase" && view != "above") throw InputError("render_camera", "", "\"chase\" or \"above\"");
    if (!(distance_m > 0.0)) throw InputError("render_distance_m", "", "a distance > 0");
    const Scene& scene = env_.scene();
    cv::Mat bgr;
    {
      py::gil_scoped_release release;
      if (!mesh_) mesh_ = std::make_shared<SceneMesh>(build_scene_mesh(scene));
      const Eigen::Isometry3d pose = env_.vehicle_pose();
      const Eigen::Vector3d heading(pose.linear()(0, 0), pose.linear()(1, 0), 0.0);
      const Eigen::Vector3d forward = heading.norm() > 1e-6 ? Eigen::Vector3d(heading.normalized()) : Eigen::Vector3d::UnitX();
      SnapshotCamera camera;
      camera.target_m = pose.translation();
      if (view == "chase") {
        camera.eye_m = pose.translation() - distance_m * forward + Eigen::Vector3d(0.0, 0.0, 0.5 * distance_m);
      } else {
        camera.eye_m = pose.translation() + Eigen::Vector3d(0.0, 0.0, distance_m);
        camera.up = forward;
      }
      camera.width_px = width_px;
      camera.height_px = height_px;
      bgr = render_snapshot(scene, *mesh_, camera, env_.trajectory_m(), pose, env_.vehicle_type());
    }
    py::array_t<std::uint8_t> rgb({bgr.rows, bgr.cols, 3});
    cv::Mat out(bgr.rows, bgr.cols, CV_8UC3, rgb.mutable_data());
    cv::cvtColor(bgr, out, cv::COLOR_BGR2RGB);
    return rgb;
  }

  const NavigationEnv& env() const { return env_; }

 private:
  NavigationEnv env_;
  std::shared_ptr<SceneMesh> mesh_;  // of the current episode's scene, built at the first render
};

// N environments stepped together in worker threads (campo.gym.NavigationVectorEnv).
// Autoreset as Gymnasium's next-step mode: the step after one that ended resets
// that environment instead, its action ignored, reward 0, neither flag set. With
// autoreset off (Gymnasium's disabled mode) an ended environment idles until
// reset() names it in its mask: not stepped, its last observation, reward 0.
class BatchEnv {
 public:
  BatchEnv(const std::string& scene, std::size_t count, int threads, bool autoreset, const py::object& overrides,
           const py::kwargs& kwargs)
      : autoreset_(autoreset),
        pool_(threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))) {
    if (count == 0) throw InputError("num_envs", "", "a number of environments >= 1");
    const std::vector<SceneOverride> list = overrides_of(overrides, "overrides");
    const NavigationOptions options = options_of(kwargs);
    envs_.reserve(count);
    for (std::size_t i = 0; i < count; ++i) envs_.emplace_back(scene, list, options);
    ended_.assign(count, 0);
  }

  // Resets the environments `mask` names (every one without a mask), environment i with seeds[i] and
  // overrides[i] (None, a dict for every environment, or a list of one per environment).
  py::tuple reset(const std::vector<std::optional<std::uint64_t>>& seeds, const py::object& overrides,
                  const std::optional<std::vector<bool>>& mask) {
    const std::size_t n = envs_.size();
    if (seeds.size() != n) throw std::invalid_argument("reset: one seed (or None) per environment");
    if (mask && mask->size() != n) throw std::invalid_argument("reset: options[\"reset_mask\"] has one flag per environment");
    std::vector<std::vector<SceneOverride>> lists(n);
    if (py::isinstance<py::list>(overrides) || py::isinstance<py::tuple>(overrides)) {
      const py::sequence each = overrides.cast<py::sequence>();
      if (each.size() != n) throw InputError("options[\"overrides\"]", "", "one dict (or None) per environment");
      for (std::size_t i = 0; i < n; ++i) {
        lists[i] = overrides_of(each[i], "options[\"overrides\"][" + std::to_string(i) + "]");
      }
    } else {
      const std::vector<SceneOverride> list = overrides_of(overrides, "options[\"overrides\"]");
      std::fill(lists.begin(), lists.end(), list);
    }
    ObservationArrays arrays(envs_.front(), n);
    std::vector<ObservationBuffers> buffers;
    for (std::size_t i = 0; i < n; ++i) buffers.push_back(arrays.buffers(i));
    {
      py::gil_scoped_release release;
      pool_.run(n, [&](std::size_t i) {
        if (!mask || (*mask)[i]) {
          envs_[i].reset(seeds[i], lists[i]);
          ended_[i] = 0;
        }
        envs_[i].write_observation(buffers[i]);
      });
    }
    return py::make_tuple(arrays.dict(), py::dict());
  }

  py::tuple step(const FloatArray& actions) {
    const std::size_t n = envs_.size();
    const int size = envs_.front().action_size();
    const float* data = action_data(actions, n, size);
    ObservationArrays arrays(envs_.front(), n);
    std::vector<ObservationBuffers> buffers;
    for (std::size_t i = 0; i < n; ++i) buffers.push_back(arrays.buffers(i));
    std::vector<StepOutcome> outcomes(n);
    std::vector<std::uint8_t> stepped_now(n, 0);  // bytes, not vector<bool>: the workers write them at once
    {
      py::gil_scoped_release release;
      pool_.run(n, [&](std::size_t i) {
        if (!ended_[i]) {
          outcomes[i] = envs_[i].step(data + i * static_cast<std::size_t>(size));
          stepped_now[i] = 1;
        } else if (autoreset_) {
          envs_[i].reset(std::nullopt);
          ended_[i] = 0;
        }
        envs_[i].write_observation(buffers[i]);
      });
    }
    py::array_t<double> rewards(static_cast<py::ssize_t>(n));
    py::array_t<bool> terminated(static_cast<py::ssize_t>(n));
    py::array_t<bool> truncated(static_cast<py::ssize_t>(n));
    py::array_t<double> progress(static_cast<py::ssize_t>(n)), dt(static_cast<py::ssize_t>(n)),
        time(static_cast<py::ssize_t>(n));
    py::array_t<bool> reached(static_cast<py::ssize_t>(n)), collided(static_cast<py::ssize_t>(n)),
        stepped(static_cast<py::ssize_t>(n)), ended(static_cast<py::ssize_t>(n));
    py::array_t<std::int64_t> waypoint(static_cast<py::ssize_t>(n));
    py::list outcome;
    for (std::size_t i = 0; i < n; ++i) {
      const StepOutcome& s = outcomes[i];
      const auto k = static_cast<py::ssize_t>(i);
      rewards.mutable_at(k) = s.reward;
      terminated.mutable_at(k) = s.terminated;
      truncated.mutable_at(k) = s.truncated;
      progress.mutable_at(k) = s.terms.progress_m;
      reached.mutable_at(k) = s.terms.reached;
      collided.mutable_at(k) = s.terms.collided;
      dt.mutable_at(k) = s.terms.dt_s;
      time.mutable_at(k) = stepped_now[i] ? s.time_s : envs_[i].episode().world().time_s();
      waypoint.mutable_at(k) = s.waypoint;
      stepped.mutable_at(k) = stepped_now[i] != 0;
      ended.mutable_at(k) = s.outcome.has_value();
      outcome.append(s.outcome ? py::object(py::str(std::string(to_string(*s.outcome)))) : py::none());
      if (stepped_now[i]) ended_[i] = s.terminated || s.truncated;
    }
    py::dict info;
    for (const auto& [key, array] : {std::pair<const char*, py::object>{"progress_m", progress}, {"reached", reached},
                                     {"collided", collided}, {"dt_s", dt}, {"time_s", time}, {"waypoint", waypoint}}) {
      info[key] = array;
      info[py::str(std::string("_") + key)] = stepped;
    }
    info["outcome"] = py::module_::import("numpy").attr("array")(outcome, "object");
    info["_outcome"] = ended;
    return py::make_tuple(arrays.dict(), rewards, terminated, truncated, info);
  }

  const NavigationEnv& first() const { return envs_.front(); }
  std::size_t size() const { return envs_.size(); }
  int threads() const { return pool_.threads(); }

 private:
  std::vector<NavigationEnv> envs_;
  std::vector<std::uint8_t> ended_;  // ended and not reset since (bytes: the workers write them at once)
  bool autoreset_;
  WorkerPool pool_;
};

// What both kinds tell campo.gym to build their spaces.
template <class Class>
void describe(py::class_<Class>& c, const NavigationEnv& (*env)(const Class&)) {
  c.def_property_readonly("vehicle_type", [env](const Class& self) { return std::string(to_string(env(self).vehicle_type())); })
      .def_property_readonly("vehicle", [env](const Class& self) { return env(self).vehicle_alias(); })
      .def_property_readonly("action_mode",
                             [env](const Class& self) { return std::string(gym::to_string(env(self).options().action_mode)); })
      .def_property_readonly("action_names", [env](const Class& self) { return env(self).action_names(); })
      .def_property_readonly("step_s", [env](const Class& self) { return env(self).step_s(); })
      .def_property_readonly("state_keys", [](const Class&) {
        std::vector<std::pair<std::string, int>> keys;
        for (const auto& [key, size] : gym::kStateKeys) keys.emplace_back(std::string(key), size);
        return keys;
      })
      .def_property_readonly("sensors", [env](const Class& self) {
        std::vector<std::tuple<std::string, int, int, double>> list;
        for (const gym::SensorLayout& s : env(self).sensors()) list.emplace_back(s.key, s.rows, s.cols, s.max_range_m);
        return list;
      })
      .def_property_readonly("imus", [env](const Class& self) {
        std::vector<std::string> keys;
        for (const gym::ImuLayout& imu : env(self).imus()) keys.push_back(imu.key);
        return keys;
      })
      .def_property_readonly("cameras", [env](const Class& self) {
        std::vector<std::tuple<std::string, int, int>> list;
        for (const gym::CameraLayout& c : env(self).cameras()) list.emplace_back(c.key, c.rows, c.cols);
        return list;
      })
      .def_property_readonly("reward_weights", [env](const Class& self) {
        const gym::RewardWeights& w = env(self).options().reward;
        py::dict d;
        d["progress_weight"] = w.progress_weight;
        d["goal_reward"] = w.goal_reward;
        d["collision_penalty"] = w.collision_penalty;
        d["time_penalty_per_s"] = w.time_penalty_per_s;
        return d;
      });
}

// Frames (H x W x 3 uint8 RGB, all one size) into an MP4 or GIF (campo.gym.save_video).
void save_video(const std::vector<py::array_t<std::uint8_t, py::array::c_style>>& frames,
                const std::filesystem::path& out, double fps) {
  if (frames.empty()) throw std::invalid_argument("save_video: no frames");
  const std::optional<VideoFormat> format = video_format_of(out);
  if (!format) throw InputError("path", "", "a file ending in .mp4 or .gif, got " + out.string());
  if (!(fps > 0.0)) throw InputError("fps", "", "frames per second > 0");
  const auto& first = frames.front();
  if (first.ndim() != 3 || first.shape(2) != 3) throw std::invalid_argument("save_video: frames of shape (H, W, 3)");
  // The encoder takes even sides: an odd last row or column is dropped.
  const cv::Size size(static_cast<int>(first.shape(1)) & ~1, static_cast<int>(first.shape(0)) & ~1);
  VideoEncoder encoder(out, *format, size, fps);
  cv::Mat bgr;
  for (const auto& frame : frames) {
    if (frame.ndim() != 3 || frame.shape(0) != first.shape(0) || frame.shape(1) != first.shape(1) || frame.shape(2) != 3) {
      throw std::invalid_argument("save_video: every frame of the first one's shape");
    }
    const cv::Mat rgb(static_cast<int>(frame.shape(0)), static_cast<int>(frame.shape(1)), CV_8UC3,
                      const_cast<std::uint8_t*>(frame.data()));
    cv::cvtColor(rgb(cv::Rect(0, 0, size.width, size.height)), bgr, cv::COLOR_RGB2BGR);
    encoder.add(bgr);
  }
  encoder.finish();
}

}  // namespace

void bind_gym(py::module_& m) {
  py::class_<SingleEnv> single(m, "_NavigationEnv", "campo.gym.NavigationEnv's native half");
  single
      .def(py::init<const std::string&, const py::object&, const py::kwargs&>(), py::arg("scene"),
           py::arg("overrides") = py::none())
      .def("reset", &SingleEnv::reset, py::arg("seed") = py::none(), py::arg("overrides") = py::none())
      .def("step", &SingleEnv::step, py::arg("action"))
      .def("render", &SingleEnv::render, py::arg("width_px") = 640, py::arg("height_px") = 480,
           py::arg("camera") = "chase", py::arg("distance_m") = 6.0);
  describe<SingleEnv>(single, [](const SingleEnv& s) -> const NavigationEnv& { return s.env(); });

  py::class_<BatchEnv> batch(m, "_NavigationBatch", "campo.gym.NavigationVectorEnv's native half");
  batch
      .def(py::init<const std::string&, std::size_t, int, bool, const py::object&, const py::kwargs&>(),
           py::arg("scene"), py::arg("num_envs"), py::arg("num_threads") = 0, py::arg("autoreset") = true,
           py::arg("overrides") = py::none())
      .def("reset", &BatchEnv::reset, py::arg("seeds"), py::arg("overrides") = py::none(),
           py::arg("mask") = py::none())
      .def("step", &BatchEnv::step, py::arg("actions"))
      .def_property_readonly("num_envs", &BatchEnv::size)
      .def_property_readonly("num_threads", &BatchEnv::threads);
  describe<BatchEnv>(batch, [](const BatchEnv& b) -> const NavigationEnv& { return b.first(); });

  m.def("_save_video", &save_video, py::arg("frames"), py::arg("path"), py::arg("fps"));
}

}  // namespace campo::python
