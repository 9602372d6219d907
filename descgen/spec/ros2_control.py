"""The spec's ``ros2_control`` block -> the model's: joints and their interfaces, hardware
parameters as ros2_control's parser reads them, controllers with their parameters (text
with a unit converted to SI) and calibrated values."""

from __future__ import annotations

import re

from .. import model as m
from .. import units
from ..yamlsource import Path_
from . import models as s
from .convert import Converter

_NUMERIC_START = re.compile(r"^\s*[-+]?(\d|\.\d)")


def ros2_control(conv: Converter, rc: s.Ros2ControlSpec) -> m.Ros2Control:
    """Needs ``conv.joint_types``: an initial position is in its joint's unit."""
    base = ("ros2_control",)
    joints = []
    for i, cj in enumerate(rc.joints):
        p = (*base, "joints", i)
        initial = None
        if cj.initial_position is not None:
            initial = conv.joint_value(cj.name, cj.initial_position, (*p, "initial_position"))
        state = tuple(m.Interface(n, initial_value=initial if n == "position" else None) for n in cj.state)
        mimic = None if cj.mimic is None else _param_text(cj.mimic)
        joints.append(
            m.ControlJoint(cj.name, tuple(m.Interface(n) for n in cj.command), state, cj.on_limit, conv.where(p), mimic)
        )
    controllers = []
    for i, c in enumerate(rc.controllers):
        p = (*base, "controllers", i)
        params = tuple((k, param(v, (*p, "params", k))) for k, v in c.params.items())
        calibrated = tuple(
            m.Calibrated(
                k,
                cal.value.si,
                None if cal.tolerance is None else cal.tolerance.si,
                cal.source,
                conv.where((*p, "calibrated", k)),
            )
            for k, cal in c.calibrated.items()
        )
        controllers.append(m.Controller(c.name, c.type, params, conv.where(p), calibrated))
    hw = tuple((k, _param_text(v)) for k, v in rc.hardware.params.items())
    return m.Ros2Control(
        rc.name,
        rc.type,
        rc.hardware.plugin,
        hw,
        tuple(joints),
        rc.update_rate.si,
        tuple(controllers),
        conv.where(base),
    )


def param(value: object, path: Path_) -> object:
    """Controller parameters pass through; text that starts with a number and has a
    unit (``"500 ms"``, ``"0.5 m/s"``, ``"90 deg/s"``) is converted to SI."""
    if isinstance(value, str) and _NUMERIC_START.match(value):
        try:
            q = units.parse(value)
        except units.QuantityError:
            return value
        if q.unitless:
            return value
        return float(q.to_base_units().magnitude) + 0.0
    if isinstance(value, list):
        return tuple(param(v, (*path, i)) for i, v in enumerate(value))
    if isinstance(value, dict):
        return tuple((str(k), param(v, (*path, str(k)))) for k, v in value.items())
    return value


def _param_text(v: object) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"  # ros2_control's parse_bool takes only true/false
    return str(v)
