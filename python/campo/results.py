"""campo's recorded results as data: a sweep's runs as a pandas DataFrame, a run's files as a `Run`.

`read_results(DIR)` reads what `campo sweep --out DIR` wrote (`DIR/results.jsonl`, docs/sweeps.md), one row per
run, with the columns named as `campo table` and `campo plot` name fields and metrics. `read_run(DIR)` reads what
`campo run --out DIR` wrote (`run.json`, `trajectory.csv`, `events.jsonl`, docs/running.md), also a sweep's
`DIR/runs/<name>/` (`--keep-runs`). Errors name the file, the line where there is one, and what was expected.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import pathlib
import warnings
from typing import Any, Callable, Iterator, Optional, Union

import numpy as np
import pandas as pd

from . import _campo
from .records import PlannerRecord, _undeclared, planner_record

__all__ = ["ResultsError", "ResultsWarning", "Run", "read_results", "read_run"]

PathLike = Union[str, "os.PathLike[str]"]


class ResultsError(ValueError):
    """A results file that cannot be read; the message names the file (and line, JSON pointer) and what was expected."""


class ResultsWarning(UserWarning):
    """Something read over rather than refused: the incomplete last line an interrupted sweep leaves behind."""


# The run's identity first; `reason` is why a failed run failed, else why the episode ended (its metric).
_IDENTITY_COLUMNS = ("id", "name", "scene", "planner", "seed", "status", "reason", "success")
# Keys of a results.jsonl line that are a string or null, as columns of the same name.
_STRING_KEYS = ("run_dir", "files_error", "campo_version", "git_rev", "scene_sha256", "spec_sha256",
                "trajectory_sha256")
# After the metrics: how the run went as a process, where its files are, where it came from.
_TRAILING_COLUMNS = ("process_wall_time_s", "run_dir", "files_error", "triage_dir", "triage_repro", "overrides",
                     "campo_version", "git_rev", "scene_sha256", "spec_sha256", "trajectory_sha256")
# Integers beyond this lose digits as float64: such a column stays a column of Python ints.
_EXACT_FLOAT_INT = 2**53
_INT64_MAX = 2**63 - 1
_UINT64_MAX = 2**64 - 1
# What trajectory.csv holds where a value does not apply (empty) or is not a number; a command is never one of them.
_CSV_MISSING = ["", "nan", "-nan", "NaN", "-NaN"]


def _refuse_constant(name: str) -> Any:
    # JSON has no NaN or Infinity; campo never writes them (a non-finite number is recorded as null).
    raise ValueError(f"{name} is not JSON")


def _parse_json(text: str, source: str) -> Any:
    """Parses JSON text; integers stay Python ints (uint64 seeds and hashes exactly)."""
    try:
        return json.loads(text, parse_constant=_refuse_constant)
    except ValueError as error:
        raise ResultsError(f"{source}: expected JSON, but {error}") from None


def _read_text(path: pathlib.Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ResultsError(f"{path}: cannot read: No such file or directory") from None
    except (OSError, UnicodeDecodeError) as error:
        reason = error.strerror if isinstance(error, OSError) and error.strerror else str(error)
        raise ResultsError(f"{path}: cannot read: {reason}") from None


def _json_lines(path: pathlib.Path, text: str, tolerate_partial_last: bool) -> Iterator[tuple[Any, str]]:
    """Each non-blank line of a JSON-lines file parsed, with its source ("FILE line N").

    A last line without its newline that is not JSON is what a sweep killed mid-write leaves: with
    `tolerate_partial_last` it is skipped with a ResultsWarning, as `campo table` does.
    """
    lines = text.split("\n")
    for number, line in enumerate(lines, start=1):
        if not line.strip(" \t\r"):
            continue
        source = f"{path} line {number}"
        try:
            yield _parse_json(line, source), source
        except ResultsError:
            if not (tolerate_partial_last and number == len(lines)):
                raise
            warnings.warn(f"{source} is incomplete (an interrupted sweep?) and was ignored", ResultsWarning,
                          stacklevel=3)


def _describe(value: Any) -> str:
    text = json.dumps(value)
    return text if len(text) <= 60 else text[:57] + "..."


class _Reader:
    """Checks one JSON object, naming the source and the JSON pointer of what is wrong."""

    def __init__(self, value: Any, source: str, pointer: str = ""):
        self.value, self.source, self.pointer = value, source, pointer
        if not isinstance(value, dict):
            self.fail(pointer, "an object", value)

    def fail(self, pointer: str, expected: str, got: Any) -> None:
        raise ResultsError(f"{self.source}: {pointer or '/'}: expected {expected}, got {_describe(got)}")

    def get(self, key: str, expected: str, accept: Callable[[Any], bool], required: bool = True) -> Any:
        if key not in self.value:
            if required:
                raise ResultsError(f"{self.source}: {self.pointer or '/'}: expected a key \"{key}\" ({expected})")
            return None
        value = self.value[key]
        if not accept(value):
            self.fail(f"{self.pointer}/{key}", expected, value)
        return value


def _is_string(value: Any) -> bool:
    return isinstance(value, str)


def _is_string_or_null(value: Any) -> bool:
    return value is None or isinstance(value, str)


def _is_seed(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= _UINT64_MAX


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _label(value: Any) -> str:
    """A parameter value's label in run names and tables (value_label in sweep/sweep_spec.cpp)."""
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return _shortest(value)
    if isinstance(value, list):
        return "x".join(_label(element) for element in value)
    return json.dumps(value)


