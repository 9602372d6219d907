"""Multi-DOF group-state values (a planar or floating virtual joint's list, issue 12) kept in the
spec, converted once to SI, checked, rendered into the SRDF and read back; and a continuous
joint's ignored lower/upper left out of an import (IMP026).

Oracles: hand-computed SI values, lxml reading the generated SRDF, srdfdom's rule that a value is
a space-separated list of doubles (split + float), and the original SRDF read with lxml."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
import yaml
from lxml import etree

from descgen.audit.spec import load_spec_text
from descgen.commands.importer.run import ImportOptions, import_description
from descgen.core.findings import InputError
from descgen.prove.semantic_roundtrip import srdf_roundtrip
from descgen.read.description import Options
from descgen.render import render_package
from tests.corpus import descriptions, imported
from tests.helpers import ROOT

SPEC = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
STATE = "    - {name: ready, group: arm, pose: ready}\n"


def _with_state(value: str, vtype: str = "planar") -> str:
    """The example spec with one more group state that sets the virtual joint to ``value``."""
    text = SPEC.replace(
        STATE,
        STATE + f"    - {{name: parked, group: arm, joints: {{virtual_joint: {{value: {value}, source: K3}}}}}}\n",
    )
    assert text != SPEC
    if vtype != "planar":
        text = text.replace("{name: virtual_joint, type: planar,", f"{{name: virtual_joint, type: {vtype},")
    return text


def _srdf_values(text: str, state: str) -> dict[str, list[float]]:
    root = etree.fromstring(text.encode())
    (gs,) = root.findall(f"group_state[@name='{state}']")
    return {j.get("name"): [float(t) for t in j.get("value").split()] for j in gs.findall("joint")}


def _codes(text: str) -> list[str]:
    with pytest.raises(InputError) as exc:
        load_spec_text(text, "spec.yaml", rules=False)
    return [f.code for f in exc.value.findings]


def test_planar_list_is_si_and_comes_back_from_the_srdf() -> None:
    robot = load_spec_text(_with_state("[1500 mm, -20 cm, 90 deg]"), "spec.yaml", rules=False).robot
    assert robot.semantic is not None
    (st,) = [s for s in robot.semantic.states if s.name == "parked"]
    assert st.multi == (("virtual_joint", (1.5, -0.2, math.pi / 2)),)  # by hand: metres, radians
    assert "virtual_joint" not in dict(st.values)  # not a 1-DOF value: FK and limit rules skip it
    files = render_package(robot, "spec.yaml")
    srdf = files[f"srdf/{robot.name}.srdf"]
    assert _srdf_values(srdf, "parked")["virtual_joint"] == [1.5, -0.2, math.pi / 2]
    assert srdf_roundtrip(files, robot, Path("gen")) == []


def test_the_srdf_roundtrip_sees_a_changed_multi_dof_value() -> None:
    robot = load_spec_text(_with_state("[1 m, 0 m, 0 deg]"), "spec.yaml", rules=False).robot
    files = render_package(robot, "spec.yaml")
    name = f"srdf/{robot.name}.srdf"
    files[name] = files[name].replace('value="1 0 0"', 'value="1 0 0.5"')
    assert "1 0 0.5" in files[name]
    assert [f.code for f in srdf_roundtrip(files, robot, Path("gen"))] == ["GEN031"]


def test_floating_list_with_a_unit_quaternion() -> None:
    h = math.sqrt(0.5)
    text = _with_state(f"[0 mm, 0 mm, 300 mm, 0, 0, {h!r}, {h!r}]", "floating")
    robot = load_spec_text(text, "spec.yaml", rules=False).robot
    assert robot.semantic is not None
    (st,) = [s for s in robot.semantic.states if s.name == "parked"]
    assert st.multi == (("virtual_joint", (0.0, 0.0, 0.3, 0.0, 0.0, h, h)),)
    srdf = render_package(robot, "spec.yaml")[f"srdf/{robot.name}.srdf"]
    assert _srdf_values(srdf, "parked")["virtual_joint"] == [0.0, 0.0, 0.3, 0.0, 0.0, h, h]


@pytest.mark.parametrize(
    ("value", "vtype", "code"),
    [
        ("[0 mm, 0 mm]", "planar", "SPEC125"),  # planar takes x, y, theta
        ("[0 mm, 0 mm, 0 mm, 0, 0, 0, 1]", "planar", "SPEC125"),
        ("[0 mm, 0 mm, 0 deg]", "floating", "SPEC125"),
        ("0 mm", "planar", "SPEC125"),  # one number for a planar joint: MoveIt drops it
        ("[0 mm, 0 mm, 0 mm, 0, 0, 0, 1.001]", "floating", "SPEC126"),  # |q|^2 = 1.002001
        ("[0 mm, 0 mm, 0 mm, 0, 0, 0, 0]", "floating", "SPEC126"),
        ("[0 mm, 0 mm, 0 mm, 0, 0, 0, 1 deg]", "floating", "SPEC127"),
        ("[0 mm, 0 deg, 0 deg]", "planar", "UNIT003"),  # y is a length
    ],
)
def test_bad_lists_fail_validate(value: str, vtype: str, code: str) -> None:
    codes = _codes(_with_state(value, vtype))
    assert code in codes if code != "UNIT003" else any(c.startswith("UNIT") for c in codes)


def test_a_list_for_a_one_dof_joint_fails() -> None:
    text = SPEC.replace(
        STATE, STATE + "    - {name: bad, group: arm, joints: {elbow_joint: {value: [0 deg, 1 deg], source: K3}}}\n"
    )
    assert "SPEC125" in _codes(text)


def test_a_near_unit_quaternion_within_1e9_is_accepted() -> None:
    w = 1.0 + 4e-10  # |q|^2 - 1 = 8e-10 (by hand), inside 1e-9
    robot = load_spec_text(_with_state(f"[0 mm, 0 mm, 0 mm, 0, 0, 0, {w!r}]", "floating"), "s.yaml", rules=False).robot
    assert robot.semantic is not None
    assert [s.multi for s in robot.semantic.states if s.name == "parked"] == [
        (("virtual_joint", (0, 0, 0, 0, 0, 0, w)),)
    ]


CORPUS = {ident: (urdf, srdf) for ident, urdf, srdf in descriptions()}


@pytest.mark.skipif("a1_description/urdf/a1.urdf" not in CORPUS, reason="example-robot-data is not installed")
def test_import_keeps_a_floating_root_joint_state() -> None:
    urdf, srdf = CORPUS["a1_description/urdf/a1.urdf"]
    assert srdf is not None
    outcome = imported(urdf, srdf)  # the import tests/test_import_corpus.py checks a1's row with
    assert outcome.proven
    assert "IMP011" not in {f.code for f in outcome.imported.report}
    original = etree.parse(str(srdf)).getroot()
    wanted = {
        (gs.get("name"), j.get("name")): [float(t) for t in j.get("value").split()]
        for gs in original.findall("group_state")
        for j in gs.findall("joint")
        if len(j.get("value").split()) > 1
    }
    assert wanted  # a1.srdf: root_joint "0. 0. 0.26 0. 0. 0. 1."
    data = yaml.safe_load(outcome.imported.spec_text)
    states = {s["name"]: s["joints"] for s in data["semantic"]["group_states"]}
    for (state, joint), values in wanted.items():
        assert re.fullmatch(r"a1\.srdf:\d+", states[state][joint]["source"])
        assert len(states[state][joint]["value"]) == len(values)
    robot = load_spec_text(outcome.imported.spec_text, "a1.yaml", rules=False).robot
    srdf_text = render_package(robot, "a1.yaml")[f"srdf/{robot.name}.srdf"]
    for (state, joint), values in wanted.items():
        assert _srdf_values(srdf_text, state)[joint] == values


CONTINUOUS = """<?xml version="1.0"?>
<robot name="wheel">
  <link name="base"/>
  <link name="tyre"/>
  <joint name="spin" type="continuous">
    <parent link="base"/><child link="tyre"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="2" effort="3" velocity="4"/>
  </joint>
