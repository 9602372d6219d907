"""Meshes resolved, copied and installed (issue 13, "Resolve and install").

A small arm whose meshes are made here with trimesh (a box STL, a cylinder OBJ, and a gripper
package's STL) is generated; yourdfpy, lxml and the bytes of the files are the oracles.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yourdfpy
from lxml import etree

from .helpers import cli, line_of

PKG = "mini_arm_description"
BOX = (0.2, 0.16, 0.1)  # m: the base mesh, written in metres
CYL_R, CYL_H = 25.0, 300.0  # mm: the arm mesh, written in millimetres (the spec scales it by 0.001)

SPEC = """\
name: mini_arm
package_paths: [../vendor]
links:
  - name: base_link
    visual:
      - geometry: {mesh: {filename: meshes/base.stl}}
    collision:
      - geometry: {mesh: {filename: meshes/base.stl}}
    inertial: {mass: 2 kg, inertia: {ixx: 0.01 kg*m^2, iyy: 0.01 kg*m^2, izz: 0.01 kg*m^2}}
  - name: arm_link
    visual:
      - geometry: {mesh: {filename: cad/arm.obj, scale: [0.001, 0.001, 0.001]}}
    collision:
      - geometry: {mesh: {filename: cad/arm.obj, scale: [0.001, 0.001, 0.001]}}
    inertial: {mass: 1 kg, inertia: {ixx: 0.01 kg*m^2, iyy: 0.01 kg*m^2, izz: 0.001 kg*m^2}}
  - name: tool_link
    visual:
      - geometry: {mesh: {filename: "package://gripper_pkg/meshes/finger.stl"}}
    inertial: {mass: 0.2 kg, inertia: {ixx: 0.001 kg*m^2, iyy: 0.001 kg*m^2, izz: 0.001 kg*m^2}}
joints:
  - name: j1
    type: revolute
    parent: base_link
    child: arm_link
    origin: {xyz: [0, 0, 100 mm]}
    axis: +z
    limit: {lower: -90 deg, upper: 90 deg, effort: 10 N*m, velocity: 1 rad/s}
  - {name: j2, type: fixed, parent: arm_link, child: tool_link, origin: {xyz: [0, 0, 300 mm]}}
"""


def make_project(root: Path, spec: str = SPEC) -> Path:
    """specs/arm.yaml with its meshes beside it, and vendor/gripper_pkg (a ROS package)."""
    (root / "specs" / "meshes").mkdir(parents=True)
    (root / "specs" / "cad").mkdir()
    trimesh.creation.box(BOX).export(root / "specs" / "meshes" / "base.stl")
    trimesh.creation.cylinder(radius=CYL_R, height=CYL_H, sections=32).export(root / "specs" / "cad" / "arm.obj")
    gripper = root / "vendor" / "gripper_pkg"
    (gripper / "meshes").mkdir(parents=True)
    (gripper / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>gripper_pkg</name><version>0.1.0</version>'
        '<description>g</description><maintainer email="a@example.com">a</maintainer><license>MIT</license></package>\n'
    )
    trimesh.creation.box((0.02, 0.02, 0.05)).export(gripper / "meshes" / "finger.stl")
    path = root / "specs" / "arm.yaml"
    path.write_text(spec)
    return path


def generate(root: Path, *more: str) -> tuple[int, str]:
    r = cli("generate", "specs/arm.yaml", *more, cwd=root)
    return r.returncode, r.stdout + r.stderr


def check(root: Path) -> tuple[int, list[dict[str, str]], str]:
    r = cli("check", "specs/arm.yaml", cwd=root)
    return r.returncode, _findings(r.stderr), r.stdout + r.stderr


def _findings(text: str) -> list[dict[str, str]]:
    """Error lines as printed: FILE:LINE:COL: error[CODE]: message (a refused spec's warnings and
    infos are printed beside its errors; these tests are about the errors)."""
    out = []
    for line in text.splitlines():
        if ": error[" in line and "]: " in line and not line.startswith(" "):
            head, _, msg = line.partition("]: ")
            where_severity, _, code = head.rpartition("[")
            out.append({"where": where_severity.rsplit(": ", 1)[0], "code": code, "msg": msg})
    return out


def sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One generated project for the read-only tests."""
    root = tmp_path_factory.mktemp("arm")
    make_project(root)
    code, out = generate(root)
    assert code == 0, out
    return root


