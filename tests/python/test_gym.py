"""campo.gym against Gymnasium itself (its env checker and vector API) and against physics.

Gymnasium comes from the environment, else from CAMPO_GYMNASIUM_PATH (the unmodified copy vendored beside
the repository; tests/CMakeLists.txt finds it). Without either the tests are skipped with the reason,
unless CAMPO_REQUIRE_GYMNASIUM=1 (as .ci/run sets), where that is a failure.
"""

import math
import os
import pathlib
import subprocess
import sys
import tempfile
import threading
import unittest
import warnings

import numpy as np

import campo

FIXTURES = pathlib.Path(__file__).resolve().parent / "fixtures"
OPEN_FIELD = str(FIXTURES / "open_field.json")

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from gymnasium_support import GYMNASIUM_ERROR, REQUIRED, needs_gymnasium  # noqa: E402 (this folder, just above)

if GYMNASIUM_ERROR is None:
    import gymnasium
    from gymnasium.utils.env_checker import check_env

    import campo.gym


class GymnasiumPresent(unittest.TestCase):
    def test_gymnasium_imports_where_required(self):
        if GYMNASIUM_ERROR is None:
            return
        if REQUIRED:
            self.fail(GYMNASIUM_ERROR + " (CAMPO_REQUIRE_GYMNASIUM=1)")
        self.skipTest(GYMNASIUM_ERROR)

    def test_the_rest_of_campo_does_not_import_gymnasium(self):
        code = "import sys, campo; campo.Episode; assert 'gymnasium' not in sys.modules, 'imported'"
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
        subprocess.run([sys.executable, "-c", code], check=True, env=env)


def rollout(env, actions, seed):
    """Observations, rewards and flags of a run of `actions` from reset(seed); stops at the end."""
    obs, _ = env.reset(seed=seed)
    steps = [(obs, 0.0, False, False, {})]
    for a in actions:
        obs, reward, terminated, truncated, info = env.step(a)
        steps.append((obs, reward, terminated, truncated, info))
        if terminated or truncated:
            break
    return steps


def hover_rotor_action(mass_kg=1.5, g=9.81, k_f=1.0e-5, w_min=150.0, w_max=1000.0):
    """The rotors mode's action for the speed at which the four rotors carry the weight (the preset quadrotor)."""
    w_hover = math.sqrt(mass_kg * g / (4.0 * k_f))
    return 2.0 * (w_hover - w_min) / (w_max - w_min) - 1.0


