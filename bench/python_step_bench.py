"""The Python module's costs (docs/PERFORMANCE.md): ep.step() against the C++ loop's own
step, and a Python planner's call rate in the C++ closed loop.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_step_bench.py [--campo-bench build/campo_bench]

1. ep.step(command) of a campo.Episode without sensors, per call, minus the C++
   Episode::step of the same scene and command (campo_bench's
   BM_EpisodeStepNoSensors, run here, in the same process tree): the overhead
   the binding adds per call (target: under 5 us).
2. A Python planner returning a fixed PlanResult, run by campo.run in the C++
   closed loop: planner calls per second, from the loop's own timing of each
   call (planner_time_ms_mean: the call, the observation's and the result's
   conversion) and end to end (planner calls over the run's wall time,
   physics included) (target: at least 20,000 calls per second).
"""
import argparse
import json
import pathlib
import subprocess
import sys
import time

import campo

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(SOURCE_DIR / "tests" / "python" / "fixtures"))
import python_planners  # noqa: E402

SCENE = str(SOURCE_DIR / "tests" / "python" / "fixtures" / "open_field.json")
NO_SENSORS = {"/objects/drone/sensors": [], "/world/time_limit_s": 1e6}


def python_step_us(steps, repeats):
    times = []
    hover = campo.Command.hold([0.0, 0.0, 1.5])
    for _ in range(repeats):
        episode = campo.Episode(SCENE, overrides=NO_SENSORS)
        episode.reset()
        for _ in range(1000):  # warm up
            episode.step(hover)
        start = time.perf_counter()
        for _ in range(steps):
            episode.step(hover)
        times.append((time.perf_counter() - start) / steps * 1e6)
    return sorted(times)[len(times) // 2]


def cpp_step_us(campo_bench):
    out = subprocess.run([campo_bench, "--benchmark_filter=BM_EpisodeStepNoSensors$", "--benchmark_format=json",
                          "--benchmark_repetitions=5", "--benchmark_report_aggregates_only=true"],
                         capture_output=True, text=True, check=True)
    for b in json.loads(out.stdout)["benchmarks"]:
        if b.get("aggregate_name") == "min" or b["name"].endswith("_median"):
            return b["real_time"]  # microseconds (the benchmark's unit)
    raise RuntimeError("no BM_EpisodeStepNoSensors result")


def planner_rates():
    record = campo.run(SCENE, planner=python_planners.Fixed(), overrides={"/objects/drone/sensors": [],
                                                                          "/world/time_limit_s": 120})
    m = record["metrics"]
    return 1000.0 / m["planner_time_ms_mean"], m["planner_calls"] / m["wall_time_s"], m["planner_calls"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campo-bench", default=str(SOURCE_DIR / "build" / "campo_bench"))
    parser.add_argument("--steps", type=int, default=20000)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    python_us = python_step_us(args.steps, args.repeats)
    cpp_us = cpp_step_us(args.campo_bench)
    per_call, end_to_end, calls = planner_rates()
    print("| measure | value | target |")
    print("| --- | --- | --- |")
    print("| ep.step() from Python, no sensors | %.2f us per call (median of %d x %d) | |" % (python_us, args.repeats,
                                                                                      args.steps))
    print("| Episode::step in C++, same scene and command | %.2f us per call (median of 5) | |" % cpp_us)
    print("| ep.step() overhead over the C++ loop | %.2f us per call | < 5 us |" % (python_us - cpp_us))
    print("| Python planner, fixed command: calls per second (the loop's timing of each call) | %.0f | >= 20,000 |"
          % per_call)
    print("| the same, end to end (%d calls over the run's wall time, physics included) | %.0f | |" % (calls,
                                                                                                    end_to_end))


if __name__ == "__main__":
    main()
