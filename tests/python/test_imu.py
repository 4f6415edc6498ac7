"""IMUs from Python: campo.Observation.imus and the Gymnasium observation's "<alias>_imu" entries.

    PYTHONPATH=build/python /usr/bin/python3 -m unittest tests/python/test_imu.py

The Gymnasium part needs Gymnasium (tests/python/gymnasium_support.py), and is skipped without it.
"""

import pathlib
import sys
import unittest

import numpy as np

import campo

FIXTURES = pathlib.Path(__file__).resolve().parent / "fixtures"
# A quadrotor hovering at (0, 0, 1.5) with "body" (control rate, white noise) and "rolled" (240 Hz,
# rolled 90 degrees on its mount, 0.1 m ahead of the body's origin, no noise).
IMU_FIELD = str(FIXTURES / "imu_field.json")
GRAVITY_UP = np.array([0.0, 0.0, 9.81])

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from gymnasium_support import GYMNASIUM_ERROR, needs_gymnasium  # noqa: E402 (this folder, just above)

if GYMNASIUM_ERROR is None:
    import campo.gym


class ObservationImusTest(unittest.TestCase):
    def test_hovering_reads_gravity_up_in_each_imus_frame(self):
        episode = campo.Episode(IMU_FIELD, seed=1)
        obs = episode.reset()
        self.assertEqual(list(obs.imus), ["body", "rolled"])
        body, rolled = obs.imus["body"], obs.imus["rolled"]
        self.assertTrue(body.valid and body.fresh)
        self.assertEqual(body.alias, "body")
        self.assertEqual(body.time_s, obs.time_s)
        self.assertEqual(body.specific_force_mps2.shape, (3,))
        # The first sample counts the vehicle as unaccelerated: gravity up, exactly for the ideal IMU.
        np.testing.assert_allclose(rolled.specific_force_mps2, [0.0, 9.81, 0.0], atol=1e-9)  # its y axis is up
        np.testing.assert_allclose(body.specific_force_mps2, GRAVITY_UP, atol=0.02)  # 0.001 / sqrt(1/60) noise
        hold = campo.Command.hold([0.0, 0.0, 1.5], yaw_rad=0.0)
        forces = []
        for _ in range(120):  # 2 s
            obs, done, _ = episode.step(hold)
            self.assertFalse(done)
            self.assertTrue(obs.imus["body"].fresh)
            self.assertAlmostEqual(obs.imus["rolled"].time_s, obs.time_s, places=9)
            forces.append(obs.imus["body"].specific_force_mps2)
        np.testing.assert_allclose(np.mean(forces, axis=0), GRAVITY_UP, atol=0.01)
        # The readings are copies: changing one changes nothing.
        reading = obs.imus["body"].specific_force_mps2
        reading[:] = 0.0
        self.assertGreater(obs.imus["body"].specific_force_mps2[2], 9.0)

    def test_turning_reads_the_turn_rate_on_each_imus_axis(self):
        episode = campo.Episode(IMU_FIELD, seed=1)
        episode.reset()
        turn = campo.Command.velocity((0.0, 0.0, 0.0), 0.5)
        for _ in range(60):  # 1 s to settle into the turn
            obs, *_ = episode.step(turn)
        yaw_start, rates_body, rates_rolled = obs.state.yaw_rad, [], []
        for _ in range(60):
            rates_body.append(obs.imus["body"].angular_rate_radps)
            rates_rolled.append(obs.imus["rolled"].angular_rate_radps)
            obs, *_ = episode.step(turn)
        turned = np.remainder(obs.state.yaw_rad - yaw_start + np.pi, 2 * np.pi) - np.pi
        # About the body's z axis, which is the rolled IMU's y axis (Rx(90) takes y to z).
        np.testing.assert_allclose(np.mean(rates_body, axis=0), [0.0, 0.0, turned], atol=0.02)
        np.testing.assert_allclose(np.mean(rates_rolled, axis=0), [0.0, turned, 0.0], atol=0.02)
        self.assertAlmostEqual(turned, 0.5, delta=0.05)


@needs_gymnasium
class GymImuTest(unittest.TestCase):
    def test_each_imu_is_a_box_of_six_floats(self):
        env = campo.gym.NavigationEnv(IMU_FIELD)
        for key in ("body_imu", "rolled_imu"):
            space = env.observation_space[key]
            self.assertEqual(space.shape, (6,))
            self.assertEqual(space.dtype, np.float32)
        obs, _ = env.reset(seed=0)
        self.assertTrue(env.observation_space.contains(obs))
        # Specific force x, y, z then angular rate x, y, z, in the IMU's frame.
        np.testing.assert_allclose(obs["rolled_imu"], [0.0, 9.81, 0.0, 0.0, 0.0, 0.0], atol=1e-5)
        np.testing.assert_allclose(obs["body_imu"][:3], GRAVITY_UP, atol=0.02)
        obs, *_ = env.step(env.action_space.sample() * 0.0)
        self.assertTrue(env.observation_space.contains(obs))
        self.assertAlmostEqual(float(obs["rolled_imu"][1]), 9.81, delta=1.0)
        envs = campo.gym.NavigationVectorEnv(IMU_FIELD, num_envs=2, num_threads=2)
        self.assertEqual(envs.single_observation_space["body_imu"].shape, (6,))
        obs, _ = envs.reset(seed=3)
        self.assertEqual(obs["rolled_imu"].shape, (2, 6))
        np.testing.assert_allclose(obs["rolled_imu"][:, 1], [9.81, 9.81], atol=1e-5)
        envs.close()


if __name__ == "__main__":
    unittest.main()
