"""campo.results against what the campo program writes: a real sweep and a real run, read back.

Run with Debian's interpreter (numpy, pandas, matplotlib) and the package on the path:

    PYTHONPATH=build/python /usr/bin/python3 -m unittest tests/python/test_results.py

CAMPO_BIN names the program (default: build/campo of this source tree); the tests fail without it.
"""

import csv
import io
import json
import math
import os
import pathlib
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import warnings

import pandas as pd

from campo import results

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
CAMPO = pathlib.Path(os.environ.get("CAMPO_BIN", SOURCE_DIR / "build" / "campo"))
EXAMPLE = SOURCE_DIR / "examples" / "python" / "analyse_sweep.py"

# Two barriers, seed 000's reactive planner: two scanner resolutions (arrays, labelled 32x32 and 16x8) against two
# speeds, two seeds with noisy ranges and jittered starts so they differ: 8 runs of under a second each (at 32x32
# the drone climbs over a barrier and reaches the goal; at 16x8 it finds no safe way and gives up).
SPEC = {
    "campo_sweep": 1,
    "name": "tiny",
    "scenes": ["two_barriers"],
    "set": {"/objects/drone/sensors/scanner/noise_stddev_m": 0.01, "/world/time_limit_s": 120},
    "axes": [{"name": "resolution", "values": [[32, 32], [16, 8]],
              "set": ["/objects/drone/sensors/scanner/resolution"]},
             {"name": "speed_mps", "values": [0.6, 1.5], "set": ["/objects/drone/planner/params/speed_mps"]}],
    "seeds": {"first": 1, "count": 2},
    "start_jitter": {"vehicle": "drone", "radius_m": 0.25},
}
# A file where this run's directory goes: its files cannot be written, so the sweep records it as failed.
BLOCKED_RUN = "two_barriers__resolution-16x8__speed_mps-1.5__seed-2"

# Made once by setUpModule: a scratch folder, the sweep and the run in it.
_scratch = None
SCRATCH = SWEEP = RUN = pathlib.Path()


def campo(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(CAMPO), *args], cwd=SCRATCH, capture_output=True, text=True, timeout=600)


def setUpModule() -> None:
    global _scratch, SCRATCH, SWEEP, RUN
    if not os.access(CAMPO, os.X_OK):
        raise RuntimeError(f"{CAMPO}: the campo program is needed (build it, or set CAMPO_BIN)")
    _scratch = tempfile.TemporaryDirectory(prefix="campo_results_test_")
    SCRATCH = pathlib.Path(_scratch.name)
    (SCRATCH / "tiny.json").write_text(json.dumps(SPEC))
    SWEEP = SCRATCH / "sweep"
    (SWEEP / "runs").mkdir(parents=True)
    (SWEEP / "runs" / BLOCKED_RUN).write_text("in the way")
    sweep = campo("sweep", str(SCRATCH / "tiny.json"), "--out", str(SWEEP), "--keep-runs", "--jobs", "2")
    # The one failure is its place to write: exit 2, as for any output that cannot be written.
    if sweep.returncode != 2 or "7 of 8 runs completed, 1 failed" not in sweep.stdout:
        raise RuntimeError(f"campo sweep: exit {sweep.returncode}\n{sweep.stdout}{sweep.stderr}")
    RUN = SCRATCH / "run"
    run = campo("run", "two_barriers", "--no-figures", "--out", str(RUN))
    if run.returncode != 0:
        raise RuntimeError(f"campo run: exit {run.returncode}\n{run.stderr}")


def tearDownModule() -> None:
    _scratch.cleanup()


def result_lines(directory: pathlib.Path) -> list[dict]:
    return [json.loads(line) for line in (directory / "results.jsonl").read_text().splitlines() if line.strip()]


def scratch_dir(name: str) -> pathlib.Path:
    directory = SCRATCH / name
    directory.mkdir()
    return directory


