"""Folders given as input are read like any other untrusted input (issue 34, items 3, 7 and 9):
regular files inside the folder, no links out, bounded size.

- a spec's ``templates:`` folder (and ``--templates``): a template that is a link out of the
  folder (to a secret file, to /proc/self/environ), a FIFO or a huge file is GEN065 at the
  template, exit 2, and nothing is generated or printed from it;
- ``--moveit-config DIR``: a YAML or SRDF that is a link out of DIR is READ044, exit 2, and
  none of its values reach a finding;
- ``audit``: ``package://`` is resolved in the URDF's own package (the nearest folder above it
  holding a package.xml) and in ``--package-path``, never in sibling folders (docs/security.md);
  a package in a ``--package-path`` folder that is a link out of it is not found there.
"""

from __future__ import annotations

import os
import shutil
import threading
from pathlib import Path

import pytest

from .helpers import cli
from .test_moveit_audit import DATA, _planted

SECRET = "DESCGEN_SECRET_TOKEN=ghp_planted0123456789"

SPEC = """\
name: tiny_arm
templates: ../tpl
links:
  - name: base_link
    collision:
      - geometry: {box: {size: [100 mm, 100 mm, 50 mm]}}
    inertial: {mass: 2 kg, from: collision}
  - name: arm_link
    collision:
      - geometry: {box: {size: [40 mm, 40 mm, 300 mm]}}
    inertial: {mass: 1 kg, from: collision}
joints:
  - name: j1
    type: revolute
    parent: base_link
    child: arm_link
    origin: {xyz: [0, 0, 50 mm]}
    axis: +z
    limit: {lower: -90 deg, upper: 90 deg, effort: 10 N*m, velocity: 1 rad/s}
"""

DEFAULTS = Path(__file__).resolve().parents[1] / "descgen" / "templates"


def _project(root: Path) -> Path:
    (root / "specs").mkdir()
    (root / "tpl").mkdir()
    (root / "specs" / "arm.yaml").write_text(SPEC)
    return root / "tpl"


def _everything(root: Path) -> str:
    """The text of every file under ``root`` (what a leak would have to be found in)."""
    out = []
    for path in root.rglob("*"):
        if path.is_file() and not path.is_symlink():
            out.append(path.read_bytes().decode("utf-8", "replace"))
    return "\n".join(out)


