"""campo.gym's vector environment: environment steps per second (docs/PERFORMANCE.md, "Vector environments").

    PYTHONPATH=build/python:../shared/vendor/python /usr/bin/python3 bench/python/vector_env_throughput.py \
        [--json out.json] [--quick]

For each LIDAR resolution and each number of environments N, three ways of
stepping the same N episodes with the same actions:

  vector     campo.gym.NavigationVectorEnv, num_threads = the cores this process may run on
  vector_1   the same with num_threads=1: the single-thread rate of the same C++ code
  loop       a Python loop over N campo.gym.NavigationEnv, autoreset by hand as the vector
             environment does (Gymnasium's next-step mode), no batching of observations

A rate is environment steps (summed over the N environments) per wall second.
Every environment is seeded (vector: reset(seed=s) seeds environment i with s + i;
loop: reset(seed=s + i)) and every variant gets the same actions, drawn once
from a seeded numpy generator, so the three do the same simulated work; the
script checks that by comparing each environment's summed reward and episode
ends across the variants (bit for bit: distinct environments share nothing).
Episodes that end (a collision, the goal, the time limit) are reset at the next
step, which counts as a step as in Gymnasium: resets are part of the cost and
their number is reported. The variants are interleaved round by round, each
round starting with the next one, so a burst of load on the machine falls on
all three rather than on one, and none always runs first after an idle wait.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time

import numpy as np

import campo
import campo.gym

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
SCENE = "trees_rolling_terrain"
VEHICLE = "drone"
SENSOR = "scanner"
# The scanner's [cols, rows] (docs/scene-format.md, "Sensors").
RESOLUTION_POINTER = f"/objects/{VEHICLE}/sensors/{SENSOR}/resolution"
SEED = 0
ACTION_SEED = 12345


CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def machine_busy_s() -> tuple[float, float]:
    """Seconds of CPU time the whole machine has spent busy, and stolen by the hypervisor (/proc/stat)."""
    fields = [int(x) for x in pathlib.Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]]
    user, nice, system, _idle, _iowait, irq, softirq, steal = fields[:8]
    return (user + nice + system + irq + softirq) / CLOCK_TICKS, steal / CLOCK_TICKS


class Usage:
    """Over an interval: the cores this process used and the cores the rest of the machine used.
    A measurement disturbed by other work shows other_cores > 0 (on two cores, the 2-thread
    variant can only gain where other_cores stays near 0)."""

    def __enter__(self):
        self.wall = time.perf_counter()
        times = os.times()
        self.own = times.user + times.system
        self.busy, self.steal = machine_busy_s()
        return self

    def __exit__(self, *exc):
        wall = time.perf_counter() - self.wall
        times = os.times()
        busy, steal = machine_busy_s()
        own = times.user + times.system - self.own
        self.wall_s = wall
        self.own_cores = own / wall
        self.other_cores = max(0.0, (busy - self.busy) - own) / wall
        self.steal_cores = (steal - self.steal) / wall
        return False


def wait_quiet(max_other_cores, max_wait_s, probe_s=3.0) -> float:
    """Waits (at most max_wait_s) until the rest of the machine used under max_other_cores over probe_s;
    returns the last probe's figure."""
    deadline = time.monotonic() + max_wait_s
    while True:
        with Usage() as u:
            time.sleep(probe_s)
        if u.other_cores < max_other_cores or time.monotonic() > deadline:
            return u.other_cores
        print(f"# waiting: the rest of the machine uses {u.other_cores:.2f} cores", file=sys.stderr, flush=True)


def cores() -> int:
    """The cores this process may run on (what `nproc` prints)."""
    return len(os.sched_getaffinity(0))


def cpu_model() -> str:
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def git_revision() -> dict:
    def git(*args):
        out = subprocess.run(["git", "-C", str(SOURCE_DIR), *args], capture_output=True, text=True)
        return out.stdout.strip() if out.returncode == 0 else None

    status = git("status", "--porcelain", "--untracked-files=no")
    return {"revision": git("rev-parse", "HEAD"), "dirty": None if status is None else bool(status)}


def provenance(argv) -> dict:
    return {
        "machine": {"nproc": cores(), "cpu_model": cpu_model(), "platform": platform.platform(),
                    "hostname": platform.node()},
        "date_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "git": git_revision(),
        "command": " ".join([sys.executable, os.path.relpath(os.path.abspath(sys.argv[0]), SOURCE_DIR)] + argv),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "campo_module": campo.__file__,
        "loadavg_at_start": os.getloadavg(),
    }