def assert_same_value(test: unittest.TestCase, got, expected, what: str) -> None:
    """A frame's cell against a JSON value: null is missing, numbers exactly equal."""
    if expected is None:
        test.assertTrue(pd.isna(got), f"{what}: {got!r} where the record has null")
    else:
        test.assertEqual(got, expected, what)
        test.assertEqual(isinstance(got, str), isinstance(expected, str), what)


class ReadResultsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        cls.frame = results.read_results(SWEEP)
        cls.lines = result_lines(SWEEP)
        cls.by_id = {line["id"]: line for line in cls.lines}

    def row(self, name: str) -> pd.Series:
        rows = self.frame[self.frame["name"] == name]
        self.assertEqual(len(rows), 1, name)
        return rows.iloc[0]

    def test_one_row_per_run_in_the_sweeps_order(self) -> None:
        manifest = json.loads((SWEEP / "sweep.json").read_text())
        self.assertEqual(len(self.lines), 8)
        self.assertEqual(len(self.frame), len(self.lines))
        # results.jsonl is in the order the runs ended (two at a time); the frame in the spec's expansion order.
        self.assertEqual(list(self.frame["id"]), [run["id"] for run in manifest["runs"]])
        # Whatever that order was: the lines reversed give the same frame.
        reversed_lines = scratch_dir("reversed")
        shutil.copy(SWEEP / "sweep.json", reversed_lines)
        (reversed_lines / "results.jsonl").write_text("".join(json.dumps(line) + "\n" for line in self.lines[::-1]))
        pd.testing.assert_frame_equal(results.read_results(reversed_lines), self.frame)
        self.assertEqual(self.frame.attrs["sweep"], "tiny")
        self.assertEqual(self.frame.attrs["axes"], ["resolution", "speed_mps"])

    def test_identity_and_axis_columns_are_those_of_each_line(self) -> None:
        for _, row in self.frame.iterrows():
            line = self.by_id[row["id"]]
            for key in ("name", "scene", "planner", "seed", "status"):
                self.assertEqual(row[key], line[key], key)
            self.assertEqual(row["speed_mps"], line["params"]["speed_mps"])
            # An array value by its label, the one in the run's name and in campo table.
            label = "x".join(str(n) for n in line["params"]["resolution"])
            self.assertEqual(row["resolution"], label)
            self.assertIn(f"__resolution-{label}__", row["name"])
            self.assertEqual(row["overrides"], line["overrides"])
            self.assertEqual(row["trajectory_sha256"], line.get("trajectory_sha256"))
            self.assertEqual(row["process_wall_time_s"], line["wall_time_s"])

    def test_metrics_are_those_of_each_runs_run_json(self) -> None:
        keys = set()
        completed = self.frame[self.frame["status"] == "completed"]
        self.assertEqual(len(completed), 7)
        for _, row in completed.iterrows():
            self.assertEqual(row["run_dir"], f"runs/{row['name']}")
            record = json.loads((SWEEP / row["run_dir"] / "run.json").read_text())
            for key, value in record["metrics"].items():
                assert_same_value(self, row[key], value, f"{row['name']}: {key}")
            keys |= record["metrics"].keys()
            self.assertEqual(row["success"], record["metrics"]["outcome"] == "reached")
        # reason is among the identity columns (a failed run's reason, else the episode's); the rest in order.
        self.assertEqual(set(self.frame.attrs["metrics"]), keys - {"reason"})
        self.assertIn("leg0_path_length_m", keys)

    def test_a_failed_run_has_its_status_and_reason_and_no_metrics(self) -> None:
        row = self.row(BLOCKED_RUN)
        self.assertEqual(row["status"], "failed")
        self.assertTrue(row["reason"].startswith("completed, but its files could not be written: "), row["reason"])
        self.assertIn(str(SWEEP / "runs" / BLOCKED_RUN), row["files_error"])
        self.assertFalse(row["success"])
        self.assertTrue(pd.isna(row["run_dir"]))
        for metric in self.frame.attrs["metrics"]:
            self.assertTrue(pd.isna(row[metric]), metric)
        self.assertEqual(row["resolution"], "16x8")
        self.assertEqual(row["seed"], 2)

    def test_dtypes(self) -> None:
        dtypes = self.frame.dtypes
        self.assertEqual(dtypes["seed"], "int64")
        self.assertEqual(dtypes["speed_mps"], "float64")
        self.assertEqual(dtypes["success"], "bool")
        for metric in ("path_ratio", "sim_time_s", "min_clearance_m", "leg0_lateral_before_climb_m", "collisions"):
            self.assertEqual(dtypes[metric], "float64", metric)  # NaN for the failed run
        for text in ("outcome", "nearest_obstacle", "reason", "status", "resolution"):
            self.assertEqual(dtypes[text], "object", text)

    def test_agrees_with_campo_table(self) -> None:
        table = campo("table", str(SWEEP), "--rows", "resolution", "--cols", "speed_mps", "--metrics",
                      "success,path_ratio,sim_time_s@reached", "--format", "csv", "--no-chart")
        self.assertEqual(table.returncode, 0, table.stderr)
        cells = list(csv.DictReader(io.StringIO(table.stdout)))
        self.assertEqual(len(cells), 4 * 3)
        for cell in cells:
            # Labels of campo table are the frame's values: the same names and values select the same runs.
            runs = self.frame[(self.frame["resolution"] == cell["resolution"]) &
                              (self.frame["speed_mps"] == float(cell["speed_mps"]))]
            self.assertEqual(len(runs), int(cell["runs"]))
            self.assertEqual((runs["status"] == "failed").sum(), int(cell["failed"]))
            if cell["metric"] == "success":
                values = runs["success"].astype(float)
            elif cell["over"] == "reached":
                values = runs.loc[runs["outcome"] == "reached", cell["metric"]].dropna()
            else:
                values = runs[cell["metric"]].dropna()
            self.assertEqual(len(values), int(cell["n"]), cell)
            if len(values) == 0:  # no run of the cell counts (none reached): campo table leaves it empty
                self.assertEqual(cell["mean"], "", cell)
                continue
            self.assertTrue(math.isclose(values.mean(), float(cell["mean"]), rel_tol=1e-12), cell)

    def test_the_path_of_results_jsonl_reads_the_same(self) -> None:
        pd.testing.assert_frame_equal(results.read_results(SWEEP / "results.jsonl"), self.frame)
        self.assertEqual(results.read_results(str(SWEEP)).attrs, self.frame.attrs)

    def test_the_last_line_of_a_rerun_counts(self) -> None:
        # The failed run is run again by a resumed sweep once its directory can be written: a second line.
        resumed = SCRATCH / "resumed"
        shutil.copytree(SWEEP, resumed)
        (resumed / "runs" / BLOCKED_RUN).unlink()
        sweep = campo("sweep", str(SCRATCH / "tiny.json"), "--out", str(resumed), "--keep-runs")
        self.assertEqual(sweep.returncode, 0, sweep.stderr)
        self.assertEqual(len(result_lines(resumed)), 9)
        frame = results.read_results(resumed)
        self.assertEqual(list(frame["id"]), list(self.frame["id"]))
        row = frame[frame["name"] == BLOCKED_RUN].iloc[0]
        self.assertEqual(row["status"], "completed")
        record = json.loads((resumed / "runs" / BLOCKED_RUN / "run.json").read_text())
        for key in ("path_ratio", "sim_time_s", "outcome", "collisions"):
            self.assertEqual(row[key], record["metrics"][key], key)
        self.assertEqual(frame["collisions"].dtype, "int64")  # no failed run left: integers stay integers

    def test_an_incomplete_last_line_is_ignored_with_a_warning(self) -> None:
        directory = scratch_dir("interrupted")
        text = (SWEEP / "results.jsonl").read_text()
        (directory / "results.jsonl").write_text(text + text.splitlines()[0][:100])
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            frame = results.read_results(directory)
        self.assertEqual([str(w.message) for w in caught],
                         [f"{directory / 'results.jsonl'} line 9 is incomplete (an interrupted sweep?) and was "
                          "ignored"])
        self.assertTrue(issubclass(caught[0].category, results.ResultsWarning))
        # Without sweep.json: the order of the file, the axes from the runs' params.
        self.assertEqual(list(frame["id"]), [line["id"] for line in self.lines])
        self.assertEqual(frame.attrs, {"sweep": "interrupted", "axes": ["resolution", "speed_mps"],
                                       "metrics": self.frame.attrs["metrics"]})

    def write_lines(self, name: str, lines: list[str]) -> pathlib.Path:
        directory = scratch_dir(name)
        (directory / "results.jsonl").write_text("".join(line + "\n" for line in lines))
        return directory / "results.jsonl"

    def test_a_line_that_is_not_json_names_file_and_line(self) -> None:
        lines = (SWEEP / "results.jsonl").read_text().splitlines()
        lines[2] = lines[2][:50]
        file = self.write_lines("not_json", lines)
        with self.assertRaises(results.ResultsError) as raised:
            results.read_results(file.parent)
        self.assertTrue(str(raised.exception).startswith(f"{file} line 3: expected JSON, but "), raised.exception)
        self.assertIsInstance(raised.exception, ValueError)

    def test_a_line_that_is_not_a_result_names_file_line_and_pointer(self) -> None:
        cases = [("status", "done", "/status: expected \"completed\" or \"failed\", got \"done\""),
                 ("seed", -1, "/seed: expected an integer seed in [0, 18446744073709551615], got -1"),
                 ("metrics", None, None),
                 ("params", [1], "/params: expected an object of axis values, got [1]")]
        for i, (key, value, message) in enumerate(cases):
            lines = [json.dumps(line) for line in self.lines]
            changed = json.loads(lines[1])
            if changed["status"] != "completed":
                changed = json.loads(lines[0])
            changed[key] = value
            lines[1] = json.dumps(changed)
            file = self.write_lines(f"bad_{i}", lines)
            with self.assertRaises(results.ResultsError) as raised:
                results.read_results(file)
            expected = message or "/metrics: expected the metrics object of a completed run, got null"
            self.assertEqual(str(raised.exception), f"{file} line 2: {expected}")
        del changed["id"]
        lines[1] = json.dumps(changed)
        file = self.write_lines("no_id", lines)
        with self.assertRaisesRegex(results.ResultsError, re.escape(f"{file} line 2: /: expected a key \"id\"")):
            results.read_results(file)

    def test_no_sweep_there(self) -> None:
        missing = SCRATCH / "no_such_sweep"
        with self.assertRaisesRegex(results.ResultsError, f"^{re.escape(str(missing))}: expected a sweep directory"):
            results.read_results(missing)
        empty = scratch_dir("empty")
        with self.assertRaisesRegex(results.ResultsError, f"^{re.escape(str(empty / 'results.jsonl'))}: cannot read"):
            results.read_results(empty)

    def test_an_axis_keeps_its_name_when_a_metric_or_run_field_has_it_too(self) -> None:
        lines = []
        for line in self.lines:
            line = dict(line, params=dict(line["params"], collisions=7, status="axis"))
            lines.append(json.dumps(line))
        frame = results.read_results(self.write_lines("clash", lines))
        self.assertEqual(list(frame["collisions"]), [7] * 8)
        self.assertEqual(list(frame["status"]), ["axis"] * 8)
        pd.testing.assert_series_equal(frame["metric_collisions"], self.frame_in_file_order()["collisions"],
                                       check_names=False)
        self.assertEqual(list(frame["run_status"]), [line["status"] for line in self.lines])
        self.assertIn("metric_collisions", frame.attrs["metrics"])

    def frame_in_file_order(self) -> pd.DataFrame:
        order = {line["id"]: i for i, line in enumerate(self.lines)}
        return self.frame.sort_values("id", key=lambda ids: ids.map(order)).reset_index(drop=True)

    def test_seeds_beyond_int64_stay_exact(self) -> None:
        lines = [dict(line, id=f"{line['id']}_big", seed=2**64 - 1 - i) for i, line in enumerate(self.lines)]
        frame = results.read_results(self.write_lines("big_seeds", [json.dumps(line) for line in lines]))
        self.assertEqual(frame["seed"].dtype, "uint64")
        self.assertEqual([int(seed) for seed in frame["seed"]], [2**64 - 1 - i for i in range(8)])

    def test_column_dtypes_of_json_values(self) -> None:
        # (values, dtype, values read back): None is a missing value (a failed run, a null metric).
        cases = [([True, False], "bool", [True, False]),
                 ([True, None], "boolean", [True, pd.NA]),  # a gate's passed flag beside a failed run
                 ([3, 4], "int64", [3, 4]),
                 ([3, None], "float64", [3.0, math.nan]),
                 ([2**63, 1], "uint64", [2**63, 1]),
                 ([2**53 + 1, None], "object", [2**53 + 1, None]),  # float64 would round it
                 ([0.5, 2], "float64", [0.5, 2.0]),
                 (["barrier", None], "object", ["barrier", None]),
                 ([None, None], "float64", [math.nan, math.nan]),
                 ([1, "a"], "object", [1, "a"])]
        for values, dtype, expected in cases:
            column = results._column(values)
            self.assertEqual(str(column.dtype), dtype, values)
            for got, want in zip(column, expected):
                if want is pd.NA or (isinstance(want, float) and math.isnan(want)):
                    self.assertTrue(pd.isna(got), values)
                else:
                    self.assertEqual(got, want, values)
                    self.assertEqual(type(got) is int, type(want) is int, values)  # exact integers stay ints

    def test_value_labels_are_those_of_campo(self) -> None:
        # std::to_chars's shortest form (value_label in sweep/sweep_spec.cpp), as campo names these values.
        expected = {0.5: "0.5", 100.0: "100", 1e15: "1e+15", 1e-05: "1e-05", 123456.0: "123456", 0.001: "0.001",
                    0.0001: "1e-04", 1e16: "1e+16", 2.5e-07: "2.5e-07", -3.75: "-3.75", 1e21: "1e+21",
                    12345.678: "12345.678", 5e-324: "5e-324", 1.7976931348623157e308: "1.7976931348623157e+308",
                    -0.0: "-0", 10000000.0: "1e+07", 0.30000000000000004: "0.30000000000000004",
                    123456789012345678.0: "123456789012345680"}
        for value, label in expected.items():
            self.assertEqual(results._label(value), label, repr(value))
        self.assertEqual(results._label([256, 256]), "256x256")
        self.assertEqual(results._label([0.5, "a", True]), "0.5xaxtrue")


class ReadRunTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        cls.recorded = results.read_run(RUN)

    def test_record_and_metrics_are_run_json(self) -> None:
        self.assertEqual(self.recorded.record, json.loads((RUN / "run.json").read_text()))
        self.assertEqual(self.recorded.metrics, self.recorded.record["metrics"])
        self.assertEqual(self.recorded.metrics["outcome"], "reached")
        self.assertEqual(self.recorded.directory, RUN)
        self.assertEqual(results.read_run(RUN / "run.json").record, self.recorded.record)

    def test_the_final_state_hash_is_exact(self) -> None:
        digits = re.search(r'"final_state_hash": (\d+)', (RUN / "run.json").read_text()).group(1)
        self.assertIsInstance(self.recorded.record["final_state_hash"], int)
        self.assertEqual(self.recorded.record["final_state_hash"], int(digits))

    def test_trajectory_is_trajectory_csv_with_numeric_columns(self) -> None:
        with open(RUN / "trajectory.csv", newline="") as file:
            table = list(csv.reader(file))
        header, rows = table[0], table[1:]
        self.assertGreater(len(rows), 100)
        self.assertEqual(len(self.recorded.trajectory), len(rows))
        self.assertEqual(list(self.recorded.trajectory.columns), header)
        for column_index, name in enumerate(header):
            column = self.recorded.trajectory[name]
            cells = [row[column_index] for row in rows]
            if name == "command":
                self.assertEqual(list(column), cells)
                continue
            self.assertEqual(column.dtype.kind, "f" if any("." in c or "e" in c or c == "" for c in cells) else "i",
                             name)
            for got, cell in zip(column, cells):
                if cell == "":
                    self.assertTrue(math.isnan(got), name)
                else:
                    self.assertEqual(got, float(cell), name)  # exactly: parsed as written

    def test_events_are_the_lines_of_events_jsonl(self) -> None:
        lines = (RUN / "events.jsonl").read_text().splitlines()
        self.assertEqual(len(lines), self.recorded.record["event_log"]["count"])
        self.assertEqual(self.recorded.events, [json.loads(line) for line in lines])
        self.assertIn("planned_waypoint", self.recorded.events[0]["decisions"])

    def test_a_sweeps_kept_run(self) -> None:
        frame = results.read_results(SWEEP)
        row = frame[frame["status"] == "completed"].iloc[-1]
        run = results.read_run(SWEEP / row["run_dir"])
        self.assertEqual(run.metrics["path_ratio"], row["path_ratio"])
        self.assertEqual(len(run.trajectory), run.metrics["planner_calls"])

    def copy_of_run(self, name: str) -> pathlib.Path:
        directory = SCRATCH / name
        shutil.copytree(RUN, directory)
        return directory

    def test_a_directory_without_events(self) -> None:
        # A sweep's triage directory holds run.json and trajectory.csv but no events.
        directory = self.copy_of_run("triage_like")
        (directory / "events.jsonl").unlink()
        self.assertIsNone(results.read_run(directory).events)
        # Older records kept the events in run.json.
        record = json.loads((directory / "run.json").read_text())
        record["events"] = self.recorded.events
        (directory / "run.json").write_text(json.dumps(record))
        self.assertEqual(results.read_run(directory).events, self.recorded.events)

    def test_errors_name_the_file_and_line(self) -> None:
        missing = SCRATCH / "no_such_run"
        with self.assertRaisesRegex(results.ResultsError, f"^{re.escape(str(missing))}: expected a run directory"):
            results.read_run(missing)

        directory = self.copy_of_run("bad_events")
        lines = (directory / "events.jsonl").read_text().splitlines()
        lines[1] = json.dumps({"time_s": "soon", "decisions": {}})
        (directory / "events.jsonl").write_text("\n".join(lines) + "\n")
        with self.assertRaises(results.ResultsError) as raised:
            results.read_run(directory)
        self.assertEqual(str(raised.exception), f"{directory / 'events.jsonl'} line 2: /time_s: expected the "
                                                "simulated time, a number of seconds, got \"soon\"")

        directory = self.copy_of_run("bad_trajectory")
        lines = (directory / "trajectory.csv").read_text().splitlines()
        cells = lines[3].split(",")
        cells[1] = "far"
        lines[3] = ",".join(cells)
        (directory / "trajectory.csv").write_text("\n".join(lines) + "\n")
        with self.assertRaises(results.ResultsError) as raised:
            results.read_run(directory)
        self.assertEqual(str(raised.exception), f"{directory / 'trajectory.csv'} line 4: column x_m: expected a "
                                                "number or nothing, got 'far'")

        directory = self.copy_of_run("bad_record")
        (directory / "run.json").write_text('{"metrics": {"outcome": "reached"')
        with self.assertRaisesRegex(results.ResultsError, f"^{re.escape(str(directory / 'run.json'))}: expected JSON"):
            results.read_run(directory)
        (directory / "run.json").write_text('{"metrics": []}')
        with self.assertRaisesRegex(results.ResultsError, re.escape(f"{directory / 'run.json'}: /metrics: expected")):
            results.read_run(directory)