# --------------------------------------------------------------------------- the package


def test_yourdfpy_finds_every_mesh_in_the_installed_layout(built: Path) -> None:
    """package:// resolved as an install does: <share>/<pkg>/..., here the generated folder."""
    shares = {PKG: built / "generated" / PKG, "gripper_pkg": built / "vendor" / "gripper_pkg"}
    asked: list[str] = []

    def handler(fname: str) -> str:
        asked.append(fname)
        pkg, _, rest = fname.removeprefix("package://").partition("/")
        return str(shares[pkg] / rest)

    urdf = yourdfpy.URDF.load(
        str(built / "generated" / PKG / "urdf" / "mini_arm.urdf"),
        filename_handler=handler,
        load_meshes=True,
        load_collision_meshes=True,
        build_collision_scene_graph=True,
    )
    # 3 visuals and 2 collisions, each a file that exists and loaded
    assert len(asked) == 5
    assert all(Path(handler(n)).is_file() for n in list(asked))
    assert len(urdf.scene.geometry) == 3 and len(urdf.collision_scene.geometry) == 2
    # the base box is the base box (hand: its size), the arm cylinder scaled from mm to m
    extents = sorted(tuple(np.round(g.extents, 6)) for g in urdf.scene.geometry.values())
    assert (0.2, 0.16, 0.1) in extents
    arm = [e for e in extents if e[2] == pytest.approx(CYL_H / 1000)]
    assert arm and arm[0][0] == pytest.approx(2 * CYL_R / 1000, rel=1e-3)


def test_own_meshes_are_copied_byte_identical_and_others_stay_references(built: Path) -> None:
    pkg = built / "generated" / PKG
    assert (pkg / "meshes" / "base.stl").read_bytes() == (built / "specs" / "meshes" / "base.stl").read_bytes()
    assert (pkg / "meshes" / "cad" / "arm.obj").read_bytes() == (built / "specs" / "cad" / "arm.obj").read_bytes()
    assert not list(pkg.rglob("finger.stl"))  # another package's mesh is not copied
    urdf = etree.parse(str(pkg / "urdf" / "mini_arm.urdf"))
    names = sorted({m.get("filename") for m in urdf.iter("mesh")})
    assert names == sorted(
        [
            f"package://{PKG}/meshes/base.stl",
            f"package://{PKG}/meshes/cad/arm.obj",
            "package://gripper_pkg/meshes/finger.stl",
        ]
    )
    # the manifest: what sha256sum -c would check from the package folder
    lines = [ln for ln in (pkg / "meshes" / "meshes.sha256").read_text().splitlines() if not ln.startswith("#")]
    assert lines == [
        f"{sha(pkg / 'meshes' / 'base.stl')}  meshes/base.stl",
        f"{sha(pkg / 'meshes' / 'cad' / 'arm.obj')}  meshes/cad/arm.obj",
    ]


def test_cmake_installs_every_folder_and_package_xml_depends_on_the_mesh_package(built: Path) -> None:
    pkg = built / "generated" / PKG
    cmake = (pkg / "CMakeLists.txt").read_text()
    installed = cmake.split("DIRECTORY", 1)[1].split("DESTINATION", 1)[0].split()
    # every folder but evidence/, which is for reviewers of the source tree, not for the robot
    folders = sorted(p.name for p in pkg.iterdir() if p.is_dir() and p.name != "evidence")
    assert installed == folders and "meshes" in installed and (pkg / "evidence").is_dir()
    # no ros2_control, no SRDF: no config/ or srdf/ to install (CMake would fail on a missing folder)
    assert "config" not in installed and "srdf" not in installed
    deps = [e.text for e in etree.parse(str(pkg / "package.xml")).iter("exec_depend")]
    assert "gripper_pkg" in deps and PKG not in deps


def test_check_passes_on_the_fresh_package(built: Path) -> None:
    code, _, out = check(built)
    assert code == 0, out


