"""Learns to fly a quadrotor through a small forest, with numpy alone (the cross-entropy method).

The drone of small_forest.json (beside this file) flies 16 m east through 21 trees in a fenced
corridor, their layout drawn from the forest generator's seed. The policy is linear (through tanh;
--hidden adds a hidden layer) over compact features: the goal's direction and distance in the body
frame, the body velocity, and the 48 x 4 LIDAR scan over 180 degrees reduced to 8 sectors' nearest
ranges. It gives the forward and left speeds of
campo.gym's "velocity" action (each in [-1, 1]). The other two are not learned: the yaw rate is 0
(the drone keeps facing east, its LIDAR covering the half-space ahead) and the up speed is a fixed
proportional law holding the goal's height, so that the policy must find its way between the
trunks rather than over the trees (a first version that learned all four flew over the forest).
Results and run time: examples/python/README.md.

The learner is the cross-entropy method: each generation samples a population of parameter
vectors from a diagonal Gaussian, scores each by its mean return over a few forests drawn for
that generation (the same forests for every candidate), and refits the Gaussian to the best
fifth. Candidates fly side by side in campo.gym's vector environment, stepped in C++ threads.
Training forests are drawn from generator seeds below HELD_OUT_SEED; the learned policy is
evaluated at the end on forests from HELD_OUT_SEED up, which it never saw, against a baseline
that flies straight at the goal.

    PYTHONPATH=build/python:../shared/vendor/python /usr/bin/python3 examples/python/learn_forest_flight.py --out out/learn
    ... learn_forest_flight.py --quick --out /tmp/learn_quick     # a smoke run: 2 generations, 4 candidates

Writes into --out: learning_curve.png, flight.mp4 (the learned policy on a held-out forest),
policy.npz and summary.json. Deterministic for a given --seed (the episodes are: the scene has no
noise, and every draw comes from one numpy generator seeded by --seed).
"""

from __future__ import annotations

import argparse
import datetime
import json
import pathlib
import time

import numpy as np

import campo.gym

SCENE = str(pathlib.Path(__file__).resolve().parent / "small_forest.json")
SENSOR = "scanner_ranges_m"
#: Forest generator seeds >= this are kept for the final evaluation; training draws below it.
HELD_OUT_SEED = 1_000_000
#: The forest's seed, by JSON pointer (the objects array addressed by alias).
FOREST_SEED = "/objects/forest/seed"

SECTORS = 8               # LIDAR columns grouped into this many azimuth sectors
NEAR_M = 4.0              # a sector's proximity feature: 1 at contact, 0 from this range on
GOAL_FAR_M = 5.0          # the goal distance feature saturates here
MAX_SPEED_MPS = 2.0       # a full velocity action
ELITE_FRACTION = 0.2
INITIAL_STD = 0.5
EXTRA_STD = 0.02          # added to the refitted standard deviation so the search does not collapse


def features(obs: dict) -> np.ndarray:
    """The policy's inputs, one row per environment, from a batched observation (n x ...)."""
    goal = np.asarray(obs["goal_body_m"], dtype=np.float64).reshape(-1, 3)
    velocity = np.asarray(obs["velocity_body_mps"], dtype=np.float64).reshape(-1, 3)
    ranges = np.asarray(obs[SENSOR], dtype=np.float64)
    ranges = ranges.reshape(goal.shape[0], -1, ranges.shape[-1])
    distance = np.linalg.norm(goal, axis=1, keepdims=True)
    direction = goal / np.maximum(distance, 1e-6)
    # Nearest range per azimuth sector (over every row), left to right as the beams are ordered.
    nearest = ranges.min(axis=1).reshape(goal.shape[0], SECTORS, -1).min(axis=2)
    proximity = np.clip(1.0 - nearest / NEAR_M, 0.0, 1.0)
    return np.hstack([direction, np.minimum(distance, GOAL_FAR_M) / GOAL_FAR_M, velocity / MAX_SPEED_MPS, proximity,
                      np.ones((goal.shape[0], 1))])


FEATURES = 3 + 1 + 3 + SECTORS + 1
ACTIONS = 2               # learned: forward, left
HEIGHT_GAIN_PER_S = 0.5   # up action per metre the goal lies above (a full action is MAX_SPEED_MPS)


def velocity_action(learned: np.ndarray, obs: dict) -> np.ndarray:
    """campo.gym's velocity action (forward, left, up, yaw rate) from the learned two, the height law and no yaw."""
    goal = np.asarray(obs["goal_body_m"], dtype=np.float64).reshape(-1, 3)
    up = np.clip(HEIGHT_GAIN_PER_S * world_height(goal, obs["orientation_wxyz"])[:, None], -1.0, 1.0)
    return np.hstack([learned, up, np.zeros_like(up)])