class Vector:
    """NavigationVectorEnv: one call steps the N environments in the worker threads."""

    def __init__(self, num_envs, threads, overrides, action_mode):
        self.env = campo.gym.NavigationVectorEnv(SCENE, num_envs=num_envs, num_threads=threads, vehicle=VEHICLE,
                                                 action_mode=action_mode, overrides=overrides)
        self.threads = self.env.num_threads
        self.totals = np.zeros(num_envs)
        self.ends = np.zeros(num_envs, dtype=np.int64)

    def reset(self, seed):
        self.env.reset(seed=seed)

    def step(self, actions):
        _, rewards, terminated, truncated, _ = self.env.step(actions)
        self.totals += rewards
        self.ends += terminated | truncated


class Loop:
    """N NavigationEnvs stepped one after the other from Python, reset the step after their episode ended."""

    def __init__(self, num_envs, overrides, action_mode):
        self.envs = [campo.gym.NavigationEnv(SCENE, vehicle=VEHICLE, action_mode=action_mode, overrides=overrides)
                     for _ in range(num_envs)]
        self.threads = 1
        self.ended = [False] * num_envs
        self.totals = np.zeros(num_envs)
        self.ends = np.zeros(num_envs, dtype=np.int64)

    def reset(self, seed):
        for i, env in enumerate(self.envs):
            env.reset(seed=seed + i)
        self.ended = [False] * len(self.envs)

    def step(self, actions):
        for i, env in enumerate(self.envs):
            if self.ended[i]:
                env.reset()
                self.ended[i] = False
                self.totals[i] += 0.0  # as the vector environment's reset step: reward 0
                continue
            _, reward, terminated, truncated, _ = env.step(actions[i])
            self.totals[i] += reward
            if terminated or truncated:
                self.ended[i] = True
                self.ends[i] += 1


