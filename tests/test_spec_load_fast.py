"""The spec loader's cheaper paths (issue 17) give what the slower ones gave.

- A primitive's inertia in link axes is plain Python (descgen/physics/inertia.py): numpy's R·I·Rᵀ is
  the oracle, and loading a spec does not import numpy.
- The YAML builder takes plain text scalars without a call: at the depth and node limits it
  still fails where a hand count says it must.
- A plain quantity string is converted without its ``Written`` wrapper: the same value and the
  same error as the ``{value: ...}`` form.
- The walk that joins a spec element's cited sources matches a plain recursive walk.
"""

from __future__ import annotations

import math
import random
import subprocess
import sys
from typing import Any

import numpy as np
import pytest
import yaml
from pydantic import BaseModel

from descgen.audit.spec import load_spec, load_spec_text
from descgen.core.findings import InputError
from descgen.core.model import Box, Cylinder, Pose, Sphere
from descgen.infra import yamlsource
from descgen.physics import inertia, rigid
from descgen.physics.transforms import rpy_matrix
from descgen.spec.quantity import Measured, Written
from descgen.spec.sources import _walk_sources
from tests.conftest import EXAMPLE, ROOT


def _numpy_in_link_frame(principal: tuple[float, float, float], rpy: tuple[float, float, float]) -> np.ndarray:
    r = rpy_matrix(rpy)
    return np.asarray(r @ np.diag(principal) @ r.T)


@pytest.mark.parametrize("seed", range(5))
def test_primitive_inertia_in_link_axes_equals_numpy(seed: int) -> None:
    rng = random.Random(seed)
    for _ in range(400):
        mass = rng.uniform(0.01, 50.0)
        shape = rng.choice(
            [
                Box((rng.uniform(0.01, 1), rng.uniform(0.01, 1), rng.uniform(0.01, 1))),
                Cylinder(rng.uniform(0.01, 0.5), rng.uniform(0.01, 1.0)),
                Sphere(rng.uniform(0.01, 0.5)),
            ]
        )
        # quarter turns (exact zeros off the diagonal) as well as general angles
        rpy = tuple(
            rng.choice([0.0, math.pi / 2, -math.pi / 2, math.pi, rng.uniform(-math.pi, math.pi)]) for _ in "rpy"
        )
        got = inertia.in_link_frame(shape, mass, Pose((0.0, 0.0, 0.0), rpy))  # type: ignore[arg-type]
        principal = inertia.principal_moments(shape, mass)
        assert got is not None and principal is not None
        want = _numpy_in_link_frame(principal, rpy)  # type: ignore[arg-type]
        mine = np.array([[got.ixx, got.ixy, got.ixz], [got.ixy, got.iyy, got.iyz], [got.ixz, got.iyz, got.izz]])
        scale = float(np.max(np.abs(want)))
        np.testing.assert_allclose(mine, want, rtol=0, atol=scale * 1e-12)
        # what numpy rounds to nothing (below 1e-12 of the largest term) is exactly 0, never -0
        for value, ref in zip(mine.ravel(), want.ravel(), strict=True):
            if abs(ref) < scale * 1e-13:
                assert value == 0.0 and math.copysign(1.0, value) == 1.0


def test_principal_moments_by_hand() -> None:
    # box 0.6 x 0.2 x 0.1 m, 2 kg: m(y²+z²)/12 ...; cylinder r 0.1 h 0.4, 3 kg; sphere r 0.2, 5 kg
    assert inertia.principal_moments(Box((0.6, 0.2, 0.1)), 2.0) == pytest.approx(
        (0.05 / 12 * 2, 0.37 / 12 * 2, 0.4 / 12 * 2)
    )
    assert inertia.principal_moments(Cylinder(0.1, 0.4), 3.0) == pytest.approx((3 * 0.19 / 12, 3 * 0.19 / 12, 0.015))
    assert inertia.principal_moments(Sphere(0.2), 5.0) == pytest.approx((0.08, 0.08, 0.08))


def test_rotation_rows_are_the_numpy_matrix() -> None:
    for rpy in ((0.3, -0.7, 1.1), (math.pi / 2, 0.0, -math.pi / 2), (0.0, 0.0, 0.0)):
        assert np.array_equal(np.array(rigid.rpy_rot(rpy)), rpy_matrix(rpy))


