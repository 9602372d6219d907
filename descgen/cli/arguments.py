"""Option values that validate themselves: argparse ``type=`` callables.

A bad value raises :class:`argparse.ArgumentTypeError` while the command line is parsed, so
the command never starts and argparse exits 2. A value whose problem has a finding code (a
duration with a wrong unit, a malformed ``NAME:=VALUE``) raises :class:`OptionError`, which
carries the finding: the parser prints it like every other finding (``<command line>:
error[CODE]: message`` and a hint), so the codes and messages stay those the README
documents. Durations go through the spec's quantity parser (``units.duration``).
"""

from __future__ import annotations

import argparse
import math
import re
from collections.abc import Callable
from pathlib import Path

from descgen.codes import Code, raisable
from descgen.codes.command import IMP008, RULE001
from descgen.codes.control import CTRL032
from descgen.codes.generate import GEN010
from descgen.codes.importer import IMP027
from descgen.codes.read import CTRL054, READ005
from descgen.core import units
from descgen.core.findings import Where

COMMAND_LINE = Where("<command line>")


class OptionError(argparse.ArgumentTypeError):
    """A bad option value with a finding code."""

    def __init__(self, code: Code, message: str, hint: str, where: Where = COMMAND_LINE) -> None:
        super().__init__(message)
        self.finding = code.finding(message, hint, "option", where)


Bounds = Callable[[], tuple[float, float]]  # (low, high) in seconds, looked up when a value is given


class Duration:
    """A time option in seconds within the command's bounds. ``bare_seconds`` reads a plain
    number as seconds, for options documented in seconds before they took units."""

    def __init__(self, option: str, bounds: Bounds, bare_seconds: bool = True) -> None:
        self.option = option
        self.bounds = bounds  # a function, so that the command's module is imported only when needed
        self.bare_seconds = bare_seconds
        self.__name__ = "duration"  # argparse names the type in its own messages

    def __call__(self, text: str) -> float:
        low, high = self.bounds()
        try:
            return units.duration(text, low, high, bare_seconds=self.bare_seconds)
        except units.QuantityError as exc:
            raise OptionError(raisable(exc.code), f"{self.option}: {exc.message}", exc.hint) from None


class Nanoseconds(Duration):
    """A wait or an age in integer nanoseconds (what the tf buffer works in); units required."""

    def __init__(self, option: str, bounds: Bounds) -> None:
        super().__init__(option, bounds, bare_seconds=False)

    def __call__(self, text: str) -> int:
        return round(super().__call__(text) * 1e9)


def xacro_arg(text: str) -> tuple[str, str]:
    """``--xacro-arg NAME:=VALUE`` as (name, value)."""
    name, sep, value = text.partition(":=")
    if not sep or not name:
        raise OptionError(
            READ005, f"--xacro-arg '{text}' is not name:=value", "write e.g. --xacro-arg use_gripper:=true"
        )
    return name, value


def launch_arg(text: str) -> tuple[str, str]:
    """``--launch-arg NAME:=VALUE`` (a launch configuration, for ``$(var NAME)`` in a
    controllers YAML) as (name, value)."""
    from descgen.core.launch_subst import check_value

    name, sep, value = text.partition(":=")
    hint = "write e.g. --launch-arg joint_prefix:=joint (one line, no control characters)"
    if not sep or not name:
        raise OptionError(CTRL054, f"--launch-arg {text!a} is not name:=value", hint)
    if (problem := check_value(name, value)) is not None:
        raise OptionError(CTRL054, f"--launch-arg: {problem}", hint)
    return name, value