class ReadSeveralVehiclesRunTest(unittest.TestCase):
    """A run of several vehicles: run.json with the run's metrics and a record per vehicle, each vehicle's own
    trajectory_<alias>.csv and events_<alias>.jsonl (docs/running.md)."""

    @classmethod
    def setUpClass(cls) -> None:
        cls.directory = SCRATCH / "two_drones"
        run = campo("run", str(SOURCE_DIR / "tests" / "python" / "fixtures" / "two_drones.json"), "--no-figures",
                    "--set", "/objects/far/planner/name=\"depth_reactive\"", "--out", str(cls.directory))
        if run.returncode != 0:
            raise RuntimeError(f"campo run: exit {run.returncode}\n{run.stderr}")
        cls.recorded = results.read_run(cls.directory)

    def test_the_runs_record_and_each_vehicles(self) -> None:
        record = json.loads((self.directory / "run.json").read_text())
        self.assertEqual(self.recorded.record, record)
        self.assertEqual(self.recorded.metrics, record["metrics"])
        self.assertEqual(self.recorded.metrics["vehicles"], 2)
        self.assertEqual(list(self.recorded.vehicles), ["near", "far"])  # scene order
        self.assertIsNone(self.recorded.events)
        for entry in record["vehicles"]:
            alias = entry["alias"]
            vehicle = self.recorded.vehicles[alias]
            self.assertEqual(vehicle.record, entry)
            self.assertEqual(vehicle.metrics, entry["metrics"])
            self.assertEqual(vehicle.planner, {"near": "straight", "far": "depth_reactive"}[alias])
            self.assertEqual(vehicle.vehicles, {})
            self.assertEqual(vehicle.events_file, f"events_{alias}.jsonl")
            self.assertEqual(len(vehicle.trajectory), entry["metrics"]["planner_calls"])
            with open(self.directory / f"trajectory_{alias}.csv", newline="") as file:
                table = list(csv.reader(file))
            self.assertEqual(list(vehicle.trajectory.columns), table[0])
            self.assertEqual(list(vehicle.trajectory["time_s"]), [float(row[0]) for row in table[1:]])
            lines = (self.directory / f"events_{alias}.jsonl").read_text().splitlines()
            self.assertEqual(len(lines), entry["event_log"]["count"])
            self.assertEqual(vehicle.events, [json.loads(line) for line in lines])
            # The run's trajectory holds every vehicle's rows, named in its first column.
            # (A column of integers in one vehicle's file and not in another's holds floats there.)
            rows = self.recorded.trajectory[self.recorded.trajectory["vehicle"] == alias].drop(columns="vehicle")
            pd.testing.assert_frame_equal(rows.reset_index(drop=True), vehicle.trajectory, check_dtype=False)
        self.assertEqual(self.recorded.trajectory.columns[0], "vehicle")
        self.assertEqual(len(self.recorded.trajectory), sum(len(v.trajectory) for v in self.recorded.vehicles.values()))
        # A decision belongs to one vehicle's planner.
        with self.assertRaisesRegex(results.ResultsError, r"several vehicles \(near, far\).*run.vehicles\[alias\]"):
            self.recorded.decision("planned_waypoint")
        far = self.recorded.vehicles["far"]
        following = far.decision("wall_following")
        held = [event for event in far.events if "wall_following" in event["decisions"]]
        self.assertEqual(list(following.index), [event["time_s"] for event in held])
        self.assertEqual(list(following), [event["decisions"]["wall_following"] for event in held])

    def test_errors_name_the_file_and_pointer(self) -> None:
        directory = SCRATCH / "two_drones_missing"
        shutil.copytree(self.directory, directory)
        (directory / "trajectory_far.csv").unlink()
        with self.assertRaisesRegex(results.ResultsError, re.escape(f"{directory / 'trajectory_far.csv'}: cannot read")):
            results.read_run(directory)
        record = json.loads((directory / "run.json").read_text())
        record["vehicles"][1]["trajectory_file"] = "../elsewhere.csv"
        (directory / "run.json").write_text(json.dumps(record))
        with self.assertRaisesRegex(results.ResultsError,
                                    re.escape(f"{directory / 'run.json'}: /vehicles/1/trajectory_file: expected the "
                                              "name of its trajectory file, got")):
            results.read_run(directory)


