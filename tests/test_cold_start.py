"""Cold start: a command imports only what it uses. ``descgen --help``, ``validate`` and
``check`` run in a fresh interpreter and must not have imported the heavy optional libraries
(trimesh and scipy come with yourdfpy or meshes, matplotlib with control plots, pinocchio and
coal with the collision matrix, mujoco with simulate), nor, for --help, pint, pydantic or
numpy. And generate draws frames.svg with Graphviz only when frames.dot changed."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import EXAMPLE, ROOT, require_tool

HEAVY = {"trimesh", "scipy", "matplotlib", "pinocchio", "mujoco", "yourdfpy", "rosbags", "networkx"}

# runs the commands in-process in a fresh interpreter and reports the top-level packages loaded
_PROBE = """
import gc, json, sys
from descgen.cli import main
seen = {}
for name, argv in (("help", ["--help"]), ("validate", ["validate", sys.argv[1]]), ("check", ["check", sys.argv[1]])):
    try:
        main(argv)
    except SystemExit as exc:
        code = exc.code
    else:
        code = 0
    seen[name] = {"code": code, "modules": sorted({m.split(".")[0] for m in sys.modules}),
                  "gc": [gc.isenabled(), gc.get_freeze_count()]}
print("PROBE" + json.dumps(seen))
"""


@pytest.fixture(scope="module")
def probe() -> dict[str, dict[str, object]]:
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, str(EXAMPLE)], capture_output=True, text=True, cwd=ROOT, timeout=120
    )
    line = next(x for x in done.stdout.splitlines() if x.startswith("PROBE"))
    result: dict[str, dict[str, object]] = json.loads(line[len("PROBE") :])
    return result


@pytest.mark.e2e
def test_help_imports_no_heavy_library(probe: dict[str, dict[str, object]]) -> None:
    help_run = probe["help"]
    assert help_run["code"] == 0
    loaded = set(help_run["modules"])  # type: ignore[call-overload]
    assert loaded & (HEAVY | {"pint", "pydantic", "numpy"}) == set()


@pytest.mark.e2e
def test_validate_imports_no_heavy_library(probe: dict[str, dict[str, object]]) -> None:
    validate = probe["validate"]
    assert validate["code"] == 0  # the example is valid: the probe really validated
    loaded = set(validate["modules"])  # type: ignore[call-overload]
    assert "pydantic" in loaded  # it did parse models
    assert "pint" not in loaded  # every quantity of the example is read without pint (units._simple_si)
    assert loaded & HEAVY == set()


@pytest.mark.e2e
def test_commands_leave_the_collector_on_with_their_imports_frozen(probe: dict[str, dict[str, object]]) -> None:
    """validate and check import their modules with the collector paused (cli._settled_import):
    it must be on again afterwards, and what the imports made frozen out of its traversal."""
    assert probe["help"]["gc"] == [True, 0]  # --help imports nothing heavy: nothing frozen
    enabled, frozen = probe["validate"]["gc"]  # type: ignore[misc]
    assert enabled is True and frozen > 20_000  # pydantic and the spec models alone make more
    enabled, after_check = probe["check"]["gc"]  # type: ignore[misc]
    assert enabled is True and after_check > frozen  # check's own imports (generate) frozen too


# what check must not pay for: proof 2 reads the URDF back with lxml (yourdfpy, and with it
# trimesh and scipy, only under --thorough); the collision matrix is reused from the committed
# SRDF by its input hash (no pinocchio, no coal); nothing simulates or plots
CHECK_HEAVY = {"trimesh", "scipy", "matplotlib", "pinocchio", "coal", "mujoco", "yourdfpy"}


@pytest.mark.e2e
def test_check_imports_no_heavy_library(probe: dict[str, dict[str, object]]) -> None:
    check = probe["check"]
    assert check["code"] == 0  # the committed example is current: check really ran every proof
    loaded = set(check["modules"])  # type: ignore[call-overload]
    assert {"lxml", "xacro"} <= loaded  # the suite runs without a result cache: xacro expanded
    # nor numpy: the sweep table check computes is plain-float kinematics (descgen/physics/sweep/motion.py)
    assert loaded & (CHECK_HEAVY | {"numpy"}) == set()


@pytest.mark.e2e
def test_check_of_recorded_evidence_imports_no_rosbags(tmp_path: Path) -> None:
    """rosbags came with check's control-evidence re-run and the evidence page's tf scenario;
    both are taken from the committed files when their recorded inputs are unchanged. The
    records are written here by ``descgen report`` on a copy (the repository's records may be of
    other library versions, or of a format version bumped since: descgen/infra/keys.py)."""
    import shutil

    from tests.helpers import cli

    for rel in ("specs/warehouse_arm.yaml", "specs/trajectories/ready.yaml"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / rel, tmp_path / rel)
    for pkg in ("warehouse_arm_description", "warehouse_arm_moveit_config"):
        shutil.copytree(ROOT / "generated" / pkg, tmp_path / "generated" / pkg)
    assert cli("report", "specs/warehouse_arm.yaml", cwd=tmp_path).returncode == 0
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, str(tmp_path / "specs" / "warehouse_arm.yaml")],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    line = next(x for x in done.stdout.splitlines() if x.startswith("PROBE"))
    check = json.loads(line[len("PROBE") :])["check"]
    assert check["code"] == 0  # the copy is current: check really compared everything
    assert "rosbags" not in set(check["modules"])


def _stub_dot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A ``dot`` first on PATH that logs each call and writes an svg naming the dot text's hash."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    log = tmp_path / "dot.log"
    stub = bin_dir / "dot"
    stub.write_text(
        "#!/bin/sh\n"
        f'echo "$@" >> "{log}"\n'
        "printf '<?xml version=\"1.0\"?>\\n<svg><title>%s</title></svg>\\n' "
        '"$(sha256sum < "$2" | cut -c1-16)" > "$4"\n',
        encoding="utf-8",
    )
    stub.chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}")
    return log


def _calls(log: Path) -> int:
    return len(log.read_text(encoding="utf-8").splitlines()) if log.exists() else 0


def test_frames_svg_is_drawn_only_when_the_dot_changed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.commands.generate import draw_frames

    log = _stub_dot(tmp_path, monkeypatch)
    evidence = tmp_path / "pkg" / "evidence"
    evidence.mkdir(parents=True)
    dot, svg = evidence / "frames.dot", evidence / "frames.svg"
    dot.write_text("digraph frames { a -> b }\n", encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    first = svg.read_text(encoding="utf-8")
    assert _calls(log) == 1 and "<svg>" in first
    draw_frames(tmp_path / "pkg")  # same dot text, same dot: not drawn again
    assert _calls(log) == 1 and svg.read_text(encoding="utf-8") == first
    dot.write_text("digraph frames { a -> c }\n", encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    assert _calls(log) == 2 and svg.read_text(encoding="utf-8") != first
    svg.unlink()  # a deleted drawing is drawn again
    draw_frames(tmp_path / "pkg")
    assert _calls(log) == 3 and svg.is_file()
    svg.write_text('<?xml version="1.0"?>\n<svg/>\n', encoding="utf-8")  # a drawing that records nothing
    draw_frames(tmp_path / "pkg")
    assert _calls(log) == 4


def test_frames_svg_is_not_drawn_again_for_a_new_header(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An edited spec changes the dot file's header (its hash) and nothing dot draws."""
    from descgen.commands.generate import draw_frames

    log = _stub_dot(tmp_path, monkeypatch)
    evidence = tmp_path / "pkg" / "evidence"
    evidence.mkdir(parents=True)
    dot = evidence / "frames.dot"
    dot.write_text("// generated from a.yaml\n// descgen spec-sha256=1\ndigraph frames { a -> b }\n", encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    dot.write_text("// generated from a.yaml\n// descgen spec-sha256=2\ndigraph frames { a -> b }\n", encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    assert _calls(log) == 1
    dot.write_text("// generated from a.yaml\n// descgen spec-sha256=3\ndigraph frames { a -> c }\n", encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    assert _calls(log) == 2
    # a comment line inside the graph is the graph's text: drawn again, as any other change
    dot.write_text("// descgen spec-sha256=3\ndigraph frames {\n// note\na -> c }\n", encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    assert _calls(log) == 3


def test_real_dot_draws_the_same_svg_whatever_the_header(tmp_path: Path) -> None:
    """The oracle for leaving the header out of the stamp: Graphviz's own output."""
    require_tool("dot")
    body = 'digraph frames {\n  "base_link" -> "tool0" [label="robot_state_publisher\\n/tf"];\n}\n'
    drawn = []
    for header in ("", "// generated from a.yaml by descgen\n// descgen spec-sha256=1 content-sha256=2\n"):
        path = tmp_path / f"f{len(drawn)}.dot"
        path.write_text(header + body, encoding="utf-8")
        done = subprocess.run(["dot", "-Tsvg", str(path)], capture_output=True, check=True)
        drawn.append(done.stdout)
    assert drawn[0] == drawn[1] and b"tool0" in drawn[0]


def test_frames_svg_is_drawn_again_by_another_dot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.commands.generate import draw_frames

    log = _stub_dot(tmp_path, monkeypatch)
    evidence = tmp_path / "pkg" / "evidence"
    evidence.mkdir(parents=True)
    (evidence / "frames.dot").write_text("digraph frames { a -> b }\n", encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    stub = tmp_path / "bin" / "dot"
    os.utime(stub, ns=(stub.stat().st_atime_ns, stub.stat().st_mtime_ns + 10**9))  # Graphviz upgraded
    draw_frames(tmp_path / "pkg")
    assert _calls(log) == 2


def test_real_dot_draws_a_valid_stamped_svg(tmp_path: Path) -> None:
    from lxml import etree

    from descgen.commands.generate import draw_frames

    require_tool("dot")
    evidence = tmp_path / "pkg" / "evidence"
    evidence.mkdir(parents=True)
    (evidence / "frames.dot").write_text('digraph frames { "base_link" -> "tool0" }\n', encoding="utf-8")
    draw_frames(tmp_path / "pkg")
    root = etree.parse(str(evidence / "frames.svg")).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert "descgen-source: frames.dot sha256" in (evidence / "frames.svg").read_text(encoding="utf-8")


def test_pint_is_imported_without_scipy_and_scipy_still_works_after() -> None:
    code = (
        "import sys; from descgen.core import units; units.to_si('19.1 in / 2', 'length');"
        "assert 'scipy' not in sys.modules, 'pint probed scipy';"
        "import scipy.spatial; print('ok')"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert done.stdout.strip() == "ok", done.stderr


# --- check's proofs: urdfdom started first and collected last; the URDF rendered once --------


def _example_plan_inputs() -> tuple[dict[str, str], object, Path]:
    from descgen.commands.generate import plan

    p = plan(EXAMPLE)
    return dict(p.files), p.robot, p.package_dir


def test_check_urdf_started_first_still_catches_a_broken_urdf() -> None:
    from descgen import prove as checks

    require_tool("check_urdf")
    files, robot, pkg = _example_plan_inputs()
    rel = f"urdf/{robot.name}.urdf"  # type: ignore[attr-defined]
    # a joint whose child link does not exist: urdfdom refuses it (docs/reference/urdf.md)
    files[rel] = files[rel].replace('<child link="tool_link"/>', '<child link="no_such_link"/>', 1)
    assert "no_such_link" in files[rel]
    named = checks.run_named(files, robot, pkg)  # type: ignore[arg-type]
    assert [n for n, _ in named] == [n for n, _ in checks.CHECKS]  # the evidence page's order
    by_name = dict(named)
    urdfdom = by_name["urdfdom's check_urdf accepts the URDF"]
    assert [f.code for f in urdfdom] == ["GEN021"]
    assert "GEN021" not in {f.code for n, found in named if n != "urdfdom's check_urdf accepts the URDF" for f in found}


@pytest.mark.parametrize(
    ("links", "rejected"),
    [
        # urdfdom logs these on stderr and still exits 0 (docs/reference/urdf.md): a failure here
        ('<link name="a"><inertial><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>', True),
        ('<link name="a"><visual><geometry/></visual></link>', True),
        # a name with "Error" in it, printed in the tree on stdout: no error
        (
            '<link name="a"/><link name="ErrorLink"/><joint name="Error_j" type="fixed"><parent link="a"/>'
            '<child link="ErrorLink"/></joint>',
            False,
        ),
    ],
)
def test_check_urdf_judges_urdfdoms_error_stream(links: str, rejected: bool, tmp_path: Path) -> None:
    from descgen.prove.urdfdom import check_urdf

    require_tool("check_urdf")

    class Robot:
        name = "r"

    found = check_urdf({"urdf/r.urdf": f'<robot name="r">{links}</robot>'}, Robot, tmp_path)  # type: ignore[arg-type]
    assert [f.code for f in found] == (["GEN021"] if rejected else [])
    if rejected:
        assert "exit 0" in found[0].message and "Error:" in found[0].message


def test_check_urdf_runs_beside_the_in_process_proofs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A check_urdf that takes 1 s: started before the in-process proofs (the first of them waits
    for its start stamp; run after them, it would stamp later), and its rejection is still reported."""
    import time

    from descgen import prove as checks

    files, robot, pkg = _example_plan_inputs()
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    started = tmp_path / "started"
    stub = bin_dir / "check_urdf"
    # the stamp appears whole (written aside, then renamed): `>` alone creates the file before
    # `date` has written, and a reader could see it exist before the stamp's own time
    stub.write_text(
        f'#!/bin/sh\ndate +%s.%N > "{started}.tmp"\nmv "{started}.tmp" "{started}"\nsleep 1\n'
        'echo "Error: planted" >&2\nexit 3\n',  # where urdfdom writes its errors
        encoding="utf-8",
    )
    stub.chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}")
    seen: list[float] = []

    def first(files: dict[str, str], robot: object, where: Path) -> list[object]:
        deadline = time.time() + 5
        while not started.exists() and time.time() < deadline:  # the stub is already running
            time.sleep(0.01)
        seen.append(time.time())
        return []

    monkeypatch.setattr(checks, "CHECKS", [("first", first), *checks.CHECKS])
    named = dict(checks.run_named(files, robot, pkg))  # type: ignore[arg-type]
    assert started.exists() and seen and float(started.read_text()) <= seen[0]
    found = named["urdfdom's check_urdf accepts the URDF"]
    assert [f.code for f in found] == ["GEN021"] and "exit 3" in found[0].message and "planted" in found[0].message


def test_the_urdf_rendered_alone_is_the_packages() -> None:
    """plan renders the URDF alone for the collision matrix, then the package once: the URDF
    alone is byte-identical to the package's, and rendering it computes no sweep evidence."""
    from descgen.prove import sweep as sweep_evidence
    from descgen.render import render_package

    _, robot, _ = _example_plan_inputs()
    full = render_package(robot, EXAMPLE.name, sweep=sweep_evidence.context)  # type: ignore[arg-type]
    rel = f"urdf/{robot.name}.urdf"  # type: ignore[attr-defined]

    def refuse(robot: object) -> object:
        raise AssertionError("sweep evidence computed for the URDF alone")

    alone = render_package(robot, EXAMPLE.name, only={rel}, sweep=refuse)  # type: ignore[arg-type]
    assert alone == {rel: full[rel]}


@pytest.mark.parametrize(
    ("command", "handler", "paused"), [("validate", "_cmd_validate", True), ("poses", "_cmd_poses", False)]
)
def test_the_collector_pauses_only_for_one_shot_commands_and_comes_back(
    command: str, handler: str, paused: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    """validate/generate/check run without the cyclic collector (their objects live to the
    end); every other command keeps it, and main leaves it on (the suite runs main in-process)."""
    import gc

    from descgen import cli

    seen: list[bool] = []
    monkeypatch.setattr(cli, handler, lambda args: seen.append(gc.isenabled()) or 0)
    assert gc.isenabled()
    assert cli.main([command, "specs/warehouse_arm.yaml"]) == 0
    assert seen == [not paused] and gc.isenabled()


def _failing_dot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, body: str) -> Path:
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    stub = bin_dir / "dot"
    stub.write_text("#!/bin/sh\n" + body, encoding="utf-8")
    stub.chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}")
    evidence = tmp_path / "pkg" / "evidence"
    evidence.mkdir(parents=True)
    (evidence / "frames.dot").write_text("digraph frames { a -> b }\n", encoding="utf-8")
    return evidence


def test_a_dot_that_does_not_finish_is_a_warning_not_a_traceback(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from descgen.commands.generate import draw_frames
    from descgen.write import frames_svg

    evidence = _failing_dot(tmp_path, monkeypatch, "exec sleep 30\n")
    monkeypatch.setattr(frames_svg, "DOT_SECONDS", 0.3)
    found = draw_frames(tmp_path / "pkg")
    assert [(f.code, f.severity) for f in found] == [("GEN094", "warning")]
    assert "did not finish in 0.3 s" in found[0].message
    assert sorted(p.name for p in evidence.iterdir()) == ["frames.dot"]  # no drawing, no temporary file left


def test_a_dot_that_fails_is_a_warning_with_what_it_said(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.commands.generate import draw_frames

    evidence = _failing_dot(tmp_path, monkeypatch, "echo 'Error: syntax error in line 1' >&2\nexit 3\n")
    found = draw_frames(tmp_path / "pkg")
    assert [f.code for f in found] == ["GEN094"]
    assert "exit 3" in found[0].message and "syntax error in line 1" in found[0].message
    assert not (evidence / "frames.svg").exists()


def test_a_tree_too_large_to_draw_is_said_and_its_old_drawing_removed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from descgen.commands.generate import draw_frames
    from descgen.write.frames_svg import MAX_DRAWN_EDGES

    log = _stub_dot(tmp_path, monkeypatch)
    evidence = tmp_path / "pkg" / "evidence"
    evidence.mkdir(parents=True)
    dot, svg = evidence / "frames.dot", evidence / "frames.svg"
    edges = "".join(f'  "l{i}" -> "l{i + 1}";\n' for i in range(MAX_DRAWN_EDGES))
    dot.write_text("digraph frames {\n" + edges + "}\n", encoding="utf-8")
    assert draw_frames(tmp_path / "pkg") == [] and svg.is_file()  # at the bound: drawn
    dot.write_text("digraph frames {\n" + edges + '  "x" -> "y";\n}\n', encoding="utf-8")
    found = draw_frames(tmp_path / "pkg")
    assert [(f.code, f.severity) for f in found] == [("GEN095", "info")]
    assert f"{MAX_DRAWN_EDGES + 1:,} transforms" in found[0].message
    assert not svg.exists() and _calls(log) == 1  # the old drawing showed another tree; dot not run


def test_the_drawing_is_readable_by_everyone_as_the_package_files_are(tmp_path: Path) -> None:
    from descgen.commands.generate import draw_frames

    require_tool("dot")
    evidence = tmp_path / "pkg" / "evidence"
    evidence.mkdir(parents=True)
    (evidence / "frames.dot").write_text('digraph frames { "base_link" -> "tool0" }\n', encoding="utf-8")
    old = os.umask(0o022)
    try:
        draw_frames(tmp_path / "pkg")
        plain = tmp_path / "plain"
        plain.write_text("x", encoding="utf-8")  # what open() makes under the same umask
    finally:
        os.umask(old)
    assert (evidence / "frames.svg").stat().st_mode & 0o777 == plain.stat().st_mode & 0o777 == 0o644
