"""``descgen import-calibration SPEC FILE --format ur|handeye|csv``: a vendor's or a tool's
calibration file becomes the spec's ``calibration:`` layer, with its provenance.

- ``ur``: UR's kinematics YAML holds whole origins; each becomes a correction of the spec's
  nominal origin (the file's value minus the spec's), so generate writes exactly the file's
  origins (tests/test_calibration.py expands the UR Xacro with the same file as the oracle).
- ``handeye``: easy_handeye2's camera pose in the effector (eye-in-hand) or base (eye-on-base)
  frame becomes the mount of the spec's sensor whose link or optical frame it names, carried
  into the sensor's parent through the fixed joints between them.
- ``csv``: joint zero offsets.

The spec's text is kept except its ``calibration:`` block, which is written again with the new
entries merged in (comments inside that block are not kept). The result is read back and each
imported value checked before anything is written.
"""

from __future__ import annotations

import difflib
import math
from pathlib import Path
from typing import Any

import numpy as np

from descgen.codes.command import CAL010, CAL011, CAL013
from descgen.core.findings import InputError, Where
from descgen.core.model import ONE_DOF, Joint, Pose, Robot
from descgen.core.record import record
from descgen.physics.kinematics import forward, joint_transform
from descgen.physics.transforms import matrix_rpy, pose_matrix

FORMATS = ("ur", "handeye", "csv")
_DEFAULT_SOURCE = {"ur": "ur_calibration", "handeye": "handeye", "csv": "joint_offsets"}
_TOOL = {"ur": "ur_calibration", "handeye": "easy_handeye2", "csv": None}
_METHOD = {
    "ur": "Universal Robots factory calibration (kinematics YAML)",
    "handeye": "hand-eye calibration",
    "csv": "joint zero offsets",
}


@record
class Imported:
    before: str
    after: str
    entries: tuple[str, ...]  # what was imported, in words

    def diff(self, name: str) -> str:
        return "".join(
            difflib.unified_diff(
                self.before.splitlines(keepends=True),
                self.after.splitlines(keepends=True),
                f"a/{name}",
                f"b/{name}",
            )
        )


def _missing(spec: Path, why: str, hint: str) -> InputError:
    return InputError([CAL011.finding(why, hint, "calibration", Where(str(spec)))])


def _nominal(robot: Robot, joint: str) -> Pose:
    for e in robot.calibration:
        if e.joint == joint:
            return e.nominal
    j = robot.joint(joint)
    assert j is not None
    return j.origin


def _q(value: float, unit: str) -> str | float:
    return 0 if value == 0.0 else f"{value!r} {unit}"


def _correction(nominal: Pose, measured: Pose) -> dict[str, Any]:
    dxyz = [_q(a - b, "m") for a, b in zip(measured.xyz, nominal.xyz, strict=True)]
    drpy = [_q(a - b, "rad") for a, b in zip(measured.rpy, nominal.rpy, strict=True)]
    return {"xyz": dxyz, "rpy": drpy}


def _ur(robot: Robot, spec: Path, file: Path, prefix: str, source: str) -> tuple[dict[str, Any], list[str]]:
    from descgen.read.calibration_files import read_ur

    ur = read_ur(file)
    joints: dict[str, Any] = {}
    said: list[str] = []
    for name, origin in ur.origins:
        full = prefix + name
        if robot.joint(full) is None:
            raise _missing(
                spec,
                f"the UR calibration gives joint {full!r}, which the spec does not have",
                "give the prefix the spec's joints carry: --prefix",
            )
        joints[full] = {"source": source, "origin": _correction(_nominal(robot, full), origin)}
        said.append(f"joint:{full}: origin from the UR kinematics file")
    return {"joints": joints, "hash": ur.hash}, said


def _fixed_path(robot: Robot, a: str, b: str) -> bool:
    """Whether only fixed joints join links ``a`` and ``b``."""

    def up(link: str) -> list[Joint]:
        out: list[Joint] = []
        seen = {link}
        while (j := robot.parent_joint(link)) is not None and j.parent is not None and j.parent not in seen:
            out.append(j)
            link = j.parent
            seen.add(link)
        return out

    ua, ub = up(a), up(b)
    common = {j.name for j in ua} & {j.name for j in ub}
    return all(j.type == "fixed" for j in ua + ub if j.name not in common)