class AnalyseSweepExampleTest(unittest.TestCase):
    def analyse(self, *args: str) -> subprocess.CompletedProcess:
        # The example imports the package these tests import, wherever the current folder is.
        package_parent = pathlib.Path(results.__file__).resolve().parents[1]
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(package_parent), os.environ.get("PYTHONPATH", "")]))
        return subprocess.run([sys.executable, str(EXAMPLE), str(SWEEP), *args], cwd=SCRATCH, env=env,
                              capture_output=True, text=True, timeout=300)

    def test_summary_and_plot(self) -> None:
        plot = SCRATCH / "path_ratio.png"
        analysed = self.analyse("--metric", "path_ratio", "--by", "resolution", "--out", str(plot))
        self.assertEqual(analysed.returncode, 0, analysed.stderr)
        data = plot.read_bytes()
        self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")
        self.assertEqual(data[12:16], b"IHDR")
        width, height = struct.unpack(">II", data[16:24])
        self.assertGreaterEqual((width, height), (800, 500))
        self.assertGreater(len(data), 20_000)
        # One summary line per group, its numbers from the runs' own records.
        printed = {line.split()[0]: line.split() for line in analysed.stdout.splitlines()[3:5]}
        self.assertEqual(set(printed), {"32x32", "16x8"})
        for label, (runs, failed) in {"32x32": (4, 0), "16x8": (4, 1)}.items():
            metrics = [json.loads(run_json.read_text())["metrics"]
                       for run_json in sorted((SWEEP / "runs").glob(f"*__resolution-{label}__*/run.json"))]
            ratios = [m["path_ratio"] for m in metrics]
            self.assertEqual(len(ratios), runs - failed)
            mean = sum(ratios) / len(ratios)
            success_rate = sum(m["outcome"] == "reached" for m in metrics) / runs
            self.assertEqual(printed[label][1:6], [str(runs), str(failed), f"{success_rate:.4g}", str(len(ratios)),
                                                   f"{mean:.4g}"])

    def test_a_rate_by_the_default_field(self) -> None:
        plot = SCRATCH / "success.png"
        analysed = self.analyse("--metric", "success", "--out", str(plot))
        self.assertEqual(analysed.returncode, 0, analysed.stderr)
        self.assertIn("success by resolution (8 runs", analysed.stdout)  # the first axis
        self.assertEqual(plot.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")

    def test_unknown_names_are_refused(self) -> None:
        analysed = self.analyse("--metric", "path_ratios", "--out", str(SCRATCH / "x.png"))
        self.assertEqual(analysed.returncode, 2)
        self.assertIn('error: --metric: expected a metric of the runs (success, avoiding_time_s', analysed.stderr)
        analysed = self.analyse("--by", "colour", "--out", str(SCRATCH / "x.png"))
        self.assertEqual(analysed.returncode, 2)
        self.assertIn('error: --by: expected a field of the runs (scene, planner, seed, resolution, speed_mps), got '
                      '"colour"', analysed.stderr)
        self.assertFalse((SCRATCH / "x.png").exists())


if __name__ == "__main__":
    unittest.main()