@needs_gymnasium
class EnvironmentApi(unittest.TestCase):
    def test_check_env_passes_for_every_action_mode_of_both_vehicles(self):
        for env_id, vehicle in (("campo/Navigate-v0", "quadrotor"), ("campo/RoverNavigate-v0", "rover")):
            for mode in campo.gym.ACTION_MODES[vehicle]:
                with self.subTest(env_id=env_id, mode=mode):
                    env = gymnasium.make(env_id, action_mode=mode, render_mode="rgb_array",
                                         overrides=self.small_scans(vehicle))
                    with warnings.catch_warnings():
                        # Positions and velocities are unbounded: Gymnasium's advice about infinite bounds.
                        warnings.filterwarnings("ignore", message=".*infinity.*")
                        check_env(env.unwrapped, skip_render_check=False)
                    self.assertEqual(env.unwrapped.vehicle_type, vehicle)
                    env.close()

    @staticmethod
    def small_scans(vehicle):
        if vehicle == "quadrotor":
            return {"/objects/drone/sensors/0/resolution": [32, 16]}
        return None

    def test_observation_space_has_the_scenes_resolution_and_goal(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, overrides={"/objects/drone/sensors/0/resolution": [24, 10]})
        space = env.observation_space
        self.assertEqual(space["scanner_ranges_m"].shape, (10, 24))  # rows x cols
        obs, info = env.reset(seed=0)
        self.assertTrue(space.contains(obs))
        self.assertEqual(info, {})
        # The goal (6, 0, 1.5) seen from the start (0, 0, 1.5), heading +x: 6 m straight ahead.
        np.testing.assert_allclose(obs["goal_body_m"], [6.0, 0.0, 0.0], atol=0.05)
        np.testing.assert_allclose(obs["position_m"], [0.0, 0.0, 1.5], atol=0.05)
        np.testing.assert_allclose(np.linalg.norm(obs["orientation_wxyz"]), 1.0, atol=1e-5)

    def test_a_colour_camera_is_a_uint8_box_of_its_image(self):
        env = campo.gym.NavigationEnv(str(FIXTURES / "camera_field.json"))
        space = env.observation_space["front_rgb"]
        self.assertEqual(space.shape, (24, 32, 3))
        self.assertEqual(space.dtype, np.uint8)
        self.assertEqual((int(space.low.min()), int(space.high.max())), (0, 255))
        obs, _ = env.reset(seed=0)
        self.assertTrue(env.observation_space.contains(obs))
        self.assertEqual(obs["front_rgb"].dtype, np.uint8)
        # The observation is the camera's image: the sky's colour along the top row.
        np.testing.assert_array_equal(obs["front_rgb"][0, 16], [round(0.2 * 255), round(0.4 * 255), round(0.8 * 255)])
        obs, *_ = env.step(env.action_space.sample())
        self.assertTrue(env.observation_space.contains(obs))
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message=".*infinity.*")
            check_env(env)
        envs = campo.gym.NavigationVectorEnv(str(FIXTURES / "camera_field.json"), num_envs=2, num_threads=2)
        self.assertEqual(envs.single_observation_space["front_rgb"].shape, (24, 32, 3))
        obs, _ = envs.reset(seed=3)
        self.assertEqual(obs["front_rgb"].shape, (2, 24, 32, 3))
        np.testing.assert_array_equal(obs["front_rgb"][0], obs["front_rgb"][1])  # no noise: the same start
        envs.close()

    def test_reset_with_a_seed_reproduces_the_episode_and_seeds_differ(self):
        noisy = {"/objects/drone/sensors/0/noise_stddev_m": 0.05}
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity", overrides=noisy)
        actions = [np.array([0.3, 0.1, 0.0, 0.2], np.float32)] * 12
        a = rollout(env, actions, seed=7)
        b = rollout(env, actions, seed=7)
        c = rollout(env, actions, seed=8)
        for (oa, ra, *_), (ob, rb, *_) in zip(a, b):
            for key in oa:
                np.testing.assert_array_equal(oa[key], ob[key])
            self.assertEqual(ra, rb)
        self.assertFalse(np.array_equal(a[-1][0]["scanner_ranges_m"], c[-1][0]["scanner_ranges_m"]),
                         "another seed draws other range noise")

    def test_default_reward_is_the_documented_sum_of_its_terms(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity")
        obs, _ = env.reset(seed=0)
        for _ in range(20):
            before = np.linalg.norm(obs["goal_body_m"])
            obs, reward, terminated, truncated, info = env.step(np.array([0.4, 0.0, 0.0, 0.0], np.float32))
            after = np.linalg.norm(obs["goal_body_m"])
            expected = info["progress_m"] + 10.0 * info["reached"] - 10.0 * info["collided"] - 0.1 * info["dt_s"]
            self.assertAlmostEqual(reward, expected, places=12)
            if not info["reached"]:
                # Progress is the distance to the goal gained (goal_body_m's norm is that distance).
                self.assertAlmostEqual(info["progress_m"], before - after, delta=1e-4)
            self.assertAlmostEqual(info["dt_s"], env.step_s, places=9)
            if terminated or truncated:
                break

    def test_goal_reached_terminates_with_the_goal_reward(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="waypoint", goal_radius_m=0.5)
        obs, _ = env.reset(seed=0)
        for _ in range(200):
            toward = obs["goal_body_m"] / max(1.0, np.linalg.norm(obs["goal_body_m"]))
            obs, reward, terminated, truncated, info = env.step(toward.astype(np.float32))
            if terminated or truncated:
                break
        self.assertTrue(terminated)
        self.assertFalse(truncated)
        self.assertTrue(info["reached"])
        self.assertEqual(info["outcome"], "reached")
        self.assertGreater(reward, 9.0)  # the goal reward, less a step's time
        self.assertLessEqual(np.linalg.norm(obs["position_m"] - np.array([6.0, 0.0, 1.5])), 0.5 + 0.05)

    def test_collision_terminates_with_the_penalty(self):
        # Straight at the post at (3, 3): through its centre, 0.3 m in radius.
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity", max_speed_mps=1.0)
        obs, _ = env.reset(seed=0)
        direction = np.array([3.0, 3.0]) / np.linalg.norm([3.0, 3.0])
        for _ in range(200):
            obs, reward, terminated, truncated, info = env.step(
                np.array([direction[0], direction[1], 0.0, 0.0], np.float32))
            if terminated or truncated:
                break
        self.assertTrue(terminated)
        self.assertFalse(truncated)
        self.assertTrue(info["collided"])
        self.assertEqual(info["outcome"], "collision")
        self.assertLess(reward, -9.0)
        self.assertLess(np.linalg.norm(obs["position_m"][:2] - np.array([3.0, 3.0])), 0.3 + 0.45)

    def test_time_limit_truncates(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity", overrides={"/world/time_limit_s": 1.0})
        env.reset(seed=0)
        steps = 0
        while True:
            _, _, terminated, truncated, info = env.step(np.zeros(4, np.float32))
            steps += 1
            if terminated or truncated:
                break
        self.assertTrue(truncated)
        self.assertFalse(terminated)
        self.assertEqual(info["outcome"], "timeout")
        self.assertEqual(steps, round(1.0 / env.step_s))

    def test_a_reward_callable_replaces_the_default(self):
        seen = []

        def reward_fn(info, obs):
            seen.append((info["progress_m"], obs["position_m"].copy()))
            return -2.5

        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity", reward_fn=reward_fn)
        env.reset(seed=0)
        _, reward, *_ = env.step(np.array([0.5, 0, 0, 0], np.float32))
        self.assertEqual(reward, -2.5)
        self.assertEqual(len(seen), 1)

    def test_render_gives_an_rgb_frame_and_save_video_writes_it(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, render_mode="rgb_array", render_size=(160, 120))
        env.reset(seed=0)
        frames = [env.render()]
        for _ in range(3):
            env.step(np.array([1.0, 0.0, 0.0], np.float32))
            frames.append(env.render())
        self.assertEqual(frames[0].shape, (120, 160, 3))
        self.assertEqual(frames[0].dtype, np.uint8)
        self.assertGreater(len(np.unique(frames[-1].reshape(-1, 3), axis=0)), 10, "a picture, not a flat colour")
        with tempfile.TemporaryDirectory() as d:
            path = pathlib.Path(d) / "flight.mp4"
            campo.gym.save_video(frames, path, fps=10)
            self.assertGreater(path.stat().st_size, 0)
        self.assertIsNone(campo.gym.NavigationEnv(OPEN_FIELD).render())
        above = campo.gym.NavigationEnv(OPEN_FIELD, render_mode="rgb_array", render_size=(160, 120),
                                        render_camera="above", render_distance_m=20.0)
        above.reset(seed=0)
        self.assertEqual(above.render().shape, (120, 160, 3))
        with self.assertRaisesRegex(ValueError, "render_camera"):
            campo.gym.NavigationEnv(OPEN_FIELD, render_mode="rgb_array", render_camera="side")

    def test_bad_options_are_refused_with_their_names(self):
        with self.assertRaisesRegex(campo.InputError, "waypoint, velocity, attitude_thrust, rotors"):
            campo.gym.NavigationEnv(OPEN_FIELD, action_mode="wheels")
        with self.assertRaisesRegex(campo.InputError, "unknown action mode"):
            campo.gym.NavigationEnv(OPEN_FIELD, action_mode="fly")
        with self.assertRaisesRegex(campo.InputError, "goal_radius_m"):
            campo.gym.NavigationEnv(OPEN_FIELD, goal_radius_m=0)
        with self.assertRaisesRegex(campo.InputError, "collision_penalty"):
            campo.gym.NavigationEnv(OPEN_FIELD, collision_penalty=float("nan"))
        with self.assertRaisesRegex(campo.InputError, "speed_of_light"):
            campo.gym.NavigationEnv(OPEN_FIELD, speed_of_light=1)
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity")
        env.reset(seed=0)
        with self.assertRaises(ValueError):
            env.step(np.array([np.nan, 0, 0, 0], np.float32))


@needs_gymnasium
class ActionModes(unittest.TestCase):
    """Each mode's scaling, checked on the vehicle's physics (the preset quadrotor and rover)."""

    def test_rotors_at_the_hover_speed_hold_altitude(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="rotors")
        obs, _ = env.reset(seed=0)
        z0 = obs["position_m"][2]
        hover = np.full(4, hover_rotor_action(), np.float32)
        for _ in range(int(2.0 / env.step_s)):
            obs, *_ = env.step(hover)
        # Thrust equals weight: no net vertical force; the drift left is the rotors' lag and rounding.
        self.assertLess(abs(obs["position_m"][2] - z0), 0.1)
        self.assertLess(abs(obs["velocity_body_mps"][2]), 0.1)
        # 10% more rotor speed is 21% more thrust: it climbs.
        env.reset(seed=0)
        climb = np.full(4, hover_rotor_action() + 0.2 * (606.6 / 850.0), np.float32)
        for _ in range(int(1.0 / env.step_s)):
            obs, *_ = env.step(climb)
        self.assertGreater(obs["position_m"][2], z0 + 0.3)

    def test_a_velocity_command_reaches_that_velocity(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity", max_speed_mps=2.0)
        obs, _ = env.reset(seed=0)
        for _ in range(int(3.0 / env.step_s)):  # 0.5 of 2 m/s forward, 0.25 of 2 m/s up
            obs, *_ = env.step(np.array([0.5, 0.0, 0.25, 0.0], np.float32))
        np.testing.assert_allclose(obs["velocity_body_mps"], [1.0, 0.0, 0.5], atol=0.1)

    def test_attitude_thrust_pitch_accelerates_forward(self):
        env = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="attitude_thrust")
        obs, _ = env.reset(seed=0)
        max_thrust = 4 * 1.0e-5 * 1000.0 ** 2
        weight = 1.5 * 9.81
        pitch_rad = math.radians(10.0)
        # Thrust that holds altitude at that tilt: weight / cos(pitch), as a fraction of the range.
        thrust = 2.0 * (weight / math.cos(pitch_rad)) / max_thrust - 1.0
        action = np.array([0.0, pitch_rad / math.radians(30.0), 0.0, thrust], np.float32)
        x0 = obs["position_m"][0]
        duration = 1.0
        for _ in range(int(duration / env.step_s)):
            obs, *_ = env.step(action)
        # From rest at g tan(pitch), less the drag (0.3 N per m/s on 1.5 kg) and the time to tilt.
        ideal = 0.5 * 9.81 * math.tan(pitch_rad) * duration ** 2
        self.assertGreater(obs["position_m"][0] - x0, 0.5 * ideal)
        self.assertLess(obs["position_m"][0] - x0, 1.05 * ideal)

    def test_rover_wheels_and_twist_drive_at_the_commanded_speed(self):
        for mode, action in (("wheels", [0.5, 0.5, 0.5, 0.5]), ("twist", [0.5, 0.0])):
            with self.subTest(mode=mode):
                env = campo.gym.NavigationEnv("vineyard", action_mode=mode, max_speed_mps=2.0)
                obs, _ = env.reset(seed=0)
                for _ in range(int(3.0 / env.step_s)):
                    obs, *_ = env.step(np.array(action, np.float32))
                # wheels: 0.5 of 10 rad/s on 0.2 m wheels; twist: 0.5 of 2 m/s.
                self.assertAlmostEqual(float(obs["velocity_body_mps"][0]), 1.0, delta=0.1)


@needs_gymnasium
class VectorEnvironment(unittest.TestCase):
    OVERRIDES = {"/objects/drone/sensors/0/resolution": [32, 16], "/world/time_limit_s": 1.5}

    def test_each_environment_is_the_single_environment_seeded_s_plus_i_with_autoreset(self):
        n = 3
        envs = campo.gym.NavigationVectorEnv(OPEN_FIELD, num_envs=n, num_threads=2, action_mode="velocity",
                                             overrides=self.OVERRIDES)
        self.assertEqual(envs.observation_space["scanner_ranges_m"].shape, (n, 16, 32))
        rng = np.random.default_rng(3)
        actions = [rng.uniform(-1, 1, (n, 4)).astype(np.float32) for _ in range(40)]
        obs, info = envs.reset(seed=20)
        batches = [(obs, np.zeros(n), np.zeros(n, bool), np.zeros(n, bool), {})]
        for a in actions:
            batches.append(envs.step(a))
        saw_autoreset = False
        for i in range(n):
            single = campo.gym.NavigationEnv(OPEN_FIELD, action_mode="velocity", overrides=self.OVERRIDES)
            obs, _ = single.reset(seed=20 + i)
            ended = False
            for k, a in enumerate(actions, start=1):
                if ended:  # Gymnasium's next-step autoreset: this step resets, reward 0, no flags
                    obs, _ = single.reset()
                    reward, terminated, truncated = 0.0, False, False
                    self.assertFalse(batches[k][4]["_progress_m"][i])
                    saw_autoreset = True
                else:
                    obs, reward, terminated, truncated, _ = single.step(a[i])
                    self.assertTrue(batches[k][4]["_progress_m"][i])
                vobs, vreward, vterminated, vtruncated, _ = batches[k]
                for key in obs:
                    np.testing.assert_array_equal(obs[key], vobs[key][i], err_msg=f"env {i} step {k} {key}")
                self.assertEqual((reward, terminated, truncated), (vreward[i], vterminated[i], vtruncated[i]))
                ended = terminated or truncated
        self.assertTrue(saw_autoreset, "the 1.5 s time limit ends episodes within 40 steps of 0.1 s")

    def test_depth_cameras_render_in_the_worker_threads_as_alone(self):
        # Each camera's OSMesa context is made current in whichever worker steps its environment.
        camera = {"/objects/drone/sensors/0": {"alias": "cam", "type": "depth_camera", "resolution": [40, 30],
                                               "mount": {"position_m": [0.15, 0, 0]}}}
        envs = campo.gym.NavigationVectorEnv("trees_rolling_terrain", num_envs=3, num_threads=2,
                                             action_mode="velocity", overrides=camera)
        self.assertEqual(envs.single_observation_space["cam_ranges_m"].shape, (30, 40))
        actions = [np.random.default_rng(1).uniform(-1, 1, (3, 4)).astype(np.float32) for _ in range(6)]
        envs.reset(seed=5)
        last = [envs.step(a)[0]["cam_ranges_m"] for a in actions][-1]
        single = campo.gym.NavigationEnv("trees_rolling_terrain", action_mode="velocity", overrides=camera)
        for i in range(3):
            single.reset(seed=5 + i)
            for a in actions:
                obs, *_ = single.step(a[i])
            np.testing.assert_array_equal(obs["cam_ranges_m"], last[i])
            self.assertLess(obs["cam_ranges_m"].min(), 10.0, "the forest is in view")

    def test_the_other_vehicles_fly_their_planners_in_the_workers(self):
        # "west" hovers; "east" flies its depth_reactive planner toward it (a planner keeping its own state
        # between calls), in each worker thread as alone.
        envs = campo.gym.NavigationVectorEnv("two_drones_head_on", num_envs=2, vehicle="west", action_mode="velocity")
        obs, _ = envs.reset(seed=0)
        single = campo.gym.NavigationEnv("two_drones_head_on", vehicle="west", action_mode="velocity")
        alone, _ = single.reset(seed=0)
        for _ in range(30):
            obs, *_ = envs.step(np.zeros((2, 4), np.float32))
            alone, *_ = single.step(np.zeros(4, np.float32))
        for key in alone:
            np.testing.assert_array_equal(alone[key], obs[key][0])
        with self.assertRaisesRegex(campo.InputError, "north"):
            campo.gym.NavigationEnv("two_drones_head_on", vehicle="north")

    def test_disabled_autoreset_idles_ended_environments_until_a_masked_reset(self):
        # Environment 0's episode lasts 0.5 s, environment 1's 1.5 s (per-environment overrides, numpy values).
        envs = campo.gym.NavigationVectorEnv(OPEN_FIELD, num_envs=2, action_mode="velocity",
                                             autoreset_mode=gymnasium.vector.AutoresetMode.DISABLED,
                                             overrides={"/objects/drone/sensors/0/resolution": [8, 8]})
        self.assertEqual(envs.metadata["autoreset_mode"], gymnasium.vector.AutoresetMode.DISABLED)
        limits = [{"/world/time_limit_s": np.float64(0.5)}, {"/world/time_limit_s": np.int64(1) + 0.5}]
        envs.reset(seed=0, options={"overrides": limits})
        hover = np.zeros((2, 4), np.float32)
        ended_at = {}
        for k in range(1, 16):
            obs, rewards, terminated, truncated, info = envs.step(hover)
            for i in range(2):
                if truncated[i]:
                    ended_at[i] = k
                if i in ended_at and k > ended_at[i]:  # idle: not stepped, its time where it ended
                    self.assertFalse(info["_progress_m"][i])
                    self.assertEqual(rewards[i], 0.0)
                    self.assertAlmostEqual(info["time_s"][i], 0.5 if i == 0 else 1.5, places=9)
        self.assertEqual(ended_at, {0: 5, 1: 15})
        obs, _ = envs.reset(options={"reset_mask": [True, False], "overrides": limits})
        obs, rewards, terminated, truncated, info = envs.step(hover)
        self.assertTrue(info["_progress_m"][0])
        self.assertFalse(info["_progress_m"][1])
        self.assertAlmostEqual(info["time_s"][0], 0.1, places=9)

    def test_observations_are_new_arrays_each_step(self):
        envs = campo.gym.NavigationVectorEnv(OPEN_FIELD, num_envs=2, action_mode="velocity", overrides=self.OVERRIDES)
        first, _ = envs.reset(seed=0)
        kept = first["position_m"].copy()
        second, *_ = envs.step(np.full((2, 4), 0.5, np.float32))
        np.testing.assert_array_equal(first["position_m"], kept)
        self.assertFalse(np.shares_memory(first["scanner_ranges_m"], second["scanner_ranges_m"]))

    def test_steps_run_with_the_interpreter_released(self):
        envs = campo.gym.NavigationVectorEnv("trees_rolling_terrain", num_envs=2, action_mode="velocity")
        envs.reset(seed=0)
        counter = [0]
        stop = threading.Event()

        def count():
            while not stop.is_set():
                counter[0] += 1

        thread = threading.Thread(target=count)
        thread.start()
        try:
            during = []
            for _ in range(5):
                before = counter[0]
                envs.step(np.zeros((2, 4), np.float32))  # two 256 x 256 scans and 48 physics steps
                during.append(counter[0] - before)
        finally:
            stop.set()
            thread.join()
        # A step holding the interpreter would leave the counter where it was.
        self.assertGreater(sum(during), 0)

    def test_gymnasium_make_vec_and_campo_make_vec(self):
        envs = gymnasium.make_vec("campo/Navigate-v0", num_envs=2, vectorization_mode="vector_entry_point",
                                  action_mode="velocity", overrides={"/objects/drone/sensors/0/resolution": [8, 8]})
        self.assertIsInstance(envs, gymnasium.vector.VectorEnv)
        obs, _ = envs.reset(seed=1)
        self.assertTrue(envs.observation_space.contains(obs))
        obs, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())
        self.assertEqual(rewards.shape, (2,))
        self.assertEqual(terminated.dtype, np.bool_)
        mine = campo.gym.make_vec("campo/RoverNavigate-v0", num_envs=2, action_mode="twist")
        self.assertEqual(mine.vehicle_type, "rover")
        self.assertEqual(mine.action_space.shape, (2, 2))


if __name__ == "__main__":
    unittest.main()
