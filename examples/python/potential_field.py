"""A potential-field planner written in Python, run in campo's C++ closed loop.

The goal attracts with unit strength; every LIDAR hit within influence_m
repels with repulsion_gain * (1/d - 1/influence_m) / d^2 (Khatib's field),
horizontally, so the quadrotor steers round obstacles at its flight height.
A vortex term (the repulsion turned 90 degrees left, times vortex_gain)
slides it along an obstacle instead of stopping in the field's local
minimum in front of it. The command is a go_to one lookahead_m along the
field's direction.

Run it on a bundled scene, or sweep it over a parameter with campo sweep:

    PYTHONPATH=build/python:examples/python /usr/bin/python3 examples/python/potential_field.py --out out/pf
    PYTHONPATH=build/python:examples/python build/campo sweep examples/python/potential_field_sweep.json --out out/pf_sweep
"""
import argparse

import numpy as np

import campo


class PotentialField(campo.Planner):
    vehicles = ("quadrotor",)

    def __init__(self, repulsion_gain=1.0, vortex_gain=1.0, influence_m=2.5, speed_mps=0.8, lookahead_m=1.0,
                 arrival_m=0.4, sensor="scanner"):
        if influence_m <= 0 or lookahead_m <= 0 or speed_mps <= 0:
            raise ValueError("influence_m, lookahead_m and speed_mps must be > 0")
        self.repulsion_gain = float(repulsion_gain)
        self.vortex_gain = float(vortex_gain)
        self.influence_m = float(influence_m)
        self.speed_mps = float(speed_mps)
        self.lookahead_m = float(lookahead_m)
        self.arrival_m = float(arrival_m)
        self.sensor = sensor
        self.next_waypoint = 0

    def parameters(self):
        return {"repulsion_gain": self.repulsion_gain, "vortex_gain": self.vortex_gain, "influence_m": self.influence_m,
                "speed_mps": self.speed_mps, "lookahead_m": self.lookahead_m,
                "arrival_m": self.arrival_m, "sensor": self.sensor}

    def plan(self, obs):
        position = obs.state.position_m
        mission = obs.mission_m
        reached = []
        while (self.next_waypoint < len(mission)
               and np.linalg.norm(mission[self.next_waypoint] - position) < self.arrival_m):
            reached.append(self.next_waypoint)
            self.next_waypoint += 1
        decisions = {"reached_waypoints": reached} if reached else None
        if self.next_waypoint == len(mission):
            return campo.PlanResult(campo.Command.hold(position), status="reached",
                                    reason="every waypoint within %.2f m" % self.arrival_m, decisions=decisions)
        goal = mission[self.next_waypoint]
        to_goal = goal - position
        force = to_goal / max(np.linalg.norm(to_goal), 1e-9)
        reading = obs.sensors.get(self.sensor)
        if reading is not None:
            points = reading.points_m.astype(np.float64)
            # Obstacles at flight height only: the ground under the vehicle repels nothing.
            points = points[np.abs(points[:, 2] - position[2]) < 0.5]
            offsets = position[:2] - points[:, :2]
            distances = np.linalg.norm(offsets, axis=1)
            near = (distances < self.influence_m) & (distances > 1e-6)
            if near.any():
                d = distances[near]
                magnitude = self.repulsion_gain * (1.0 / d - 1.0 / self.influence_m) / d ** 2
                repulsion = np.zeros(3)
                repulsion[:2] = (offsets[near] / d[:, None] * magnitude[:, None]).sum(axis=0) / near.sum()
                vortex = self.vortex_gain * np.array([-repulsion[1], repulsion[0], 0.0])
                force = force + repulsion + vortex
        direction = force / max(np.linalg.norm(force), 1e-9)
        step = min(self.lookahead_m, np.linalg.norm(to_goal))
        target = position + direction * step
        target[2] = goal[2]
        return campo.PlanResult(campo.Command.go_to(target, speed_mps=self.speed_mps, face_target=True),
                                decisions=decisions)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="two_barriers")
    parser.add_argument("--repulsion-gain", type=float, default=1.0)
    parser.add_argument("--vortex-gain", type=float, default=1.0)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", help="run directory to write (run.json, trajectory.csv, figures)")
    args = parser.parse_args()
    record = campo.run(args.scene, planner=PotentialField(repulsion_gain=args.repulsion_gain,
                                                                  vortex_gain=args.vortex_gain), out=args.out,
                       seed=args.seed,
                       overrides={"/objects/drone/sensors/scanner/resolution": [32, 32]})
    m = record["metrics"]
    print("%s: %s (%s), path %.2f m, ratio %.3f, min clearance %.2f m, %d planner calls, %.3f ms per call" % (
        args.scene, m["outcome"], m["reason"], m["path_length_m"], m["path_ratio"], m["min_clearance_m"],
        m["planner_calls"], m["planner_time_ms_mean"]))


if __name__ == "__main__":
    main()