def test_audit_of_the_generated_urdf_and_of_the_spec_agree_no_mesh_is_missing(built: Path) -> None:
    urdf = built / "generated" / PKG / "urdf" / "mini_arm.urdf"
    paths = ("--package-path", str(built / "generated"), "--package-path", str(built / "vendor"))
    for target in (str(urdf), str(built / "specs" / "arm.yaml")):
        r = cli("audit", target, *paths, "--format", "json", cwd=built)
        codes = [f["code"] for f in json.loads(r.stdout)["findings"]]
        assert r.returncode == 0, r.stdout
        assert not {"GEOM003", "GEOM004", "GEOM005"} & set(codes), (target, codes)
    # the control: without the vendor folder the gripper's mesh is not found
    r = cli("audit", str(urdf), "--package-path", str(built / "generated"), "--format", "json", cwd=built)
    unresolved = [f for f in json.loads(r.stdout)["findings"] if f["code"] == "GEOM005"]
    assert [f["message"].split("'")[3] for f in unresolved] == ["package://gripper_pkg/meshes/finger.stl"]


# --------------------------------------------------------------------------- staleness


def test_check_flags_a_source_mesh_edited_after_generation(tmp_path: Path) -> None:
    make_project(tmp_path)
    assert generate(tmp_path)[0] == 0
    trimesh.creation.box((0.2, 0.16, 0.12)).export(tmp_path / "specs" / "meshes" / "base.stl")
    code, found, out = check(tmp_path)
    assert code == 1, out
    got = {(f["code"], f["where"].rsplit("/", 2)[-2] + "/" + f["where"].rsplit("/", 1)[-1]) for f in found}
    assert ("GEN060", "meshes/base.stl") in got  # the copy differs from its source
    assert ("GEN005", "meshes/meshes.sha256") in got  # the recorded hash is stale too
    assert not any("arm.obj" in f["where"] for f in found)
    assert generate(tmp_path)[0] == 0  # the source changed, the copy was not edited: overwritten
    assert check(tmp_path)[0] == 0


def test_a_copy_edited_in_the_package_is_stale_and_not_overwritten(tmp_path: Path) -> None:
    make_project(tmp_path)
    assert generate(tmp_path)[0] == 0
    copy = tmp_path / "generated" / PKG / "meshes" / "cad" / "arm.obj"
    copy.write_bytes(copy.read_bytes() + b"v 0 0 0\n")
    edited = copy.read_bytes()
    code, found, out = check(tmp_path)
    assert code == 1 and [f["code"] for f in found if f["code"].startswith("GEN")] == ["GEN060"], out
    code, out = generate(tmp_path)
    assert code == 1 and "error[GEN004]: meshes/cad/arm.obj was edited by hand" in out
    assert copy.read_bytes() == edited
    assert generate(tmp_path, "--force")[0] == 0
    assert copy.read_bytes() == (tmp_path / "specs" / "cad" / "arm.obj").read_bytes()


def test_a_missing_copy_is_reported_and_a_mesh_no_longer_used_is_removed(tmp_path: Path) -> None:
    make_project(tmp_path)
    assert generate(tmp_path)[0] == 0
    pkg = tmp_path / "generated" / PKG
    (pkg / "meshes" / "base.stl").unlink()
    code, found, out = check(tmp_path)
    assert code == 1 and ("GEN006", str(pkg / "meshes" / "base.stl")) in {(f["code"], f["where"]) for f in found}
    assert generate(tmp_path)[0] == 0
    # the arm now uses a primitive: its copy is no longer generated, so check reports it and generate drops it
    spec = tmp_path / "specs" / "arm.yaml"
    spec.write_text(
        SPEC.replace(
            "      - geometry: {mesh: {filename: cad/arm.obj, scale: [0.001, 0.001, 0.001]}}\n",
            "      - geometry: {cylinder: {diameter: 50 mm, length: 300 mm}}\n",
        )
    )
    code, found, out = check(tmp_path)
    assert ("GEN007", str(pkg / "meshes" / "cad" / "arm.obj")) in {(f["code"], f["where"]) for f in found}, out
    assert generate(tmp_path)[0] == 0
    assert not (pkg / "meshes" / "cad" / "arm.obj").exists() and (pkg / "meshes" / "base.stl").is_file()
    assert check(tmp_path)[0] == 0


# --------------------------------------------------------------------------- input errors


