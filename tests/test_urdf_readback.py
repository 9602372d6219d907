"""The lxml read-back reader of proof 2 (descgen/read/urdf_readback.py) against its oracles:
yourdfpy on every example-robot-data URDF and on the generated one, urdfdom's check_urdf on
what it refuses, and hand-computed rotations and defaults (docs/reference/urdf.md)."""

from __future__ import annotations

import logging
import math
from dataclasses import fields, is_dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from descgen.audit.spec import load_spec
from descgen.prove import run_all
from descgen.prove.urdf_roundtrip import from_yourdfpy, urdf_roundtrip, urdf_roundtrip_yourdfpy
from descgen.read import urdf_readback as rb
from descgen.render import render_package

from .conftest import EXAMPLE, require_tool
from .corpus import descriptions

CORPUS = descriptions()


def _differences(a: Any, b: Any, path: str = "robot") -> list[str]:
    """Every field where two read robots differ (floats within 1e-12; source lines ignored,
    since the yourdfpy side has none)."""
    if is_dataclass(a) and is_dataclass(b) and type(a) is type(b):
        out: list[str] = []
        for f in fields(a):
            if f.name != "line":
                out += _differences(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
        return out
    if isinstance(a, tuple) and isinstance(b, tuple):
        if len(a) != len(b):
            return [f"{path}: {len(a)} items vs {len(b)}"]
        return [d for i, (x, y) in enumerate(zip(a, b, strict=True)) for d in _differences(x, y, f"{path}[{i}]")]
    if isinstance(a, float) and isinstance(b, float):
        return [] if abs(a - b) <= 1e-12 else [f"{path}: {a!r} vs {b!r}"]
    return [] if a == b and type(a) is type(b) else [f"{path}: {a!r} vs {b!r}"]


def _yourdfpy(source: Path | str) -> rb.Robot:
    import io

    import yourdfpy

    logging.getLogger("yourdfpy").setLevel(logging.CRITICAL)
    target = str(source) if isinstance(source, Path) else io.StringIO(source)
    urdf = yourdfpy.URDF.load(target, build_scene_graph=False, load_meshes=False)
    return from_yourdfpy(urdf.robot)


@pytest.mark.skipif(not CORPUS, reason="example-robot-data is not installed")
@pytest.mark.parametrize(("ident", "path"), [(i, u) for i, u, _ in CORPUS], ids=[i for i, _, _ in CORPUS])
def test_agrees_with_yourdfpy_on_the_corpus(ident: str, path: Path) -> None:
    try:
        theirs = _yourdfpy(path)
    except KeyError:  # yourdfpy: a robot without a name; urdfdom refuses it too
        with pytest.raises(rb.ReadbackError, match="no name"):
            rb.read(path.read_text(encoding="utf-8"))
        return
    mine = rb.read(path.read_text(encoding="utf-8"))
    assert _differences(mine, theirs) == []
    assert len(mine.links) > 0


def test_the_corpus_is_all_there() -> None:
    if not CORPUS:
        pytest.skip("example-robot-data is not installed")
    assert len(CORPUS) == 69


ROBOT = load_spec(EXAMPLE).robot
FILES = render_package(ROBOT, "specs/warehouse_arm.yaml")
URDF = FILES["urdf/warehouse_arm.urdf"]


def test_agrees_with_yourdfpy_on_the_generated_urdf() -> None:
    mine = rb.read(URDF)
    assert _differences(mine, _yourdfpy(URDF)) == []
    assert [j.name for j in mine.joints] == [j.name for j in ROBOT.joints]
    # and both proofs accept the generated URDF
    assert urdf_roundtrip(FILES, ROBOT, Path("/pkg")) == []
    assert urdf_roundtrip_yourdfpy(FILES, ROBOT, Path("/pkg")) == []


def test_thorough_adds_the_yourdfpy_readback() -> None:
    files = dict(FILES)
    files["urdf/warehouse_arm.urdf"] = URDF.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 0 1"/>', 1)
    quick = [f.message for f in run_all(files, ROBOT, Path("/pkg")) if f.code == "GEN030"]
    thorough = [f.message for f in run_all(files, ROBOT, Path("/pkg"), thorough=True) if f.code == "GEN030"]
    assert quick and all("lxml read-back reader" in m for m in quick)
    assert [m for m in thorough if "by yourdfpy" in m] and set(quick) < set(thorough)


def _rx(a: float) -> np.ndarray:
    return np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])


def _ry(a: float) -> np.ndarray:
    return np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])


def _rz(a: float) -> np.ndarray:
    return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])


@pytest.mark.parametrize(
    "rpy", [(0.3, 0.0, 0.0), (0.0, -1.1, 0.0), (0.0, 0.0, 2.0), (0.4, -0.7, 1.9), (3.0, 1.5, -2.5)]
)
def test_rpy_is_fixed_axis_xyz(rpy: tuple[float, float, float]) -> None:
    """R = Rz(yaw) Ry(pitch) Rx(roll) (docs/reference/urdf.md, urdfdom's setFromRPY)."""
    m = np.array(rb.rpy_matrix((1.0, -2.0, 0.5), rpy))
    want = _rz(rpy[2]) @ _ry(rpy[1]) @ _rx(rpy[0])
    assert np.allclose(m[:3, :3], want, atol=1e-15, rtol=0)
    assert m[:3, 3].tolist() == [1.0, -2.0, 0.5] and m[3].tolist() == [0.0, 0.0, 0.0, 1.0]


