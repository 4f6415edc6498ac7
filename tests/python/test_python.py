"""The campo Python module: episodes stepped from Python, Python planners in the C++ closed loop
(campo.run, campo run/sweep --planner python:...), errors across the boundary.

    PYTHONPATH=build/python /usr/bin/python3 -m unittest tests/python/test_python.py

CAMPO_BIN names the program (default: build/campo of this source tree).
"""

import json
import os
import pathlib
import re
import stat
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np

import campo

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
FIXTURES = pathlib.Path(__file__).resolve().parent / "fixtures"
sys.path.insert(0, str(FIXTURES))
import python_planners  # noqa: E402 (the fixtures folder is on the path just above)

CAMPO = pathlib.Path(os.environ.get("CAMPO_BIN", SOURCE_DIR / "build" / "campo"))
OPEN_FIELD = str(FIXTURES / "open_field.json")
TWO_DRONES = str(FIXTURES / "two_drones.json")  # near: 2 m to fly, far: 5 m, 8 m apart
GOAL = np.array([6.0, 0.0, 1.5])


def go_to_goal(episode, speed_mps=0.8, arrival_m=0.3):
    """Steps `episode` as GoStraight would plan it; returns the number of steps."""
    planner = python_planners.GoStraight(speed_mps, arrival_m)
    obs = episode.observation
    steps = 0
    while not episode.done:
        # The planner's own status is not the episode's business here: only its commands.
        result = planner.plan(obs)
        obs, done, info = episode.step(result.command)
        steps += 1
        if result.status == "reached":
            break
    return steps


class EpisodeTest(unittest.TestCase):
    def test_observation_and_steps(self):
        episode = campo.Episode(OPEN_FIELD, seed=2)
        obs = episode.reset()
        self.assertEqual(obs.time_s, 0.0)
        np.testing.assert_allclose(obs.state.position_m, [0.0, 0.0, 1.5], atol=1e-9)
        np.testing.assert_allclose(obs.mission_m, [GOAL])
        self.assertEqual(obs.vehicle, "quadrotor")
        self.assertEqual(list(obs.sensors), ["scanner"])
        scan = obs.sensors["scanner"]
        # resolution [cols, rows] = [16, 8]: an image of 8 rows by 16 columns.
        self.assertEqual(scan.ranges_m.shape, (8, 16))
        self.assertEqual(scan.ranges_m.dtype, np.float32)
        self.assertEqual(scan.hits.shape, (8, 16))
        self.assertEqual(scan.points_m.shape, (int(scan.hits.sum()), 3))
        # The depth map is the ranges over the maximum range (10 m for scanner3d), 1 where nothing was hit.
        expected = np.where(scan.hits == 1, scan.ranges_m / 10.0, 1.0)
        np.testing.assert_allclose(scan.depth, expected, rtol=1e-6)
        obs, done, info = episode.step(campo.Command.go_to(GOAL, speed_mps=0.8))
        self.assertFalse(done)
        self.assertAlmostEqual(obs.time_s, 1 / 60, places=12)  # one control tick at 60 Hz
        self.assertIsNone(info["outcome"])

    def test_ranges_are_views_of_the_sensor_buffer(self):
        episode = campo.Episode(OPEN_FIELD, seed=2)
        first = episode.reset().sensors["scanner"].ranges_m
        self.assertFalse(first.flags.owndata)
        self.assertFalse(first.flags.writeable)
        again = episode.observation.sensors["scanner"].ranges_m
        self.assertTrue(np.shares_memory(first, again))
        kept = first.copy()
        # Climb 3 m: the next scans (10 Hz, every 6th tick) see the ground from higher up.
        for _ in range(60):
            obs, done, info = episode.step(campo.Command.altitude(4.5))
        self.assertTrue(np.shares_memory(first, obs.sensors["scanner"].ranges_m))
        self.assertFalse(np.array_equal(first, kept))  # the view follows the sensor
        # A view outlives its episode: the buffer stays alive with the array.
        episode.reset()
        del episode
        self.assertEqual(float(first.sum()), float(first.sum()))

    def test_overrides_reach_the_scene(self):
        episode = campo.Episode(OPEN_FIELD, overrides={"/objects/drone/sensors/scanner/resolution": [64, 32]})
        self.assertEqual(episode.reset().sensors["scanner"].ranges_m.shape, (32, 64))

    def test_same_seed_and_commands_same_run_as_a_planner_in_the_loop(self):
        episode = campo.Episode(OPEN_FIELD, seed=5, overrides={"/objects/drone/state_noise/position_stddev_m": 0.05})
        episode.reset()
        go_to_goal(episode)
        self.assertFalse(episode.done)  # the caller decided it was there; the episode goes on until told
        # The in-loop planner ends the run with "reached" at the same tick: give the episode that decision.
        with tempfile.TemporaryDirectory() as out:
            record = campo.run(OPEN_FIELD, planner=python_planners.GoStraight(), seed=5,
                               overrides={"/objects/drone/state_noise/position_stddev_m": 0.05},
                               out=os.path.join(out, "run"))
        self.assertEqual(record["metrics"]["outcome"], "reached")
        stepped = campo.Episode(OPEN_FIELD, seed=5, overrides={"/objects/drone/state_noise/position_stddev_m": 0.05})
        stepped.reset()
        steps = go_to_goal(stepped)
        # The same decisions at the same ticks: the loop's last call said "reached", the caller stepped its command.
        self.assertEqual(steps, record["metrics"]["planner_calls"])

    def test_metrics_and_write_match_campo_run(self):
        with tempfile.TemporaryDirectory() as out:
            episode = campo.Episode(OPEN_FIELD, seed=1, overrides={"/world/time_limit_s": 3})
            episode.reset()
            steps = 0
            while not episode.done:
                obs, done, info = episode.step(campo.Command.go_to(GOAL, speed_mps=0.8))
                steps += 1
            self.assertEqual(info["outcome"], "timeout")
            metrics = episode.metrics()
            self.assertEqual(metrics["outcome"], "timeout")
            self.assertEqual(metrics["planner_calls"], steps)
            self.assertAlmostEqual(metrics["sim_time_s"], 3.0, places=9)
            record = episode.write(os.path.join(out, "ep"))
            on_disk = json.loads(pathlib.Path(out, "ep", "run.json").read_text())
            self.assertEqual(on_disk, record)
            for key, value in metrics.items():
                self.assertEqual(on_disk["metrics"][key], value, key)
            self.assertEqual(on_disk["parameters"]["planner"]["name"], "external")
            self.assertEqual(on_disk["parameters"]["world"]["seed"], 1)
            for name in ("trajectory.csv", "events.jsonl", "scene.json", "map.png", "side.png"):
                self.assertTrue(pathlib.Path(out, "ep", name).is_file(), name)
            run = campo.read_run(os.path.join(out, "ep"))
            self.assertEqual(len(run.trajectory), steps)
            # The same commands from campo's program, through a Python planner: the same final state, bit for bit.
            cli = subprocess.run([str(CAMPO), "run", OPEN_FIELD, "--planner", "python:python_planners:GoStraight",
                                  "--seed", "1", "--set", "/world/time_limit_s=3",
                                  "--set", "/objects/drone/planner/params/arrival_m=0.0",
                                  "--set", "/objects/drone/planner/name=\"python:python_planners:GoStraight\"",
                                  "--out", os.path.join(out, "cli"), "--no-figures"],
                                 capture_output=True, text=True, timeout=300, env=python_env(), cwd=FIXTURES)
            self.assertEqual(cli.returncode, 0, cli.stderr)
            by_cli = json.loads(pathlib.Path(out, "cli", "run.json").read_text())
            self.assertEqual(by_cli["final_state_hash"], on_disk["final_state_hash"])

    def test_episode_ends_and_refuses_more_steps(self):
        episode = campo.Episode(OPEN_FIELD, overrides={"/world/time_limit_s": 0.1})
        episode.reset()
        with self.assertRaisesRegex(RuntimeError, "still running"):
            episode.metrics()
        while not episode.done:
            episode.step(campo.Command.hold([0, 0, 1.5]))
        with self.assertRaisesRegex(RuntimeError, "ended"):
            episode.step(campo.Command.hold([0, 0, 1.5]))
        # reset starts the same episode again
        obs = episode.reset()
        self.assertEqual(obs.time_s, 0.0)
        self.assertFalse(episode.done)


def corrupt_leg_of_third_event(events):
    """Rewrites the third line of an events file with its "leg" decision a string, not the integer declared."""
    lines = events.read_text().split("\n")
    line = json.loads(lines[2])
    line["decisions"]["leg"] = "first"
    lines[2] = json.dumps(line)
    events.write_text("\n".join(lines))


def python_env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(FIXTURES), env.get("PYTHONPATH", "")])
    return env


# Timings differ between any two runs; every other metric is the decisions' and the physics'.
TIMING_METRICS = {"planner_time_ms_max", "planner_time_ms_mean", "wall_time_s"}


def step_with_planners(episode, planners):
    """Steps a scene of several vehicles with each live vehicle's planner's whole PlanResult (so its status
    ends its mission as the loop would) until the run ends; returns every step's (observations, dones, infos,
    agents after it)."""
    obs = episode.observation
    steps = []
    while not episode.done:
        obs, dones, infos = episode.step({alias: planners[alias].plan(obs[alias]) for alias in episode.agents})
        steps.append((obs, dones, infos, episode.agents))
    return steps


