"""Bounds that hold at 10,000 links or elements (issue 34 item 11, issue 35): each command's
work is linear in the input or stops at a bound that is reported as a finding, never a crash.

Work is counted, not timed: a quadratic path shows as calls that grow with the findings.

- validate: the spans of the elements that hold bad values are found in one pass over the marks
  (``spec/load.py:_inside`` rescanned every mark per finding and bad value: 300 unit errors took
  100 s), and a bad quantity repeated (a YAML alias, a copied line) is parsed once.
- the YAML node bound fits a 10,000-link spec and still refuses an alias bomb, its hint saying
  what it protects.
- sweep: SWEEP007 (exit 2, nothing swept) past joints x links x steps; SWEEP008 (collisions
  not checked) past the pair tests, pinocchio's shape pairs or its tree depth (pinocchio's URDF
  parser crashed with exit 139 on a 5,000-link chain).
- simulate: SIM017 (exit 2) before MuJoCo compiles a robot past its bounds.
- import: IMP035 (exit 2, nothing written) for more links than descgen answers for, or a spec
  that validate would refuse for its size (it used to be written and blamed on the description).
"""

from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path
from typing import Any

import pytest

from descgen.audit.spec import INPUT_RULES, load_spec_text
from descgen.core import units
from descgen.core.findings import InputError
from descgen.infra import yamlsource
from descgen.physics import collision
from descgen.spec import load
from tests.helpers import ROOT, cli

sys.path.insert(0, str(ROOT / "benchmarks"))
from synthetic import chain_spec


def chain_urdf(n: int, joint: str = "revolute", shapes: bool = True) -> str:
    """A serial chain of ``n`` links (``joint`` joints), each a 40 x 40 x 100 mm box of 1 g."""
    box = '<geometry><box size="0.04 0.04 0.1"/></geometry>'
    out = ['<robot name="chain">']
    for i in range(n):
        coll = f'<collision><origin xyz="0 0 0.05"/>{box}</collision>' if shapes else ""
        out.append(
            f'<link name="link{i}"><inertial><origin xyz="0 0 0.05"/><mass value="0.001"/>'
            '<inertia ixx="1e-6" iyy="1e-6" izz="1e-6" ixy="0" ixz="0" iyz="0"/></inertial>'
            f'<visual><origin xyz="0 0 0.05"/>{box}</visual>{coll}</link>'
        )
    for i in range(1, n):
        limit = '<limit lower="-1.5708" upper="1.5708" effort="2000" velocity="1"/>' if joint != "fixed" else ""
        out.append(
            f'<joint name="joint{i}" type="{joint}"><parent link="link{i - 1}"/><child link="link{i}"/>'
            f'<origin xyz="0 0 0.1" rpy="0 0 0.2618"/><axis xyz="0 1 0"/>{limit}</joint>'
        )
    out.append("</robot>")
    return "\n".join(out) + "\n"


def _write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


# --- validate: linear in the findings ------------------------------------------------------------


class _Counted(dict):  # type: ignore[type-arg]
    """A marks table that counts the passes over it."""

    passes = 0

    def items(self) -> Any:
        type(self).passes += 1
        return super().items()


def _passes_over_marks(text: str) -> tuple[int, int]:
    """(passes over the marks tables, errors) when ``text`` is validated."""
    doc = yamlsource.loads(text, "r.yaml")
    _Counted.passes = 0
    doc = dataclasses.replace(doc, value_marks=_Counted(doc.value_marks), key_marks=_Counted(doc.key_marks))
    with pytest.raises(InputError) as err:
        load.from_document(doc, rules=INPUT_RULES)
    return _Counted.passes, len(err.value.findings)


def test_unit_errors_cost_passes_independent_of_their_number() -> None:
    one = chain_spec(60).replace("mass: 1 g", "mass: 1 m", 1)
    sixty = chain_spec(60).replace("mass: 1 g", "mass: 1 m")
    few, n1 = _passes_over_marks(one)
    many, n60 = _passes_over_marks(sixty)
    assert (n1, n60) == (1, 60)
    # the old rescan made two passes per (finding, bad value): thousands here
    assert many == few <= 8, (few, many)


