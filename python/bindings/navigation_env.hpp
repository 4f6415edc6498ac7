#pragma once
/// The task behind campo.gym's environments (docs/python.md, "Gymnasium
/// environments"): one vehicle of a scene flown or driven from normalised
/// actions toward its mission's waypoints, with a reward, termination and
/// truncation, and observations written as flat float32 arrays. Plain C++
/// (no Python): campo.gym's single environment steps one, its vector
/// environment many in worker threads with the interpreter released.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "campo/episode.hpp"
#include "campo/planner.hpp"
#include "campo/random.hpp"
#include "session/run_session.hpp"

namespace campo::gym {

/// How an action drives the vehicle. Every action is a float vector in
/// [-1, 1]^n (values outside are clipped), scaled to the vehicle's ranges.
enum class ActionMode {
  waypoint,         ///< both: go_to a point in the heading frame, action * waypoint_range_m (quadrotor x, y, z; rover x, y)
  velocity,         ///< quadrotor: heading-frame velocity * max_speed_mps and yaw rate * max_yaw_rate_radps
  attitude_thrust,  ///< quadrotor: roll, pitch * max_tilt_deg, yaw rate * max_yaw_rate_radps, thrust over [0, max]
  rotors,           ///< quadrotor: each rotor speed over [min, max] of the motor range
  twist,            ///< rover: forward speed * max_speed_mps, yaw rate * max_yaw_rate_radps
  wheels,           ///< rover: each wheel speed * max_wheel_speed_radps
};
std::string_view to_string(ActionMode mode);
/// The mode named `name`; std::invalid_argument listing the modes else.
ActionMode action_mode(std::string_view name);
/// The modes a vehicle type accepts, its default first.
std::vector<ActionMode> action_modes(VehicleType type);
/// Whether a mode drives the actuators or the attitude directly, so that it
/// acts at every control tick by default rather than at the sensor rate.
bool is_low_level(ActionMode mode);

/// The weights of the default reward, per step:
///   progress_weight * progress_m + goal_reward * reached
///   - collision_penalty * collided - time_penalty_per_s * dt_s.
struct RewardWeights {
  double progress_weight = 1.0;     ///< per metre of distance to the current waypoint gained
  double goal_reward = 10.0;        ///< once, when the last waypoint is reached
  double collision_penalty = 10.0;  ///< once, at the step that collides
  double time_penalty_per_s = 0.1;  ///< per simulated second
};

/// What happened in one step, from which rewards are made (a replacement
/// reward in Python receives these).
struct RewardTerms {
  double progress_m = 0.0;  ///< distance to the current waypoint at the start minus at the end of the step
  bool reached = false;     ///< the last waypoint was reached in this step
  bool collided = false;    ///< the vehicle touched something in this step
  double dt_s = 0.0;        ///< simulated time the step took
};
double reward(const RewardWeights& weights, const RewardTerms& terms);

/// Options of an environment; each keyword of campo.gym's constructors is a field.
struct NavigationOptions {
  std::string vehicle;  ///< alias of the vehicle driven; empty: the first, as campo run chooses
  ActionMode action_mode = ActionMode::waypoint;
  /// Control ticks one step lasts (the action held meanwhile); 0: one tick for
  /// the low-level modes, else the ticks of one sensor period, so that each
  /// step sees a fresh scan.
  int ticks_per_step = 0;
  double goal_radius_m = 1.0;       ///< a waypoint counts as reached within this distance, > 0
  double waypoint_range_m = 3.0;    ///< waypoint mode: reach of a full action, m
  double waypoint_speed_mps = 1.0;  ///< waypoint mode: go_to speed, > 0
  double max_speed_mps = 2.0;       ///< velocity (quadrotor) and twist (rover) modes: speed of a full action
  double max_yaw_rate_radps = 1.0;  ///< velocity, attitude_thrust, twist: yaw rate of a full action
  RewardWeights reward;
};

/// One sensor's part of an observation: a rows x cols float32 image of ranges, m.
struct SensorLayout {
  std::string key;  ///< "<alias>_ranges_m"
  int rows = 0;
  int cols = 0;
  double max_range_m = 0.0;
};

/// One colour camera's part of an observation: a rows x cols x 3 uint8 RGB image.
struct CameraLayout {
  std::string key;  ///< "<alias>_rgb"
  int rows = 0;
  int cols = 0;
};

/// One IMU's part of an observation: 6 float32, its latest sample in its own frame:
/// specific force x, y, z (m/s²), then angular rate x, y, z (rad/s); zeros before its first sample.
struct ImuLayout {
  std::string key;  ///< "<alias>_imu"
};

/// The shape of an observation: the state keys below, then one image per sensor.
inline constexpr std::array<std::pair<std::string_view, int>, 5> kStateKeys{{
    {"position_m", 3},                   // world frame
    {"orientation_wxyz", 4},             // body to world, unit quaternion
    {"velocity_body_mps", 3},            // linear velocity in the body frame
    {"angular_velocity_body_radps", 3},  // in the body frame
    {"goal_body_m", 3},                  // the current waypoint in the body frame
}};

/// Where one observation is written: a float32 array per key of kStateKeys,
/// then per sensor, each of its size; and the step's outputs.
struct ObservationBuffers {
  std::array<float*, kStateKeys.size()> state{};
  std::vector<float*> sensors;
  std::vector<std::uint8_t*> cameras;  ///< rows * cols * 3 bytes each, RGB, row 0 at the top
  std::vector<float*> imus;            ///< 6 floats each (ImuLayout)
};

struct StepOutcome {
  RewardTerms terms;
  double reward = 0.0;
  bool terminated = false;  ///< the goal reached, or the mission ended otherwise (collision, failure)
  bool truncated = false;   ///< the scene's time limit passed
  double time_s = 0.0;
  int waypoint = 0;                  ///< index of the current waypoint (the mission's size once reached)
  std::optional<Outcome> outcome;    ///< once the episode has ended
};

/// The scene's episode driven from actions. Not thread-safe; distinct
/// environments share nothing and may be stepped in different threads.
class NavigationEnv {
 public:
  /// Reads and checks the scene (a file or a bundled scene's name) with
  /// `overrides` applied to every episode; InputError for bad input.
  NavigationEnv(const std::string& scene, const std::vector<SceneOverride>& overrides, const NavigationOptions& options);
  ~NavigationEnv();
  NavigationEnv(NavigationEnv&&) noexcept;
  NavigationEnv& operator=(NavigationEnv&&) noexcept;