def _handeye(
    robot: Robot, spec: Path, file: Path, prefix: str, sensor: str | None, source: str
) -> tuple[dict[str, Any], list[str]]:
    from descgen.read.calibration_files import read_handeye

    he = read_handeye(file)
    parent, child = prefix + he.parent, prefix + he.child
    found = [
        s
        for s in robot.sensors
        if (sensor is not None and s.name == sensor) or (sensor is None and child in (s.link, s.optical_frame))
    ]
    if len(found) != 1:
        raise _missing(
            spec,
            f"no single sensor of the spec is the hand-eye result's tracking frame {child!r}"
            if sensor is None
            else f"the spec has no sensor {sensor!r}",
            "name the sensor with --sensor (a sensor of the spec's sensors:)",
        )
    sn = found[0]
    sj = robot.joint(sn.joint)
    links = {lk.name for lk in robot.links}
    if sj is None or sj.parent is None or parent not in links:
        raise _missing(spec, f"the hand-eye result's frame {parent!r} is not a link of the spec", "give --prefix")
    if not _fixed_path(robot, sj.parent, parent):
        raise _missing(
            spec,
            f"{parent!r} and the sensor's parent {sj.parent!r} are joined by a joint that moves",
            "mount the sensor on the frame the hand-eye result is in (its parent in sensors:)",
        )
    poses = forward(robot)
    t_parent = np.linalg.inv(poses[sj.parent]) @ poses[parent]
    t_he = pose_matrix(he.xyz, (0.0, 0.0, 0.0))
    t_he[:3, :3] = _quat_matrix(he.quat_xyzw)
    to_link: np.ndarray = np.eye(4)
    if child == sn.optical_frame and sn.optical_joint is not None:
        oj = robot.joint(sn.optical_joint)
        assert oj is not None
        to_link = np.linalg.inv(joint_transform(oj))
    elif child != sn.link:  # --sensor named one whose frames the result does not name
        raise _missing(
            spec,
            f"the hand-eye result is the pose of {child!r}, not of sensor {sn.name!r}'s link or optical frame",
            "check --sensor",
        )
    t = t_parent @ t_he @ to_link
    rpy = matrix_rpy(t[:3, :3])
    origin = {"xyz": [_q(float(c), "m") for c in t[:3, 3]], "rpy": [_q(c, "rad") for c in rpy]}
    return {"sensors": {sn.name: {"source": source, "origin": origin}}}, [
        f"sensor:{sn.name}: mount from the hand-eye result ({he.kind}, {he.child} in {he.parent})"
    ]


def _quat_matrix(q: tuple[float, float, float, float]) -> np.ndarray:
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def _csv(robot: Robot, spec: Path, file: Path, prefix: str, source: str) -> tuple[dict[str, Any], list[str]]:
    from descgen.read.calibration_files import read_offsets_csv

    joints: dict[str, Any] = {}
    said: list[str] = []
    for name, number, unit, line in read_offsets_csv(file):
        full = prefix + name
        j = robot.joint(full)
        if j is None or j.type not in ONE_DOF:
            raise InputError(
                [
                    CAL011.finding(
                        f"row {line}: {full!r} is not a revolute, continuous or prismatic joint of the spec",
                        "name the spec's joints (or give --prefix)",
                        "calibration",
                        Where(str(file), line),
                    )
                ]
            )
        # no unit: SI, as the format says, in the joint's own unit
        value = f"{number} {unit or ('m' if j.type == 'prismatic' else 'rad')}"
        joints[full] = {"source": source, "offset": value}
        said.append(f"joint:{full}: zero offset {value}")
    return {"joints": joints}, said