class SeveralVehiclesEpisodeTest(unittest.TestCase):
    """campo.Episode over a scene of several vehicles: dicts keyed by alias (PettingZoo's parallel API)."""

    def test_dict_in_dict_out_and_agents_shrink_as_missions_end(self):
        episode = campo.Episode(TWO_DRONES, seed=4)
        self.assertEqual(episode.possible_agents, ["near", "far"])
        self.assertEqual(episode.agents, [])  # before reset()
        obs = episode.reset()
        self.assertEqual(sorted(obs), ["far", "near"])
        self.assertEqual(episode.agents, ["near", "far"])
        np.testing.assert_allclose(obs["near"].state.position_m, [0, 0, 1.5], atol=1e-9)
        np.testing.assert_allclose(obs["far"].state.position_m, [0, 8, 1.5], atol=1e-9)
        np.testing.assert_allclose(obs["near"].mission_m, [[2, 0, 1.5]])
        np.testing.assert_allclose(obs["far"].mission_m, [[5, 8, 1.5]])
        self.assertEqual(sorted(episode.observation), ["far", "near"])

        planners = {alias: python_planners.GoStraight() for alias in episode.possible_agents}
        steps = step_with_planners(episode, planners)
        # The near drone (2 m) ends first: in the step it ends it is in the dicts, done, with its outcome...
        ended = next(i for i, (_, dones, _, _) in enumerate(steps) if dones.get("near"))
        obs, dones, infos, agents = steps[ended]
        self.assertEqual(sorted(obs), ["far", "near"])
        self.assertEqual(dones, {"near": True, "far": False, "__all__": False})
        self.assertEqual(infos["near"]["outcome"], "reached")
        self.assertEqual(infos["near"]["reason"], "at the goal")
        self.assertIsNone(infos["far"]["outcome"])
        self.assertEqual(agents, ["far"])
        # ...and absent from every step after it.
        for obs, dones, infos, agents in steps[ended + 1:]:
            self.assertEqual(list(obs), ["far"])
            self.assertEqual(list(infos), ["far"])
            self.assertEqual(sorted(dones), ["__all__", "far"])
        obs, dones, infos, agents = steps[-1]
        self.assertEqual(dones, {"far": True, "__all__": True})
        self.assertEqual(infos["far"]["outcome"], "reached")
        self.assertEqual(agents, [])
        self.assertEqual(episode.observation, {})
        self.assertTrue(episode.done)

        metrics = episode.metrics()
        self.assertEqual(sorted(metrics), ["fleet", "vehicles"])
        self.assertEqual(sorted(metrics["vehicles"]), ["far", "near"])
        fleet = metrics["fleet"]
        self.assertTrue(fleet["all_reached"])
        self.assertEqual((fleet["vehicles"], fleet["vehicles_reached"], fleet["collisions"]), (2, 2, 0))
        near, far = metrics["vehicles"]["near"], metrics["vehicles"]["far"]
        # What the step a mission ended in said is what the run's record says.
        self.assertEqual(steps[ended][2]["near"]["time_s"], near["sim_time_s"])
        self.assertEqual(steps[-1][2]["far"]["time_s"], far["sim_time_s"])
        self.assertEqual(fleet["makespan_s"], far["sim_time_s"])
        self.assertLess(near["sim_time_s"], far["sim_time_s"])
        # One control tick at 60 Hz per step while the vehicle flew, and one planner call per tick.
        self.assertEqual(far["planner_calls"], len(steps))
        self.assertEqual(near["planner_calls"], ended + 1)
        self.assertEqual(planners["near"].calls, ended + 1)
        self.assertAlmostEqual(far["sim_time_s"], (len(steps) - 1) / 60, places=9)
        # The two never came nearer than the 8 m between their straight lines, less two rotor radii at most.
        self.assertLessEqual(fleet["min_vehicle_distance_m"], 8.0)
        self.assertGreater(fleet["min_vehicle_distance_m"], 7.0)

    def test_same_decisions_as_campo_run_same_run_bit_for_bit(self):
        episode = campo.Episode(TWO_DRONES, seed=4)
        episode.reset()
        step_with_planners(episode, {alias: python_planners.GoStraight() for alias in episode.possible_agents})
        metrics = episode.metrics()
        with tempfile.TemporaryDirectory() as out:
            record = episode.write(os.path.join(out, "ep"), figures=False)
            self.assertEqual(record, json.loads(pathlib.Path(out, "ep", "run.json").read_text()))
            self.assertEqual(record["metrics"], metrics["fleet"])
            for vehicle in record["vehicles"]:
                self.assertEqual(vehicle["metrics"], metrics["vehicles"][vehicle["alias"]])
                self.assertEqual(vehicle["parameters"]["planner"]["name"], "external")
                self.assertEqual(vehicle["planner_provenance"]["name"], "external")
            # campo's program, each vehicle with the same planner in its closed loop.
            planner = '={"name": "python:python_planners:GoStraight"}'
            cli, _ = run_campo("run", TWO_DRONES, "--seed", "4", "--set", "/objects/near/planner" + planner,
                               "--set", "/objects/far/planner" + planner, "--out", os.path.join(out, "cli"),
                               "--no-figures", cwd=FIXTURES, timeout=300)
            self.assertEqual(cli.returncode, 0, cli.stderr)
            by_cli = json.loads(pathlib.Path(out, "cli", "run.json").read_text())
            self.assertEqual(by_cli["final_state_hash"], record["final_state_hash"])
            for stepped, looped in zip(record["vehicles"], by_cli["vehicles"]):
                self.assertEqual(stepped["alias"], looped["alias"])
                self.assertEqual(stepped["trajectory_file"], "trajectory_%s.csv" % stepped["alias"])
                self.assertEqual(pathlib.Path(out, "ep", stepped["trajectory_file"]).read_bytes(),
                                 pathlib.Path(out, "cli", looped["trajectory_file"]).read_bytes())
                for key, value in looped["metrics"].items():
                    if key not in TIMING_METRICS:
                        self.assertEqual(stepped["metrics"][key], value, key)
            for key, value in by_cli["metrics"].items():
                if key not in TIMING_METRICS:
                    self.assertEqual(record["metrics"][key], value, key)
            # And from Python, an object per vehicle: the same run, each vehicle's record naming its planner.
            by_run = campo.run(TWO_DRONES, planner={"near": python_planners.GoStraight(),
                                                    "far": python_planners.GoStraight()},
                               seed=4, out=os.path.join(out, "py"), figures=False)
            self.assertEqual(by_run["final_state_hash"], record["final_state_hash"])
            for vehicle in by_run["vehicles"]:
                self.assertEqual(vehicle["parameters"]["planner"]["name"], "python:python_planners:GoStraight")
                self.assertEqual(vehicle["parameters"]["planner"]["parameters"], {"speed_mps": 0.8, "arrival_m": 0.3})
                self.assertEqual(vehicle["planner_provenance"]["source"],
                                 str(FIXTURES / "python_planners.py"))
                self.assertEqual(pathlib.Path(out, "py", vehicle["trajectory_file"]).read_bytes(),
                                 pathlib.Path(out, "cli", vehicle["trajectory_file"]).read_bytes())

    def test_wrong_missing_and_ended_aliases_are_value_errors_naming_them(self):
        episode = campo.Episode(TWO_DRONES)
        obs = episode.reset()
        hold = {alias: campo.Command.hold(obs[alias].state.position_m) for alias in obs}
        with self.assertRaisesRegex(ValueError, 'no command for vehicle "far"'):
            episode.step({"near": hold["near"]})
        with self.assertRaisesRegex(ValueError, 'no vehicle "wingman" in the scene: its vehicles are "near", "far"'):
            episode.step({**hold, "wingman": hold["near"]})
        with self.assertRaisesRegex(TypeError, 'vehicle "far": expected a campo.Command or a campo.PlanResult'):
            episode.step({"near": hold["near"], "far": [5, 8, 1.5]})
        with self.assertRaisesRegex(TypeError, "dict"):
            episode.step(hold["near"])
        with self.assertRaisesRegex(ValueError, 'vehicle "near": the planner\'s decisions: .*reached_waypoints'):
            episode.step({"near": campo.PlanResult(hold["near"], decisions={"reached_waypoints": "all"}),
                          "far": hold["far"]})
        # A command the vehicle cannot follow (a rover's, to a quadrotor) names it and changes nothing.
        with self.assertRaisesRegex(ValueError, "far: "):
            episode.step({"near": hold["near"], "far": campo.Command.twist(0.5, 0.0)})
        self.assertEqual(episode.observation["near"].time_s, 0.0)
        obs, dones, infos = episode.step({"near": campo.PlanResult(hold["near"], status="reached"),
                                          "far": hold["far"]})
        self.assertEqual(infos["near"]["outcome"], "reached")
        self.assertEqual(infos["near"]["time_s"], 0.0)
        with self.assertRaisesRegex(ValueError, 'vehicle "near" has ended its mission'):
            episode.step(hold)
        with self.assertRaisesRegex(campo.InputError, "no vehicle to choose"):
            campo.Episode(TWO_DRONES, vehicle="far")

    def test_a_collision_ends_one_mission_and_the_run_goes_on(self):
        episode = campo.Episode(TWO_DRONES, overrides={"/world/time_limit_s": 4})
        obs = episode.reset()
        far_hold = campo.Command.hold(obs["far"].state.position_m)
        # The near drone dives into the ground; the far one hovers.
        while "near" in episode.agents:
            obs, dones, infos = episode.step({"near": campo.Command.go_to([1, 0, -2], speed_mps=3.0), "far": far_hold})
        self.assertEqual(infos["near"]["outcome"], "collision")
        self.assertFalse(dones["__all__"])
        ended_at = infos["near"]["time_s"]
        while not episode.done:
            obs, dones, infos = episode.step({"far": far_hold})
        self.assertEqual(infos["far"]["outcome"], "timeout")
        metrics = episode.metrics()
        self.assertEqual(metrics["vehicles"]["near"]["outcome"], "collision")
        self.assertEqual(metrics["vehicles"]["near"]["sim_time_s"], ended_at)
        self.assertEqual(metrics["fleet"]["outcome"], "collision")

    def test_python_planners_per_vehicle_and_the_scenes_for_the_rest(self):
        with tempfile.TemporaryDirectory() as out:
            # One object for the far drone: the near one keeps the scene's planner (straight).
            record = campo.run(TWO_DRONES, planner={"far": python_planners.GoStraight(speed_mps=1.0)},
                               out=os.path.join(out, "far"), figures=False)
            planners = {v["alias"]: v["parameters"]["planner"] for v in record["vehicles"]}
            self.assertEqual(planners["near"]["name"], "straight")
            self.assertEqual(planners["far"], {"name": "python:python_planners:GoStraight",
                                               "parameters": {"speed_mps": 1.0, "arrival_m": 0.3}})
            self.assertTrue(record["metrics"]["all_reached"])
            scene = json.loads(pathlib.Path(out, "far", "scene.json").read_text())
            self.assertEqual(scene["objects"][2]["planner"]["name"], "python:python_planners:GoStraight")
            # One object: the chosen vehicle's (vehicle=, else the first), as --planner.
            for vehicle, chosen in (("", "near"), ("far", "far")):
                record = campo.run(TWO_DRONES, planner=python_planners.GoStraight(), vehicle=vehicle, figures=False)
                names = {v["alias"]: v["parameters"]["planner"]["name"] for v in record["vehicles"]}
                other = "far" if chosen == "near" else "near"
                self.assertEqual(names, {chosen: "python:python_planners:GoStraight", other: "straight"})
        with self.assertRaisesRegex(campo.InputError, 'planner: wingman: a vehicle of .*two_drones.json \\("near", "far"\\)'):
            campo.run(TWO_DRONES, planner={"wingman": python_planners.GoStraight()})
        with self.assertRaisesRegex(campo.InputError, "planner: far: a planner name or an object with a plan"):
            campo.run(TWO_DRONES, planner={"far": object()})
        with self.assertRaisesRegex(campo.InputError, "overrides: /objects/far/planner/params/speed_mps: .*own constructor"):
            campo.run(TWO_DRONES, planner={"far": python_planners.GoStraight()},
                      overrides={"/objects/far/planner/params/speed_mps": 2.0})


    def test_some_vehicles_from_python_the_rest_by_their_planners(self):
        episode = campo.Episode(TWO_DRONES, seed=4, agents=["far"])
        self.assertEqual(episode.possible_agents, ["far"])
        obs = episode.reset()
        self.assertEqual(list(obs), ["far"])
        with self.assertRaisesRegex(ValueError, 'vehicle "near" is driven by its planner \\(straight\\), not from '
                                                'Python: the agents are "far"'):
            episode.step({"near": campo.Command.hold([0, 0, 1.5]), "far": campo.Command.hold([0, 8, 1.5])})
        step_with_planners(episode, {"far": python_planners.GoStraight()})
        metrics = episode.metrics()
        self.assertEqual(sorted(metrics["vehicles"]), ["far", "near"])  # the run's record holds every vehicle
        with tempfile.TemporaryDirectory() as out:
            record = episode.write(os.path.join(out, "ep"), figures=False)
            planners = {v["alias"]: (v["parameters"]["planner"]["name"], v["planner_provenance"]["name"])
                        for v in record["vehicles"]}
            self.assertEqual(planners, {"near": ("straight", "straight"), "far": ("external", "external")})
            # The same as campo.run with that planner for the far drone and the scene's for the near one.
            by_run = campo.run(TWO_DRONES, seed=4, planner={"far": python_planners.GoStraight()},
                               out=os.path.join(out, "run"), figures=False)
            self.assertEqual(by_run["final_state_hash"], record["final_state_hash"])
            for stepped, looped in zip(record["vehicles"], by_run["vehicles"]):
                self.assertEqual(pathlib.Path(out, "ep", stepped["trajectory_file"]).read_bytes(),
                                 pathlib.Path(out, "run", looped["trajectory_file"]).read_bytes())
                for key, value in looped["metrics"].items():
                    if key not in TIMING_METRICS:
                        self.assertEqual(stepped["metrics"][key], value, key)
            self.assertEqual(record["vehicles"][0]["parameters"]["planner"]["parameters"],
                             by_run["vehicles"][0]["parameters"]["planner"]["parameters"])
        # Overrides reach the planners that run, and are refused for the vehicles stepped from Python.
        speed = {"/objects/near/planner/params/speed_mps": 1.0}
        episode = campo.Episode(TWO_DRONES, agents=["far"], overrides={**speed, "/world/time_limit_s": 8})
        episode.reset()
        while not episode.done:
            episode.step({alias: campo.Command.hold([0, 8, 1.5]) for alias in episode.agents})
        outcomes = {alias: m["outcome"] for alias, m in episode.metrics()["vehicles"].items()}
        self.assertEqual(outcomes, {"near": "reached", "far": "timeout"})  # the far drone hovers
        with tempfile.TemporaryDirectory() as out:
            record = episode.write(out + "/ep", figures=False)
        self.assertEqual(record["vehicles"][0]["parameters"]["planner"]["parameters"]["speed_mps"], 1.0)
        with self.assertRaisesRegex(campo.InputError, "overrides: /objects/near/planner/params/speed_mps: "
                                                      "campo.Episode runs no planner for the vehicles it steps"):
            campo.Episode(TWO_DRONES, agents=["near"], overrides=speed)
        with self.assertRaisesRegex(campo.InputError, 'agents: wingman: a vehicle of .*two_drones.json'):
            campo.Episode(TWO_DRONES, agents=["wingman"])
        with self.assertRaisesRegex(campo.InputError, "agents: at least one vehicle"):
            campo.Episode(TWO_DRONES, agents=[])
        with self.assertRaisesRegex(campo.InputError, "agents: a list of vehicle aliases, got 'far'"):
            campo.Episode(TWO_DRONES, agents="far")

    def test_a_vehicles_python_planner_past_its_call_limit_fails_that_vehicle_alone(self):
        record = campo.run(TWO_DRONES, planner={"far": python_planners.Sleeper(after_s=0.2)}, call_limit_s=0.5,
                           figures=False)
        outcomes = {v["alias"]: v["metrics"]["outcome"] for v in record["vehicles"]}
        self.assertEqual(outcomes, {"near": "reached", "far": "failed"})
        self.assertIn("python:python_planners:Sleeper did not return within", record["vehicles"][1]["metrics"]["reason"])
        self.assertEqual(record["metrics"]["outcome"], "failed")

    def test_one_vehicle_named_as_an_agent_is_keyed_too(self):
        # Code written for several vehicles runs a scene of one when it names its agents.
        episode = campo.Episode(OPEN_FIELD, seed=2, agents=["drone"])
        self.assertEqual(episode.possible_agents, ["drone"])
        self.assertEqual(list(episode.reset()), ["drone"])
        steps = step_with_planners(episode, {"drone": python_planners.GoStraight()})
        self.assertEqual(steps[-1][1], {"drone": True, "__all__": True})
        metrics = episode.metrics()
        self.assertTrue(metrics["fleet"]["all_reached"])
        record = campo.run(OPEN_FIELD, seed=2, planner=python_planners.GoStraight(), figures=False)
        for key, value in record["metrics"].items():
            if key not in TIMING_METRICS:
                self.assertEqual(metrics["vehicles"]["drone"][key], value, key)
        with tempfile.TemporaryDirectory() as out:
            written = episode.write(os.path.join(out, "ep"), figures=False)
            self.assertEqual(written["final_state_hash"], record["final_state_hash"])
            self.assertNotIn("vehicles", written)  # a scene of one vehicle's files, as ever

    def test_a_vehicles_declared_decisions_read_back_from_its_own_events_file(self):
        with tempfile.TemporaryDirectory() as out:
            campo.run(TWO_DRONES, planner={"far": python_planners.Declares()}, out=os.path.join(out, "r"),
                      figures=False)
            run = campo.read_run(os.path.join(out, "r"))
            far = run.vehicles["far"]
            self.assertEqual(far.planner, "python:python_planners:Declares")
            self.assertEqual(run.vehicles["near"].planner, "straight")
            distance = far.decision("distance_m")
            self.assertEqual(len(distance), len(far.events))
            self.assertEqual(distance.iloc[0], 5.0)  # from the start (0, 8, 1.5) to the goal (5, 8, 1.5)
            position = far.trajectory[["x_m", "y_m", "z_m"]].to_numpy()
            expected = np.linalg.norm(position - [5.0, 8.0, 1.5], axis=1)[: len(distance)]
            np.testing.assert_allclose(distance.to_numpy(), expected, atol=1e-6)
            corrupt_leg_of_third_event(pathlib.Path(out, "r", "events_far.jsonl"))
            with self.assertRaisesRegex(campo.ResultsError, r"events_far.jsonl line 3: /decisions/leg: expected integer"):
                campo.read_run(os.path.join(out, "r")).vehicles["far"].decision("leg")


