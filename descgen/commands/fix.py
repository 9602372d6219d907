"""``descgen fix SPEC`` (and ``import --fix``): the fixes that cannot change what the robot is,
applied to the spec's text and printed as a diff.

A fix is safe when it names the same thing the way Jazzy reads it, or removes what Jazzy does
not read: a hardware plugin Jazzy renamed one to one (``fake_components/GenericSystem`` ->
``mock_components/GenericSystem``, CTRL045), GenericSystem parameters it renamed one to one
(``fake_sensor_commands`` -> ``mock_sensor_commands``, CTRL046), a controller parameter
Jazzy removed (CTRL063, written on a line of its own under ``params:``), and the waivers of
the findings so fixed. A value that would change the robot (a mass, a tensor, a limit) is
never touched: its finding's hint gives the value that would pass.

The text is edited in place (comments, order and formatting stay), then read again: the fix
is kept only if the robot's links and joints are exactly what they were, the fixed findings
are gone and no finding is new (FIX001 otherwise: nothing is written).
"""

from __future__ import annotations

import dataclasses
import difflib
import re
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from descgen.codes.command import FIX001
from descgen.core.findings import Finding, InputError, Where
from descgen.core.record import record
from descgen.infra.yamlsource import Document, loads

# CTRL045's and CTRL046's one-to-one renames (audit/rules/control.py holds the full tables; a
# Gazebo Classic plugin has no one-to-one Jazzy replacement, so it is not fixed here)
PLUGIN_RENAMES = {"fake_components/GenericSystem": "mock_components/GenericSystem"}
PARAM_RENAMES = {"fake_sensor_commands": "mock_sensor_commands", "fake_gpio_commands": "mock_gpio_commands"}


@record
class Fix:
    """One finding fixed: its code and subject, and what changed, in words."""

    code: str
    subject: str
    what: str
    message: str  # the finding's, to tell it from another of the same code and subject
    target: str = ""  # CTRL063: the controller, and the parameter removed from it
    param: str = ""


@record
class Fixed:
    """The spec's text after the safe fixes, and which findings they fixed."""

    before: str
    after: str
    fixes: tuple[Fix, ...]

    def diff(self, name: str) -> str:
        return "".join(
            difflib.unified_diff(
                self.before.splitlines(keepends=True),
                self.after.splitlines(keepends=True),
                fromfile=f"a/{name}",
                tofile=f"b/{name}",
            )
        )


def fix_text(text: str, file: str) -> Fixed:
    """The safe fixes of the spec ``text`` (named ``file`` in messages). Raises InputError when
    the spec cannot be read (its errors), or with FIX001 when a fix would change the robot."""
    robot, found = _read(text, file)
    lines = text.splitlines(keepends=True)
    doc = loads(text, file)
    fixes: list[Fix] = []
    deleted: set[int] = set()  # 0-based line numbers
    for f in found:
        for fixer in _FIXERS.get(f.code, ()):
            done = fixer(f, doc, lines, deleted)
            if done is not None:
                dropped = _REMOVED.search(f.message) if f.code == "CTRL063" else None
                where = (dropped["controller"], dropped["param"]) if dropped else ("", "")
                fixes.append(Fix(f.code, f.subject, done, f.message, *where))
                break
    if not fixes:
        return Fixed(text, text, ())
    fixed = {(x.code, x.subject, x.message) for x in fixes}
    left = {(f.code, f.subject) for f in found if (f.code, f.subject, f.message) not in fixed}
    _drop_waivers(doc, lines, deleted, {(x.code, x.subject) for x in fixes} - left)
    after = "".join(line for i, line in enumerate(lines) if i not in deleted)
    _verify(robot, found, after, file, fixes)
    return Fixed(text, after, tuple(fixes))


def _read(text: str, file: str) -> tuple[Any, list[Finding]]:
    """The model and every rule's finding (waived ones too: a fix makes their waiver needless)."""
    from descgen.audit.registry import run
    from descgen.audit.spec import load_spec_text

    loaded = load_spec_text(text, file, rules=False)
    return loaded.robot, run(loaded.robot)


# -- the fixers: each edits ``lines`` for one finding, or returns None when it cannot ----------

Fixer = Callable[[Finding, Document, list[str], set[int]], str | None]
_COMMENT = re.compile(r"(^|\s)#")


def _replace(lines: list[str], pattern: re.Pattern[str], new: str) -> int:
    """Every match of ``pattern`` outside a comment, its group 1 replaced by ``new``; how many."""
    n = 0
    for i, line in enumerate(lines):
        m = _COMMENT.search(line)
        code, comment = (line[: m.start()], line[m.start() :]) if m else (line, "")
        code, k = pattern.subn(lambda g: g.group(0).replace(g.group(1), new), code)
        if k:
            lines[i] = code + comment
            n += k
    return n


