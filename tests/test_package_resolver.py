"""One package resolver for every command (issue 28): where ``package://`` and ``$(find)``
packages are found (descgen/meshes/packages.py, docs/packages.md).

The layouts are built here as colcon and ament lay them out (a source workspace, an isolated
and a merged install, the ament index's markers, a --symlink-install), and each is searched as
ROS's tools search it. Then every command that reads a spec or a description is run with a
mesh in a sibling package found three ways: recorded in the spec (``package_paths:``, outside
the project), ``--package-path`` and a sourced environment (``AMENT_PREFIX_PATH``); and with
none of them, when each must say the package is missing, at the mesh, the same way.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
import trimesh

from descgen.core.findings import InputError
from descgen.meshes.packages import environment, find_package, search
from descgen.meshes.paths import resolve

from .conftest import ROOT
from .helpers import cli

FINGER = (0.02, 0.02, 0.06)  # m: the sibling package's mesh, a box
MESH = "package://gripper_pkg/meshes/finger.stl"


def _package(folder: Path, name: str = "gripper_pkg", manifest_name: str | None = None) -> Path:
    (folder / "meshes").mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{manifest_name or name}</name></package>")
    trimesh.creation.box(FINGER).export(folder / "meshes" / "finger.stl")
    return folder


# --- the layouts ----------------------------------------------------------------------------------


def test_a_source_workspace_is_crawled_as_colcon_crawls_it(tmp_path: Path) -> None:
    src = tmp_path / "ws" / "src"
    found = _package(src / "grippers" / "gripper_pkg")
    _package(src / "ignored" / "hidden_pkg", "hidden_pkg")
    (src / "ignored" / "COLCON_IGNORE").write_text("")
    _package(src / ".git" / "dot_pkg", "dot_pkg")
    _package(found / "test" / "nested_pkg", "nested_pkg")  # below a package: colcon does not look
    assert find_package("gripper_pkg", [src]) == found
    assert find_package("hidden_pkg", [src]) is None
    assert find_package("dot_pkg", [src]) is None
    assert find_package("nested_pkg", [src]) is None


def test_colcon_installs_isolated_and_merged(tmp_path: Path) -> None:
    isolated = _package(tmp_path / "a" / "install" / "gripper_pkg" / "share" / "gripper_pkg")
    merged = _package(tmp_path / "b" / "install" / "share" / "gripper_pkg")
    assert find_package("gripper_pkg", [tmp_path / "a" / "install"]) == isolated
    assert find_package("gripper_pkg", [tmp_path / "b" / "install"]) == merged


def test_an_installed_package_is_found_by_the_ament_index_under_its_folder_name(tmp_path: Path) -> None:
    # example-robot-data's package.xml says example_robot_descriptions, its URDFs say
    # package://example-robot-data/: ament_index_python answers by the marker and the folder
    share = tmp_path / "prefix" / "share"
    installed = _package(share / "example-robot-data", manifest_name="example_robot_descriptions")
    (share / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    assert find_package("example-robot-data", [share]) is None  # no marker: not a package of that name
    (share / "ament_index" / "resource_index" / "packages" / "example-robot-data").write_text("")
    assert find_package("example-robot-data", [share]) == installed
    assert find_package("example-robot-data", [tmp_path / "prefix"]) == installed  # the prefix itself


def test_a_folder_without_a_package_xml_is_not_a_package(tmp_path: Path) -> None:
    # a spec's package_paths: may leave the project: package://etc/passwd must not find /etc
    (tmp_path / "etc").mkdir()
    (tmp_path / "etc" / "passwd").write_text("root:x:0:0\n")
    assert find_package("etc", [tmp_path]) is None
    assert resolve("package://etc/passwd", tmp_path, tmp_path, [tmp_path]).state == "unresolved"


def test_a_symlink_install_reads_its_source_package_and_nothing_else(tmp_path: Path) -> None:
    source = _package(tmp_path / "ws" / "src" / "gripper_pkg")
    secret = tmp_path / "secret.stl"
    shutil.copy(source / "meshes" / "finger.stl", secret)
    share = tmp_path / "ws" / "install" / "gripper_pkg" / "share" / "gripper_pkg"
    (share / "meshes").mkdir(parents=True)
    # colcon build --symlink-install: every installed file is a link into the source package
    (share / "package.xml").symlink_to(source / "package.xml")
    (share / "meshes" / "finger.stl").symlink_to(source / "meshes" / "finger.stl")
    (share / "meshes" / "out.stl").symlink_to(secret)
    install = [tmp_path / "ws" / "install"]
    ok = resolve(MESH, tmp_path, tmp_path, install)
    assert (ok.state, ok.path) == ("ok", (source / "meshes" / "finger.stl").resolve())
    assert resolve("package://gripper_pkg/meshes/out.stl", tmp_path, tmp_path, install).state == "escapes"
    # a package.xml that links to another package's does not widen the package
    (share / "package.xml").unlink()
    (share / "package.xml").symlink_to(_package(tmp_path / "other", "other_pkg") / "package.xml")
    assert find_package("gripper_pkg", install) is None


def test_the_environment_and_the_order(tmp_path: Path) -> None:
    overlay = tmp_path / "overlay"
    underlay = tmp_path / "underlay"
    for prefix in (overlay, underlay):
        _package(prefix / "share" / "gripper_pkg")
    legacy = tmp_path / "legacy"
    legacy.mkdir()
    env = {
        "AMENT_PREFIX_PATH": f"{overlay}:{tmp_path / 'gone'}:{underlay}:relative/prefix",
        "ROS_PACKAGE_PATH": f"{legacy}",
    }
    assert environment(env) == (overlay / "share", underlay / "share", legacy)  # the overlay first
    given = tmp_path / "given"
    _package(given / "gripper_pkg")
    order = search([given], env)
    assert order == (given, overlay / "share", underlay / "share", legacy)
    assert find_package("gripper_pkg", order) == given / "gripper_pkg"  # --package-path before the environment
    assert find_package("gripper_pkg", search([], env)) == overlay / "share" / "gripper_pkg"


def test_the_spec_s_folders_come_before_the_command_line(tmp_path: Path) -> None:
    from descgen.audit.spec import load_spec

    recorded = _package(tmp_path / "ws_a" / "gripper_pkg")
    given = _package(tmp_path / "ws_b" / "gripper_pkg")
    spec = tmp_path / "project" / "specs" / "s.yaml"
    spec.parent.mkdir(parents=True)
    spec.write_text(
        "name: s\npackage_paths: [../../ws_a]\nlinks:\n  - name: base_link\n"
        f"    visual:\n      - geometry: {{mesh: {{filename: '{MESH}'}}}}\n"
    )
    files = dict(load_spec(spec, package_paths=(tmp_path / "ws_b",)).robot.mesh_files)
    assert files == {MESH: str((recorded / "meshes" / "finger.stl").resolve())}
    # and the command line's when the spec records none
    spec.write_text(spec.read_text().replace("package_paths: [../../ws_a]\n", ""))
    files = dict(load_spec(spec, package_paths=(tmp_path / "ws_b",)).robot.mesh_files)
    assert files == {MESH: str((given / "meshes" / "finger.stl").resolve())}


def test_the_crawl_stops_at_its_bound(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import descgen.meshes.packages as packages

    src = tmp_path / "src"
    for i in range(30):
        (src / f"empty_{i:02d}").mkdir(parents=True)
    _package(src / "zz_repo" / "gripper_pkg")  # after the 30 empty folders, sorted by name
    monkeypatch.setattr(packages, "CRAWL_FOLDERS", 10)
    monkeypatch.setattr(packages, "_crawled", {})
    assert find_package("gripper_pkg", [src]) is None
    monkeypatch.setattr(packages, "CRAWL_FOLDERS", 1000)
    monkeypatch.setattr(packages, "_crawled", {})
    assert find_package("gripper_pkg", [src]) == src / "zz_repo" / "gripper_pkg"
    # a link loop back to the top ends at the depth bound, and the first find stands
    (src / "zz_repo" / "loop").symlink_to(src)
    monkeypatch.setattr(packages, "_crawled", {})
    assert find_package("gripper_pkg", [src]) == src / "zz_repo" / "gripper_pkg"


# --- every command --------------------------------------------------------------------------------

SOURCES = ("recorded", "flag", "environment", "none")


def _project(tmp_path: Path, source: str, monkeypatch: pytest.MonkeyPatch) -> tuple[Path, list[str]]:
    """The example robot with a finger mesh from gripper_pkg, in a colcon workspace beside the
    project (an isolated install); (project, the options every command gets)."""
    install = tmp_path / "ws" / "install"
    _package(install / "gripper_pkg" / "share" / "gripper_pkg")
    project = tmp_path / "project"
    (project / "specs" / "trajectories").mkdir(parents=True)
    text = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
    tool = "  - name: tool_link\n    description: tool flange frame, axes aligned with the forearm\n"
    assert tool in text
    text = text.replace(tool, tool + f"    visual:\n      - geometry: {{mesh: {{filename: '{MESH}'}}}}\n", 1)
    if source == "recorded":
        text = text.replace("name: warehouse_arm\n", "name: warehouse_arm\npackage_paths: [../../ws/install]\n", 1)
    (project / "specs" / "warehouse_arm.yaml").write_text(text)
    shutil.copy(ROOT / "specs" / "trajectories" / "ready.yaml", project / "specs" / "trajectories" / "ready.yaml")
    if source == "environment":
        monkeypatch.setenv("AMENT_PREFIX_PATH", str(install / "gripper_pkg"))
    return project, (["--package-path", str(install)] if source == "flag" else [])


@pytest.mark.parametrize("source", SOURCES)
def test_every_command_finds_a_spec_s_sibling_package_the_same_way(
    tmp_path: Path, source: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    project, opts = _project(tmp_path, source, monkeypatch)
    spec = "specs/warehouse_arm.yaml"
    runs = {
        "validate": ["validate", spec],
        "generate": ["generate", spec],
        "control": ["control", spec, "--trajectory", "specs/trajectories/ready.yaml"],
        "check": ["check", spec],
        "report": ["report", spec],
        "poses": ["poses", spec],
        "frames": ["frames", spec],
        "audit": ["audit", spec],
        "faults": ["faults", spec],
        "sweep": ["sweep", spec, "--steps", "3"],
        "simulate": ["simulate", spec, "--seconds", "0.1", "--pose", "ready"],
        "tf-scenario": ["tf-scenario", spec, "--out", "bag", "--duration", "1"],
    }
    for name, args in runs.items():
        ran = cli(*args, *opts, cwd=project)
        if source == "none":
            # the same refusal from every command: exit 2, SPEC062 at the mesh's line
            assert ran.returncode == 2, (name, ran.stderr[-800:])
            assert "error[SPEC062]" in ran.stderr and f"mesh '{MESH}'" in ran.stderr, (name, ran.stderr[-800:])
            assert "Traceback" not in ran.stderr
        else:
            assert ran.returncode == 0, (name, ran.stdout[-800:], ran.stderr[-800:])
            assert "SPEC062" not in ran.stderr, name
    if source != "none":
        # generate referenced the package (not copied) and depends on it
        package = project / "generated" / "warehouse_arm_description"
        assert "<exec_depend>gripper_pkg</exec_depend>" in (package / "package.xml").read_text()
        assert MESH in (package / "urdf" / "warehouse_arm.urdf").read_text()
        assert not (package / "meshes").exists()
    # view: the meshes it shows are those of the same file
    from descgen.commands.view import load, mesh_plan

    folders = search([Path(opts[1])] if opts else [], os.environ)
    if source == "none":
        with pytest.raises(InputError, match="names package 'gripper_pkg'"):
            load(project / spec, folders)
    else:
        robot, _ = load(project / spec, folders)
        shown, findings = mesh_plan(robot)
        assert set(shown) == {MESH} and not findings
        np_extent = shown[MESH].vertices.max(axis=0) - shown[MESH].vertices.min(axis=0)
        assert [round(float(x), 6) for x in np_extent] == list(FINGER)


URDF = f"""<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="j" type="revolute">
    <parent link="base_link"/><child link="finger"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="finger">
    <inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="{MESH}"/></geometry></visual>
    <collision><geometry><mesh filename="{MESH}"/></geometry></collision>
  </link>
