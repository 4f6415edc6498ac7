"""What a planner records beyond the generic decisions, as it declares it (docs/python.md, "Planner records").

A planner declares each of its own decision fields, its replanning steps' fields and its metrics once: name, type,
unit, meaning (campo/record_fields.hpp). `planner_record(name)` returns a built-in or plugin planner's declarations,
or those of a Python planner class (its `decision_fields`), read from the same declarations the figures read.
"""

from __future__ import annotations

import dataclasses
from typing import NamedTuple, Optional

from . import _campo

__all__ = ["PlannerRecord", "RecordField", "planner_record"]


class RecordField(NamedTuple):
    """One declared field. A Python planner's `decision_fields` lists them (or plain 4-tuples)."""

    name: str
    """Its key in the record."""
    type: str
    """What its JSON value is: "flag", "integer", "number" (an integer too), "text", "array" or "object"."""
    unit: str
    """"m", "deg", ...; "" if none."""
    meaning: str
    """One line."""


@dataclasses.dataclass(frozen=True)
class PlannerRecord:
    """A planner's declared fields, each part in declaration order."""

    name: str
    """The planner's name."""
    decisions: tuple[RecordField, ...]
    """The fields it adds to the decisions of events.jsonl (beside the typed ones)."""
    replan: tuple[RecordField, ...]
    """The fields of its replanning steps' details (a decision's `replan`)."""
    metrics: tuple[RecordField, ...]
    """Its own metrics, if any."""

    def decision(self, name: str) -> RecordField:
        """The declared decision field `name`; KeyError naming the declared ones when it is not declared."""
        for field in self.decisions:
            if field.name == name:
                return field
        raise KeyError(_undeclared(self.name, name, self.decisions))


def _undeclared(planner: str, name: str, fields: tuple[RecordField, ...]) -> str:
    declared = ", ".join(field.name for field in fields) or "none"
    return f"planner {planner} declares no decision field \"{name}\" (it declares: {declared})"


def planner_record(name: str) -> Optional[PlannerRecord]:
    """The declared fields of planner `name`: a built-in planner's, a loaded plugin's, or, for
    "python:module:Class", the class's `decision_fields` (the module is imported). None for a planner that declares
    nothing (its own decision keys are free) and for "external" (campo.Episode's runs); "" is the default planner.
    campo.InputError when `name` names no planner, or a Python class cannot be imported or declares malformed fields.
    """
    parts = _campo._planner_fields(name)
    if parts is None:
        return None
    fields = {part: tuple(RecordField(*field) for field in parts[part]) for part in ("decisions", "replan", "metrics")}
    return PlannerRecord(name=name, **fields)