class PythonPlannerTest(unittest.TestCase):
    def test_runs_to_the_goal_in_the_closed_loop(self):
        planner = python_planners.GoStraight(speed_mps=1.0)
        record = campo.run(OPEN_FIELD, planner=planner)
        m = record["metrics"]
        self.assertEqual(m["outcome"], "reached")
        self.assertEqual(m["planner_calls"], planner.calls)
        self.assertGreaterEqual(m["path_ratio"], 1.0)
        self.assertLess(m["path_ratio"], 1.2)
        self.assertEqual(record["parameters"]["planner"]["name"], "python:python_planners:GoStraight")
        self.assertEqual(record["parameters"]["planner"]["parameters"], {"speed_mps": 1.0, "arrival_m": 0.3})
        provenance = record["provenance"]["planner"]
        self.assertEqual(provenance["source"], python_planners.__file__)
        self.assertEqual(len(provenance["sha256"]), 64)

    def test_an_exception_in_plan_fails_the_run_with_its_traceback(self):
        with tempfile.TemporaryDirectory() as out:
            record = campo.run(OPEN_FIELD, planner=python_planners.FailsAfter(0.5), out=os.path.join(out, "r"))
            m = record["metrics"]
            self.assertEqual(m["outcome"], "failed")
            self.assertIn("Traceback (most recent call last)", m["reason"])
            self.assertIn("python_planners.py", m["reason"])
            self.assertIn("ZeroDivisionError: the gain schedule divided by zero", m["reason"])
            self.assertEqual(m["planner_calls"], 31)  # t = 0 .. 0.5 s at 60 Hz; the call that raised is not counted
            self.assertTrue(pathlib.Path(out, "r", "trajectory.csv").is_file())

    def test_plan_result_is_checked(self):
        with self.assertRaisesRegex(ValueError, "status: expected one of running, reached"):
            campo.PlanResult(campo.Command.hold([0, 0, 1]), status="done")
        with self.assertRaisesRegex(ValueError, "target_m: expected 3 numbers, got 2"):
            campo.Command.go_to([1, 2])
        self.assertEqual(campo.Command.twist(0.5, 0.1).kind, "twist")

        class ReturnsNone(campo.Planner):
            def plan(self, obs):
                return None
        m = campo.run(OPEN_FIELD, planner=ReturnsNone())["metrics"]
        self.assertEqual(m["outcome"], "failed")
        self.assertIn("expected a campo.PlanResult", m["reason"])

        class Twists(campo.Planner):
            def plan(self, obs):
                return campo.PlanResult(campo.Command.twist(0.5, 0.0))
        m = campo.run(OPEN_FIELD, planner=Twists())["metrics"]
        self.assertEqual(m["outcome"], "failed")
        self.assertIn("command the vehicle cannot follow", m["reason"])

    def test_planner_overrides_reach_the_planner_chosen(self):
        # The scene names no planner: overrides of its parameters go to the planner given (issue 31).
        record = campo.run(OPEN_FIELD, planner="straight", overrides={"/objects/drone/planner/params/speed_mps": 2.0})
        self.assertEqual(record["parameters"]["planner"]["parameters"]["speed_mps"], 2.0)
        with self.assertRaisesRegex(campo.InputError, "/objects/2/planner/params/speed_mps: expected a number in"):
            campo.run(OPEN_FIELD, planner="straight", overrides={"/objects/drone/planner/params/speed_mps": 99})
        # A planner object was built by the caller: overrides of its parameters would be dropped.
        with self.assertRaisesRegex(campo.InputError, "takes its parameters from its own constructor"):
            campo.run(OPEN_FIELD, planner=python_planners.GoStraight(speed_mps=1.0),
                      overrides={"/objects/drone/planner/params/speed_mps": 2.0})
        # An Episode runs no planner at all.
        with self.assertRaisesRegex(campo.InputError, "campo.Episode runs no planner"):
            campo.Episode(OPEN_FIELD, overrides={"/objects/drone/planner/params/speed_mps": 2.0})
        with self.assertRaisesRegex(campo.InputError, "campo.Episode runs no planner"):
            campo.Episode(OPEN_FIELD, overrides={"/objects/drone/planner": {"name": "straight"}})

    def test_vehicle_types_are_declared(self):
        with self.assertRaisesRegex(campo.InputError, "drives a rover only, not a quadrotor"):
            campo.run(OPEN_FIELD, planner="python:python_planners:RoverOnly")