def test_a_template_linked_out_of_its_folder_is_refused(tmp_path: Path) -> None:
    tpl = _project(tmp_path)
    secret = tmp_path / "outside" / "secret.txt"
    secret.parent.mkdir()
    secret.write_text(SECRET + "\n")
    (tpl / "display.launch.py.j2").symlink_to(secret)
    r = cli("generate", "specs/arm.yaml", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "tpl/display.launch.py.j2: error[GEN065]:" in r.stderr and "symbolic link out of" in r.stderr
    assert "hint:" in r.stderr and "Traceback" not in r.stderr
    assert SECRET not in r.stdout + r.stderr
    assert not (tmp_path / "generated").exists()


def test_the_environment_never_renders_into_the_package(tmp_path: Path) -> None:
    """The issue's case: a link to /proc/self/environ rendered the CI tokens into display.launch.py,
    and ``check`` printed them in its diff."""
    tpl = _project(tmp_path)
    r = cli("generate", "specs/arm.yaml", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr  # the defaults, generated first
    (tpl / "display.launch.py.j2").symlink_to("/proc/self/environ")
    for command in ("generate", "check"):
        r = cli(command, "specs/arm.yaml", cwd=tmp_path)
        assert r.returncode == 2, (command, r.stdout + r.stderr)
        assert "error[GEN065]" in r.stderr and "Traceback" not in r.stderr
        assert "PATH=" not in r.stdout + r.stderr
    assert "PATH=" not in _everything(tmp_path / "generated")
    # the same with --templates (a folder named on the command line is read the same way)
    r = cli("generate", "specs/arm.yaml", "--templates", str(tpl), cwd=tmp_path)
    assert r.returncode == 2 and "error[GEN065]" in r.stderr and "PATH=" not in r.stdout + r.stderr


@pytest.mark.parametrize("name", [".git/config", "../.git/config", "secrets.txt"])
def test_a_template_includes_only_templates(tmp_path: Path, name: str) -> None:
    """``templates: ..`` is inside the project, and so is .git/config, where actions/checkout
    keeps its token: only the folder's own *.j2 files are templates (found by the independent
    check of issue 34)."""
    _project(tmp_path)
    (tmp_path / "specs" / "arm.yaml").write_text(SPEC.replace("templates: ../tpl", "templates: .."))
    (tmp_path / ".git").mkdir()
    (tmp_path / ".git" / "config").write_text(SECRET + "\n")
    (tmp_path / "secrets.txt").write_text(SECRET + "\n")
    (tmp_path / "display.launch.py.j2").write_text(f'# {{% include "{name}" %}}\n')
    for command in ("generate", "check"):
        r = cli(command, "specs/arm.yaml", cwd=tmp_path)
        assert r.returncode == 2 and "Traceback" not in r.stderr, (command, r.stdout + r.stderr)
        assert SECRET not in r.stdout + r.stderr
    assert not (tmp_path / "generated").exists()


def test_a_link_inside_the_folder_is_still_read(tmp_path: Path) -> None:
    tpl = _project(tmp_path)
    text = (DEFAULTS / "CMakeLists.txt.j2").read_text() + "# team override\n"
    (tpl / "shared").mkdir()
    (tpl / "shared" / "cmake.j2").write_text(text)
    (tpl / "CMakeLists.txt.j2").symlink_to(Path("shared") / "cmake.j2")
    r = cli("generate", "specs/arm.yaml", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert (
        (tmp_path / "generated" / "tiny_arm_description" / "CMakeLists.txt").read_text().endswith("# team override\n")
    )


def test_a_fifo_template_is_refused_without_blocking(tmp_path: Path) -> None:
    tpl = _project(tmp_path)
    os.mkfifo(tpl / "package.xml.j2")
    # a writer that would unblock a blocking open, so a regression fails instead of hanging
    opened = threading.Event()

    def writer() -> None:
        try:
            fd = os.open(tpl / "package.xml.j2", os.O_WRONLY | os.O_NONBLOCK)
        except OSError:
            return
        opened.set()
        os.close(fd)

    r = cli("generate", "specs/arm.yaml", cwd=tmp_path, timeout=60)
    threading.Thread(target=writer, daemon=True).start()
    assert r.returncode == 2, r.stdout + r.stderr
    assert "tpl/package.xml.j2: error[GEN065]: is a FIFO (named pipe), not a regular file" in r.stderr
    assert not (tmp_path / "generated").exists()


def test_a_huge_template_is_refused_before_reading(tmp_path: Path) -> None:
    tpl = _project(tmp_path)
    with open(tpl / "package.xml.j2", "wb") as fh:
        fh.truncate(200 * 1024 * 1024)  # sparse: no disk used, and never read
    r = cli("generate", "specs/arm.yaml", cwd=tmp_path)
    assert r.returncode == 2 and "error[GEN065]" in r.stderr and "at most 1 MiB" in r.stderr, r.stderr
    assert not (tmp_path / "generated").exists()


# --------------------------------------------------------------------------- --moveit-config


@pytest.mark.parametrize("name", ["joint_limits.yaml", "kinematics.yaml", "initial_positions.yaml"])
def test_a_moveit_yaml_linked_out_of_the_folder_is_refused(tmp_path: Path, name: str) -> None:
    folder = _planted(tmp_path, [])
    outside = tmp_path / "outside.yaml"
    # values MoveIt would report with their text: a leak would print them in findings
    outside.write_text(f"joint_limits:\n  {SECRET.split('=')[1]}: {{has_velocity_limits: 7}}\n")
    (folder / "config" / name).unlink()
    (folder / "config" / name).symlink_to(outside)
    r = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder)
    assert r.returncode == 2, r.stdout + r.stderr
    assert f"config/{name}: error[READ044]:" in r.stderr and "hint:" in r.stderr, r.stderr
    assert "ghp_planted" not in r.stdout + r.stderr and "Traceback" not in r.stderr


def test_a_moveit_srdf_and_controllers_linked_out_are_refused(tmp_path: Path) -> None:
    folder = _planted(tmp_path, [])
    srdf = next((folder / "config").glob("*.srdf"))
    moved = tmp_path / "elsewhere.srdf"
    shutil.move(srdf, moved)
    srdf.symlink_to(moved)
    r = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder)
    assert r.returncode == 2 and f"{srdf.name}: error[READ044]" in r.stderr, r.stderr
    srdf.unlink()
    shutil.move(moved, srdf)
    yaml_file = folder / "config" / "ros2_controllers.yaml"
    moved = tmp_path / "elsewhere.yaml"
    shutil.move(yaml_file, moved)
    yaml_file.symlink_to(moved)
    r = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder)
    assert r.returncode == 2 and "ros2_controllers.yaml: error[READ044]" in r.stderr, r.stderr


def test_a_config_folder_linked_out_is_refused(tmp_path: Path) -> None:
    folder = _planted(tmp_path, [])
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "config").symlink_to(folder / "config")  # the package's config/ lives elsewhere
    r = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", pkg)
    assert r.returncode == 2 and "error[READ044]" in r.stderr and "Traceback" not in r.stderr, r.stderr
    # the folder itself, named directly, is read
    assert cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder).returncode in (0, 1)


def test_a_robot_name_never_becomes_a_path_into_the_moveit_folder(tmp_path: Path) -> None:
    from descgen.read.moveit_config import find_srdf

    folder = _planted(tmp_path, [])
    outside = tmp_path / "x.srdf"
    outside.write_text("<robot name='x'/>")
    assert find_srdf(folder / "config", "../../x") != outside
    assert find_srdf(folder / "config", "../../x") == next((folder / "config").glob("*.srdf"))


