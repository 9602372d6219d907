"""Package names and meshes of other packages: ``package.name`` (REP 144), ``--package-path``
for validate/generate/check, and what import writes for both.

Oracles: lxml for package.xml and the URDF, ``ast`` for the launch files, REP 144's rules written
out here from https://ros.org/reps/rep-0144.html, trimesh for a mesh's inertia.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml
from lxml import etree

from tests.helpers import cli


def rep144(name: str) -> bool:
    """REP 144's mandatory rules, each as the REP states it."""
    return (
        len(name) >= 2
        and re.fullmatch(r"[a-z0-9_]+", name) is not None
        and name[0] in "abcdefghijklmnopqrstuvwxyz"
        and "__" not in name
    )


def _tetra(path: Path) -> trimesh.Trimesh:
    """A closed tetrahedron (10 cm legs), written as a binary STL."""
    mesh = trimesh.Trimesh(
        vertices=[[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]], faces=[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    )
    assert mesh.is_watertight and mesh.volume > 0
    path.parent.mkdir(parents=True, exist_ok=True)
    mesh.export(path)
    return mesh


def _vendor(root: Path, name: str = "vendor_meshes") -> Path:
    """A ROS package outside the project, holding one mesh."""
    pkg = root / name
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text(f'<?xml version="1.0"?><package format="3"><name>{name}</name></package>')
    _tetra(pkg / "meshes" / "part.stl")
    return pkg


SPEC = """name: {robot}
{package}links:
  - name: base_link
    visual:
      - geometry: {{mesh: {{filename: {mesh}}}}}
    inertial:
      mass: 2 kg
      inertia: {{ixx: 0.01 kg*m^2, iyy: 0.01 kg*m^2, izz: 0.01 kg*m^2}}
  - name: arm
    inertial:
      mass: 1 kg
      inertia: {{ixx: 0.01 kg*m^2, iyy: 0.01 kg*m^2, izz: 0.01 kg*m^2}}
joints:
  - name: shoulder
    type: revolute
    parent: base_link
    child: arm
    origin: {{xyz: [0 mm, 0 mm, 100 mm]}}
    axis: +z
    limit: {{lower: -90 deg, upper: 90 deg, effort: 10 N*m, velocity: 1 rad/s}}
"""


def _spec(folder: Path, robot: str, mesh: str, package: str = "") -> Path:
    path = folder / "specs" / "r.yaml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(SPEC.format(robot=robot, package=package, mesh=mesh))
    return path


# -- package.name ----------------------------------------------------------------------------------


def test_a_robot_named_2dof_x_generates_the_package_named_in_the_spec(tmp_path: Path) -> None:
    _tetra(tmp_path / "specs" / "meshes" / "base.stl")
    spec = _spec(tmp_path, "2dof_x", "meshes/base.stl", "package: {name: two_dof_x_description}\n")
    out = tmp_path / "out"
    ran = cli("generate", spec, "--out", out)
    assert ran.returncode == 0, ran.stderr
    pkg = out / "two_dof_x_description"
    assert [p.name for p in out.iterdir() if not p.name.startswith(".")] == ["two_dof_x_description"]
    assert etree.parse(str(pkg / "package.xml")).findtext("name") == "two_dof_x_description"
    assert "project(two_dof_x_description)" in (pkg / "CMakeLists.txt").read_text()
    shares = [
        node.args[0].value
        for node in ast.walk(ast.parse((pkg / "launch" / "display.launch.py").read_text()))
        if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "FindPackageShare"
    ]
    assert shares == ["two_dof_x_description"]
    urdf = etree.parse(str(pkg / "urdf" / "2dof_x.urdf")).getroot()
    assert urdf.get("name") == "2dof_x"  # the robot keeps its name; only the package is renamed
    assert [m.get("filename") for m in urdf.iter("mesh")] == ["package://two_dof_x_description/meshes/base.stl"]
    assert (pkg / "meshes" / "base.stl").read_bytes() == (tmp_path / "specs" / "meshes" / "base.stl").read_bytes()
    assert cli("check", spec, "--out", out).returncode == 0


def test_a_derived_name_that_is_no_package_name_fails_with_the_exact_fix(tmp_path: Path) -> None:
    _tetra(tmp_path / "specs" / "meshes" / "base.stl")
    spec = _spec(tmp_path, "2dof_x", "meshes/base.stl")
    ran = cli("validate", spec)
    assert ran.returncode == 2
    assert "Traceback" not in ran.stderr
    assert f"{spec}:1:7: error[SPEC120]" in ran.stderr  # at the robot's name
    fix = re.search(r"hint: add package: \{name: (\S+)\} to the spec", ran.stderr)
    assert fix is not None, ran.stderr
    assert rep144(fix.group(1))
    # doing exactly what the hint says makes the spec valid
    spec.write_text(spec.read_text().replace("links:", f"package: {{name: {fix.group(1)}}}\nlinks:", 1))
    assert cli("validate", spec).returncode == 0


@pytest.mark.parametrize("bad", ["Two_dof", "2dof_pkg", "two__dof", "two-dof", "x"])
def test_an_invalid_package_name_is_refused_at_its_line(tmp_path: Path, bad: str) -> None:
    assert not rep144(bad)
    _tetra(tmp_path / "specs" / "meshes" / "base.stl")
    spec = _spec(tmp_path, "arm", "meshes/base.stl", f"package:\n  name: {bad}\n")
    ran = cli("validate", spec)
    assert ran.returncode == 2 and "Traceback" not in ran.stderr
    assert f"{spec}:3:9: error[SPEC120]" in ran.stderr, ran.stderr
    suggested = re.search(r"hint: write e\.g\. name: (\S+)", ran.stderr)
    assert suggested is not None and rep144(suggested.group(1))


def test_an_uppercase_robot_name_still_validates_with_a_warning(tmp_path: Path) -> None:
    """Specs that validated before keep validating: catkin_pkg takes Arm_description (with a warning)."""
    _tetra(tmp_path / "specs" / "meshes" / "base.stl")
    spec = _spec(tmp_path, "Arm", "meshes/base.stl")
    ran = cli("validate", spec)
    assert ran.returncode == 0
    assert "warning[SPEC121]" in ran.stderr and "add package: {name: arm_description}" in ran.stderr


# -- --package-path ----------------------------------------------------------------------------------


def test_a_mesh_of_another_package_needs_package_path_and_is_referenced_not_copied(tmp_path: Path) -> None:
    vendor = tmp_path / "outside"
    _vendor(vendor)
    spec = _spec(tmp_path / "proj", "arm", "package://vendor_meshes/meshes/part.stl")
    without = cli("validate", spec)
    assert without.returncode == 2 and "error[SPEC062]" in without.stderr
    assert "--package-path" in without.stderr  # the hint names the way out
    assert cli("validate", spec, "--package-path", vendor).returncode == 0
    out = tmp_path / "out"
    ran = cli("generate", spec, "--out", out, "--package-path", vendor)
    assert ran.returncode == 0, ran.stderr
    pkg = out / "arm_description"
    urdf = etree.parse(str(pkg / "urdf" / "arm.urdf")).getroot()
    assert [m.get("filename") for m in urdf.iter("mesh")] == ["package://vendor_meshes/meshes/part.stl"]
    depends = [e.text for e in etree.parse(str(pkg / "package.xml")).iter("exec_depend")]
    assert "vendor_meshes" in depends
    assert not (pkg / "meshes").exists()  # another package's file is not copied
    assert cli("check", spec, "--out", out, "--package-path", vendor).returncode == 0
    # check without the flag cannot find the mesh: input error, not a stale package
    assert cli("check", spec, "--out", out).returncode == 2


def test_inertia_from_a_mesh_of_another_package_uses_the_resolved_file(tmp_path: Path) -> None:
    vendor = tmp_path / "outside"
    mesh = _vendor(vendor) / "meshes" / "part.stl"
    spec = _spec(tmp_path / "proj", "arm", "package://vendor_meshes/meshes/part.stl")
    # the base link's inertia comes from its mesh (mass only)
    text = spec.read_text().replace(
        "      mass: 2 kg\n      inertia: {ixx: 0.01 kg*m^2, iyy: 0.01 kg*m^2, izz: 0.01 kg*m^2}",
        "      mass: 2 kg\n      from: visual",
        1,
    )
    spec.write_text(text)
    out = tmp_path / "out"
    ran = cli("generate", spec, "--out", out, "--package-path", vendor)
    assert ran.returncode == 0, ran.stderr
    urdf = etree.parse(str(out / "arm_description" / "urdf" / "arm.urdf")).getroot()
    inertia = urdf.find("link[@name='base_link']/inertial/inertia")
    assert inertia is not None
    tm = trimesh.load(mesh)
    tm.density = 2.0 / tm.volume
    expected = tm.moment_inertia  # about the centre of mass, in the mesh's axes
    got = np.array(
        [
            [float(inertia.get("ixx")), float(inertia.get("ixy")), float(inertia.get("ixz"))],
            [float(inertia.get("ixy")), float(inertia.get("iyy")), float(inertia.get("iyz"))],
            [float(inertia.get("ixz")), float(inertia.get("iyz")), float(inertia.get("izz"))],
        ]
    )
    assert np.allclose(got, expected, rtol=1e-9, atol=1e-15)


@pytest.mark.parametrize("how", ["dotdot", "link", "link to a sibling sharing the name's prefix"])
def test_a_package_uri_cannot_leave_its_package(tmp_path: Path, how: str) -> None:
    vendor = tmp_path / "outside"
    pkg = _vendor(vendor)
    secret = vendor / "secret.stl"  # inside the --package-path folder, but outside the package
    if how.endswith("prefix"):  # <pkg>_evil/ starts with <pkg>'s path, and is not inside it
        secret = pkg.parent / f"{pkg.name}_evil" / "secret.stl"
        secret.parent.mkdir()
    _tetra(secret)
    if how == "dotdot":
        name = "package://vendor_meshes/../secret.stl"
    else:
        (pkg / "meshes" / "leak.stl").symlink_to(secret)
        name = "package://vendor_meshes/meshes/leak.stl"
    spec = _spec(tmp_path / "proj", "arm", name)
    ran = cli("validate", spec, "--package-path", vendor)
    assert ran.returncode == 2 and "error[SPEC061]" in ran.stderr, ran.stderr
    assert cli("generate", spec, "--out", tmp_path / "out", "--package-path", vendor).returncode == 2
    assert not (tmp_path / "out" / "arm_description").exists()


# -- import --------------------------------------------------------------------------------------------

URDF = """<?xml version="1.0"?>
<robot name="{robot}">
  <link name="base_link">
    <visual><geometry><mesh filename="package://{pkg}/meshes/part.stl"/></geometry></visual>
    <inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
</robot>
"""


@pytest.mark.parametrize(
    ("robot", "mesh_pkg", "expected"),
    [
        ("2dof_x", "vendor_meshes", "robot_2dof_x_description"),  # no REP 144 name
        ("acme", "acme_description", "acme_descgen_description"),  # the meshes' own package (UR's case)
        ("acme", "vendor_meshes", None),  # acme_description is right: nothing written
    ],
)
def test_import_names_the_package_when_the_derived_name_cannot_be_it(
    tmp_path: Path, robot: str, mesh_pkg: str, expected: str | None
) -> None:
    vendor = tmp_path / "outside"
    _vendor(vendor, mesh_pkg)
    src = tmp_path / "robot.urdf"
    src.write_text(URDF.format(robot=robot, pkg=mesh_pkg))
    spec = tmp_path / "proj" / "specs" / "r.yaml"
    ran = cli("import", src, "-o", spec, "--package-path", vendor)
    assert ran.returncode == 0, ran.stderr
    data = yaml.safe_load(spec.read_text())
    assert data["name"] == robot
    assert (data.get("package") or {}).get("name") == expected
    assert ("info[IMP014]" in ran.stderr) == (expected is not None)
    out = tmp_path / "out"
    assert cli("generate", spec, "--out", out, "--package-path", vendor).returncode == 0
    name = expected or f"{robot}_description"
    assert rep144(name)
    xml = etree.parse(str(out / name / "package.xml"))
    assert xml.findtext("name") == name
    assert mesh_pkg in [e.text for e in xml.iter("exec_depend")]
    assert cli("check", spec, "--out", out, "--package-path", vendor).returncode == 0