def _shortest(value: float) -> str:
    """The double as C++'s std::to_chars writes it: shortest digits, fixed or scientific, whichever is shorter."""
    if not math.isfinite(value):
        return repr(value)
    sign = "-" if math.copysign(1.0, value) < 0 else ""
    digits, exponent = _digits(abs(value))
    # value = 0.digits x 10^exponent
    if exponent >= len(digits):
        fixed = digits + "0" * (exponent - len(digits))
    elif exponent > 0:
        fixed = digits[:exponent] + "." + digits[exponent:]
    else:
        fixed = "0." + "0" * -exponent + digits
    mantissa = digits[0] + ("." + digits[1:] if len(digits) > 1 else "")
    scientific_exponent = exponent - 1
    scientific = f"{mantissa}e{'-' if scientific_exponent < 0 else '+'}{abs(scientific_exponent):02d}"
    return sign + (fixed if len(fixed) <= len(scientific) else scientific)


def _digits(value: float) -> tuple[str, int]:
    """The shortest round-trip digits of a non-negative double and its exponent e: value = 0.DIGITS x 10^e."""
    if value == 0:
        return "0", 1
    mantissa, _, exponent = f"{value!r}".partition("e")
    whole, _, fraction = mantissa.partition(".")
    digits = (whole + fraction).lstrip("0")
    leading_zeros = len(whole + fraction) - len((whole + fraction).lstrip("0"))
    position = len(whole) - leading_zeros + (int(exponent) if exponent else 0)
    return digits.rstrip("0") or "0", position


def _column(values: list[Any]) -> pd.Series:
    """A column of JSON values (None for missing) with a sensible dtype.

    Numbers become float64 with NaN where missing, integers int64 (uint64 beyond) when none is missing; booleans
    bool, or pandas' nullable boolean when some are missing; anything else, and integers that float64 would round
    (beyond 2^53), stays Python objects with None where missing.
    """
    present = [value for value in values if value is not None]
    complete = len(present) == len(values)
    if not present:
        return pd.Series(values, dtype="float64")
    if all(isinstance(value, bool) for value in present):
        return pd.Series(values, dtype="bool" if complete else "boolean")
    if all(_is_number(value) for value in present):
        integers = all(isinstance(value, int) for value in present)
        if integers and complete and all(abs(value) <= _INT64_MAX for value in present):
            return pd.Series(values, dtype="int64")
        if integers and complete and all(0 <= value <= _UINT64_MAX for value in present):
            return pd.Series(values, dtype="uint64")
        if all(not isinstance(value, int) or abs(value) <= _EXACT_FLOAT_INT for value in present):
            return pd.Series([np.nan if value is None else value for value in values], dtype="float64")
    return pd.Series(values, dtype="object")


