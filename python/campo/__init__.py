"""campo from Python: drive the closed loop, write planners, read results.

The simulation stays C++ (the native module campo._campo); Python gets
episodes stepped Gymnasium-style, planners called from the C++ loop, and
results as pandas data frames. See docs/python.md.

    import campo
    ep = campo.Episode("two_barriers", seed=3)
    obs = ep.reset()
    while not ep.done:
        obs, done, info = ep.step(campo.Command.go_to([16, 0, 3], speed_mps=0.6))
    print(ep.metrics()["outcome"])

A scene of several vehicles is stepped with dicts keyed by alias (PettingZoo's parallel API):

    ep = campo.Episode("two_drones_head_on")
    obs = ep.reset()
    while not ep.done:
        obs, dones, infos = ep.step({a: campo.Command.go_to(obs[a].mission_m[-1]) for a in ep.agents})
"""

import os as _os

from . import _campo
from ._campo import (  # noqa: F401 (re-exported)
    AttitudeThrust,
    Command,
    Episode,
    InputError,
    Observation,
    OutputError,
    PlannerExit,
    PlannerInterrupted,
    PlanResult,
    Rotors,
    SensorReading,
    State,
    Velocity,
    Wheels,
    __version__,
    bundled_scene,
    planners,
    run,
)
from .records import PlannerRecord, RecordField, planner_record  # noqa: F401
from .results import ResultsError, ResultsWarning, Run, read_results, read_run  # noqa: F401

# Installed by pip (pyproject.toml; docs/python.md, "Install with pip"), the package carries the bundled
# scenes and sweep specs in data/scenes, searched after the working directory's scenes/; from build/python
# or a cmake --install prefix it has none, and libcampo finds them from its own folder (sweep/bundled.cpp).
_package_scenes = _os.path.join(_os.path.dirname(_os.path.abspath(__file__)), "data", "scenes")
if _os.path.isdir(_package_scenes):
    _campo._set_package_bundled_folder(_package_scenes)


class Planner:
    """Base class of planners written in Python.

    Subclass it and define plan(self, obs) returning a campo.PlanResult; it
    runs in campo's C++ closed loop through campo.run(scene, planner=...), or
    by name: `campo run --planner python:package.module:ClassName`, or a sweep
    spec's planner of that form, whose params become the constructor's keyword
    arguments. An exception in plan() ends the run as failed, its traceback
    the run's reason, as does a decision its `decision_fields` do not declare.
    """

    #: The vehicle types the planner drives.
    vehicles = ("quadrotor", "rover")

    #: Its own decision fields, declared: a list of campo.RecordField(name, type, unit, meaning) (or 4-tuples).
    #: When declared, every key of its decisions other than the typed ones must be one of them, of its type;
    #: None (the default): its own keys are free.
    decision_fields = None

    def plan(self, obs):
        raise NotImplementedError("a campo.Planner defines plan(self, obs)")

    def parameters(self):
        """The planner's effective parameters, recorded in run.json."""
        return {}