</robot>
"""


@pytest.mark.parametrize("source", ("flag", "environment", "none"))
def test_every_command_finds_a_description_s_sibling_package_the_same_way(
    tmp_path: Path, source: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    install = tmp_path / "ws" / "install"
    _package(install / "gripper_pkg" / "share" / "gripper_pkg")
    desc = tmp_path / "bot_description"
    (desc / "urdf").mkdir(parents=True)
    (desc / "package.xml").write_text("<package format='3'><name>bot_description</name></package>")
    (desc / "urdf" / "bot.urdf").write_text(URDF)
    (desc / "urdf" / "bot.urdf.xacro").write_text(
        URDF.replace('<robot name="bot">', '<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">')
    )
    opts = ["--package-path", str(install)] if source == "flag" else []
    if source == "environment":
        monkeypatch.setenv("AMENT_PREFIX_PATH", str(install / "gripper_pkg"))
    for path in (desc / "urdf" / "bot.urdf", desc / "urdf" / "bot.urdf.xacro"):
        runs = {
            "audit": ["audit", path, "--format", "json"],
            "frames": ["frames", path],
            "faults": ["faults", path],
            "sweep": ["sweep", path, "--steps", "3"],
            "simulate": ["simulate", path, "--seconds", "0.1"],
            "import": ["import", path, "-o", tmp_path / f"specs_{path.suffix}" / "bot.yaml"],
        }
        for name, args in runs.items():
            ran = cli(*args, *opts)
            assert "Traceback" not in ran.stderr
            out = ran.stdout + ran.stderr
            if source == "none":
                # a description someone else wrote: the meshes are reported, the rest still runs
                said = {"audit": "GEOM005", "import": "GEOM005", "simulate": "SIM008", "sweep": "SWEEP006"}
                assert name in ("frames", "faults") or said[name] in out, (name, out[-800:])
            else:
                assert not any(c in out for c in ("GEOM005", "SIM008", "SWEEP006")), (name, out[-800:])
        spec = tmp_path / f"specs_{path.suffix}" / "bot.yaml"
        validated = cli("validate", spec, *opts)
        assert validated.returncode == (2 if source == "none" else 0), validated.stderr[-800:]


def test_view_shows_a_collada_mesh_of_a_sourced_package_in_metres(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A COLLADA visual written in centimetres (``<unit meter="0.01"/>``), in a package the
    environment names: view shows it at its size in metres, as RViz applies the unit."""
    from descgen.commands.view import load, mesh_plan
    from descgen.commands.view.server import _urdf_model

    from .test_simulate_collada import _collada_cube

    prefix = tmp_path / "install"
    pkg = _package(prefix / "share" / "gripper_pkg")
    (pkg / "meshes" / "cube.dae").write_bytes(_collada_cube(4.0, 0.01))  # a 4 cm cube written in cm
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    (prefix / "share" / "ament_index" / "resource_index" / "packages" / "gripper_pkg").write_text("")
    urdf = tmp_path / "bot.urdf"
    urdf.write_text(URDF.replace(MESH, "package://gripper_pkg/meshes/cube.dae"))
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    robot, text = load(urdf, search([], os.environ))
    shown, findings = mesh_plan(robot)
    assert set(shown) == {"package://gripper_pkg/meshes/cube.dae"} and not findings
    model = _urdf_model(text, shown)
    (geometry,) = [g for name, g in model.scene.geometry.items() if name.startswith("finger/visual")]
    extent = geometry.bounds[1] - geometry.bounds[0]
    assert [round(float(x), 9) for x in extent] == [0.04, 0.04, 0.04]