def _results_file(path: PathLike) -> pathlib.Path:
    path = pathlib.Path(path)
    if path.is_dir():
        return path / "results.jsonl"
    if path.exists() or path.name == "results.jsonl":
        return path
    raise ResultsError(f"{path}: expected a sweep directory (campo sweep --out DIR) or its results.jsonl, "
                       "but there is no such file or directory")


def _manifest(path: pathlib.Path) -> tuple[str, list[str], list[str]]:
    """The sweep's name, its axis names (in spec order) and run IDs (in expansion order) from a sweep.json.

    Without one: the directory's name, and no axes or order (table_layout in sweep/results.cpp).
    """
    if not path.exists():
        return path.parent.resolve().name, [], []
    source = str(path)
    document = _Reader(_parse_json(_read_text(path), source), source)
    spec_file = document.get("spec_file", "the spec's file name", _is_string)
    spec = _Reader(document.get("spec", "the spec as read", lambda value: isinstance(value, dict)), source, "/spec")
    name = spec.get("name", "the sweep's name", _is_string, required=False) or pathlib.Path(spec_file).stem
    axes = spec.get("axes", "an array of axes", lambda value: isinstance(value, list), required=False) or []
    axis_names = [_Reader(axis, source, f"/spec/axes/{i}").get("name", "the axis's name", _is_string)
                  for i, axis in enumerate(axes)]
    runs = document.get("runs", "an array of the runs", lambda value: isinstance(value, list))
    run_ids = [_Reader(run, source, f"/runs/{i}").get("id", "the run's ID", _is_string) for i, run in enumerate(runs)]
    return name, axis_names, run_ids


def _read_line(value: Any, source: str) -> dict[str, Any]:
    """One results.jsonl line checked as `campo table` checks it (read_result in sweep/results.cpp)."""
    line = _Reader(value, source)
    run = {
        "id": line.get("id", "the run's ID, a string", _is_string),
        "scene": line.get("scene", "the scene's name, a string", _is_string),
        "params": line.get("params", "an object of axis values", lambda v: isinstance(v, dict)),
        "seed": line.get("seed", "an integer seed in [0, 18446744073709551615]", _is_seed),
        "status": line.get("status", "\"completed\" or \"failed\"", lambda v: v in ("completed", "failed")),
        "overrides": line.get("overrides", "an array of strings",
                              lambda v: isinstance(v, list) and all(isinstance(o, str) for o in v)),
    }
    # Results written before names and planners were recorded lack them.
    run["name"] = line.get("name", "the run's name, a string", _is_string, required=False) or run["id"]
    run["planner"] = line.get("planner", "the planner's label, a string", _is_string, required=False)
    if run["status"] == "completed":
        run["metrics"] = line.get("metrics", "the metrics object of a completed run", lambda v: isinstance(v, dict))
    else:
        line.get("metrics", "null for a failed run", lambda v: v is None)
        run["metrics"] = None
        run["reason"] = line.get("reason", "why the run failed, a string", _is_string)
    run["process_wall_time_s"] = line.get("wall_time_s", "a number of seconds", _is_number, required=False)
    for key in _STRING_KEYS:
        run[key] = line.get(key, "a string or null", _is_string_or_null, required=False)
    triage = line.get("triage", "an object", lambda v: isinstance(v, dict), required=False) or {}
    run["triage_dir"], run["triage_repro"] = triage.get("dir"), triage.get("repro")
    return run