def import_text(
    text: str,
    spec: Path,
    file: Path,
    fmt: str,
    *,
    source: str | None = None,
    prefix: str = "",
    sensor: str | None = None,
    date: str | None = None,
    replace: bool = False,
) -> Imported:
    """The spec's text with ``file`` merged into its ``calibration:`` (checked, not written)."""
    import yaml

    from descgen.audit.spec import load_spec_text

    robot = load_spec_text(text, str(spec), rules=False).robot
    name = source or _DEFAULT_SOURCE[fmt]
    if fmt == "ur":
        new, said = _ur(robot, spec, file, prefix, name)
    elif fmt == "handeye":
        new, said = _handeye(robot, spec, file, prefix, sensor, name)
    else:
        new, said = _csv(robot, spec, file, prefix, name)
    data = yaml.safe_load(text) or {}
    cal: dict[str, Any] = dict(data.get("calibration") or {})
    provenance: dict[str, Any] = {"method": _METHOD[fmt]}
    if _TOOL[fmt]:
        provenance["tool"] = _TOOL[fmt]
    provenance["file"] = str(file)
    if date:
        provenance["date"] = date
    if new.get("hash"):
        provenance["hash"] = str(new["hash"])
    cal["sources"] = {**(cal.get("sources") or {}), name: provenance}
    for section in ("joints", "sensors"):
        merged = dict(cal.get(section) or {})
        for key, entry in (new.get(section) or {}).items():
            prev = merged.get(key)
            if isinstance(prev, dict) and not replace and prev.get("source") != entry["source"]:
                raise InputError(
                    [
                        CAL013.finding(
                            f"calibration.{section}.{key} cites source {prev.get('source')!r}; the import would "
                            f"replace it with values from {entry['source']!r}",
                            "import with --source set to that name to update the entry, or pass --replace",
                            "calibration",
                            Where(str(spec)),
                        )
                    ]
                )
            # the same source: the fields this import gives are updated, the others kept
            merged[key] = entry if replace or not isinstance(prev, dict) else {**prev, **entry}
        if merged:
            cal[section] = merged
    block = yaml.safe_dump({"calibration": cal}, sort_keys=False, default_flow_style=None, width=100)
    after = _splice(text, block)
    _check(after, spec, robot, fmt, file, new)
    return Imported(text, after, tuple(said))


def _splice(text: str, block: str) -> str:
    lines = text.splitlines(keepends=True)
    start = next((i for i, ln in enumerate(lines) if ln.startswith("calibration:")), None)
    if start is None:
        sep = "" if not text or text.endswith("\n") else "\n"
        return text + sep + "\n" + block
    end = start + 1
    # the block ends at the next line that is not indented (a key, a comment, a document end)
    while end < len(lines) and (lines[end].strip() == "" or lines[end][:1] in (" ", "\t")):
        end += 1
    while end > start + 1 and lines[end - 1].strip() == "":  # keep the blank lines before the next key
        end -= 1
    return "".join(lines[:start]) + block + "".join(lines[end:])


def _check(after: str, spec: Path, before: Robot, fmt: str, file: Path, new: dict[str, Any]) -> None:
    """The merged spec reads, and gives each imported joint the origin the file states (UR)."""
    from descgen.audit.spec import load_spec_text

    try:
        robot = load_spec_text(after, str(spec), rules=False).robot
    except InputError as exc:
        why = next((f for f in exc.findings if f.blocks), exc.findings[0])
        raise InputError(
            [
                CAL010.finding(
                    f"the spec with this calibration does not read: {why.message}",
                    why.hint or "fix the spec or the calibration file",
                    "calibration",
                    Where(str(spec)),
                )
            ]
        ) from None
    if fmt != "ur":
        return
    from descgen.read.calibration_files import read_ur

    for name, origin in read_ur(file).origins:
        joint = next((j for j in new["joints"] if j.endswith(name)), None)
        got = robot.joint(joint) if joint else None
        if got is None or not all(
            math.isclose(a, b, rel_tol=0, abs_tol=1e-12)
            for a, b in zip((*got.origin.xyz, *got.origin.rpy), (*origin.xyz, *origin.rpy), strict=True)
        ):
            raise InputError(
                [
                    CAL010.finding(
                        f"joint {joint!r} does not read back with the file's origin",
                        "report it: a descgen bug",
                        "calibration",
                        Where(str(spec)),
                    )
                ]
            )


def import_file(spec: Path, file: Path, fmt: str, write: bool, **options: Any) -> Imported:
    """``descgen import-calibration``: merged, checked, and written when ``write``."""
    from descgen.infra.yamlsource import read_text
    from descgen.write.spec_file import write_spec

    text = read_text(spec, str(spec))
    done = import_text(text, spec, file, fmt, **options)
    if write:
        write_spec(spec, done.after)
    return done


__all__ = ["FORMATS", "Imported", "import_file", "import_text"]