def variant(text: str) -> tuple[str, tuple[tuple[str, str], ...]]:
    """``--variant NAME:[ARG:=VALUE[,ARG:=VALUE]...]`` (import): a hardware variant (mock,
    gazebo, real) and the Xacro arguments that select it, as (name, ((arg, value), ...))."""
    name, sep, rest = text.partition(":")
    hint = "write e.g. --variant mock:use_mock_hardware:=true or --variant real: (no arguments)"
    if not sep or name not in ("mock", "gazebo", "real"):
        raise OptionError(IMP027, f"--variant '{text}' is not mock|gazebo|real:[ARG:=VALUE,...]", hint)
    args = []
    for item in rest.split(",") if rest else []:
        arg, sep, value = item.partition(":=")
        if not sep or not arg:
            raise OptionError(IMP027, f"--variant '{text}': '{item}' is not name:=value", hint)
        args.append((arg, value))
    return name, tuple(args)


def plant_fault(text: str) -> tuple[str, str]:
    """``--plant-fault JOINT:=KIND`` as (joint, kind); whether the joint exists is checked
    against the robot (``control.system.plant_faults``)."""
    from descgen.commands.control.system import FAULT_KINDS

    joint, sep, kind = text.partition(":=")
    if not sep or not joint:
        raise OptionError(
            CTRL032, f"--plant-fault {text!a} is not JOINT:=KIND", "write e.g. --plant-fault elbow_joint:=stuck"
        )
    if kind not in FAULT_KINDS:
        raise OptionError(
            CTRL032, f"--plant-fault {text!a}: unknown fault kind {kind!a}", f"use one of {', '.join(FAULT_KINDS)}"
        )
    return joint, kind


def path(text: str) -> Path:
    """A file or folder named on the command line; empty text is no path (``Path("")`` would
    quietly be the current folder)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty path names nothing")
    return Path(text)


def templates_folder(text: str) -> Path:
    """``--templates DIR``: a folder of template overrides."""
    folder = Path(text)
    if not folder.is_dir():
        raise OptionError(
            GEN010, f"--templates {folder} is not a folder", "name a folder of template overrides", Where(str(folder))
        )
    return folder


def folder(text: str) -> Path:
    """A folder that must exist (``--package-path``): a typo would otherwise be ignored and
    every ``$(find)`` or ``package://`` under it reported as missing."""
    given = Path(text)
    if not given.is_dir():
        what = "does not exist" if not given.exists() else "is not a folder"
        raise argparse.ArgumentTypeError(f"{text!a} {what}")
    return given


def rule_code(text: str) -> str:
    """``descgen rules CODE``: a code of the catalogue, in any case."""
    from descgen.audit.catalogue import explain
    from descgen.output import report

    code = text.strip().upper()
    if explain(code) is None:
        raise OptionError(
            RULE001, f"no code {report.printable(text, 80)} in the catalogue", "run descgen rules for the list"
        )
    return code


def import_units(text: str) -> object:
    """``--units`` of import: ``mm,deg,kg`` (any subset, any order) or ``si``."""
    from descgen.commands.importer.quantity import Units

    try:
        return Units.parse(text)
    except ValueError as exc:
        raise OptionError(IMP008, f"--units: {exc}", "write e.g. --units mm,deg,kg or --units si") from None


MAX_JOBS = 64  # descgen.commands.tf.bagaudit.MAX_JOBS, not imported: parsing must not import rosbags' users


def jobs(text: str) -> int:
    """How many processes a command may run at once: a whole number from 1 to MAX_JOBS."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text[:40]}' is not a whole number of processes") from None
    if not 1 <= n <= MAX_JOBS:
        raise argparse.ArgumentTypeError(f"{n} processes is outside 1 to {MAX_JOBS}")
    return n


def port(text: str) -> int:
    """A TCP port for ``descgen view``: 0 (any free port) or 1 to 65535."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text[:40]}' is not a port number") from None
    if not 0 <= n <= 65535:
        raise argparse.ArgumentTypeError(f"{n} is outside 0 (any free port) to 65535")
    return n


def host(text: str) -> str:
    """An address to bind ``descgen view`` to: an IP address or ``localhost`` (never a name that
    needs a lookup: what is exposed must be clear from the command line)."""
    import ipaddress

    if text == "localhost":
        return "127.0.0.1"
    try:
        return str(ipaddress.ip_address(text))
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text[:40]}' is not an IP address (e.g. 127.0.0.1)") from None