def documented_fields():
    """Each planner's declared fields as docs/planners.md shows them, {(planner, part): [RecordField]}: tables
    generated from the C++ declarations (RecordFields::markdown) and kept equal to them by
    tests/planners/config_docs_test, read here as text, independently of the module."""
    text = (SOURCE_DIR / "docs" / "planners.md").read_text(encoding="utf-8")
    tables = {}
    for planner, part, table in re.findall(r"<!-- fields (\S+) (\S+) -->\n(.*?)<!-- end fields -->", text, re.S):
        fields = []
        for row in table.strip().split("\n")[2:]:  # after the header and its rule
            cells = [cell.strip().replace("\\|", "|") for cell in re.split(r"(?<!\\)\|", row)[1:-1]]
            fields.append(campo.RecordField(cells[0].strip("`"), *cells[1:]))
        tables[(planner, part)] = fields
    return tables


class PlannerRecordTest(unittest.TestCase):
    """Planners' declared record fields seen from Python (issue 32 point 2)."""

    def test_built_in_declarations_are_the_cpp_ones(self):
        documented = documented_fields()
        self.assertIn(("rover_route", "decisions"), documented)  # the docs were read
        seen = {}
        for name in campo.planners():
            record = campo.planner_record(name)
            if record is None:
                continue
            self.assertEqual(record.name, name)
            for part in ("decisions", "replan", "metrics"):
                if getattr(record, part):
                    seen[(name, part)] = list(getattr(record, part))
        self.assertEqual(seen, documented)
        gap = campo.planner_record("rover_route").decision("gap")
        self.assertEqual((gap.name, gap.type, gap.unit), ("gap", "object", ""))
        self.assertIsNone(campo.planner_record("straight"))  # declares nothing
        self.assertIsNone(campo.planner_record("external"))  # campo.Episode's runs
        with self.assertRaisesRegex(KeyError, 'rover_route declares no decision field "gaps" \\(it declares: gap\\)'):
            campo.planner_record("rover_route").decision("gaps")
        with self.assertRaisesRegex(campo.InputError, 'a registered planner \\(straight, .*rover_route.*\\) or '
                                                      '"python:module:Class", got "rover"'):
            campo.planner_record("rover")

    def test_a_python_planner_declares_its_decision_fields(self):
        record = campo.planner_record("python:python_planners:Declares")
        self.assertEqual(record.decisions, (campo.RecordField("distance_m", "number", "m", "distance to the goal"),
                                            campo.RecordField("leg", "integer", "", "the mission leg flown")))
        self.assertEqual((record.replan, record.metrics), ((), ()))
        self.assertIsNone(campo.planner_record("python:python_planners:FreeKeys"))

    def test_declared_decisions_are_checked(self):
        m = campo.run(OPEN_FIELD, planner=python_planners.Declares("undeclared"))["metrics"]
        self.assertEqual(m["outcome"], "failed")
        self.assertIn('the planner\'s decisions: PlanResult: /decisions/speed: expected a declared field '
                      '(distance_m, leg), got "speed"', m["reason"])
        self.assertEqual(m["planner_calls"], 0)  # its first call broke the declaration
        m = campo.run(OPEN_FIELD, planner=python_planners.Declares("type"))["metrics"]
        self.assertEqual(m["outcome"], "failed")
        self.assertIn('/decisions/leg: expected integer (the mission leg flown), got "first"', m["reason"])
        # A malformed declaration is bad input, by object and by name.
        expected = (r"python:python_planners:BadDeclaration.decision_fields\[0\]: expected a type of flag, integer, "
                    r"number, text, array or object, got \('distance_m', 'real'")
        with self.assertRaisesRegex(campo.InputError, expected):
            campo.run(OPEN_FIELD, planner=python_planners.BadDeclaration())
        with self.assertRaisesRegex(campo.InputError, expected):
            campo.run(OPEN_FIELD, planner="python:python_planners:BadDeclaration")
        with self.assertRaisesRegex(campo.InputError, expected):
            campo.planner_record("python:python_planners:BadDeclaration")

    def test_a_declaring_planners_run_records_and_reads_its_fields(self):
        with tempfile.TemporaryDirectory() as out:
            record = campo.run(OPEN_FIELD, planner=python_planners.Declares(), out=os.path.join(out, "r"))
            self.assertEqual(record["metrics"]["outcome"], "reached")
            run = campo.read_run(os.path.join(out, "r"))
            self.assertEqual(run.planner, "python:python_planners:Declares")
            self.assertEqual(run.planner_record, campo.planner_record("python:python_planners:Declares"))
            distance = run.decision("distance_m")
            # Every call recorded it: one value per event, the distance from the recorded trajectory's position.
            self.assertEqual(len(distance), len(run.events))
            self.assertEqual(list(distance.index), [event["time_s"] for event in run.events])
            self.assertEqual(distance.index.name, "time_s")
            self.assertEqual(distance.iloc[0], 6.0)  # from the start (0, 0, 1.5) to the goal (6, 0, 1.5)
            position = run.trajectory[["x_m", "y_m", "z_m"]].to_numpy()
            expected = np.linalg.norm(position - GOAL, axis=1)[: len(distance)]
            np.testing.assert_allclose(distance.to_numpy(), expected, atol=1e-6)
            self.assertEqual(run.decision("leg").dtype, np.int64)
            with self.assertRaisesRegex(campo.ResultsError, 'planner python:python_planners:Declares declares no '
                                                            'decision field "speed" \\(it declares: distance_m, leg\\)'):
                run.decision("speed")
            # A recorded value not of its declared type is refused, naming the line and the pointer.
            corrupt_leg_of_third_event(pathlib.Path(out, "r", "events.jsonl"))
            with self.assertRaisesRegex(campo.ResultsError, r"events.jsonl line 3: /decisions/leg: expected integer "
                                                            r"\(the mission leg flown\)"):
                campo.read_run(os.path.join(out, "r")).decision("leg")

    def test_a_planner_that_declares_nothing_keeps_free_keys(self):
        with tempfile.TemporaryDirectory() as out:
            record = campo.run(OPEN_FIELD, planner=python_planners.FreeKeys(), out=os.path.join(out, "r"),
                               overrides={"/world/time_limit_s": 0.5}, figures=False)
            self.assertEqual(record["metrics"]["outcome"], "timeout")
            run = campo.read_run(os.path.join(out, "r"))
            self.assertEqual(run.events[0]["decisions"], {"anything": {"at": "all"}})
            self.assertIsNone(run.planner_record)
            with self.assertRaisesRegex(campo.ResultsError, 'declares no decision field "anything" \\(it declares: '
                                                            'none\\)'):
                run.decision("anything")