def _validate(tmp_path: Path, spec: str) -> tuple[int, list[dict[str, str]]]:
    make_project(tmp_path, spec)
    r = cli("validate", "specs/arm.yaml", cwd=tmp_path)
    assert "Traceback" not in r.stderr
    return r.returncode, _findings(r.stderr)


def _at(spec: str, needle: str) -> str:
    return f"specs/arm.yaml:{line_of(spec, needle)}"


def test_a_missing_mesh_is_a_validate_error_at_its_reference(tmp_path: Path) -> None:
    spec = SPEC.replace("filename: cad/arm.obj, scale", "filename: cad/gone.obj, scale", 1)
    code, found = _validate(tmp_path, spec)
    assert code == 2
    assert [(f["code"], f["where"].rpartition(":")[0]) for f in found] == [("SPEC060", _at(spec, "cad/gone.obj"))]
    assert "'cad/gone.obj' does not exist" in found[0]["msg"]
    r = cli("generate", "specs/arm.yaml", cwd=tmp_path)  # nothing written
    assert r.returncode == 2 and not (tmp_path / "generated").exists()


@pytest.mark.parametrize(
    "name",
    [
        "../../../../../../etc/passwd",
        "/etc/passwd",
        "file:///etc/passwd",
        "meshes/../../vendor/gripper_pkg/meshes/finger.stl",  # exists, but outside the spec's folder
        "package://gripper_pkg/../../../../../../etc/passwd",
        "linked/passwd",  # a link inside the spec's folder that leads out
    ],
)
def test_a_mesh_path_that_escapes_is_refused(tmp_path: Path, name: str) -> None:
    spec = SPEC.replace("filename: meshes/base.stl}}\n    collision", f'filename: "{name}"}}}}\n    collision', 1)
    assert name in spec
    make_project(tmp_path, spec)
    (tmp_path / "specs" / "linked").mkdir()
    os.symlink("/etc/passwd", tmp_path / "specs" / "linked" / "passwd")
    r = cli("validate", "specs/arm.yaml", cwd=tmp_path)
    found = _findings(r.stderr)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert [(f["code"], f["where"].rpartition(":")[0]) for f in found] == [("SPEC061", _at(spec, name))]


def test_unknown_package_own_package_and_fifo_are_refused(tmp_path: Path) -> None:
    spec = (
        SPEC.replace("package://gripper_pkg/", "package://no_such_pkg/")
        .replace(
            "filename: meshes/base.stl}}\n    collision",
            f"filename: package://{PKG}/meshes/base.stl}}}}\n    collision",
        )
        .replace("cad/arm.obj, scale", "cad/pipe.obj, scale", 1)
    )
    make_project(tmp_path, spec)
    os.mkfifo(tmp_path / "specs" / "cad" / "pipe.obj")  # a read would block: refused by stat, never opened
    r = cli("validate", "specs/arm.yaml", cwd=tmp_path, timeout=30)
    found = _findings(r.stderr)
    assert r.returncode == 2
    assert sorted((f["code"], f["where"].rpartition(":")[0]) for f in found) == sorted(
        [
            ("SPEC062", _at(spec, f"package://{PKG}/meshes/base.stl")),
            ("SPEC063", _at(spec, "cad/pipe.obj")),
            ("SPEC062", _at(spec, "package://no_such_pkg/")),
        ]
    )


def test_recorded_templates_stay_in_the_project_and_folders_are_relative(tmp_path: Path) -> None:
    spec = SPEC.replace("package_paths: [../vendor]", "package_paths: [../vendor, ../../outside, /usr/share]")
    spec = spec.replace("name: mini_arm\n", "name: mini_arm\ntemplates: ../../tpl\n")
    (tmp_path / "x").mkdir()
    (tmp_path / "outside").mkdir()  # a real folder outside the project x/: a workspace may lie there
    (tmp_path / "tpl").mkdir()
    code, found = _validate(tmp_path / "x", spec)
    assert code == 2

    def at(needle: str) -> str:
        line = spec.splitlines()[line_of(spec, needle) - 1]
        return f"specs/arm.yaml:{line_of(spec, needle)}:{line.index(needle) + 1}"

    # templates render the package (code): they stay in the project; an absolute folder is this
    # machine's only; a package folder outside the project is fine (only packages are read there)
    assert sorted((f["code"], f["where"]) for f in found) == sorted(
        [("SPEC064", at("/usr/share")), ("SPEC064", at("../../tpl"))]
    )