def _plugin_pattern(old: str) -> re.Pattern[str]:
    """``old`` as a hardware plugin: a spec's ``plugin: old`` (quoted or not) or pass-through
    XML's ``<plugin>old</plugin>``; the word elsewhere (a comment, a description) is not a plugin."""
    token = re.escape(old)
    return re.compile(rf"(?:\bplugin\s*:\s*[\"']?|<plugin>\s*)({token})(?=[\"']?\s*(?:$|</plugin>|[,}}\s]))")


def _plugin(f: Finding, doc: Document, lines: list[str], deleted: set[int]) -> str | None:
    for old, new in PLUGIN_RENAMES.items():
        if old not in f.message:
            continue
        pattern = _plugin_pattern(old)
        # one edit renames every block's plugin: a later block's finding is fixed by then
        if _replace(lines, pattern, new) or not any(pattern.search(line) for line in lines):
            return f"{old} -> {new}"
    return None


def _hw_param(f: Finding, doc: Document, lines: list[str], deleted: set[int]) -> str | None:
    """A GenericSystem parameter under the spec's ``hardware: params:`` (the mock hardware's;
    a vendor driver's variant may take a parameter of the same name, which is not renamed),
    renamed where its key stands, in block or flow style."""
    for old, new in PARAM_RENAMES.items():
        path = ("ros2_control", "hardware", "params", old)
        if f" sets {old}," not in f.message or path not in doc.key_marks:
            continue
        line, col = doc.key_marks[path][0] - 1, doc.key_marks[path][1] - 1
        text = lines[line]
        at = col + 1 if text[col : col + 1] in ("'", '"') else col
        if text[at : at + len(old)] == old:
            lines[line] = text[:at] + new + text[at + len(old) :]
            return f"{old} -> {new}"
    return None


_REMOVED = re.compile(r"controller '(?P<controller>[^']+)' sets '(?P<param>[\w.]+)', which")


def _removed_param(f: Finding, doc: Document, lines: list[str], deleted: set[int]) -> str | None:
    """A removed parameter written as ``key: value`` on a line of its own under the
    controller's ``params:`` (dotted keys as nested mappings or one dotted key)."""
    m = _REMOVED.search(f.message)
    controllers = _get(doc.data, ("ros2_control", "controllers"))
    if m is None or not isinstance(controllers, list):
        return None
    for i, c in enumerate(controllers):
        if not isinstance(c, dict) or c.get("name") != m["controller"]:
            continue
        parts = tuple(m["param"].split("."))
        for path in (
            ("ros2_control", "controllers", i, "params", *parts),
            ("ros2_control", "controllers", i, "params", m["param"]),
        ):
            if not isinstance(_get(doc.data, path), (str, int, float, bool, type(None))) or path not in doc.key_marks:
                continue
            line = doc.key_marks[path][0] - 1
            if path not in doc.value_marks or doc.value_marks[path][0] - 1 != line or not _one_line(lines, line):
                return None
            deleted.add(line)
            return f"removed {m['param']} from controller {m['controller']}"
    return None


_SCALAR_ENTRY = re.compile(r"\s*[\w.\"'-]+\s*:\s*[^{\[|>&*!\s][^{\[]*")  # key: a plain or quoted scalar


def _one_line(lines: list[str], i: int) -> bool:
    """``key: scalar`` alone on its line, in block style, the next line not deeper."""
    text = lines[i]
    body = _COMMENT.split(text, maxsplit=1)[0].rstrip()
    if not _SCALAR_ENTRY.fullmatch(body):
        return False
    indent = len(text) - len(text.lstrip())
    nxt = next((line for line in lines[i + 1 :] if line.strip() and not line.lstrip().startswith("#")), "")
    return not nxt or len(nxt) - len(nxt.lstrip()) <= indent


_FIXERS: dict[str, tuple[Fixer, ...]] = {
    "CTRL045": (_plugin,),
    "CTRL046": (_hw_param,),
    "CTRL063": (_removed_param,),
}


def _get(data: Any, path: Sequence[Any]) -> Any:
    for key in path:
        try:
            data = data[key]
        except (KeyError, IndexError, TypeError):
            return None
    return data


def _drop_waivers(doc: Document, lines: list[str], deleted: set[int], fixed: set[tuple[str, str]]) -> None:
    """The waivers of the fixed findings, removed with the lines they stand on (each entry on
    lines of its own, as import writes them); the ``waivers:`` key too when none is left."""
    waivers = _get(doc.data, ("waivers",))
    if not isinstance(waivers, list):
        return
    starts = [doc.value_marks.get(("waivers", i), (0, 0))[0] - 1 for i in range(len(waivers))]
    ends = [*(s for s in starts[1:]), _section_end(lines, starts[-1] if starts else 0)]
    dropped = 0
    for i, w in enumerate(waivers):
        if isinstance(w, dict) and (w.get("code"), w.get("subject")) in fixed and starts[i] >= 0:
            span = range(starts[i], ends[i])
            if any(_shares_line(lines, k, starts, i) for k in span):
                continue
            deleted.update(span)
            dropped += 1
    if dropped == len(waivers) and ("waivers",) in doc.key_marks:
        deleted.add(doc.key_marks[("waivers",)][0] - 1)