def read_results(path: PathLike) -> pd.DataFrame:
    """A sweep's runs as a DataFrame, one row per run (docs/python.md, "Reading results").

    `path` is a sweep directory (`campo sweep --out DIR`) or its `results.jsonl`. When a run appears more than once
    (a resumed sweep that retried it) its last line counts, and an incomplete last line (an interrupted sweep) is
    ignored with a ResultsWarning, as in `campo table`. Rows follow the sweep's expansion order (from `sweep.json`
    beside the file; without it, the order of first appearance).

    Columns: `id`, `name`, `scene`, `planner`, `seed`, `status` (`completed` or `failed`), `reason` (a failed run's
    reason; else the episode's, the `reason` metric), `success` (outcome `reached`; False for a failed run, as
    `campo table`'s `success`); one column per axis, named as the axis (array values as their labels, "256x256");
    every key of the runs' `metrics` as in run.json (NaN or None where a run has none: every metric of a failed
    run); then `process_wall_time_s` (the line's `wall_time_s`), `run_dir`, `files_error`, `triage_dir`,
    `triage_repro`, `overrides`, `campo_version`, `git_rev`, `scene_sha256`, `spec_sha256`, `trajectory_sha256`.
    A name taken twice is kept by the axis; the other column is prefixed `run_` (identity and provenance) or
    `metric_` (a metric). `frame.attrs` holds the sweep's name (`sweep`), its `axes` and `metrics` columns in order.

    Raises ResultsError naming the file, line and JSON pointer of a line that is not what campo writes, and the
    path when there is no sweep there.
    """
    file = _results_file(path)
    text = _read_text(file)
    sweep_name, axes, expansion_order = _manifest(file.parent / "sweep.json")
    runs: dict[str, dict[str, Any]] = {}
    for value, source in _json_lines(file, text, tolerate_partial_last=True):
        run = _read_line(value, source)
        runs[run["id"]] = run  # a retried run: the last line counts, in the place of the first
    rank = {run_id: i for i, run_id in enumerate(expansion_order)}
    ordered = sorted(enumerate(runs.values()), key=lambda item: rank.get(item[1]["id"], len(rank) + item[0]))
    rows = [run for _, run in ordered]

    for run in rows:
        axes += [axis for axis in run["params"] if axis not in axes]
    metrics: list[str] = []
    for run in rows:
        metrics += [key for key in (run["metrics"] or {}) if key not in metrics and key != "reason"]

    columns: dict[str, list[Any]] = {}
    taken = set(axes)

    def add(name: str, values: list[Any], prefix: str) -> str:
        column = prefix + name if name in taken else name
        columns[column] = values
        return column

    for key in _IDENTITY_COLUMNS:
        if key == "success":
            values = [run["status"] == "completed" and run["metrics"].get("outcome") == "reached" for run in rows]
        elif key == "reason":
            values = [run["reason"] if run["metrics"] is None else run["metrics"].get("reason") for run in rows]
        else:
            values = [run[key] for run in rows]
        add(key, values, "run_")
    for axis in axes:
        columns[axis] = [_axis_value(run["params"].get(axis)) for run in rows]
    metric_columns = [add(key, [None if run["metrics"] is None else run["metrics"].get(key) for run in rows], "metric_")
                      for key in metrics]
    for key in _TRAILING_COLUMNS:
        add(key, [run[key] for run in rows], "run_")
    frame = pd.DataFrame({name: _column(values) for name, values in columns.items()}, index=pd.RangeIndex(len(rows)))
    frame.attrs.update(sweep=sweep_name, axes=axes, metrics=metric_columns)
    return frame


def _axis_value(value: Any) -> Any:
    # Arrays (a resolution [256, 256]) by their label, as in run names and tables: one hashable value per run.
    return _label(value) if isinstance(value, list) else value