# --------------------------------------------------------------------------- audit: package:// lookups

URDF = """<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="package://{pkg}/meshes/m.stl"/></geometry></visual>
  </link>
</robot>
"""

PACKAGE_XML = (
    '<?xml version="1.0"?>\n<package format="3"><name>{name}</name><version>0.1.0</version>'
    '<description>d</description><maintainer email="a@example.com">a</maintainer><license>MIT</license></package>\n'
)


def _mesh(folder: Path) -> None:
    import trimesh

    (folder / "meshes").mkdir(parents=True)
    trimesh.creation.box((0.1, 0.1, 0.1)).export(folder / "meshes" / "m.stl")


def _mesh_codes(r) -> list[str]:  # type: ignore[no-untyped-def]
    return [c for c in ("GEOM030", "GEOM031", "GEOM032", "GEOM033") if f"[{c}]" in r.stderr]


def _states(urdf: Path, *more: str) -> dict[str, str]:
    from descgen.meshes.paths import resolve_names

    return resolve_names(
        ["package://other_pkg/meshes/m.stl", "package://my_pkg/meshes/m.stl"], urdf, [Path(m) for m in more]
    )[0]


def test_audit_does_not_look_in_sibling_folders(tmp_path: Path) -> None:
    """ws/my_pkg/urdf/r.urdf names package://other_pkg: ws/other_pkg (a sibling of the URDF's
    package) and ws/my_pkg/other_pkg (a sibling of the URDF's folder) were both searched."""
    ws = tmp_path / "ws"
    own = ws / "my_pkg"
    (own / "urdf").mkdir(parents=True)
    (own / "package.xml").write_text(PACKAGE_XML.format(name="my_pkg"))
    _mesh(own)
    _mesh(ws / "other_pkg")
    (ws / "other_pkg" / "package.xml").write_text(PACKAGE_XML.format(name="other_pkg"))
    _mesh(own / "urdf" / "other_pkg")
    urdf = own / "urdf" / "r.urdf"
    urdf.write_text(URDF.format(pkg="other_pkg"))
    states = _states(urdf)
    assert states == {"package://other_pkg/meshes/m.stl": "unresolved", "package://my_pkg/meshes/m.stl": "ok"}
    # named with --package-path, the sibling package is found
    assert _states(urdf, str(ws))["package://other_pkg/meshes/m.stl"] == "ok"
    # end to end: the audit says the package is not found (and reads no mesh of it)
    r = cli("audit", urdf)
    assert "other_pkg" in r.stderr and "Traceback" not in r.stderr
    assert cli("audit", urdf, "--package-path", ws).stderr.count("other_pkg") < r.stderr.count("other_pkg")


def test_audit_without_a_package_resolves_only_package_path(tmp_path: Path) -> None:
    (tmp_path / "d").mkdir()
    _mesh(tmp_path / "d" / "other_pkg")  # a sibling folder of the URDF, no package.xml anywhere
    urdf = tmp_path / "d" / "r.urdf"
    urdf.write_text(URDF.format(pkg="other_pkg"))
    assert _states(urdf)["package://other_pkg/meshes/m.stl"] == "unresolved"


def test_a_package_path_entry_linked_out_is_not_followed(tmp_path: Path) -> None:
    ws = tmp_path / "ws"
    ws.mkdir()
    outside = tmp_path / "outside" / "other_pkg"
    _mesh(outside)
    (outside / "package.xml").write_text(PACKAGE_XML.format(name="other_pkg"))
    (ws / "other_pkg").symlink_to(outside)
    (tmp_path / "d").mkdir()
    urdf = tmp_path / "d" / "r.urdf"
    urdf.write_text(URDF.format(pkg="other_pkg"))
    assert _states(urdf, str(ws))["package://other_pkg/meshes/m.stl"] == "unresolved"
    assert _states(urdf, str(tmp_path / "outside"))["package://other_pkg/meshes/m.stl"] == "ok"


def test_a_package_xml_fifo_in_package_path_does_not_block(tmp_path: Path) -> None:
    from descgen.meshes.packages import find_package

    ws = tmp_path / "ws"
    (ws / "pkg").mkdir(parents=True)
    os.mkfifo(ws / "package.xml")
    os.mkfifo(ws / "pkg" / "package.xml")
    got: list[object] = []
    t = threading.Thread(target=lambda: got.append(find_package("other_pkg", [ws])), daemon=True)
    t.start()
    t.join(10)
    if t.is_alive():  # unblock the read so the thread ends, then fail
        fd = os.open(ws / "pkg" / "package.xml", os.O_WRONLY | os.O_NONBLOCK)
        os.close(fd)
        pytest.fail("find_package blocked reading a FIFO package.xml")
    assert got == [None]