def test_quarter_turn_about_z_maps_x_to_y() -> None:
    m = np.array(rb.rpy_matrix((0.0, 0.0, 0.0), (0.0, 0.0, math.pi / 2)))
    assert np.allclose(m[:3, :3] @ [1, 0, 0], [0, 1, 0], atol=1e-15)


_DEFAULTS = """<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="package://p/m.stl"/></geometry></visual>
    <inertial><mass value="2"/><inertia ixx="1" ixy="0.1" ixz="0.2" iyy="3" iyz="0.3" izz="4"/></inertial>
  </link>
  <link name="b"/>
  <link name="c"/>
  <joint name="j" type="continuous">
    <parent link="a"/><child link="b"/>
    <limit effort="5" velocity="6"/>
    <dynamics damping="0.5"/>
    <mimic joint="k"/>
    <safety_controller k_velocity="7"/>
  </joint>
  <joint name="k" type="revolute">
    <parent link="a"/><child link="c"/><axis/><origin xyz="1 2 3"/>
    <limit effort="1" velocity="1" upper="0.5"/>
  </joint>
  <gazebo><anything/></gazebo>
</robot>
"""


def test_urdfdom_defaults() -> None:
    """Each default as docs/reference/urdf.md gives it for urdfdom."""
    r = rb.read(_DEFAULTS)
    a, _, _ = r.links
    j, k = r.joints
    identity = tuple(tuple(float(i == c) for c in range(4)) for i in range(4))
    assert a.visuals[0].origin == identity and a.visuals[0].geometry.scale == (1.0, 1.0, 1.0)
    assert a.visuals[0].material is None and a.inertial is not None and a.inertial.origin == identity
    assert a.inertial.inertia == ((1.0, 0.1, 0.2), (0.1, 3.0, 0.3), (0.2, 0.3, 4.0))
    assert j.origin == identity and j.axis == (1.0, 0.0, 0.0)  # no <axis>: 1 0 0
    assert j.limit == rb.Limit(0.0, 0.0, 5.0, 6.0)
    assert j.dynamics == (0.5, 0.0) and j.mimic == ("k", 1.0, 0.0) and j.safety == (0.0, 0.0, 0.0, 7.0)
    assert k.axis == (0.0, 0.0, 0.0)  # <axis/> without xyz: 0 0 0, accepted by check_urdf
    assert k.limit == rb.Limit(0.0, 0.5, 1.0, 1.0) and k.origin[0][3] == 1.0 and k.origin[2][3] == 3.0
    assert (j.line, k.line) == (8, 15)


# urdfdom refuses each of these (docs/reference/urdf.md, "Fatal"); so must the read-back
_JOINT = '<joint name="j" type="{type}"><parent link="a"/><child link="b"/>{inner}</joint>'
_LIMIT = '<limit effort="1" velocity="1" lower="-1" upper="1"/>'
FATAL = {
    "number with a comma": ("revolute", f'<origin xyz="1,5 0 0"/>{_LIMIT}'),
    "nan is no decimal": ("revolute", f'<origin xyz="nan 0 0"/>{_LIMIT}'),
    "two numbers for xyz": ("revolute", f'<origin xyz="1 0"/>{_LIMIT}'),
    "revolute without limit": ("revolute", ""),
    "limit without effort": ("prismatic", '<limit velocity="1" lower="0" upper="1"/>'),
    "empty dynamics": ("revolute", f"{_LIMIT}<dynamics/>"),
    "safety without k_velocity": ("revolute", f'{_LIMIT}<safety_controller k_position="1"/>'),
    "mimic without joint": ("revolute", f'{_LIMIT}<mimic multiplier="2"/>'),
    "unknown type": ("hinge", ""),
}


@pytest.mark.parametrize("case", sorted(FATAL))
def test_refuses_what_urdfdom_refuses(case: str, tmp_path: Path) -> None:
    kind, inner = FATAL[case]
    text = f'<robot name="r">\n<link name="a"/>\n<link name="b"/>\n{_JOINT.format(type=kind, inner=inner)}\n</robot>\n'
    with pytest.raises(rb.ReadbackError) as err:
        rb.read(text)
    assert err.value.line == 4
    (tmp_path / "r.urdf").write_text(text, encoding="utf-8")
    import subprocess

    tool = require_tool("check_urdf")
    assert subprocess.run([tool, str(tmp_path / "r.urdf")], capture_output=True).returncode != 0


@pytest.mark.parametrize(
    "link",
    [
        '<inertial><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>',
        '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0"/></inertial>',
        "<visual><geometry/></visual>",
        '<collision><geometry><capsule radius="1" length="2"/></geometry></collision>',
    ],
)
def test_refuses_what_urdfdom_only_logs(link: str) -> None:
    """urdfdom logs these and goes on (check treats the log line as a failure): refused here."""
    with pytest.raises(rb.ReadbackError):
        rb.read(f'<robot name="r"><link name="a">{link}</link></robot>')


def test_no_entity_is_expanded_and_no_file_read(tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("TOPSECRET", encoding="utf-8")
    text = (
        f'<?xml version="1.0"?><!DOCTYPE robot [<!ENTITY s SYSTEM "file://{secret}">]>'
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="&s;"/></geometry></visual></link></robot>'
    )
    try:
        r = rb.read(text)
    except Exception as exc:  # refusing is fine too, as long as nothing was read
        assert "TOPSECRET" not in str(exc)
        return
    assert "TOPSECRET" not in repr(r)