@pytest.mark.e2e
def test_loading_a_spec_does_not_import_numpy() -> None:
    """The loader and the model builder (inertia from a primitive included) run without numpy;
    the whole-model rules (rules=False here) are the audit's, which may use it."""
    probe = (
        "import sys\n"
        "from descgen.audit.spec import load_spec\n"
        f"loaded = load_spec({str(EXAMPLE)!r}, rules=False)\n"
        "assert any(lk.inertial and lk.inertial.inertia for lk in loaded.robot.links)\n"
        "print('numpy' in sys.modules)\n"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "False"


# -- YAML limits, counted by hand ----------------------------------------------------------


def _nested(levels: int) -> str:
    return "[" * levels + "x" + "]" * levels


def test_a_scalar_just_inside_the_depth_limit_loads() -> None:
    doc = yamlsource.loads(_nested(yamlsource.MAX_DEPTH), "d.yaml")  # the scalar at depth 64
    node: Any = doc.data
    for _ in range(yamlsource.MAX_DEPTH):
        node = node[0]
    assert node == "x"


def test_a_scalar_just_beyond_the_depth_limit_fails_at_the_scalar() -> None:
    levels = yamlsource.MAX_DEPTH + 1  # lists at depths 0..64, the scalar at 65
    with pytest.raises(InputError) as err:
        yamlsource.loads(_nested(levels), "d.yaml")
    (f,) = err.value.findings
    assert "nested too deeply" in f.message
    assert (f.where.line, f.where.col) == (1, levels + 1)


def test_the_node_limit_counts_plain_scalars(monkeypatch: pytest.MonkeyPatch) -> None:
    text = "[a, b, c]"  # four nodes: the list and three scalars
    monkeypatch.setattr(yamlsource, "MAX_NODES", 4)
    assert yamlsource.loads(text, "n.yaml").data == ["a", "b", "c"]
    monkeypatch.setattr(yamlsource, "MAX_NODES", 3)
    with pytest.raises(InputError) as err:
        yamlsource.loads(text, "n.yaml")
    (f,) = err.value.findings
    assert f.code == "YAML003" and (f.where.line, f.where.col) == (1, 8)  # at 'c'


def test_key_marks_equal_the_pure_python_composer() -> None:
    text = EXAMPLE.read_text(encoding="utf-8")
    doc = yamlsource.loads(text, "t.yaml")
    want: dict[tuple[Any, ...], tuple[int, int]] = {}

    def walk(node: yaml.Node, path: tuple[Any, ...]) -> None:
        if isinstance(node, yaml.MappingNode):
            for k, v in node.value:
                want[(*path, k.value)] = (k.start_mark.line + 1, k.start_mark.column + 1)
                walk(v, (*path, k.value))
        elif isinstance(node, yaml.SequenceNode):
            for i, item in enumerate(node.value):
                walk(item, (*path, i))

    walk(yaml.compose(text, Loader=yaml.SafeLoader), ())
    assert len(want) > 100 and doc.key_marks == want


# -- quantities -----------------------------------------------------------------------------


def _spec(box_side: str) -> str:
    return (
        "name: q\n"
        "links:\n"
        "  - name: base\n"
        f"    collision: [{{geometry: {{box: {{size: [{box_side}, 40 mm, 40 mm]}}}}}}]\n"
        "    inertial: {mass: 1 kg, from: collision}\n"
    )


@pytest.mark.parametrize("side", ["40 mm", "4 cm", "0.04 m", "1.5 in"])
def test_a_plain_quantity_converts_as_its_mapping_form(side: str) -> None:
    plain = load_spec_text(_spec(f'"{side}"'), rules=False).robot.links[0]
    mapped = load_spec_text(_spec(f'{{value: "{side}"}}'), rules=False).robot.links[0]
    assert plain.collisions == mapped.collisions
    assert plain.inertial == mapped.inertial


@pytest.mark.parametrize("side", ["3 kg", "40", "40 mmm", "40 km"])
def test_a_bad_plain_quantity_fails_as_its_mapping_form(side: str) -> None:
    messages = []
    for written in (f'"{side}"', f'{{value: "{side}"}}'):
        with pytest.raises(InputError) as err:
            load_spec_text(_spec(written), rules=False)
        messages.append([(f.code, f.message, f.hint) for f in err.value.findings])
    assert messages[0] == messages[1] and messages[0]


# -- sources --------------------------------------------------------------------------------


def _plain_walk(obj: object, out: list[str]) -> None:
    """The walk as it was before the type-identity shortcuts: the reference."""
    if isinstance(obj, str | int | float | type(None)):
        return
    if isinstance(obj, Measured | Written):
        if obj.source:
            out.append(obj.source)
    elif isinstance(obj, BaseModel):
        src = getattr(obj, "source", None)
        if isinstance(src, str):
            out.append(src)
        for name in type(obj).model_fields:
            if name != "source":
                _plain_walk(getattr(obj, name), out)
    elif isinstance(obj, list | tuple):
        for item in obj:
            _plain_walk(item, out)
    elif isinstance(obj, dict):
        for item in obj.values():
            _plain_walk(item, out)


def test_sources_of_every_element_equal_the_plain_walk() -> None:
    spec = load_spec(EXAMPLE, rules=False).spec
    elements: list[object] = [spec, *spec.links, *spec.joints, *spec.parts, *spec.sensors]
    cited = 0
    for element in elements:
        want: list[str] = []
        _plain_walk(element, want)
        assert _walk_sources(element) == want
        cited += len(want)
    assert cited > 5  # the example cites its measurements: the walk really found some


# -- the per-spec memo of converted quantity texts -------------------------------------------


def test_the_memo_gives_the_spec_validation_without_it_gives() -> None:
    from descgen.spec.models import RobotSpec
    from descgen.spec.plausibility import ranges_from
    from descgen.spec.quantity import MEMO

    doc = yamlsource.load(EXAMPLE)
    ranges, _ = ranges_from(doc)
    memo: dict[Any, Any] = {}
    with_memo = RobotSpec.model_validate(doc.data, context={"ranges": ranges, MEMO: memo})
    without = RobotSpec.model_validate(doc.data, context={"ranges": ranges})
    assert with_memo == without
    written = sum(1 for v in doc.value_marks if isinstance(v, tuple))
    assert 0 < len(memo) < written  # it was used, and texts repeat


def test_a_repeated_bad_value_is_reported_at_each_place() -> None:
    spec = _spec('"3 kg"').replace("40 mm, 40 mm]", '"3 kg", 40 mm]')  # two sides, the same bad text
    with pytest.raises(InputError) as err:
        load_spec_text(spec, rules=False)
    cols = sorted(f.where.col for f in err.value.findings if "3 kg" in f.message)
    assert len(cols) == 2 and cols[0] < cols[1]


def test_each_spec_judges_its_values_by_its_own_plausibility() -> None:
    """The memo lives in one validation's context: a size refused by one spec's narrowed range
    must not be remembered as refused, or accepted, for the next spec."""
    narrowed = _spec('"40 mm"') + "plausibility: {size: {min: 1 mm, max: 10 mm}}\n"
    for order in ((narrowed, _spec('"40 mm"')), (_spec('"40 mm"'), narrowed)):
        for text in order:
            if text is narrowed:
                with pytest.raises(InputError) as err:
                    load_spec_text(text, rules=False)
                assert {f.code for f in err.value.findings} == {"UNIT004"}
            else:
                assert load_spec_text(text, rules=False).robot.links[0].collisions


def _joints(limits: list[tuple[str, str]]) -> str:
    """A chain whose joint i has type and lower limit ``limits[i]``."""
    lines = ["name: j", "links:", "  - name: l0"]
    lines += [f"  - name: l{i + 1}" for i in range(len(limits))]
    lines.append("joints:")
    for i, (kind, lower) in enumerate(limits):
        upper = "90 deg" if kind == "revolute" else "100 mm"
        lines += [
            f"  - name: j{i + 1}",
            f"    type: {kind}",
            f"    parent: l{i}",
            f"    child: l{i + 1}",
            "    axis: +z",
            f"    limit: {{lower: {lower}, upper: {upper}, effort: 10 N*m, velocity: 1 rad/s}}"
            if kind == "revolute"
            else f"    limit: {{lower: {lower}, upper: {upper}, effort: 10 N, velocity: 1 m/s}}",
        ]
    return "\n".join(lines) + "\n"


def test_the_builder_converts_a_repeated_text_by_each_joint_type() -> None:
    """The same text is an angle on a revolute joint and wrong on a prismatic one (a length):
    the builder's conversions must not answer one for the other."""
    for order in (["revolute", "prismatic"], ["prismatic", "revolute"]):
        with pytest.raises(InputError) as err:
            load_spec_text(_joints([(kind, "-90 deg") for kind in order]), rules=False)
        bad = [f for f in err.value.findings if f.code.startswith("UNIT")]
        assert [f.subject for f in bad] == [f"joints.{order.index('prismatic')}.limit.lower"]


def test_the_builder_reports_a_repeated_bad_limit_at_each_joint() -> None:
    with pytest.raises(InputError) as err:
        load_spec_text(_joints([("prismatic", "-90 deg"), ("prismatic", "-90 deg")]), rules=False)
    lines = sorted(f.where.line for f in err.value.findings if f.code.startswith("UNIT"))
    assert len(lines) == 2 and lines[0] < lines[1]
