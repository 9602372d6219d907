"""The issue's Xacro corpus: the ros2_control demo descriptions (rrbot, diffbot, the 6-axis
r6bot) and Universal Robots' ur_mocked with two ur_type values, vendored in
tests/data/xacro_corpus (README there), expanded with --package-path only.

Each is imported (round trip proven, ros2_control and controllers in the spec), its URDF is
generated and compared with the original expansion by pinocchio (every frame at 5 random
configurations, masses and inertias, within 1e-9), its ros2_control blocks by lxml and its
controllers file by yaml.safe_load; ``check`` passes (or fails at the defects ``audit``
reports on the original), and ``audit`` of the spec reports the original's codes."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import yaml
from lxml import etree

from descgen.commands.importer.run import Outcome
from descgen.read.description import Options, audit
from descgen.read.xacro_file import expand_located
from tests.corpus import imported_once, spec_of
from tests.helpers import ROOT, cli

CORPUS = ROOT / "tests" / "data" / "xacro_corpus"
DOC = ROOT / "docs" / "import-corpus.md"


@dataclass(frozen=True)
class Case:
    ident: str
    xacro: str
    controllers: str | None = None
    args: dict[str, str] = field(default_factory=dict)
    launch_args: dict[str, str] = field(default_factory=dict)  # --launch-arg, for $(var) in the controllers
    # defects of the original that the spec keeps (validate fails there, as audit reports)
    defects: frozenset[str] = frozenset()
    slow: bool = False


CASES = (
    Case("rrbot", "ros2_control_demo_example_1/urdf/rrbot.urdf.xacro"),
    Case(
        "rrbot+controllers",
        "ros2_control_demo_example_1/urdf/rrbot.urdf.xacro",
        "ros2_control_demo_example_1/config/rrbot_controllers.yaml",
        # the joints are written $(var joint_prefix)1; bringup/launch/rrbot.launch.py loads the file
        # with allow_substs=True and declares joint_prefix with default_value="joint"
        launch_args={"joint_prefix": "joint"},
    ),
    Case(
        "diffbot",
        "ros2_control_demo_example_2/urdf/diffbot.urdf.xacro",
        "ros2_control_demo_example_2/config/diffbot_controllers.yaml",
    ),
    Case(
        "r6bot",
        "ros2_control_demo_example_7/urdf/r6bot.urdf.xacro",
        "ros2_control_demo_example_7/config/r6bot_controller.yaml",
        # the demo's command min/max on joints 5 and 6 exceed their URDF limits
        defects=frozenset({"CTRL008"}),
    ),
    Case("ur5e", "ur_description/urdf/ur_mocked.urdf.xacro", None, {"ur_type": "ur5e", "name": "ur5e"}, slow=True),
    Case("ur10e", "ur_description/urdf/ur_mocked.urdf.xacro", None, {"ur_type": "ur10e", "name": "ur10e"}, slow=True),
)


def _params(case: Case) -> list[object]:
    return [pytest.param(c, id=c.ident, marks=[pytest.mark.slow] if c.slow else []) for c in CASES]


def _options(case: Case) -> Options:
    return Options(
        controllers=CORPUS / case.controllers if case.controllers else None,
        xacro_args=case.args,
        package_paths=(CORPUS,),
        launch_args=case.launch_args,
    )


def _import(case: Case) -> tuple[Outcome, Path]:
    # the spec lives outside this project, in a folder of its own, and records the corpus relative
    # to itself; generate and check get --package-path too, which finds the same folder
    return imported_once("xacro", case.ident, CORPUS / case.xacro, _options(case))


def _imported(case: Case) -> Outcome:
    return _import(case)[0]


def _spec(case: Case, tmp_path: Path) -> Path:
    """The imported spec, where import meant it to be (its package_paths: are relative to it)."""
    return spec_of(_import(case))


def _generate(case: Case, tmp_path: Path) -> tuple[Path, Path]:
    spec = _spec(case, tmp_path)
    out = tmp_path / "gen"
    ran = cli("generate", spec, "--out", out, "--package-path", CORPUS, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    (package,) = out.iterdir()
    return spec, package


def _original(case: Case, tmp_path: Path) -> Path:
    ex = expand_located(CORPUS / case.xacro, case.xacro, case.args, (CORPUS,), False)
    p = tmp_path / "original.urdf"
    p.write_bytes(ex.xml)
    return p


@pytest.mark.parametrize("case", _params(CASES))
def test_the_import_is_proven_with_ros2_control_in_the_spec(case: Case) -> None:
    outcome = _imported(case)
    assert not outcome.imported.differences, outcome.imported.differences[:5]
    assert not outcome.invalid
    spec = yaml.safe_load(outcome.imported.spec_text)
    assert "ros2_control" in spec
    assert all(etree.fromstring(p["xml"].encode()).tag != "ros2_control" for p in spec.get("passthrough", []))
    if case.controllers:
        original = yaml.safe_load((CORPUS / case.controllers).read_text())
        named = {c["name"] for c in spec["ros2_control"]["controllers"]}
        cm = (original.get("controller_manager") or {}).get("ros__parameters") or {}
        declared = {k for k, v in cm.items() if isinstance(v, dict) and "type" in v}
        assert named == declared | {k for k in original if k != "controller_manager"}


@pytest.mark.slow
@pytest.mark.parametrize("case", [c for c in CASES if not c.defects], ids=lambda c: c.ident)
def test_the_generated_robot_is_the_original(case: Case, tmp_path: Path) -> None:
    import pinocchio as pin

    from tests.test_import_oracle import _pinocchio, _random_configs, _same

    original = _original(case, tmp_path)
    _, package = _generate(case, tmp_path)
    (written,) = (package / "urdf").glob("*.urdf")
    configs = _random_configs(pin.buildModelFromUrdf(str(original)), case.ident)
    poses_a, bodies_a = _pinocchio(original, configs)
    poses_b, bodies_b = _pinocchio(written, configs)
    _same(bodies_a, bodies_b, "inertials")
    for a, b in zip(poses_a, poses_b, strict=True):
        _same(a, b, "frame poses")
    # ros2_control as lxml reads it: plugin, params and every interface with its params
    ra, rb = (etree.parse(str(p)).getroot() for p in (original, written))

    def block(e: etree._Element) -> list[object]:
        return [
            (
                b.get("name"),
                b.findtext("hardware/plugin").strip(),
                {p.get("name"): p.text.strip() for p in b.findall("hardware/param")},
                [
                    (j.tag, j.get("name"), [(i.tag, i.get("name")) for i in j if isinstance(i.tag, str)])
                    for j in b
                    if j.tag in ("joint", "sensor", "gpio")
                ],
            )
            for b in e.findall("ros2_control")
        ]

    assert block(ra) == block(rb)
    for e in ra.iterfind("ros2_control//param"):
        if e.getparent().tag == "hardware":
            continue
        path = ra.getroottree().getpath(e.getparent().getparent()).split("/")[-1]
        name = e.getparent().getparent().get("name")
        iface = e.getparent()
        back = rb.find(
            f"ros2_control/{iface.getparent().tag}[@name='{name}']/{iface.tag}[@name='{iface.get('name')}']"
            f"/param[@name='{e.get('name')}']"
        )
        assert back is not None and float(back.text) == float(e.text), (path, name, e.get("name"))
    if case.controllers:
        text = (CORPUS / case.controllers).read_text()
        for name, value in case.launch_args.items():  # what launch hands the controller manager
            text = text.replace(f"$(var {name})", value)
        original_ctl = yaml.safe_load(text)
        written_ctl = yaml.safe_load((package / "config" / "ros2_controllers.yaml").read_text())
        for name, entry in original_ctl.items():
            if name == "controller_manager" or "ros__parameters" not in entry:
                continue
            mine = {k: v for k, v in entry["ros__parameters"].items() if k != "type"}
            # generate puts an empty controller's type under controller_manager only
            assert (written_ctl.get(name) or {}).get("ros__parameters", {}) == mine, name
            cm = written_ctl["controller_manager"]["ros__parameters"]
            assert cm[name]["type"] == entry["ros__parameters"]["type"], name


@pytest.mark.slow
@pytest.mark.parametrize("case", _params(CASES))
def test_check_passes_and_audit_agrees(case: Case, tmp_path: Path) -> None:
    spec = _spec(case, tmp_path)
    # no --package-path: the spec records the corpus's folder, relative to itself
    gen = cli("generate", spec, "--out", tmp_path / "gen", cwd=tmp_path)
    assert gen.returncode == 0, gen.stderr[-2000:]
    ran = cli("check", spec, "--out", tmp_path / "gen", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    # the defects audit reports on the original are the spec's, waived by import (IMP038): still
    # printed, each with its waiver
    assert set(re.findall(r"error\[(\w+)\]", ran.stderr)) == case.defects
    assert ran.stderr.count("  waived: imported as is") == len(re.findall(r"error\[\w+\]", ran.stderr))
    original = {(f.code, f.subject) for f in audit(CORPUS / case.xacro, _options(case)) if f.severity == "error"}
    assert {c for c, _ in original} == set(case.defects)
    mine = cli("audit", spec, "--package-path", CORPUS, "--format", "json", cwd=tmp_path)
    found = {(f["code"], f["subject"]) for f in __import__("json").loads(mine.stdout)["findings"]}
    everything = {(f.code, f.subject) for f in audit(CORPUS / case.xacro, _options(case))}
    assert {(c, s) for c, s in found if c[:3] not in ("IMP", "SPE")} == {
        (c, s) for c, s in everything if c[:4] not in ("READ",)
    }


HEADER = "| robot | xacro | --xacro-arg | links / joints | ros2_control | controllers | round trip |"


def _row(case: Case) -> str:
    outcome = _imported(case)
    spec = yaml.safe_load(outcome.imported.spec_text)
    rc = spec.get("ros2_control")
    robot = outcome.imported.robot
    args = " ".join(f"`{k}:={v}`" for k, v in case.args.items()) or "–"
    n = len(rc.get("controllers", [])) if rc and case.controllers else 0
    controllers = f"{n} imported" if case.controllers else "–"
    if case.launch_args:
        controllers += " with " + " ".join(f"`--launch-arg {k}:={v}`" for k, v in case.launch_args.items())
    verdict = "proven" if outcome.proven else "differs" if outcome.imported.differences else "fails validate"
    if case.defects:
        verdict += f" (validate fails at {', '.join(sorted(case.defects))}, as audit reports)"
    return (
        f"| {case.ident} | `{case.xacro}` | {args} | {len(robot.links)} / {len(robot.joints)} | "
        f"{'yes' if rc else 'pass-through'} | {controllers} | {verdict} |"
    )


def table() -> str:
    return "\n".join([HEADER, "|---|---|---|---|---|---|---|", *(_row(c) for c in CASES)])


@pytest.mark.slow
def test_the_xacro_table_in_the_docs_is_true() -> None:
    text = DOC.read_text()
    assert "## Xacro packages" in text
    section = text.split("## Xacro packages", 1)[1]
    rows = [line for line in section.splitlines() if line.startswith("|")]
    assert "\n".join(rows) == table(), "regenerate with: python -m tests.test_import_xacro_corpus"


if __name__ == "__main__":
    print(table())