@dataclasses.dataclass
class Run:
    """The files of one run (`campo run --out DIR`, a sweep's `runs/<name>/`), read by read_run()."""

    directory: pathlib.Path
    """The run's directory."""
    record: dict[str, Any] = dataclasses.field(repr=False)
    """run.json as read (integers exact: `final_state_hash` is a Python int)."""
    trajectory: pd.DataFrame = dataclasses.field(repr=False)
    """trajectory.csv, one row per planner call: every column numeric (NaN where empty) but `command`."""
    events: Optional[list[dict[str, Any]]] = dataclasses.field(repr=False)
    """The planner decisions, one {"time_s", "decisions"} per line of events.jsonl (or run.json's `events` array
    of older records); None where the directory holds neither (a sweep's triage directory), and for a run of
    several vehicles (each vehicle's are in `vehicles`)."""
    vehicles: dict[str, "Run"] = dataclasses.field(default_factory=dict, repr=False)
    """A run of several vehicles: each vehicle's own, by alias in scene order, its `record` the vehicle's entry
    of run.json's `vehicles` (alias, metrics, parameters, ...), its trajectory and events its own files.
    Empty for a run of one vehicle."""
    events_file: str = dataclasses.field(default="events.jsonl", repr=False)
    """The file of the directory `events` were read from (events_<alias>.jsonl for a vehicle of several)."""

    @property
    def metrics(self) -> dict[str, Any]:
        """run.json's `metrics`."""
        return self.record["metrics"]

    @property
    def planner(self) -> str:
        """The name of the run's planner, as run.json's `parameters.planner.name` records it ("" when absent)."""
        parameters = self.record.get("parameters")
        planner = parameters.get("planner") if isinstance(parameters, dict) else None
        name = planner.get("name") if isinstance(planner, dict) else None
        return name if isinstance(name, str) else ""

    @property
    def planner_record(self) -> Optional[PlannerRecord]:
        """The declared fields of the run's planner (campo.planner_record), None when it declares none."""
        return planner_record(self.planner)

    def decision(self, name: str) -> pd.Series:
        """The values of the planner's declared decision field `name` over the run: a Series indexed by `time_s`,
        one entry per event that holds the field, named `name`, its dtype as read_results' columns.

        The field is looked up by the planner's declaration (campo.planner_record); an undeclared name, or a
        planner that declares nothing, raises ResultsError listing what it declares. Each value is checked against
        its declaration: one that is not of its type raises ResultsError naming the file and its JSON pointer.
        """
        if self.vehicles:
            raise ResultsError(f"{self.directory}: a run of several vehicles ({', '.join(self.vehicles)}), each "
                               f"with its own planner: read one's with run.vehicles[alias].decision({name!r})")
        record = self.planner_record
        label = self.planner or "straight"
        fields = record.decisions if record else ()
        if not any(field.name == name for field in fields):
            raise ResultsError(f"{self.directory}: {_undeclared(label, name, fields)}")
        if self.events is None:
            raise ResultsError(f"{self.directory}: expected the planner's decisions (events.jsonl), but the run "
                               "directory holds none")
        # Where each event was read: a line of events.jsonl (campo writes no blank lines), else run.json's array.
        in_lines = (self.directory / self.events_file).exists()
        times, values = [], []
        for i, event in enumerate(self.events):
            decisions = event["decisions"]
            if name not in decisions:
                continue
            source, pointer = ((f"{self.directory / self.events_file} line {i + 1}", "/decisions") if in_lines
                               else (str(self.directory / "run.json"), f"/events/{i}/decisions"))
            try:
                _campo._check_record(self.planner, "decisions", {name: decisions[name]}, source, pointer)
            except _campo.InputError as error:
                raise ResultsError(str(error)) from None
            times.append(event["time_s"])
            values.append(decisions[name])
        series = _column(values)
        series.index = pd.Index(times, name="time_s", dtype="float64")
        series.name = name
        return series