  const NavigationOptions& options() const { return options_; }
  VehicleType vehicle_type() const;
  const std::string& vehicle_alias() const;
  const std::vector<SensorLayout>& sensors() const { return sensors_; }
  const std::vector<CameraLayout>& cameras() const { return cameras_; }
  const std::vector<ImuLayout>& imus() const { return imus_; }
  int action_size() const;
  /// Physical meaning of each action component, for documentation and errors: "vx_mps", ...
  std::vector<std::string> action_names() const;
  /// Simulated seconds of one step.
  double step_s() const;

  /// Starts a new episode. A seed reseeds the environment's generator; each
  /// episode's world seed (sensor and state noise) is drawn from it. `overrides`
  /// apply to this episode only, after the environment's.
  void reset(std::optional<std::uint64_t> seed, const std::vector<SceneOverride>& overrides = {});
  /// Applies `action` (action_size() values) for one step; not once ended.
  StepOutcome step(const float* action);
  bool done() const;
  void write_observation(const ObservationBuffers& out) const;

  /// The episode's truth for rendering: the scene, the trajectory so far and the vehicle's pose.
  const Scene& scene() const;
  const std::vector<Eigen::Vector3d>& trajectory_m() const { return trajectory_m_; }
  Eigen::Isometry3d vehicle_pose() const;
  const Episode& episode() const;

 private:
  Command command_of(const float* action) const;
  /// One control tick: the driven vehicle's decision, the others' planners' (a planner that raises, or
  /// commands what its vehicle cannot follow, ends that vehicle's mission as failed, as in run_episode).
  void advance(PlanResult driven);
  double distance_to_waypoint() const;

  RunRequest request_;
  NavigationOptions options_;
  PreparedRun prepared_;          // the environment's scene, overrides applied
  std::optional<PreparedRun> episode_scene_;  // this episode's, when reset() was given overrides
  std::size_t vehicle_index_ = 0;
  std::vector<SensorLayout> sensors_;
  std::vector<CameraLayout> cameras_;
  std::vector<ImuLayout> imus_;
  int ticks_per_step_ = 1;
  Rng rng_{0};
  std::optional<Episode> episode_;
  std::vector<std::unique_ptr<Planner>> planners_;  // the other vehicles', null for the driven one
  std::size_t waypoint_ = 0;
  std::vector<Eigen::Vector3d> trajectory_m_;
  // Vehicle limits the actions scale to.
  std::array<double, 2> rotor_range_radps_{};
  double max_thrust_n_ = 0.0;
  double max_tilt_rad_ = 0.0;
  double max_wheel_speed_radps_ = 0.0;
};

}  // namespace campo::gym