def world_height(v_body: np.ndarray, q_wxyz) -> np.ndarray:
    """The world z of body-frame vectors (n x 3) under body-to-world unit quaternions (n x 4): the third row
    of the rotation matrix, so that the drone's pitch does not read as the goal lying above or below."""
    w, x, y, z = np.asarray(q_wxyz, dtype=np.float64).reshape(-1, 4).T
    row = np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=1)
    return (row * v_body).sum(axis=1)


class Policy:
    """tanh(W2 tanh(W1 x)) with a bias feature in x and a bias unit in the hidden layer; W1 alone if hidden == 0."""

    def __init__(self, hidden: int):
        self.hidden = hidden
        self.shapes = [(ACTIONS, FEATURES)] if hidden == 0 else [(hidden, FEATURES), (ACTIONS, hidden + 1)]
        self.size = sum(r * c for r, c in self.shapes)

    def unpack(self, theta: np.ndarray) -> list[np.ndarray]:
        out, at = [], 0
        for rows, cols in self.shapes:
            out.append(theta[at:at + rows * cols].reshape(rows, cols))
            at += rows * cols
        return out

    def act(self, thetas: np.ndarray, x: np.ndarray) -> np.ndarray:
        """Actions for rows of features x, row i by parameters thetas[i]."""
        actions = np.empty((x.shape[0], ACTIONS))
        for i in range(x.shape[0]):
            layers = self.unpack(thetas[i])
            h = x[i]
            if self.hidden:
                h = np.append(np.tanh(layers[0] @ h), 1.0)
            actions[i] = np.tanh(layers[-1] @ h)
        return actions


def straight_to_goal(obs: dict) -> np.ndarray:
    """The baseline: full speed straight at the goal, heading held (no look at the LIDAR)."""
    goal = np.asarray(obs["goal_body_m"], dtype=np.float64).reshape(-1, 3)
    direction = goal / np.maximum(np.linalg.norm(goal, axis=1, keepdims=True), 1e-6)
    return np.hstack([direction, np.zeros((goal.shape[0], 1))])