</robot>
"""


def test_continuous_lower_upper_are_left_out_and_reported(tmp_path: Path) -> None:
    path = tmp_path / "wheel.urdf"
    path.write_text(CONTINUOUS)
    outcome = import_description(path, ImportOptions(Options()))
    assert outcome.proven  # it differed at limit/lower and limit/upper before
    (f,) = [f for f in outcome.imported.report if f.code == "IMP026"]
    assert f.subject == "joint:spin" and "lower=-1 rad, upper=2 rad" in f.message
    assert f.where.file == str(path) and f.where.line == 7  # the <limit> element's line
    (joint,) = yaml.safe_load(outcome.imported.spec_text)["joints"]
    assert set(joint["limit"]) >= {"effort", "velocity"}
    assert not {"lower", "upper"} & set(joint["limit"])


ARM = """<?xml version="1.0"?>
<robot name="arm1">
  <link name="base"/><link name="upper"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>
"""
ARM_SRDF = """<?xml version="1.0"?>
<robot name="arm1">
  <group name="arm"><joint name="j1"/></group>
  <group_state name="odd" group="arm"><joint name="j1" value="0.5 0.25"/></group_state>
  <group_state name="home" group="arm"><joint name="j1" value="0.5"/></group_state>
</robot>
"""


def test_several_numbers_for_a_one_dof_joint_are_still_reported(tmp_path: Path) -> None:
    """IMP011 stays for what the spec cannot hold: a list for a joint that is no planar or
    floating virtual joint; the state is left out (it has no other value)."""
    (tmp_path / "arm1.urdf").write_text(ARM)
    (tmp_path / "arm1.srdf").write_text(ARM_SRDF)
    outcome = import_description(tmp_path / "arm1.urdf", ImportOptions(Options(srdf=tmp_path / "arm1.srdf")))
    (f,) = [f for f in outcome.imported.report if f.code == "IMP011"]
    assert f.where.line == 4 and "'0.5 0.25'" in f.message
    states = yaml.safe_load(outcome.imported.spec_text)["semantic"]["group_states"]
    assert [s["name"] for s in states] == ["home"]
