"""A random-walk agent stepping a campo.Episode from Python, Gymnasium-style.

Every second (60 control ticks) it picks a point step_m from where the
quadrotor is, in a random direction at the mission's height, from a seeded
numpy generator, so the same seed walks the same walk; the run's metrics
and files are those of `campo run`.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/random_walk.py --seed 3 --out out/walk
"""
import argparse

import numpy as np

import campo


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="two_barriers")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--step-m", type=float, default=1.5, help="how far each random target lies")
    parser.add_argument("--time-limit-s", type=float, default=20.0)
    parser.add_argument("--out", help="run directory to write once the episode ends")
    args = parser.parse_args()

    rng = np.random.default_rng(args.seed)
    episode = campo.Episode(args.scene, seed=args.seed, overrides={"/world/time_limit_s": args.time_limit_s})
    obs = episode.reset()
    height_m = obs.mission_m[-1][2]
    steps = 0
    done = False
    while not done:
        if steps % 60 == 0:  # a new target every second
            heading = rng.uniform(-np.pi, np.pi)
            target = obs.state.position_m + args.step_m * np.array([np.cos(heading), np.sin(heading), 0.0])
            target[2] = height_m
        obs, done, info = episode.step(campo.Command.go_to(target, speed_mps=1.0))
        steps += 1
    metrics = episode.metrics()
    print("%d steps: %s (%s), path %.2f m, min clearance %.2f m" % (
        steps, metrics["outcome"], metrics["reason"], metrics["path_length_m"], metrics["min_clearance_m"]))
    if args.out:
        episode.write(args.out)
        print("wrote", args.out)


if __name__ == "__main__":
    main()