def test_findings_inside_bad_elements_are_still_dropped() -> None:
    # a bad box size must not also be "zero size" or a wrong inertia: the stand-in's cascades
    # are dropped, the bad values themselves reported, each once
    text = chain_spec(5).replace(
        "size: [40 mm, 40 mm, 100 mm]}}}]\n    inertial", "size: [40 kg, 40 mm, 100 mm]}}}]\n    inertial"
    )
    with pytest.raises(InputError) as err:
        load_spec_text(text, "r.yaml")
    codes = sorted({f.code for f in err.value.findings})
    assert codes == ["UNIT003"], [(f.code, f.message) for f in err.value.findings]
    assert len(err.value.findings) == 5


def test_a_bad_quantity_repeated_through_aliases_is_parsed_once(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = []
    parse = units.parse
    monkeypatch.setattr(units, "parse", lambda text: calls.append(text) or parse(text))
    units._to_si_cached.cache_clear()
    lines = ["name: aliases", "links:", "  - name: base", "    visual:"]
    lines += ["      - &v {geometry: {box: {size: [40 kg, 40 mm, 100 mm]}}}"]
    lines += ["      - *v"] * 999
    with pytest.raises(InputError) as err:
        load_spec_text("\n".join(lines) + "\n", "a.yaml")
    assert len(err.value.findings) == 1000  # one per visual: each is reported at the anchor
    assert calls.count("40 kg") == 1
    units._to_si_cached.cache_clear()


def test_a_remembered_refusal_is_raised_anew() -> None:
    units._to_si_cached.cache_clear()
    errors = []
    for _ in range(2):
        with pytest.raises(units.QuantityError) as err:
            units.to_si("40 kg", "length")
        errors.append(err.value)
    assert errors[0] is not errors[1] and errors[0].message == errors[1].message
    assert errors[0].code == errors[1].code == "UNIT003"


# --- the YAML bounds fit 10,000 links, and still refuse an alias bomb ---------------------------


def test_a_10000_link_spec_fits_the_yaml_bounds() -> None:
    text = chain_spec(10_000)
    assert len(text.encode()) < yamlsource.MAX_BYTES
    # nodes per link, counted on 100 links (the count is linear): the 10,000-link spec has 100 times
    # as many, and a link written out in full has about twice the synthetic chain's
    builder = yamlsource._Builder("c.yaml")
    import yaml

    builder.build(yaml.compose(chain_spec(100), Loader=yamlsource._LOADER), (), 0)
    assert 2 * builder.count * 100 < yamlsource.MAX_NODES


def test_an_alias_bomb_is_refused_at_once_with_a_hint_saying_what_the_bound_protects() -> None:
    lines = ["a0: &a0 [" + ", ".join(['"lol"'] * 9) + "]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 10)]
    with pytest.raises(InputError) as err:
        yamlsource.loads("\n".join(lines) + "\n", "lol.yaml")
    (f,) = err.value.findings
    assert f.code == "YAML003" and "500,000 YAML nodes repeated through aliases" in f.message
    assert "billion laughs" in f.hint and "memory" in f.hint
    # aliases a1..a4 repeat 74,718 nodes; the 7th *a4 (66,430 nodes each) inside a5 passes the bound,
    # long before a5 is built (597,871 nodes); the finding stands at the anchor of what is repeated
    assert (f.where.line, f.where.col) == (5, 5)


def test_the_alias_bound_counts_each_repeated_node_once(monkeypatch: pytest.MonkeyPatch) -> None:
    # b repeats a (3 nodes) twice, c repeats b (1 + 2 x 3 = 7 nodes) twice: 6 + 14 = 20 repeated,
    # the a's inside a repeated b being part of b's count
    text = "a: &a [x, y]\nb: &b [*a, *a]\nc: [*b, *b]\n"
    monkeypatch.setattr(yamlsource, "MAX_REPEATED", 20)
    assert yamlsource.loads(text, "r.yaml").data["c"] == [[["x", "y"]] * 2] * 2
    monkeypatch.setattr(yamlsource, "MAX_REPEATED", 19)
    with pytest.raises(InputError) as err:
        yamlsource.loads(text, "r.yaml")
    assert err.value.findings[0].where.line == 2  # the collection repeated: b, at its anchor


def test_the_node_bound_hint_names_10000_links(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(yamlsource, "MAX_NODES", 3)
    with pytest.raises(InputError) as err:
        yamlsource.loads("[a, b, c]", "n.yaml")
    (f,) = err.value.findings
    assert f.code == "YAML003" and "more than 3 YAML nodes" in f.message and "10,000-link" in f.hint


# --- sweep ---------------------------------------------------------------------------------------


def _sweep(path: Path, *args: str) -> tuple[int, dict[str, Any], str]:
    """Exit code, the JSON report, and every finding as text (``warning[SWEEP008]: ...``)."""
    ran = cli("sweep", path, *args, "--format", "json")
    assert "Traceback" not in ran.stderr
    doc = json.loads(ran.stdout) if ran.stdout else {}
    said = [f"{f['severity']}[{f['code']}]: {f['message']}" for f in doc.get("findings", [])]
    return ran.returncode, doc, "\n".join([ran.stderr, *said])


def test_sweep_past_the_pose_bound_is_sweep007(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import descgen.physics.sweep as sweep

    path = _write(tmp_path, "c.urdf", chain_urdf(5))
    work = 4 * 5 * (2 + 1)  # joints x links x (steps + 1)
    monkeypatch.setattr(sweep, "MAX_POSES", work)
    code, doc, _ = _sweep(path, "--steps", "2")
    assert code == 0 and len(doc["sweep"]["joints"]) == 4
    monkeypatch.setattr(sweep, "MAX_POSES", work - 1)
    code, _, err = _sweep(path, "--steps", "2")
    assert code == 2 and "error[SWEEP007]" in err and f"{work:,} link poses" in err, err


def test_sweep_past_the_pair_tests_is_sweep008(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import descgen.physics.sweep as sweep

    monkeypatch.setattr(sweep, "MAX_CHECKS", 3)
    code, doc, err = _sweep(_write(tmp_path, "c.urdf", chain_urdf(5)), "--steps", "2")
    assert code == 0 and "warning[SWEEP008]" in err and "SWEEP005" not in err, err
    assert doc["sweep"]["collisions_checked"] is False and len(doc["sweep"]["joints"]) == 4
    assert all(j["pairs_checked"] is None for j in doc["sweep"]["joints"])


@pytest.mark.parametrize(
    ("bound", "value", "words"), [("MAX_DEPTH", 3, "joints deep"), ("MAX_SHAPE_PAIRS", 9, "pairs")]
)
def test_what_pinocchio_cannot_take_is_sweep008(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, bound: str, value: int, words: str
) -> None:
    monkeypatch.setattr(collision, bound, value)  # 5 links: 4 deep, 10 pairs of shapes
    code, _, err = _sweep(_write(tmp_path, "c.urdf", chain_urdf(5)), "--steps", "2")
    assert code == 0 and "warning[SWEEP008]" in err and words in err, err


def test_a_5000_link_chain_is_a_finding_not_a_crash(tmp_path: Path) -> None:
    # the crash case itself: pinocchio overflowed its stack (exit 139) on this chain
    code, _, err = _sweep(_write(tmp_path, "c.urdf", chain_urdf(5000)))
    assert code == 2 and "error[SWEEP007]" in err, err


def test_a_deep_chain_with_one_moving_joint_keeps_pinocchio_out(tmp_path: Path) -> None:
    # within the pose bound (one joint), past pinocchio's depth: directions only
    text = chain_urdf(1500, joint="fixed", shapes=False).replace(
        '<joint name="joint1499" type="fixed">', '<joint name="joint1499" type="revolute">'
    )
    text = text.replace(
        '<axis xyz="0 1 0"/></joint>\n</robot>',
        '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n</robot>',
    )
    code, doc, err = _sweep(_write(tmp_path, "d.urdf", text), "--steps", "2")
    assert code == 0, err
    assert "joints deep" in (doc["sweep"]["not_checked_because"] or ""), doc["sweep"]["not_checked_because"]


def test_pairs_follow_the_old_all_pairs_walk() -> None:
    """The pairs walk over other groups' later links gives the pairs, in the order, of the walk
    over every pair of links."""
    from descgen.physics.sweep import motion

    def every_pair(poses: Any, geometry: Any, disabled: Any) -> tuple[tuple[str, str], ...]:
        names = [n for n in geometry if n in poses[0]]
        seq = {n: motion._relative(poses, n) for n in names}
        out = []
        for i, a in enumerate(names):
            for b in names[i + 1 :]:
                if frozenset((a, b)) not in disabled and motion._gap(seq[a], seq[b]) > motion.MOVES:
                    out.append((a, b))
        return tuple(out)

    from descgen.physics.zero_pose import forward, forward_from
    from descgen.read.urdf import read_urdf_text

    robot, _ = read_urdf_text(chain_urdf(12).encode(), "c.urdf")
    names = [lk.name for lk in robot.links]
    disabled = {frozenset(("link0", "link5")), frozenset(("link3", "link9"))}
    for j in robot.joints[::3]:
        base = forward(robot, {})
        poses = [forward_from(robot, {j.name: v}, base, {}) for v in (-1.0, 0.0, 0.5)]
        assert motion._pairs(poses, names, disabled) == every_pair(poses, names, disabled)
        assert motion._pairs(poses, names, disabled, limit=2) is None


# --- simulate ------------------------------------------------------------------------------------


def test_simulate_bounds_by_hand() -> None:
    from descgen.commands import simulate
    from descgen.read.urdf import read_urdf_text

    robot, _ = read_urdf_text(chain_urdf(10).encode(), "c.urdf")
    simulate_work = 9 * 10 * 19 // 6  # sum of depth^2 for depths 1..9
    steps = round(2.0 / simulate.gravity.TIMESTEP)
    assert simulate.too_large(robot, 2.0, False) == ""
    bound = steps * simulate_work
    old = simulate.MAX_WORK
    try:
        simulate.MAX_WORK = bound
        assert simulate.too_large(robot, 2.0, False) == ""
        simulate.MAX_WORK = bound - 1
        assert f"{bound:,}" in simulate.too_large(robot, 2.0, False)
    finally:
        simulate.MAX_WORK = old


def test_simulate_past_a_bound_is_sim017_before_mujoco(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("mujoco")
    from descgen.commands import simulate

    compiled = []
    monkeypatch.setattr(simulate, "compile_robot", lambda *a, **k: compiled.append(a))
    monkeypatch.setattr(simulate, "MAX_DOFS", 8)  # 10 links, 9 joints
    ran = cli("simulate", _write(tmp_path, "c.urdf", chain_urdf(10)))
    assert ran.returncode == 2 and "error[SIM017]" in ran.stderr and "9 degrees of freedom" in ran.stderr
    assert "Traceback" not in ran.stderr and not compiled


def test_simulate_10000_links_is_a_finding(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    ran = cli("simulate", _write(tmp_path, "c.urdf", chain_urdf(10_000)))
    assert ran.returncode == 2 and "error[SIM017]" in ran.stderr and "10,000 links" in ran.stderr, ran.stderr


# --- import --------------------------------------------------------------------------------------


def test_import_past_the_link_bound_writes_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.commands.importer import run

    monkeypatch.setattr(run, "MAX_LINKS", 4)
    out = tmp_path / "c.yaml"
    ran = cli("import", _write(tmp_path, "c.urdf", chain_urdf(5)), "-o", out)
    assert ran.returncode == 2 and "error[IMP035]" in ran.stderr and "5 links" in ran.stderr, ran.stderr
    assert not out.exists()


def test_import_of_a_spec_validate_would_refuse_is_not_blamed_on_the_description(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(yamlsource, "MAX_NODES", 200)
    out = tmp_path / "c.yaml"
    ran = cli("import", _write(tmp_path, "c.urdf", chain_urdf(5)), "-o", out)
    assert ran.returncode == 2 and "error[IMP035]" in ran.stderr and "YAML nodes" in ran.stderr, ran.stderr
    assert "defect of the description" not in ran.stderr and not out.exists()


def test_pinocchio_is_not_given_a_robot_past_its_bounds(monkeypatch: pytest.MonkeyPatch) -> None:
    # the collision matrix's way in (generate): GEN070 at the matrix, before pinocchio is imported
    from descgen.read.urdf import read_urdf_text

    robot, _ = read_urdf_text(chain_urdf(5).encode(), "c.urdf")
    assert collision.too_large(robot) == ""
    monkeypatch.setattr(collision, "MAX_SHAPE_PAIRS", 9)  # 5 shapes make 10 pairs
    monkeypatch.setitem(sys.modules, "pinocchio", None)  # importing it would fail
    with pytest.raises(InputError) as err:
        collision.load_scene(robot, "<robot/>", {}, "", 0.0)
    (f,) = err.value.findings
    assert f.code == "GEN070" and "10 pairs" in f.message, f.message
    monkeypatch.setattr(collision, "MAX_SHAPE_PAIRS", 10)
    monkeypatch.setattr(collision, "MAX_DEPTH", 3)  # 4 joints deep
    assert "4 joints deep" in collision.too_large(robot)