class ErrorsTest(unittest.TestCase):
    def test_input_errors_name_file_pointer_and_expectation(self):
        with self.assertRaisesRegex(campo.InputError, "no_such_scene.json"):
            campo.Episode(str(FIXTURES / "no_such_scene.json"))
        with self.assertRaisesRegex(campo.InputError, "/objects/2/sensors/0/resolution/0 \\(drone/scanner\\): expected an integer"):
            campo.Episode(OPEN_FIELD, overrides={"/objects/drone/sensors/scanner/resolution": [0, 8]})
        with self.assertRaisesRegex(campo.InputError, "unknown planner \"nope\""):
            campo.run(OPEN_FIELD, planner="nope")
        with self.assertRaisesRegex(campo.InputError, "No module named 'no_such_module'"):
            campo.run(OPEN_FIELD, planner="python:no_such_module:Planner")
        with self.assertRaisesRegex(campo.InputError, "(?s)/objects/2/planner/params: .*constructing it failed:.*unexpected keyword argument 'gain'"):
            campo.run(OPEN_FIELD, planner="python:python_planners:GoStraight",
                      overrides={"/objects/drone/planner": {"name": "python:python_planners:GoStraight",
                                                            "params": {"gain": 2}}})
        self.assertTrue(issubclass(campo.InputError, ValueError))

    def test_outputs_that_cannot_be_written_are_output_errors_and_leave_nothing(self):
        with tempfile.TemporaryDirectory() as tmp:
            fifo = os.path.join(tmp, "fifo")
            os.mkfifo(fifo)
            episode = campo.Episode(OPEN_FIELD, seed=1, overrides={"/world/time_limit_s": 1})
            episode.reset()
            while not episode.done:
                episode.step(campo.Command.go_to(GOAL, speed_mps=0.8))
            with self.assertRaisesRegex(campo.OutputError, "fifo: out: is a FIFO, expected a directory"):
                episode.write(fifo)
            with self.assertRaisesRegex(campo.OutputError, "fifo: out: is a FIFO"):
                campo.run(OPEN_FIELD, planner="straight", out=fifo)
            self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))
            self.assertTrue(issubclass(campo.OutputError, campo.InputError))
            # A full file system (a tmpfs of 8 KiB in a private mount namespace, where mounting is allowed):
            # the error names the file and the reason, and the folder the write made is gone again.
            mount = os.path.join(tmp, "mnt")
            os.mkdir(mount)
            script = ("import campo, os, sys\n"
                      "e = campo.Episode(sys.argv[1], seed=1, overrides={'/world/time_limit_s': 1})\n"
                      "e.reset()\n"
                      "while not e.done: e.step(campo.Command.hold([0, 0, 1.5]))\n"
                      "try:\n"
                      "    e.write(os.path.join(sys.argv[2], 'deep', 'run'))\n"
                      "except campo.OutputError as error:\n"
                      "    print('OutputError', error)\n"
                      "print(sorted(os.listdir(sys.argv[2])))\n")
            shell = 'mount -t tmpfs -o size=8k tmpfs "$2" || exit 99; exec "$1" -c "$3" "$4" "$2"'
            done = subprocess.run(["unshare", "-m", "sh", "-c", shell, "sh", sys.executable, mount, script, OPEN_FIELD],
                                  capture_output=True, text=True, env=os.environ)
            if done.returncode == 99 or "Operation not permitted" in done.stderr:
                self.skipTest("cannot mount a tmpfs in a private namespace here (needs root)")
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertRegex(done.stdout, "OutputError .*/mnt/deep/run/.*: cannot write: No space left on device")
            self.assertTrue(done.stdout.rstrip().endswith("[]"), done.stdout)


class CommandLineTest(unittest.TestCase):
    def test_campo_run_and_sweep_take_python_planners(self):
        with tempfile.TemporaryDirectory() as out:
            run = subprocess.run([str(CAMPO), "run", OPEN_FIELD, "--planner", "python:python_planners:GoStraight",
                                  "--out", os.path.join(out, "run")], capture_output=True, text=True, timeout=300,
                                 env=python_env(), cwd=out)
            self.assertEqual(run.returncode, 0, run.stderr)
            record = json.loads(pathlib.Path(out, "run", "run.json").read_text())
            self.assertEqual(record["metrics"]["outcome"], "reached")
            self.assertEqual(record["provenance"]["planner"]["source"], str(FIXTURES / "python_planners.py"))
            spec = {"campo_sweep": 1, "name": "py", "scenes": [OPEN_FIELD],
                    "planners": [{"name": "python:python_planners:GoStraight", "label": "straight_py"}],
                    "axes": [{"name": "speed_mps", "values": [0.5, 1.0],
                              "set": ["/objects/drone/planner/params/speed_mps"]}],
                    "seeds": {"first": 0, "count": 2}}
            pathlib.Path(out, "spec.json").write_text(json.dumps(spec))
            sweep = subprocess.run([str(CAMPO), "sweep", "spec.json", "--out", "sweep", "--jobs", "2"],
                                   capture_output=True, text=True, timeout=600, env=python_env(), cwd=out)
            self.assertEqual(sweep.returncode, 0, sweep.stderr)
            frame = campo.read_results(os.path.join(out, "sweep"))
            self.assertEqual(len(frame), 4)
            self.assertTrue((frame["outcome"] == "reached").all())
            # Slower runs take longer: the parameter reached the Python planner's constructor.
            by_speed = frame.groupby("speed_mps")["sim_time_s"].mean()
            self.assertGreater(by_speed[0.5], by_speed[1.0] * 1.5)
            failing = subprocess.run([str(CAMPO), "run", OPEN_FIELD, "--planner", "python:python_planners:FailsAfter",
                                      "--out", os.path.join(out, "failing")], capture_output=True, text=True,
                                     timeout=300, env=python_env(), cwd=out)
            self.assertEqual(failing.returncode, 0, failing.stderr)  # a failed run is a run: recorded, exit 0
            failed = json.loads(pathlib.Path(out, "failing", "run.json").read_text())
            self.assertEqual(failed["metrics"]["outcome"], "failed")
            self.assertIn("ZeroDivisionError", failed["metrics"]["reason"])


def run_campo(*args, cwd, env=None, timeout=120):
    """campo with the fixtures on PYTHONPATH; returns (CompletedProcess, seconds it took)."""
    started = time.monotonic()
    done = subprocess.run([str(CAMPO), *args], capture_output=True, text=True, timeout=timeout,
                          env=env or python_env(), cwd=cwd)
    return done, time.monotonic() - started


def read_events(run_dir):
    lines = pathlib.Path(run_dir, "events.jsonl").read_bytes().splitlines()
    return lines, [json.loads(line) for line in lines]