def _shares_line(lines: list[str], k: int, starts: list[int], i: int) -> bool:
    """Whether line ``k`` holds another waiver too (a flow sequence on one line)."""
    return any(s == k for j, s in enumerate(starts) if j != i)


def _section_end(lines: list[str], start: int) -> int:
    """The line after the last waiver entry: the next line as shallow as ``waivers:`` itself."""
    for k in range(start + 1, len(lines)):
        text = lines[k]
        if text.strip() and not text.startswith((" ", "\t", "-")):
            return k
    return len(lines)


# -- the proof that nothing but the fixed findings changed ---------------------------------


def _verify(robot: Any, before: list[Finding], text: str, file: str, fixes: Iterable[Fix]) -> None:
    try:
        robot_after, after = _read(text, file)
    except InputError as exc:
        why = next((f for f in exc.findings if f.blocks), exc.findings[0]).message
        raise _refused(file, f"the fixed spec does not read: {why}") from None
    removed = {(x.target, x.param) for x in fixes if x.param}
    if _plain(_expected(robot, removed)) != _plain(_expected(robot_after, set())):
        raise _refused(file, "a fix changed more of the robot than the names and parameters it fixes")
    gone = {(f.code, f.subject, f.message) for f in fixes}
    old = sorted((f.code, f.subject, _renamed(f.message)) for f in before if (f.code, f.subject, f.message) not in gone)
    new = sorted((f.code, f.subject, f.message) for f in after)
    if new != old:
        raise _refused(file, "the findings after the fix are not those before it less the fixed ones")


def _mock_renamed(variants: Any) -> Any:
    """The mock variant (GenericSystem: the spec's default hardware) renamed as the fixes rename
    it; another variant's plugin and parameters are its vendor's, and must stay as they are."""
    return tuple(
        dataclasses.replace(v, plugin=_renamed(v.plugin), params=tuple((_renamed(k), x) for k, x in v.params))
        if _renamed(v.plugin) == "mock_components/GenericSystem"
        else v
        for v in variants
    )


def _renamed(message: str) -> str:
    """A finding's message as it reads once the renames are made (it may name the plugin)."""
    for old, new in (*PLUGIN_RENAMES.items(), *PARAM_RENAMES.items()):
        message = message.replace(old, new)
    return message


def _expected(robot: Any, removed: set[tuple[str, str]]) -> Any:
    """The robot as the fixes should leave it, for comparison: the renames made everywhere,
    the removed parameters gone, and what a fix may change besides (the waivers, the spec's
    hash) set aside. Everything else must be equal, value for value."""
    rc = robot.ros2_control
    if rc is not None:
        controllers = tuple(
            dataclasses.replace(c, params=tuple(p for p in c.params if (c.name, p[0]) not in removed), marks=())
            for c in rc.controllers
        )
        blocks = tuple(
            dataclasses.replace(
                b,
                plugin=_renamed(b.plugin),
                params=tuple((_renamed(k), v) for k, v in b.params),
                variants=_mock_renamed(b.variants),
            )
            for b in rc.blocks
        )
        rc = dataclasses.replace(
            rc,
            plugin=_renamed(rc.plugin),
            params=tuple((_renamed(k), v) for k, v in rc.params),
            controllers=controllers,
            blocks=blocks,
            variants=_mock_renamed(rc.variants),
        )
    passthrough = tuple(_renamed(x) for x in robot.passthrough)
    return dataclasses.replace(robot, ros2_control=rc, passthrough=passthrough, waivers=(), spec_hash=None)


def _plain(value: Any) -> Any:
    if isinstance(value, Where):
        return None
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return tuple(_plain(getattr(value, f.name)) for f in dataclasses.fields(value))
    if isinstance(value, (tuple, list)):
        return tuple(_plain(v) for v in value)
    return value


def _refused(file: str, why: str) -> InputError:
    return InputError(
        [
            FIX001.finding(
                f"no fix written: {why}", "report it; fix by hand as the findings' hints say", "fix", Where(file)
            )
        ]
    )


def fix_file(path: Path, write: bool) -> Fixed:
    """``descgen fix``: the fixes of the spec at ``path``, written in place when ``write``."""
    from descgen.infra.yamlsource import read_text
    from descgen.write.spec_file import write_spec

    text = read_text(path, str(path))
    fixed = fix_text(text, str(path))
    if write and fixed.fixes:
        write_spec(path, fixed.after)
    return fixed