# --- the vendored corpus (tests/data/jazzy_corpus) -------------------------------------------------

CORPUS = ROOT / "tests" / "data" / "jazzy_corpus"


def _corpus_cases() -> list[dict[str, object]]:
    import yaml

    return list(yaml.safe_load((CORPUS / "corpus.yaml").read_text())["cases"])


@pytest.mark.parametrize("case", _corpus_cases(), ids=lambda c: str(c["id"]))
def test_every_reader_resolves_the_corpus_meshes_alike(
    case: dict[str, object], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Each corpus robot's meshes, named across sibling packages: the audit's loader, view,
    simulate's MuJoCo emitter and the sweep's collision model use the same files, whether the
    corpus is given with --package-path or as a sourced ROS_PACKAGE_PATH."""
    from descgen.commands.view import mesh_plan
    from descgen.read.description import Options, load_description
    from descgen.render.mujoco_urdf import emit

    xacro = CORPUS / str(case["xacro"])
    args = {str(k): str(v) for k, v in dict(case.get("args") or {}).items()}  # type: ignore[call-overload]
    flag = load_description(xacro, Options(xacro_args=args, package_paths=search([CORPUS], {})))[0]
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(CORPUS))
    sourced = load_description(xacro, Options(xacro_args=args, package_paths=search([], os.environ)))[0]
    names = {
        shape.geometry.filename
        for lk in flag.links
        for shape in lk.shapes()
        if getattr(shape.geometry, "filename", None) is not None
    }
    assert names, "every corpus robot has meshes"
    files = dict(flag.mesh_files)
    # every mesh named with package:// or $(find) is found, inside the corpus, the same way twice
    found = {n for n in names if n in files}
    assert found, names
    assert all(Path(files[n]).resolve().is_relative_to(CORPUS.resolve()) for n in found)
    assert dict(sourced.mesh_files) == files and dict(sourced.mesh_status) == dict(flag.mesh_status)
    # view shows exactly the files the resolver accepted (no search of its own)
    shown, _ = mesh_plan(flag)
    assert set(shown) == {n for n, s in flag.mesh_status if s == "ok"}
    # MuJoCo gets every collision mesh the resolver found (none left out as "not a file")
    emitted = emit(flag)
    assert not [f for f in emitted.findings if "is not a file inside" in f.message]


def test_an_absolute_mesh_is_read_only_inside_the_folders_named(tmp_path: Path) -> None:
    """``file://$(find pkg)/meshes/x.stl`` expanded is this machine's absolute path: the audit
    reads it inside a folder the user named (or the description's package), as RViz would, and
    import writes it ``package://pkg/...``; anywhere else it is GEOM004, and a spec never has one."""
    from descgen.meshes.paths import resolve_names

    ws = tmp_path / "ws"
    pkg = _package(ws / "gripper_pkg")
    finger = (pkg / "meshes" / "finger.stl").resolve()
    outside = tmp_path / "outside.stl"
    shutil.copy(finger, outside)
    desc = tmp_path / "desc" / "bot.urdf"  # its own folder: a relative name could not leave it
    desc.parent.mkdir()
    names = [f"file://{finger}", str(finger), f"file://{outside}"]
    loose = ws / "loose" / "part.stl"  # under the folder named, in no package
    loose.parent.mkdir()
    shutil.copy(finger, loose)
    names.append(f"file://{loose.resolve()}")
    status, files = resolve_names(names, desc, [ws])
    assert status == {names[0]: "ok", names[1]: "ok", names[2]: "escapes", names[3]: "escapes"}
    assert files[names[0]] == finger
    assert resolve_names(names[:1], desc, [])[0] == {names[0]: "escapes"}  # the folder not named

    urdf = URDF.replace(MESH, f"file://{finger}")
    desc.write_text(urdf)
    spec = tmp_path / "project" / "specs" / "bot.yaml"
    ran = cli("import", desc, "-o", spec, "--package-path", ws)
    assert ran.returncode == 0, ran.stderr
    assert "info[IMP036]" in ran.stderr and "GEOM004" not in ran.stderr
    text = spec.read_text()
    assert MESH in text and str(tmp_path) not in text
    assert cli("validate", spec).returncode == 0