class CommandValuesTest(unittest.TestCase):
    def test_non_finite_targets_are_refused_naming_the_argument(self):
        nan, inf = float("nan"), float("inf")
        with self.assertRaisesRegex(ValueError, r"^target_m: expected 3 finite numbers, got \[nan, 0.0, 1.5\]$"):
            campo.Command.go_to([nan, 0.0, 1.5])
        with self.assertRaisesRegex(ValueError, r"^target_m: expected 3 finite numbers, got \[1.0, -inf, 1.5\]$"):
            campo.Command.go_to(np.array([1.0, -inf, 1.5]))
        with self.assertRaisesRegex(ValueError, r"^speed_mps: expected a finite number, got inf$"):
            campo.Command.go_to([1, 0, 1.5], speed_mps=inf)
        with self.assertRaisesRegex(ValueError, r"^point_m: expected 3 finite numbers"):
            campo.Command.hold([0, 0, inf])
        with self.assertRaisesRegex(ValueError, r"^yaw_rad: expected a finite number, got nan$"):
            campo.Command.hold([0, 0, 1], yaw_rad=nan)
        with self.assertRaisesRegex(ValueError, r"^point_m: expected 3 finite numbers"):
            campo.Command.face([nan, nan, nan])
        with self.assertRaisesRegex(ValueError, r"^z_m: expected a finite number, got -inf$"):
            campo.Command.altitude(-inf)
        with self.assertRaisesRegex(ValueError, r"^w_radps: expected a finite number, got nan$"):
            campo.Command.twist(0.5, nan)
        # Finite values still make commands; huge ones too (the vehicle's limits bound what it does).
        self.assertEqual(campo.Command.go_to([1e300, 0, 1.5]).kind, "go_to")
        self.assertEqual(campo.Command.hold([0, 0, 1], yaw_rad=0.5).kind, "hold")