def test_a_workspace_outside_the_project_is_searched_for_packages_only(tmp_path: Path) -> None:
    # the gripper package lives in a colcon workspace beside the project: ws/src/<repo>/<pkg>
    project = tmp_path / "project"
    make_project(project, SPEC.replace("package_paths: [../vendor]", "package_paths: [../../ws/src]"))
    repo = tmp_path / "ws" / "src" / "grippers"
    repo.mkdir(parents=True)
    (project / "vendor" / "gripper_pkg").rename(repo / "gripper_pkg")
    r = cli("validate", "specs/arm.yaml", cwd=project)
    assert r.returncode == 0, r.stderr
    code, out = generate(project)
    assert code == 0, out
    xml = (project / "generated" / PKG / "package.xml").read_text()
    assert "<exec_depend>gripper_pkg</exec_depend>" in xml
    # a spec is someone else's data: a folder up to / finds packages, never /etc as package "etc"
    hostile = SPEC.replace("package_paths: [../vendor]", "package_paths: [" + "../" * 40 + "]").replace(
        "package://gripper_pkg/meshes/finger.stl", "package://etc/passwd"
    )
    (project / "specs" / "arm.yaml").write_text(hostile)
    r = cli("validate", "specs/arm.yaml", cwd=project)
    assert r.returncode == 2
    assert [f["code"] for f in _findings(r.stderr)] == ["SPEC062"], r.stderr


def test_two_files_copied_to_one_place_are_refused(tmp_path: Path) -> None:
    # meshes/base.stl and base.stl would both be the package's meshes/base.stl
    spec = SPEC.replace(
        "      - geometry: {mesh: {filename: meshes/base.stl}}\n    inertial",
        "      - geometry: {mesh: {filename: base.stl}}\n    inertial",
    )
    make_project(tmp_path, spec)
    trimesh.creation.box((0.1, 0.1, 0.1)).export(tmp_path / "specs" / "base.stl")
    r = cli("validate", "specs/arm.yaml", cwd=tmp_path)
    assert r.returncode == 2
    assert [f["code"] for f in _findings(r.stderr)] == ["SPEC065"]


# --------------------------------------------------------------------------- recorded templates


def test_recorded_templates_make_generate_and_check_agree(tmp_path: Path) -> None:
    make_project(tmp_path, SPEC.replace("name: mini_arm\n", "name: mini_arm\ntemplates: ../tpl\n"))
    (tmp_path / "tpl").mkdir()
    default = Path(__file__).resolve().parents[1] / "descgen" / "templates" / "CMakeLists.txt.j2"
    (tmp_path / "tpl" / "CMakeLists.txt.j2").write_text(default.read_text() + "# team override\n")
    assert generate(tmp_path)[0] == 0
    assert (tmp_path / "generated" / PKG / "CMakeLists.txt").read_text().endswith("# team override\n")
    assert check(tmp_path)[0] == 0  # no --templates needed: the spec says which


def test_recorded_templates_render_in_the_sandbox(tmp_path: Path) -> None:
    """A template named by a spec is someone else's code: no walk from a value to Python."""
    make_project(tmp_path, SPEC.replace("name: mini_arm\n", "name: mini_arm\ntemplates: ../tpl\n"))
    (tmp_path / "tpl").mkdir()
    payload = "{{ ''.__class__.__mro__[1].__subclasses__() }}\n"
    (tmp_path / "tpl" / "CMakeLists.txt.j2").write_text(payload)
    code, out = generate(tmp_path)
    assert code == 2 and "error[GEN061]" in out and "sandbox" in out and "Traceback" not in out
    assert "subprocess" not in out and not (tmp_path / "generated").exists()
    # the same file named with --templates is the user's own code: jinja2 runs it (the control)
    code, out = generate(tmp_path, "--templates", str(tmp_path / "tpl"))
    assert "<class 'subprocess.Popen'>" in (tmp_path / "generated" / PKG / "CMakeLists.txt").read_text()