def read_run(path: PathLike) -> Run:
    """Reads a run's directory (or its run.json): run.json, trajectory.csv and events.jsonl (docs/python.md);
    for a run of several vehicles each one's trajectory_<alias>.csv and events_<alias>.jsonl (Run.vehicles).

    Raises ResultsError naming the file (and line) that is missing or not what campo writes.
    """
    path = pathlib.Path(path)
    directory = path.parent if path.name == "run.json" and not path.is_dir() else path
    if not directory.is_dir():
        raise ResultsError(f"{directory}: expected a run directory (campo run --out DIR) or its run.json, "
                           "but there is no such directory")
    record_file = directory / "run.json"
    record = _Reader(_parse_json(_read_text(record_file), str(record_file)), str(record_file)).value
    reader = _Reader(record, str(record_file))
    reader.get("metrics", "the run's metrics, an object", lambda v: isinstance(v, dict))
    if "vehicles" not in record:
        return Run(directory=directory, record=record, trajectory=_read_trajectory(directory / "trajectory.csv"),
                   events=_read_events(directory / "events.jsonl", record, str(record_file)))
    # Several vehicles (docs/running.md): the run's metrics at the top, each vehicle's record and files its own.
    entries = reader.get("vehicles", "an array of the vehicles' records", lambda v: isinstance(v, list) and v)
    vehicles = {}
    for i, value in enumerate(entries):
        entry = _Reader(value, str(record_file), f"/vehicles/{i}")
        if not isinstance(value, dict):
            entry.fail(f"/vehicles/{i}", "a vehicle's record, an object", value)
        alias = entry.get("alias", "the vehicle's alias, a string", _is_string)
        entry.get("metrics", "the vehicle's metrics, an object", lambda v: isinstance(v, dict))
        trajectory_file = entry.get("trajectory_file", "the name of its trajectory file", _is_file_name)
        log = entry.get("event_log", "its event log, an object", lambda v: isinstance(v, dict))
        events_file = _Reader(log, str(record_file), f"/vehicles/{i}/event_log").get(
            "file", "the name of its events file", _is_file_name)
        vehicles[alias] = Run(directory=directory, record=value,
                              trajectory=_read_trajectory(directory / trajectory_file),
                              events=_read_events(directory / events_file, {}, str(record_file)),
                              events_file=events_file)
    trajectory = pd.concat([run.trajectory.assign(vehicle=alias) for alias, run in vehicles.items()],
                           ignore_index=True)
    trajectory = trajectory[["vehicle"] + [c for c in trajectory.columns if c != "vehicle"]]
    return Run(directory=directory, record=record, trajectory=trajectory, events=None, vehicles=vehicles)


def _is_file_name(value: Any) -> bool:
    """A file of the run's own directory, not a path elsewhere."""
    return isinstance(value, str) and value not in ("", ".", "..") and "/" not in value and "\\" not in value


def _read_trajectory(path: pathlib.Path) -> pd.DataFrame:
    if not path.is_file():
        raise ResultsError(f"{path}: cannot read: No such file or directory")
    try:
        # round_trip: every number exactly as written (the default parser may be one unit in the last place off).
        frame = pd.read_csv(path, dtype={"command": "object"}, float_precision="round_trip", keep_default_na=False,
                            na_values=_CSV_MISSING)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError, ValueError) as error:
        raise ResultsError(f"{path}: expected campo's trajectory CSV, but {error}") from None
    for name in frame.columns:
        if name == "command":
            continue
        if frame[name].dtype == object:
            numbers = pd.to_numeric(frame[name], errors="coerce")
            bad = frame[name].notna() & numbers.isna()
            if bad.any():
                row = int(np.flatnonzero(bad.to_numpy())[0])
                raise ResultsError(f"{path} line {row + 2}: column {name}: expected a number or nothing, "
                                   f"got {frame[name].iloc[row]!r}")
            frame[name] = numbers
    return frame


def _read_events(path: pathlib.Path, record: dict[str, Any], record_source: str) -> Optional[list[dict[str, Any]]]:
    if not path.exists():
        # Records from before events.jsonl existed keep the decisions in run.json.
        if "events" in record:
            return _check_events(record["events"], record_source)
        return None
    events = []
    for value, source in _json_lines(path, _read_text(path), tolerate_partial_last=False):
        event = _Reader(value, source)
        event.get("time_s", "the simulated time, a number of seconds", _is_number)
        event.get("decisions", "an object of the planner's decisions", lambda v: isinstance(v, dict))
        events.append(value)
    return events


def _check_events(events: Any, source: str) -> list[dict[str, Any]]:
    if not isinstance(events, list):
        raise ResultsError(f"{source}: /events: expected an array of events, got {_describe(events)}")
    for i, value in enumerate(events):
        event = _Reader(value, source, f"/events/{i}")
        event.get("time_s", "the simulated time, a number of seconds", _is_number)
        event.get("decisions", "an object of the planner's decisions", lambda v: isinstance(v, dict))
    return events