class PlannerLimitsTest(unittest.TestCase):
    """Python planners held to wall-clock, memory and size limits (docs/python.md, Limits)."""

    def assert_failed_by(self, record, *fragments):
        m = record["metrics"]
        self.assertEqual(m["outcome"], "failed", m["reason"])
        for fragment in fragments:
            self.assertIn(fragment, m["reason"])

    def test_a_call_past_its_limit_ends_the_run_as_failed(self):
        cases = [(python_planners.Sleeper(), "Sleeper"), (python_planners.Spinner(), "Spinner"),
                 (python_planners.Stubborn(), "Stubborn")]
        for planner, name in cases:
            with self.subTest(planner=name), tempfile.TemporaryDirectory() as out:
                started = time.monotonic()
                record = campo.run(OPEN_FIELD, planner=planner, out=os.path.join(out, "r"), call_limit_s=0.5,
                                   figures=False)
                self.assertLess(time.monotonic() - started, 10)
                self.assert_failed_by(record, "plan() of python:python_planners:%s did not return within the "
                                              "per-call limit of 0.5 s wall clock" % name, "CAMPO_PYTHON_CALL_LIMIT_S")
                written = json.loads(pathlib.Path(out, "r", "run.json").read_text())
                self.assertEqual(written["metrics"]["outcome"], "failed")
                self.assertTrue(pathlib.Path(out, "r", "trajectory.csv").is_file())
        # The process goes on: the next run is unaffected.
        self.assertEqual(campo.run(OPEN_FIELD, planner=python_planners.GoStraight(1.0))["metrics"]["outcome"],
                         "reached")

    def test_limits_from_the_environment_and_their_errors(self):
        with tempfile.TemporaryDirectory() as out:
            env = python_env()
            env["CAMPO_PYTHON_CALL_LIMIT_S"] = "0.5"
            done, seconds = run_campo("run", OPEN_FIELD, "--planner", "python:python_planners:Spinner",
                                      "--no-figures", "--out", "spin", cwd=out, env=env)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertLess(seconds, 30)
            record = json.loads(pathlib.Path(out, "spin", "run.json").read_text())
            self.assert_failed_by(record, "per-call limit of 0.5 s")
            # The constructor is a call too: a planner that cannot be made in time is bad input.
            sleeper = {"name": "python:python_planners:Sleeper", "params": {"in_constructor": True}}
            done, _ = run_campo("run", OPEN_FIELD, "--set", "/objects/drone/planner=" + json.dumps(sleeper),
                                "--out", "ctor", cwd=out, env=env)
            self.assertEqual(done.returncode, 2, done.stderr)
            self.assertRegex(done.stderr, r"^error: .*the constructor of python:python_planners:Sleeper did not "
                                          r"return within the per-call limit of 0.5 s")
            self.assertFalse(pathlib.Path(out, "ctor").exists())
            env["CAMPO_PYTHON_CALL_LIMIT_S"] = "soon"
            done, _ = run_campo("run", OPEN_FIELD, "--planner", "python:python_planners:GoStraight", "--out", "bad",
                                cwd=out, env=env)
            self.assertEqual(done.returncode, 2, done.stderr)
            self.assertIn('error: environment: CAMPO_PYTHON_CALL_LIMIT_S: expected a number of seconds >= 0 '
                          '(0: no limit), got "soon"', done.stderr)

    def test_the_per_call_limit_holds_in_a_sweeps_runs(self):
        # Each run is a process forked from the sweep's, which validated the planner first: the
        # watchdog must run in the child too (a sleeping planner hung the sweep until its own limit).
        with tempfile.TemporaryDirectory() as out:
            env = python_env()
            env["CAMPO_PYTHON_CALL_LIMIT_S"] = "0.5"
            spec = {"campo_sweep": 1, "name": "sleepy", "scenes": [OPEN_FIELD],
                    "planners": [{"name": "python:python_planners:Sleeper", "label": "sleeper"}],
                    "seeds": {"first": 0, "count": 2}}
            pathlib.Path(out, "spec.json").write_text(json.dumps(spec))
            done, seconds = run_campo("sweep", "spec.json", "--out", "sweep", "--jobs", "1", cwd=out, env=env)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertLess(seconds, 60)
            frame = campo.read_results(os.path.join(out, "sweep"))
            self.assertEqual(list(frame["outcome"]), ["failed", "failed"])
            for reason in frame["reason"]:
                self.assertIn("per-call limit of 0.5 s", reason)

    def test_whole_run_time_limit(self):
        with tempfile.TemporaryDirectory() as out:
            # campo run --time-limit: a planner sleeping forever (no per-call limit) is stopped at 1 s.
            env = python_env()
            env["CAMPO_PYTHON_CALL_LIMIT_S"] = "0"
            done, seconds = run_campo("run", OPEN_FIELD, "--planner", "python:python_planners:Sleeper",
                                      "--time-limit", "1", "--no-figures", "--out", "slept", cwd=out, env=env)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertLess(seconds, 30)
            record = json.loads(pathlib.Path(out, "slept", "run.json").read_text())
            self.assertEqual(record["metrics"]["outcome"], "failed")
            self.assertEqual(record["metrics"]["reason"],
                             "exceeded the wall-clock limit of 1 s for the whole run (--time-limit) and was stopped")
            self.assertIn("failed (exceeded the wall-clock limit of 1 s", done.stdout)
            # campo.run(time_limit_s=): the same, for a planner spinning in Python.
            record = campo.run(OPEN_FIELD, planner=python_planners.Spinner(), time_limit_s=0.5, call_limit_s=0)
            self.assertEqual(record["metrics"]["reason"],
                             "exceeded the wall-clock limit of 0.5 s for the whole run (time_limit_s) and was stopped")
            # A run within its limit is the same run, bit for bit.
            done, _ = run_campo("run", OPEN_FIELD, "--planner", "python:python_planners:GoStraight", "--no-figures",
                                "--out", "free", cwd=out)
            self.assertEqual(done.returncode, 0, done.stderr)
            done, _ = run_campo("run", OPEN_FIELD, "--planner", "python:python_planners:GoStraight", "--no-figures",
                                "--time-limit", "600", "--out", "limited", cwd=out)
            self.assertEqual(done.returncode, 0, done.stderr)
            free = json.loads(pathlib.Path(out, "free", "run.json").read_text())
            limited = json.loads(pathlib.Path(out, "limited", "run.json").read_text())
            self.assertEqual(free["metrics"]["outcome"], "reached")
            self.assertEqual(free["final_state_hash"], limited["final_state_hash"])
            self.assertEqual(pathlib.Path(out, "free", "trajectory.csv").read_bytes(),
                             pathlib.Path(out, "limited", "trajectory.csv").read_bytes())
            for bad in ["0", "-1", "nan", "inf"]:
                done, _ = run_campo("run", OPEN_FIELD, "--time-limit", bad, "--out", "bad", cwd=out)
                self.assertEqual(done.returncode, 2, done.stderr)
                self.assertIn("error: ", done.stderr)
                self.assertFalse(pathlib.Path(out, "bad").exists())

    def test_memory_growth_is_bounded(self):
        with tempfile.TemporaryDirectory() as out:
            env = python_env()
            env["CAMPO_PYTHON_MEMORY_LIMIT_MIB"] = "256"
            done, _ = run_campo("run", OPEN_FIELD, "--planner", "python:python_planners:Leaks", "--no-figures",
                                "--out", "leak", cwd=out, env=env)
            self.assertEqual(done.returncode, 0, done.stderr)
            record = json.loads(pathlib.Path(out, "leak", "run.json").read_text())
            self.assert_failed_by(record, "the process's resident memory grew by", "since "
                                  "python:python_planners:Leaks was made, past the limit of 256 MiB "
                                  "(CAMPO_PYTHON_MEMORY_LIMIT_MIB)")
            # 16 MiB a call: stopped after about 256 / 16 calls (the watchdog looks every 0.05 s).
            self.assertLess(record["metrics"]["planner_calls"], 60)

    def test_huge_decisions_are_thinned_before_they_are_copied(self):
        n, k = 1_000_000, 2048
        expected = [[float((i * (n - 1) + (k - 1) // 2) // (k - 1)), 0.0, 1.5] for i in range(k)]
        for as_numpy in (False, True):
            with self.subTest(numpy=as_numpy), tempfile.TemporaryDirectory() as out:
                planner = python_planners.HugeDecisions(n, as_numpy=as_numpy, calls=3)
                record = campo.run(OPEN_FIELD, planner=planner, out=os.path.join(out, "r"), figures=False)
                m = record["metrics"]
                self.assertEqual(m["outcome"], "aborted", m["reason"])
                # A million points converted cost 1.5 s a call; thinned first, a few milliseconds.
                self.assertLess(m["planner_time_ms_max"], 150)
                lines, events = read_events(os.path.join(out, "r"))
                self.assertEqual(len(events), 3)
                for line, event in zip(lines, events):
                    self.assertLessEqual(len(line), 256 << 10)
                    self.assertEqual(event["decisions"]["thinned"], {"/planned_path": n})
                    self.assertEqual(event["decisions"]["planned_path"], expected)

    def test_decisions_over_a_line_are_dropped_or_refused(self):
        class Blob(campo.Planner):
            def __init__(self, decisions):
                self.decisions = decisions
                self.calls = 0

            def plan(self, obs):
                self.calls += 1
                status = "aborted" if self.calls > 2 else "running"
                return campo.PlanResult(campo.Command.hold([0, 0, 1.5]), status=status, decisions=self.decisions)

        with tempfile.TemporaryDirectory() as out:
            # A decision that cannot fit a line is dropped unconverted, noted with a lower bound of its size.
            big = {"avoiding": True, "blob": "x" * 5_000_000}
            record = campo.run(OPEN_FIELD, planner=Blob(big), out=os.path.join(out, "drop"), figures=False)
            self.assertEqual(record["metrics"]["outcome"], "aborted", record["metrics"]["reason"])
            _, events = read_events(os.path.join(out, "drop"))
            self.assertEqual(events[0]["decisions"]["avoiding"], True)
            self.assertNotIn("blob", events[0]["decisions"])
            self.assertGreaterEqual(events[0]["decisions"]["omitted"]["blob"], 5_000_002)
            # Decisions too large in all, each small enough for a line: refused, the run failed.
            many = {"k%03d" % i: "y" * 200_000 for i in range(40)}
            record = campo.run(OPEN_FIELD, planner=Blob(many))
            self.assert_failed_by(record, "the planner's decisions hold more than 4 MiB of JSON")
            # Nesting has a bound too.
            deep = []
            for _ in range(150):
                deep = [deep]
            record = campo.run(OPEN_FIELD, planner=Blob({"deep": deep}))
            self.assert_failed_by(record, "nest lists and dicts deeper than 100 levels")

    def test_a_planner_that_exits_ends_its_run_not_campo(self):
        with tempfile.TemporaryDirectory() as out:
            for params, expected in [({"status": 3}, "called os._exit(3): campo ended the run as failed instead "
                                                     "of the process"),
                                     ({"status": 4, "use_sys": True}, "SystemExit: 4")]:
                with self.subTest(params=params):
                    name = "exit_%d" % params["status"]
                    planner = {"name": "python:python_planners:Exits", "params": params}
                    done, _ = run_campo("run", OPEN_FIELD, "--set", "/objects/drone/planner=" + json.dumps(planner),
                                        "--no-figures", "--out", name, cwd=out)
                    self.assertEqual(done.returncode, 0, done.stderr)  # a failed run is a run
                    record = json.loads(pathlib.Path(out, name, "run.json").read_text())
                    self.assert_failed_by(record, expected)
                    for file in ("events.jsonl", "trajectory.csv", "scene.json"):
                        self.assertTrue(pathlib.Path(out, name, file).is_file())
        # sys.exit inside campo.run: the run fails, the caller's process goes on.
        record = campo.run(OPEN_FIELD, planner=python_planners.Exits(status=5, use_sys=True))
        self.assert_failed_by(record, "SystemExit: 5")

    def test_the_embedded_interpreter_is_the_one_campo_was_built_against(self):
        with tempfile.TemporaryDirectory() as out:
            # Another Python first on the PATH, with its own prefix (as pyenv's or a virtual environment's),
            # and PYTHONHOME naming it: neither numpy nor even a standard library there.
            fake = pathlib.Path(out, "fake")
            (fake / "bin").mkdir(parents=True)
            lib = fake / "lib" / ("python%d.%d" % sys.version_info[:2])
            (lib / "lib-dynload").mkdir(parents=True)
            (lib / "os.py").write_text("raise SystemExit('the wrong Python')\n")
            python3 = fake / "bin" / "python3"
            python3.write_text("#!/bin/sh\necho the wrong Python >&2\nexit 1\n")
            python3.chmod(0o755)
            (fake / "bin" / "python").symlink_to("python3")
            for home in (False, True):
                with self.subTest(pythonhome=home):
                    env = python_env()
                    env["PATH"] = os.pathsep.join([str(fake / "bin"), env.get("PATH", "")])
                    if home:
                        env["PYTHONHOME"] = str(fake)
                    name = "home" if home else "path"
                    done, _ = run_campo("run", OPEN_FIELD, "--planner", "python:python_planners:GoStraight",
                                        "--no-figures", "--out", name, cwd=out, env=env)
                    self.assertEqual(done.returncode, 0, done.stderr)
                    record = json.loads(pathlib.Path(out, name, "run.json").read_text())
                    self.assertEqual(record["metrics"]["outcome"], "reached")


class ExamplesTest(unittest.TestCase):
    def run_example(self, *args, cwd=None):
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join([str(SOURCE_DIR / "examples" / "python"), env.get("PYTHONPATH", "")])
        return subprocess.run([sys.executable, *args], capture_output=True, text=True, timeout=600, env=env,
                              cwd=cwd or SOURCE_DIR)

    def test_random_walk_is_reproducible(self):
        with tempfile.TemporaryDirectory() as out:
            first = self.run_example("examples/python/random_walk.py", "--seed", "4", "--time-limit-s", "5",
                                     "--out", os.path.join(out, "a"))
            self.assertEqual(first.returncode, 0, first.stderr)
            second = self.run_example("examples/python/random_walk.py", "--seed", "4", "--time-limit-s", "5",
                                      "--out", os.path.join(out, "b"))
            a = json.loads(pathlib.Path(out, "a", "run.json").read_text())
            b = json.loads(pathlib.Path(out, "b", "run.json").read_text())
            self.assertEqual(a["final_state_hash"], b["final_state_hash"])
            self.assertEqual(a["metrics"]["planner_calls"], 300)  # 5 s at 60 Hz
            self.assertGreater(a["metrics"]["path_length_m"], 0.1)

    def test_potential_field_runs_and_sweeps(self):
        run = self.run_example("examples/python/potential_field.py", "--repulsion-gain", "1")
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("two_barriers:", run.stdout)
        with tempfile.TemporaryDirectory() as out:
            env = dict(os.environ)
            env["PYTHONPATH"] = os.pathsep.join([str(SOURCE_DIR / "examples" / "python"), env.get("PYTHONPATH", "")])
            sweep = subprocess.run([str(CAMPO), "sweep", str(SOURCE_DIR / "examples/python/potential_field_sweep.json"),
                                    "--out", out, "--jobs", "2"], capture_output=True, text=True, timeout=600,
                                   env=env, cwd=SOURCE_DIR)
            self.assertEqual(sweep.returncode, 0, sweep.stderr)
            frame = campo.read_results(out)
            self.assertEqual(len(frame), 6)
            self.assertEqual(sorted(frame["repulsion_gain"].unique()), [0.5, 1.0, 2.0])
            # A stronger field keeps the drone farther from the barrier.
            clearance = frame.groupby("repulsion_gain")["min_clearance_m"].mean()
            self.assertLess(clearance[0.5], clearance[2.0])


class EpisodeResetSeed(unittest.TestCase):
    def test_reset_with_a_seed_is_the_episode_made_with_that_seed(self):
        noisy = {"/objects/drone/sensors/0/noise_stddev_m": 0.05}

        def ranges(obs):
            return obs.sensors["scanner"].ranges_m

        reseeded = campo.Episode(OPEN_FIELD, seed=1, overrides=noisy).reset(seed=2)
        made_with = campo.Episode(OPEN_FIELD, seed=2, overrides=noisy).reset()
        other = campo.Episode(OPEN_FIELD, seed=1, overrides=noisy).reset()
        np.testing.assert_array_equal(ranges(reseeded), ranges(made_with))
        self.assertFalse(np.array_equal(ranges(reseeded), ranges(other)), "seed 1 draws other range noise")
        episode = campo.Episode(OPEN_FIELD, seed=1, overrides=noisy)
        episode.reset(seed=2)
        np.testing.assert_array_equal(ranges(episode.reset()), ranges(made_with), "the seed stays for the next runs")


class LowLevelCommandsTest(unittest.TestCase):
    """campo.Velocity, campo.AttitudeThrust, campo.Rotors (quadrotor) and campo.Wheels (rover) stepped through
    campo.Episode on the bundled scenes (docs/python.md, Commands)."""

    @staticmethod
    def hover_rotor_speed(scene):
        # The scene's drone has the preset airframe (no params): its rotors carry the weight m g at
        # 4 k_f w^2 = m g, with QuadrotorConfig's mass_kg 1.5 and thrust_coefficient 1e-5.
        path = campo.bundled_scene(scene)
        drone = next(o for o in json.loads(pathlib.Path(path).read_text())["objects"] if o["type"] == "quadrotor")
        assert "params" not in drone, "the preset airframe is assumed"
        return (1.5 * 9.81 / (4 * 1.0e-5)) ** 0.5

    def step_for(self, episode, command, seconds):
        obs = episode.observation
        start = obs.time_s
        while obs.time_s < start + seconds - 1e-9:
            obs, done, info = episode.step(command)
            self.assertFalse(done, info)
        return obs

    def test_commands_read_back_and_refuse_bad_values(self):
        v = campo.Velocity(velocity_mps=(1.0, 0.5, -0.2), yaw_rate_radps=0.3)
        self.assertIsInstance(v, campo.Command)
        self.assertEqual(v.kind, "velocity")
        self.assertEqual(v.velocity_mps, (1.0, 0.5, -0.2))
        self.assertEqual(v.yaw_rate_radps, 0.3)
        a = campo.AttitudeThrust(roll_rad=0.1, pitch_rad=-0.2, yaw_rate_radps=0.0, thrust_n=15.0)
        self.assertEqual((a.kind, a.roll_rad, a.pitch_rad, a.thrust_n), ("attitude_thrust", 0.1, -0.2, 15.0))
        self.assertEqual(campo.Rotors(np.full(4, 600.0)).speeds_radps, (600.0,) * 4)
        self.assertEqual(campo.Wheels(speeds_radps=[1, 2, 3, 4]).kind, "wheels")
        self.assertEqual(campo.Command.rotors([1, 2, 3, 4]).kind, "rotors")
        self.assertEqual(repr(campo.Wheels([1, 2, 3, 4])), "Wheels(speeds_radps=(1.0, 2.0, 3.0, 4.0))")
        with self.assertRaisesRegex(ValueError, r"^speeds_radps: expected 4 numbers, got 3$"):
            campo.Rotors([600, 600, 600])
        with self.assertRaisesRegex(ValueError, r"^speeds_radps: expected 4 finite numbers"):
            campo.Wheels([1, float("nan"), 1, 1])
        with self.assertRaisesRegex(ValueError, r"^thrust_n: expected a finite number, got inf$"):
            campo.AttitudeThrust(thrust_n=float("inf"))
        with self.assertRaisesRegex(ValueError, r"^velocity_mps: expected 3 finite numbers"):
            campo.Velocity([0, 0, float("nan")])

    def test_hover_rotor_speeds_hold_altitude_then_velocity_flies_forward(self):
        episode = campo.Episode("two_barriers")
        obs = episode.reset()
        start = np.array(obs.state.position_m)
        w = self.hover_rotor_speed("two_barriers")
        obs = self.step_for(episode, campo.Rotors([w] * 4), 3.0)
        # The rotors start at hover speed: thrust equals weight, it stays where it was.
        np.testing.assert_allclose(obs.state.position_m, start, atol=0.01)
        obs = self.step_for(episode, campo.Rotors([1.05 * w] * 4), 1.0)
        self.assertGreater(obs.state.position_m[2], start[2] + 0.2)  # 10 % more thrust: it climbs
        climbed = np.array(obs.state.position_m)
        # 1 m/s forward (the heading is +x), level: it gets there and keeps its height.
        obs = self.step_for(episode, campo.Velocity(velocity_mps=(1.0, 0.0, 0.0)), 4.0)
        np.testing.assert_allclose(obs.state.velocity_mps, [1.0, 0.0, 0.0], atol=0.1)
        self.assertGreater(obs.state.position_m[0], climbed[0] + 2.5)
        self.assertAlmostEqual(obs.state.position_m[2], climbed[2], delta=0.3)
        # Hold where it is afterwards: it stops.
        obs = self.step_for(episode, campo.Command.hold(obs.state.position_m), 6.0)
        self.assertLess(np.linalg.norm(obs.state.velocity_mps), 0.05)
        obs, done, info = episode.step(campo.Command.hold(obs.state.position_m))
        self.assertEqual(info["collisions"], 0)

    def test_attitude_thrust_pitch_accelerates_forward(self):
        episode = campo.Episode("two_barriers")
        episode.reset()
        pitch = 0.15
        obs = self.step_for(episode, campo.AttitudeThrust(pitch_rad=pitch, thrust_n=1.5 * 9.81 / np.cos(pitch)), 1.0)
        self.assertAlmostEqual(np.radians(obs.state.rpy_deg[1]), pitch, delta=0.01)
        self.assertGreater(obs.state.velocity_mps[0], 0.5)  # g tan(0.15) = 1.5 m/s^2, tilting took some of the second
        self.assertAlmostEqual(obs.state.velocity_mps[1], 0.0, delta=0.05)

    def test_wheels_drive_the_rover_forward(self):
        episode = campo.Episode("vineyard")
        obs = episode.reset()
        start = np.array(obs.state.position_m)
        heading = np.array([np.cos(obs.state.yaw_rad), np.sin(obs.state.yaw_rad)])
        # 3 rad/s on every wheel of radius 0.2 m (the preset): 0.6 m/s forward.
        obs = self.step_for(episode, campo.Wheels([3.0] * 4), 3.0)
        forward = np.dot(np.array(obs.state.velocity_mps[:2]), heading)
        self.assertAlmostEqual(forward, 0.6, delta=0.05)
        self.assertGreater(np.dot(np.array(obs.state.position_m[:2]) - start[:2], heading), 1.2)
        # Left wheels slower than the right: it turns left (counter-clockwise).
        obs = self.step_for(episode, campo.Wheels([2.0, 4.0, 2.0, 4.0]), 1.0)
        self.assertGreater(obs.state.angular_velocity_radps[2], 0.05)

    def test_each_vehicle_refuses_the_others_commands(self):
        drone = campo.Episode("two_barriers")
        drone.reset()
        with self.assertRaisesRegex(ValueError, "wheels"):
            drone.step(campo.Wheels([1.0] * 4))
        rover = campo.Episode("vineyard")
        rover.reset()
        for command in (campo.Rotors([600.0] * 4), campo.Velocity((1.0, 0.0, 0.0)), campo.AttitudeThrust(thrust_n=10)):
            with self.assertRaisesRegex(ValueError, command.kind):
                rover.step(command)

    def test_trajectory_records_the_command_values(self):
        episode = campo.Episode("two_barriers")
        episode.reset()
        w = self.hover_rotor_speed("two_barriers")
        self.step_for(episode, campo.Rotors([w] * 4), 0.1)
        self.step_for(episode, campo.Velocity((0.5, 0.0, 0.0), yaw_rate_radps=0.1), 0.1)
        # The run ends (a planner's "aborted") so that it can be written.
        episode.step(campo.PlanResult(campo.Velocity((0.5, 0.0, 0.0), yaw_rate_radps=0.1), status="aborted",
                                      reason="enough"))
        self.assertTrue(episode.done)
        with tempfile.TemporaryDirectory() as out:
            episode.write(out, figures=False)
            run = campo.read_run(out)
            t = run.trajectory
            rotors = t[t["command"] == "rotors"]
            velocity = t[t["command"] == "velocity"]
            self.assertGreater(len(rotors), 0)
            self.assertGreater(len(velocity), 0)
            np.testing.assert_allclose(rotors["cmd_rotor_2_radps"], w)
            np.testing.assert_allclose(velocity["cmd_forward_mps"], 0.5)
            np.testing.assert_allclose(velocity["cmd_yaw_rate_radps"], 0.1)
            self.assertTrue(np.isnan(rotors["cmd_forward_mps"]).all())
            self.assertNotIn("cmd_thrust_n", t.columns)  # no attitude_thrust in this run


CAMERA_FIELD = str(FIXTURES / "camera_field.json")


class ColourCameraTest(unittest.TestCase):
    def test_images_are_zero_copy_views_kept_alive_by_their_base(self):
        episode = campo.Episode(CAMERA_FIELD, seed=1)
        obs = episode.reset()
        self.assertEqual(list(obs.images), ["front"])
        image = obs.images["front"]
        self.assertEqual(image.shape, (24, 32, 3))  # resolution [cols, rows] = [32, 24]
        self.assertEqual(image.dtype, np.uint8)
        self.assertFalse(image.flags.owndata)
        self.assertFalse(image.flags.writeable)
        self.assertIsNotNone(image.base)
        # The sky along the top row, exactly the configured colour; the red box ahead and left.
        np.testing.assert_array_equal(image[0, 16], [round(0.2 * 255), round(0.4 * 255), round(0.8 * 255)])
        red = (image[..., 0].astype(int) > 2 * image[..., 1]) & (image[..., 0].astype(int) > 2 * image[..., 2])
        self.assertGreater(int(red[:, :16].sum()), 5)
        self.assertEqual(int(red[:, 16:].sum()), 0)
        # Another observation's array shares the camera's buffer; the images follow the camera.
        self.assertTrue(np.shares_memory(image, episode.observation.images["front"]))
        kept = image.copy()
        for _ in range(60):  # climb 3 m over 1 s: the next images see the ground from higher up
            obs, done, info = episode.step(campo.Command.altitude(4.5))
        self.assertTrue(np.shares_memory(image, obs.images["front"]))
        self.assertFalse(np.array_equal(image, kept))
        # The array outlives its episode: its base keeps the buffer alive.
        del obs, episode
        import gc
        gc.collect()
        self.assertEqual(image.shape, (24, 32, 3))
        self.assertEqual(int(image.astype(np.int64).sum()), int(image.astype(np.int64).sum()))
        np.testing.assert_array_equal(image[0, 16], [round(0.2 * 255), round(0.4 * 255), round(0.8 * 255)])


if __name__ == "__main__":
    unittest.main()