def measure_reset_s(overrides, action_mode, count) -> float:
    """Median wall time of one NavigationEnv.reset() (a new episode: the world, its planners, the first scan)."""
    env = campo.gym.NavigationEnv(SCENE, vehicle=VEHICLE, action_mode=action_mode, overrides=overrides)
    env.reset(seed=SEED)
    times = []
    for _ in range(count):
        start = time.perf_counter()
        env.reset()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def bench_case(resolution, num_envs, args, threads):
    """One resolution and N: the three variants built, reset and warmed up, then stepped round by round (a
    round: each variant its block of steps, the same actions). With --wait-quiet, each round waits for the
    machine to be idle first, and a round during which the rest of the machine used more than
    --disturbed-cores is discarded and run again (at most --max-discards times in the case, then kept and
    counted): the rows say how many were discarded and what the rest of the machine used in each kept one."""
    overrides = {RESOLUTION_POINTER: [resolution, resolution]}
    env_steps = args.env_steps[resolution] if isinstance(args.env_steps, dict) else args.env_steps
    steps = max(1, env_steps // num_envs)  # vector steps per repeat
    warmup = max(1, steps // 10)
    variants = {
        "vector": Vector(num_envs, threads, overrides, args.action_mode),
        "vector_1": Vector(num_envs, 1, overrides, args.action_mode),
        "loop": Loop(num_envs, overrides, args.action_mode),
    }
    rng = np.random.default_rng(ACTION_SEED)

    def draw(count):
        return rng.uniform(-1.0, 1.0, (count, num_envs, 4)).astype(np.float32)

    warmup_actions = draw(warmup)
    for v in variants.values():
        v.reset(SEED)
        for a in warmup_actions:
            v.step(a)
    ends_before = {name: int(v.ends.sum()) for name, v in variants.items()}
    kept = {name: [] for name in variants}  # per kept round: (wall_s, own_cores, other_cores, steal_cores)
    discarded = 0
    waited_s = 0.0
    rounds_run = 0
    while len(kept["vector"]) < args.repeats:
        if args.wait_quiet:
            start = time.monotonic()
            wait_quiet(args.quiet_cores, args.max_wait_s, probe_s=1.0)
            waited_s += time.monotonic() - start
        block = draw(steps)  # every variant steps these, kept or not, so they stay in step with each other
        round_usage = {}
        # Each round starts with the next variant, so that none always runs first after the idle wait.
        names = list(variants)
        shift = rounds_run % len(names)
        rounds_run += 1
        for name in names[shift:] + names[:shift]:
            v = variants[name]
            with Usage() as u:
                for a in block:
                    v.step(a)
            round_usage[name] = (u.wall_s, u.own_cores, u.other_cores, u.steal_cores)
        disturbed = max(x[2] for x in round_usage.values())
        if args.wait_quiet and disturbed > args.disturbed_cores and discarded < args.max_discards:
            discarded += 1
            print(f"# {resolution} x {resolution}, N={num_envs}: round discarded (the rest of the machine used "
                  f"{disturbed:.2f} cores)", file=sys.stderr, flush=True)
            continue
        for name in variants:
            kept[name].append(round_usage[name])
    # The same work in every variant: each environment's summed reward and episode ends agree bit for bit.
    reference = variants["vector_1"]
    same_work = all(np.array_equal(v.totals, reference.totals) and np.array_equal(v.ends, reference.ends)
                    for v in variants.values())
    rows = []
    for name, v in variants.items():
        rates = [steps * num_envs / x[0] for x in kept[name]]
        rows.append({
            "resolution": resolution, "num_envs": num_envs, "variant": name, "num_threads": v.threads,
            "vector_steps_per_repeat": steps, "env_steps_per_repeat": steps * num_envs, "warmup_vector_steps": warmup,
            "repeats": args.repeats, "rates_env_steps_per_s": rates, "median": statistics.median(rates),
            "min": min(rates), "max": max(rates),
            # Over every round run, discarded ones included (their steps were taken too).
            "episode_ends_timed": int(v.ends.sum()) - ends_before[name],
            "env_steps_run": (len(kept[name]) + discarded) * steps * num_envs,
            "own_cores": [x[1] for x in kept[name]],
            "other_cores": [x[2] for x in kept[name]],
            "steal_cores": [x[3] for x in kept[name]],
            "rounds_discarded": discarded,
            "waited_for_quiet_s": waited_s,
            "same_work_as_vector_1": same_work,
        })
    return rows


def ratio_rows(results):
    """Per case: the ratios of the medians, and the median and range of the ratios round by round (the
    variants of one round step the same environments through the same states: paired)."""
    by = {(r["resolution"], r["num_envs"], r["variant"]): r for r in results}
    out = []

    def paired(a, b):
        ratios = [x / y for x, y in zip(a["rates_env_steps_per_s"], b["rates_env_steps_per_s"])]
        return {"median": statistics.median(ratios), "min": min(ratios), "max": max(ratios)}

    for (resolution, n, variant), r in by.items():
        if variant != "vector":
            continue
        one = by[(resolution, n, "vector_1")]
        loop = by[(resolution, n, "loop")]
        out.append({"resolution": resolution, "num_envs": n,
                    "threads_over_1_thread": r["median"] / one["median"],
                    "vector_over_loop": r["median"] / loop["median"],
                    "vector_1_over_loop": one["median"] / loop["median"],
                    "threads_over_1_thread_paired": paired(r, one),
                    "vector_over_loop_paired": paired(r, loop)})
    return out


def fmt_ratio(q):
    return f"{q['median']:.2f} ({q['min']:.2f}-{q['max']:.2f})"


def fmt_rate(r):
    return f"{r['median']:,.0f} ({r['min']:,.0f}-{r['max']:,.0f})"


def markdown(report) -> str:
    threads = report["config"]["threads"]
    by = {(r["resolution"], r["num_envs"], r["variant"]): r for r in report["results"]}
    ratios = {(q["resolution"], q["num_envs"]): q for q in report["ratios"]}
    lines = [
        f"| LIDAR | N | vector, {threads} threads | vector, 1 thread | Python loop | {threads} threads / 1, round by round | "
        "vector / loop, round by round | cores used: vector, 1 thread, loop | rest of the machine, cores (max); rounds discarded | "
        "episode ends (timed, per variant) |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for resolution in report["config"]["resolutions"]:
        for n in report["config"]["num_envs"]:
            v, one, loop = (by[(resolution, n, k)] for k in ("vector", "vector_1", "loop"))
            q = ratios[(resolution, n)]
            lines.append(f"| {resolution} x {resolution} | {n} | {fmt_rate(v)} | {fmt_rate(one)} | {fmt_rate(loop)} | "
                         f"{fmt_ratio(q['threads_over_1_thread_paired'])} | {fmt_ratio(q['vector_over_loop_paired'])} | "
                         + ", ".join(f"{statistics.median(x['own_cores']):.2f}" for x in (v, one, loop)) + " | "
                         f"{max(max(x['other_cores']) for x in (v, one, loop)):.2f}; {v['rounds_discarded']} | "
                         f"{v['episode_ends_timed']} |")
    return "\n".join(lines)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=pathlib.Path, help="write the results and their provenance here")
    parser.add_argument("--resolutions", type=int, nargs="+", default=[64, 256], help="the scanner's rows = cols")
    parser.add_argument("--num-envs", type=int, nargs="+", default=[1, 2, 8, 32])
    parser.add_argument("--threads", type=int, default=cores(), help="the vector variant's threads (default: nproc)")
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--env-steps", type=int, default=None,
                        help="environment steps per repeat (default: 4096 at 64 x 64 and below, 1024 above)")
    parser.add_argument("--action-mode", default="velocity", help="a quadrotor action mode (default: velocity)")
    parser.add_argument("--wait-quiet", action="store_true",
                        help="before each round, wait until the rest of the machine is (nearly) idle, and run again "
                             "a round it disturbed")
    parser.add_argument("--quiet-cores", type=float, default=0.05, help="--wait-quiet: idle means under this many cores")
    parser.add_argument("--max-wait-s", type=float, default=600.0, help="--wait-quiet: then measure anyway")
    parser.add_argument("--disturbed-cores", type=float, default=0.25,
                        help="--wait-quiet: a round is discarded when the rest of the machine used more cores than this")
    parser.add_argument("--max-discards", type=int, default=50, help="--wait-quiet: rounds discarded per case at most")
    parser.add_argument("--quick", action="store_true",
                        help="a smoke test of seconds: 16 x 16, N = 1 and 2, 2 repeats of a few steps")
    args = parser.parse_args(argv)
    if args.quick:
        args.resolutions, args.num_envs, args.repeats = [16], [1, 2], 2
        args.env_steps = args.env_steps or 8
    if args.env_steps is None:
        args.env_steps = {res: 4096 if res <= 64 else 1024 for res in args.resolutions}
    report = {"benchmark": "vector_env_throughput", "provenance": provenance(argv)}
    probe = campo.gym.NavigationEnv(SCENE, vehicle=VEHICLE, action_mode=args.action_mode)
    report["config"] = {
        "scene": SCENE, "vehicle": VEHICLE, "sensor": SENSOR, "resolution_pointer": RESOLUTION_POINTER,
        "action_mode": args.action_mode, "step_s": probe.step_s, "threads": args.threads,
        "resolutions": args.resolutions, "num_envs": args.num_envs, "repeats": args.repeats,
        "env_steps_per_repeat": args.env_steps, "seed": SEED, "action_seed": ACTION_SEED,
        "actions": "uniform in [-1, 1]^4, float32, numpy default_rng(action_seed), the same for every variant",
    }
    del probe
    report["reset_s_median"] = {}
    report["results"] = []
    for resolution in args.resolutions:
        overrides = {RESOLUTION_POINTER: [resolution, resolution]}
        report["reset_s_median"][str(resolution)] = measure_reset_s(overrides, args.action_mode, 3 if args.quick else 20)
        for n in args.num_envs:
            report["results"].extend(bench_case(resolution, n, args, args.threads))
            r = report["results"][-3:]
            print(f"# {resolution} x {resolution}, N={n}: " +
                  ", ".join(f"{x['variant']} {x['median']:,.0f}/s" for x in r), file=sys.stderr, flush=True)
    report["ratios"] = ratio_rows(report["results"])
    report["provenance"]["loadavg_at_end"] = os.getloadavg()
    table = markdown(report)
    report["markdown"] = table
    print(table)
    print("\nreset (a new episode) median: " + ", ".join(
        f"{res} x {res}: {s * 1e3:.2f} ms" for res, s in report["reset_s_median"].items()))
    if not all(r["same_work_as_vector_1"] for r in report["results"]):
        print("WARNING: the variants' rewards or episode ends differ: they did not do the same work", file=sys.stderr)
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(report, indent=1) + "\n")
    return report


if __name__ == "__main__":
    main()