def sweep_steps(text: str) -> int:
    """``descgen sweep --steps N``: steps per joint, 1 to 3600 (descgen.physics.sweep.MAX_STEPS, not
    imported: parsing must not import numpy)."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!a} is not a whole number") from None
    if not 1 <= n <= 3600:
        raise argparse.ArgumentTypeError(f"{n} is not between 1 and 3600")
    return n


_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]{0,127}$")
_PREFIX = re.compile(r"^[A-Za-z0-9_./-]{0,64}$")
_DATE = re.compile(r"^\d{4}-\d{2}-\d{2}$")


def name(text: str) -> str:
    """A plain identifier (a calibration source, a sensor of the spec)."""
    if not _NAME.fullmatch(text):
        raise argparse.ArgumentTypeError(f"{text[:40]!a} is not a name (letters, digits and _, e.g. ur_factory)")
    return text


def prefix(text: str) -> str:
    """A joint and frame name prefix (``left_``): what names may start with."""
    if not _PREFIX.fullmatch(text):
        raise argparse.ArgumentTypeError(f"{text[:40]!a} is not a name prefix (letters, digits, _ . / -)")
    return text


def date(text: str) -> str:
    """A calendar date, YYYY-MM-DD."""
    import datetime

    if not _DATE.fullmatch(text):
        raise argparse.ArgumentTypeError(f"{text[:40]!a} is not a date YYYY-MM-DD")
    try:
        datetime.date.fromisoformat(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!a} is not a calendar date") from None
    return text


class Length:
    """A length option with a unit (``1 mm``, ``0.5 in``), in metres; positive and at most 1 m."""

    def __init__(self, option: str) -> None:
        self.option = option
        self.__name__ = "length"

    def __call__(self, text: str) -> float:
        try:
            value = units.to_si(text, "length")
        except units.QuantityError as exc:
            raise OptionError(raisable(exc.code), f"{self.option}: {exc.message}", exc.hint) from None
        if not 0 < value <= 1.0 or not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{self.option} {text[:40]!a} is not between 0 and 1 m")
        return value


def robot_mapping(text: str) -> object:
    """``--robot GLOB=ROBOT[@VERSION]`` (tf-audit): which recordings are of which robot."""
    from descgen.commands.fleet.identity import parse

    try:
        return parse(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"'{text[:60]}': {exc}") from None


def address(text: str) -> str:
    """``--address`` of a Ray cluster: host:port, ray://host:port or auto; one printable word."""
    if not text or len(text) > 300 or any(not c.isprintable() or c.isspace() for c in text):
        raise argparse.ArgumentTypeError("give the head node as host:port, ray://host:port or auto")
    return text


def start_time(text: str) -> int:
    """``--start`` of tf-scenario: an ISO 8601 date and time (UTC unless it says otherwise), as
    nanoseconds since the epoch."""
    from datetime import UTC, datetime

    try:
        when = datetime.fromisoformat(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text[:40]}' is not an ISO 8601 time, e.g. 2026-11-29T08:00:00") from None
    if when.tzinfo is None:
        when = when.replace(tzinfo=UTC)
    if not 1970 <= when.astimezone(UTC).year < 2100:
        raise argparse.ArgumentTypeError(f"{text[:40]} is outside 1970 to 2099")
    delta = when - datetime(1970, 1, 1, tzinfo=UTC)
    return (delta.days * 86400 + delta.seconds) * 1_000_000_000 + delta.microseconds * 1000


def percent(text: str) -> float:
    """A share in percent, 0 to 100 (a trailing % allowed)."""
    try:
        value = float(text.strip().removesuffix("%"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text[:40]}' is not a percentage, e.g. 0.5") from None
    if not 0.0 <= value <= 100.0:  # NaN fails both
        raise argparse.ArgumentTypeError(f"{text[:40]} is outside 0 to 100 percent")
    return value