def rollout_batch(envs, act, forest_seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Returns and goal-reached flags of one episode per environment, all in the forest of forest_seed.

    act(obs) gives the batch's actions. An environment that has ended is given a zero action (hover)
    until the last one ends; its autoreset episode is not counted."""
    obs, _ = envs.reset(seed=0, options={"overrides": {FOREST_SEED: int(forest_seed)}})
    n = envs.num_envs
    returns = np.zeros(n)
    reached = np.zeros(n, dtype=bool)
    done = np.zeros(n, dtype=bool)
    while not done.all():
        actions = act(obs)
        actions[done] = 0.0
        obs, rewards, terminated, truncated, info = envs.step(actions.astype(np.float32))
        live = ~done
        returns[live] += rewards[live]
        reached[live] |= info["reached"][live]
        done |= (terminated | truncated) & live
    return returns, reached


def evaluate(envs, policy: Policy, thetas: np.ndarray, forest_seeds) -> tuple[np.ndarray, np.ndarray]:
    """Returns and reached flags, candidates x forests, flown in chunks of the vector environment's size."""
    count, n = thetas.shape[0], envs.num_envs
    returns = np.zeros((count, len(forest_seeds)))
    reached = np.zeros((count, len(forest_seeds)), dtype=bool)
    for start in range(0, count, n):
        chunk = thetas[start:start + n]
        padded = np.vstack([chunk, np.repeat(chunk[-1:], n - len(chunk), axis=0)])  # the last chunk filled up
        for k, forest in enumerate(forest_seeds):
            r, g = rollout_batch(envs, lambda obs: velocity_action(policy.act(padded, features(obs)), obs), forest)
            returns[start:start + len(chunk), k] = r[:len(chunk)]
            reached[start:start + len(chunk), k] = g[:len(chunk)]
    return returns, reached


def evaluate_controller(envs, act, forest_seeds) -> tuple[np.ndarray, np.ndarray]:
    """One controller over many forests, one episode each (a batch per forest, its first environment counted)."""
    returns, reached = [], []
    for forest in forest_seeds:
        r, g = rollout_batch(envs, act, forest)
        returns.append(r[0])
        reached.append(g[0])
    return np.array(returns), np.array(reached)


def fly_video(policy: Policy, theta: np.ndarray, forest_seed: int, path: pathlib.Path, max_frames: int,
              size: tuple[int, int]) -> dict:
    """Flies the policy once in a single rendering environment and writes the frames as a video."""
    env = campo.gym.NavigationEnv(SCENE, action_mode="velocity", render_mode="rgb_array", render_size=size,
                                  max_speed_mps=MAX_SPEED_MPS)
    obs, _ = env.reset(seed=0, options={"overrides": {FOREST_SEED: int(forest_seed)}})
    frames = [env.render()]
    total, info = 0.0, {}
    while len(frames) < max_frames:
        action = velocity_action(policy.act(theta[None, :], features(obs)), obs)[0]
        obs, reward, terminated, truncated, info = env.step(action.astype(np.float32))
        total += reward
        frames.append(env.render())
        if terminated or truncated:
            break
    fps = env.metadata["render_fps"]
    campo.gym.save_video(frames, path, fps)
    return {"forest_seed": forest_seed, "frames": len(frames), "fps": fps, "return": total,
            "outcome": info.get("outcome"), "time_s": info.get("time_s")}


def plot_curve(history: list[dict], held_out: dict, path: pathlib.Path, title: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    gen = [h["generation"] for h in history]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=[3, 2])
    top.plot(gen, [h["best_return"] for h in history], "o-", ms=3, label="best candidate")
    top.plot(gen, [h["mean_policy_return"] for h in history], "s-", ms=3, label="distribution mean (the policy kept)")
    top.plot(gen, [h["mean_return"] for h in history], ".-", label="population mean")
    top.set_ylabel("return per episode\n(m of progress + goal - collision - time)")
    top.grid(alpha=0.3)
    top.legend(loc="lower right", fontsize=8)
    bottom.plot(gen, [100 * h["population_success"] for h in history], ".-", label="population")
    bottom.plot(gen, [100 * h["mean_policy_success"] for h in history], "s-", ms=3, label="distribution mean")
    for key, style, label in (("success_fraction", "-", "learned policy"), ("baseline_success_fraction", ":",
                                                                             "straight to the goal")):
        bottom.axhline(100 * held_out[key], color="0.3", ls=style, lw=1.2,
                       label=f"{label}, {held_out['episodes']} held-out forests: {100 * held_out[key]:.0f} %")
    bottom.set_ylabel("goal reached (%)")
    bottom.set_ylim(-5, 130)  # room for the legend above 100 %
    bottom.set_xlabel("generation (each on forests drawn for it)")
    bottom.grid(alpha=0.3)
    bottom.legend(loc="upper left", fontsize=7, ncol=2)
    top.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--generations", type=int, default=40)
    parser.add_argument("--population", type=int, default=32, help="candidates per generation")
    parser.add_argument("--forests", type=int, default=6, help="training forests per generation")
    parser.add_argument("--eval-forests", type=int, default=100, help="held-out forests of the final evaluation")
    parser.add_argument("--hidden", type=int, default=0, help="hidden units (0: a linear policy, the default)")
    parser.add_argument("--seed", type=int, default=0, help="seeds the learner and the forests drawn for training")
    parser.add_argument("--num-envs", type=int, default=0,
                        help="environments stepped together (default: population + 1, the distribution mean included)")
    parser.add_argument("--num-threads", type=int, default=0, help="C++ worker threads (default: the machine's cores)")
    parser.add_argument("--out", type=pathlib.Path, default=None,
                        help="output folder (default: learn_forest_flight_<UTC time> here)")
    parser.add_argument("--quick", action="store_true",
                        help="a smoke run: 2 generations of 4 candidates on 2 forests, 4 held-out forests, a short video")
    args = parser.parse_args(argv)
    max_frames, render_size = 400, (480, 360)
    if args.quick:
        args.generations, args.population, args.forests, args.eval_forests = 2, 4, 2, 4
        max_frames, render_size = 20, (240, 180)
    if args.population < 2 or args.generations < 1 or args.forests < 1 or args.eval_forests < 1:
        parser.error("--population >= 2, --generations, --forests and --eval-forests >= 1")
    out = args.out or pathlib.Path(f"learn_forest_flight_{datetime.datetime.now(datetime.timezone.utc):%Y%m%dT%H%M%SZ}")
    out.mkdir(parents=True, exist_ok=True)

    rng = np.random.default_rng(args.seed)
    policy = Policy(args.hidden)
    num_envs = args.num_envs or args.population + 1
    envs = campo.gym.make_vec("campo/Navigate-v0", num_envs=num_envs, scene=SCENE, action_mode="velocity",
                              max_speed_mps=MAX_SPEED_MPS, num_threads=args.num_threads)
    elites = max(2, int(round(ELITE_FRACTION * args.population)))
    print(f"{policy.size} parameters ({FEATURES} features, {args.hidden} hidden, {ACTIONS} actions); "
          f"{args.population} candidates x {args.forests} forests per generation; "
          f"{num_envs} environments on {envs.num_threads} threads", flush=True)

    mean = np.zeros(policy.size)
    std = np.full(policy.size, INITIAL_STD)
    history, episodes, steps_s = [], 0, time.perf_counter()
    started = time.perf_counter()
    for generation in range(1, args.generations + 1):
        forests = rng.integers(0, HELD_OUT_SEED, size=args.forests)
        candidates = mean + std * rng.standard_normal((args.population, policy.size))
        # The distribution mean flies too (last row), for the curve of the policy that will be kept.
        returns, reached = evaluate(envs, policy, np.vstack([candidates, mean]), forests)
        episodes += returns.size
        fitness = returns[:-1].mean(axis=1)
        order = np.argsort(-fitness, kind="stable")
        elite = candidates[order[:elites]]
        record = {"generation": generation, "mean_return": float(fitness.mean()), "best_return": float(fitness[order[0]]),
                  "mean_policy_return": float(returns[-1].mean()), "population_success": float(reached[:-1].mean()),
                  "best_success": float(reached[order[0]].mean()), "mean_policy_success": float(reached[-1].mean()),
                  "forests": [int(f) for f in forests], "elapsed_s": time.perf_counter() - started}
        history.append(record)
        mean = elite.mean(axis=0)
        std = elite.std(axis=0) + EXTRA_STD
        print(f"generation {generation:3d}: return mean {record['mean_return']:7.2f} best {record['best_return']:7.2f} "
              f"policy {record['mean_policy_return']:7.2f} | reached: population {100 * record['population_success']:5.1f} % "
              f"policy {100 * record['mean_policy_success']:5.1f} % | {record['elapsed_s']:6.1f} s", flush=True)
    train_s = time.perf_counter() - started

    # Held-out forests: the learned policy (the final distribution mean) and the straight-to-goal baseline.
    # One forest per batch, so a vector environment of one: the forests differ, the batch's cannot.
    held_out = [HELD_OUT_SEED + i for i in range(args.eval_forests)]
    single = campo.gym.make_vec("campo/Navigate-v0", num_envs=1, scene=SCENE, action_mode="velocity",
                                max_speed_mps=MAX_SPEED_MPS, num_threads=1)
    learned_returns, learned_reached = evaluate_controller(
        single, lambda obs: velocity_action(policy.act(mean[None, :], features(obs)), obs), held_out)
    base_returns, base_reached = evaluate_controller(single, straight_to_goal, held_out)
    print(f"held-out forests ({len(held_out)}): learned policy reached the goal in {learned_reached.mean():.0%} "
          f"(mean return {learned_returns.mean():.2f}), straight to the goal in {base_reached.mean():.0%} "
          f"(mean return {base_returns.mean():.2f})", flush=True)

    held_out_summary = {"forest_seeds": [held_out[0], held_out[-1]], "episodes": len(held_out),
                        "success_fraction": float(learned_reached.mean()), "mean_return": float(learned_returns.mean()),
                        "baseline": "straight_to_goal", "baseline_success_fraction": float(base_reached.mean()),
                        "baseline_mean_return": float(base_returns.mean())}
    shown = held_out[int(np.argmax(learned_reached))] if learned_reached.any() else held_out[0]
    video = fly_video(policy, mean, shown, out / "flight.mp4", max_frames, render_size)
    np.savez(out / "policy.npz", theta=mean, std=std, hidden=args.hidden, sectors=SECTORS, near_m=NEAR_M,
             goal_far_m=GOAL_FAR_M, max_speed_mps=MAX_SPEED_MPS, scene=SCENE)
    plot_curve(history, held_out_summary, out / "learning_curve.png",
               f"Cross-entropy method, small forest: {args.population} candidates x {args.forests} forests "
               f"per generation (seed {args.seed})")
    summary = {
        "scene": SCENE, "learner": "cross-entropy method", "policy_parameters": policy.size, "hidden_units": args.hidden,
        "generations": args.generations, "population": args.population, "forests_per_generation": args.forests,
        "seed": args.seed, "num_envs": num_envs, "num_threads": envs.num_threads, "quick": args.quick,
        "evaluations": int(episodes), "wall_time_s": time.perf_counter() - started, "train_time_s": train_s,
        "held_out": held_out_summary,
        "video": video, "history": history,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    print(f"wrote {out}/learning_curve.png, flight.mp4 ({video['outcome']} after {video['frames']} frames), "
          f"policy.npz, summary.json in {summary['wall_time_s']:.0f} s", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
