"""Meshes measured (descgen/meshes/load.py), mesh inertia (descgen/physics/inertia.py) and the mesh rules
(GEOM030-GEOM033) on meshes the tests make with trimesh and on example-robot-data's own."""

from __future__ import annotations

import math
import struct
from pathlib import Path

import numpy as np
import pytest
import trimesh
from lxml import etree

from descgen.audit.spec import load_spec
from descgen.meshes import load as meshes
from descgen.read.description import Options, audit

from .corpus import share
from .helpers import cli


def _ascii_stl(mesh: trimesh.Trimesh, path: Path) -> Path:
    # ASCII STL keeps the vertices as written (binary STL rounds them to float32)
    path.write_text(trimesh.exchange.stl.export_stl_ascii(mesh))
    return path


def _spec(tmp_path: Path, collision: str, mass: str = "6 kg") -> Path:
    spec = tmp_path / "arm.yaml"
    spec.write_text(
        f"""name: arm
links:
  - name: base_link
  - name: arm_link
    collision:
      - {collision}
    inertial: {{mass: {mass}, from: collision}}
joints:
  - name: shoulder
    type: revolute
    parent: base_link
    child: arm_link
    axis: +z
    limit: {{lower: -1 rad, upper: 1 rad, velocity: 1 rad/s, effort: 10 N*m}}
"""
    )
    return spec


def _inertial(spec: Path) -> tuple[tuple[float, float, float], np.ndarray]:
    link = next(lk for lk in load_spec(spec).robot.links if lk.name == "arm_link")
    assert link.inertial is not None and link.inertial.inertia is not None
    return link.inertial.origin.xyz, np.array(link.inertial.inertia.matrix())


# -- mesh inertia ---------------------------------------------------------------------------


def test_box_mesh_inertia_is_the_box_formula(tmp_path: Path) -> None:
    box = trimesh.creation.box([0.1, 0.2, 0.3])
    box.apply_translation([0.01, 0.02, 0.15])  # off the mesh origin: the centre of mass must follow
    _ascii_stl(box, tmp_path / "box.stl")
    com, tensor = _inertial(_spec(tmp_path, "geometry: {mesh: {filename: box.stl}}"))
    m, (a, b, c) = 6.0, (0.1, 0.2, 0.3)
    expected = np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12])
    np.testing.assert_allclose(tensor, expected, rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(com, (0.01, 0.02, 0.15), rtol=1e-9, atol=1e-12)


def test_box_mesh_inertia_follows_the_collision_origin_and_scale(tmp_path: Path) -> None:
    # the same box written in millimetres, scaled to metres and turned 90 deg about z:
    # x and y swap, so Ixx takes the formula of the 0.2 m side; the centre moves to the origin
    box = trimesh.creation.box([100, 200, 300])
    _ascii_stl(box, tmp_path / "box_mm.stl")
    collision = (
        "{origin: {xyz: [0, 0, 500 mm], rpy: [0, 0, 90 deg]}, "
        "geometry: {mesh: {filename: box_mm.stl, scale: [0.001, 0.001, 0.001]}}}"
    )
    com, tensor = _inertial(_spec(tmp_path, collision))
    m, (a, b, c) = 6.0, (0.1, 0.2, 0.3)
    expected = np.diag([m * (a * a + c * c) / 12, m * (b * b + c * c) / 12, m * (a * a + b * b) / 12])
    np.testing.assert_allclose(tensor, expected, rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(com, (0.0, 0.0, 0.5), atol=1e-9)


def test_cylinder_mesh_inertia(tmp_path: Path) -> None:
    r, h, n, m = 0.05, 0.3, 512, 2.0
    cyl = trimesh.creation.cylinder(radius=r, height=h, sections=n)
    _ascii_stl(cyl, tmp_path / "cyl.stl")
    _, tensor = _inertial(_spec(tmp_path, "geometry: {mesh: {filename: cyl.stl}}", mass=f"{m} kg"))
    # The mesh is a prism over a regular n-gon of circumradius r. Its polar moment of area
    # is J = n r^4 sin(2pi/n) (2 + cos(2pi/n)) / 12 over the area A = n r^2 sin(2pi/n) / 2, so
    # Izz = m r^2 (2 + cos(2pi/n)) / 6 and Ixx = Iyy = Izz / 2 + m h^2 / 12, exactly (by hand):
    k = 2 + math.cos(2 * math.pi / n)
    prism = np.diag([m * r * r * k / 12 + m * h * h / 12] * 2 + [m * r * r * k / 6])
    np.testing.assert_allclose(tensor, prism, rtol=1e-6, atol=1e-12)
    # ... and the round cylinder's formula within the tessellation error: k/3 = 1 - 1e-4 at
    # n = 512 ((1 - cos x)/3 with x = 2pi/512), so 2e-5 relative is out of reach of it only
    # if the integration is wrong, not the facets
    round_ = np.diag([m * (3 * r * r + h * h) / 12] * 2 + [m * r * r / 2])
    np.testing.assert_allclose(tensor, round_, rtol=5e-5, atol=1e-12)
    # and trimesh's own mass properties (an independent implementation) at the same mass
    oracle = cyl.moment_inertia * (m / cyl.volume)
    np.testing.assert_allclose(tensor, oracle, rtol=1e-6, atol=1e-12)


def test_open_mesh_inertia_is_refused_with_the_reason(tmp_path: Path) -> None:
    box = trimesh.creation.box([0.1, 0.2, 0.3])
    # one face of the box is two triangles sharing a diagonal: removing both leaves the
    # square's 4 sides as edges of one triangle each (by hand: 4 open edges)
    normals = box.face_normals
    keep = ~np.isclose(normals[:, 2], 1.0)
    assert keep.sum() == 10
    open_box = trimesh.Trimesh(box.vertices, box.faces[keep], process=False)
    _ascii_stl(open_box, tmp_path / "open.stl")
    spec = _spec(tmp_path, "geometry: {mesh: {filename: open.stl}}")
    ran = cli("validate", spec)
    assert ran.returncode == 2 and "Traceback" not in ran.stderr
    line = next(x for x in ran.stderr.splitlines() if "INER030" in x)
    assert line.startswith(f"{spec}:7:34:")  # the value of `from:` (line 7, after "    inertial: {mass: 6 kg, from: ")
    assert "open.stl" in line and "not watertight" in line and "4 open edges" in line


def test_unreadable_mesh_inertia_is_an_input_error(tmp_path: Path) -> None:
    (tmp_path / "junk.stl").write_text("solid junk\n not a facet\nendsolid junk\n")
    spec = _spec(tmp_path, "geometry: {mesh: {filename: junk.stl}}")
    ran = cli("validate", spec)
    assert ran.returncode == 2 and "Traceback" not in ran.stderr
    assert "INER031" in ran.stderr and "junk.stl" in ran.stderr


# -- reading meshes, bounded ----------------------------------------------------------------


def test_measure_box_in_file_units(tmp_path: Path) -> None:
    box = trimesh.creation.box([100, 200, 300])
    path = _ascii_stl(box, tmp_path / "box.stl")
    facts = meshes.measure(path)
    assert facts.problem is None
    np.testing.assert_allclose(facts.lower or (), (-50, -100, -150))
    np.testing.assert_allclose(facts.upper or (), (50, 100, 150))
    loaded = meshes.load(path)  # what only the built mesh tells, for the spec's mesh inertia
    assert loaded.watertight and len(loaded.faces) == 12 and loaded.open_edges == 0
    assert loaded.volume == pytest.approx(100 * 200 * 300, rel=1e-12)
    assert meshes.size_in_metres(facts, (0.001, 0.001, 0.001)) == pytest.approx((0.1, 0.2, 0.3), rel=1e-12)


def test_collada_unit_scales_the_size(tmp_path: Path) -> None:
    box = trimesh.creation.box([100, 200, 300])
    dae = trimesh.exchange.dae.export_collada(box).decode()
    assert "<unit" not in dae  # trimesh writes none (docs/reference/viewer_and_meshes.md)
    dae = dae.replace("<asset>", '<asset><unit meter="0.001" name="millimeter"/>', 1)
    path = tmp_path / "box.dae"
    path.write_text(dae)
    facts = meshes.measure(path)
    assert facts.problem is None and facts.unit_meter == 0.001
    # RViz and Gazebo apply <unit meter>: the part is 0.1 x 0.2 x 0.3 m at scale 1
    assert meshes.size_in_metres(facts, (1, 1, 1)) == pytest.approx((0.1, 0.2, 0.3), rel=1e-9)


def test_collada_with_a_dtd_is_refused_before_parsing(tmp_path: Path) -> None:
    box = trimesh.creation.box([1, 1, 1])
    dae = trimesh.exchange.dae.export_collada(box).decode()
    hostile = dae.replace("<COLLADA", '<!DOCTYPE c [<!ENTITY x SYSTEM "file:///etc/hostname">]>\n<COLLADA', 1)
    path = tmp_path / "dtd.dae"
    path.write_text(hostile)
    with pytest.raises(meshes.MeshError, match="DTD"):
        meshes.load(path)


def test_binary_stl_with_an_absurd_triangle_count_is_refused_from_its_header(tmp_path: Path) -> None:
    path = tmp_path / "huge.stl"
    path.write_bytes(b"\0" * 80 + struct.pack("<I", 3_000_000_000) + b"\0" * 50)
    with pytest.raises(meshes.MeshError, match="3000000000 triangles"):
        meshes.load(path)


@pytest.mark.parametrize(("name", "data"), [("x.ply", b"ply\n"), ("x.stl", b""), ("x.obj", b"v 1 2\nf 1 2 9\n")])
def test_unusable_files_give_a_problem_not_a_traceback(tmp_path: Path, name: str, data: bytes) -> None:
    path = tmp_path / name
    path.write_bytes(data)
    facts = meshes.measure(path)
    assert facts.problem and "\n" not in facts.problem


def test_same_bytes_are_parsed_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """With a cache folder the bytes are hashed (the entry's name), so two files of the same
    content are one measurement; with caching off only the stat data names a file (hashing
    the corpus's meshes costs more than measuring its few copies twice)."""
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(tmp_path / "cache"))
    calls: list[str] = []
    real = meshes._parse

    def counting(data: bytes, kind: str) -> meshes.Loaded:
        calls.append(kind)
        return real(data, kind)

    monkeypatch.setattr(meshes, "_parse", counting)
    box = trimesh.creation.box([0.123, 0.456, 0.789])  # sizes no other test uses: not cached yet
    a = _ascii_stl(box, tmp_path / "a.stl")
    b = _ascii_stl(box, tmp_path / "b.stl")
    assert meshes.measure(a) == meshes.measure(b) == meshes.measure(a)
    assert calls == ["stl"]
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")
    c = _ascii_stl(trimesh.creation.box([0.321, 0.654, 0.987]), tmp_path / "c.stl")
    assert meshes.measure(c) == meshes.measure(c)
    assert calls == ["stl", "stl"]  # one file, unchanged: measured once


# -- the audit on example-robot-data: one mesh exported in millimetres --------------------------


def test_audit_names_the_link_and_file_of_a_mesh_1000_times_too_large(tmp_path: Path) -> None:
    root = share()
    if root is None:
        pytest.skip("example-robot-data is not installed")
    urdf = root / "example-robot-data" / "robots" / "ur_description" / "urdf" / "ur5_robot.urdf"
    tree = etree.parse(str(urdf))
    mesh = tree.xpath("//link/collision//mesh[contains(@filename, 'forearm.stl')]")[0]
    link = mesh.xpath("ancestor::link")[0].get("name")
    original = root / mesh.get("filename")[len("package://") :]
    scaled = trimesh.load(original, force="mesh")
    scaled.apply_scale(1000.0)  # what a CAD export in millimetres holds
    scaled.export(tmp_path / "forearm_mm.stl")
    mesh.set("filename", "forearm_mm.stl")
    copy = tmp_path / "ur5_mm.urdf"
    tree.write(str(copy))
    found = audit(copy, Options(package_paths=(root,)))
    wrong_unit = [f for f in found if f.code == "GEOM031"]
    assert len(wrong_unit) == 1
    f = wrong_unit[0]
    assert f.severity == "error" and f.subject == f"link:{link}"
    assert "forearm_mm.stl" in f.message and "1000x" in f.message
    assert 'scale="0.001 0.001 0.001"' in f.hint
    # the unmodified robot has no such finding
    assert not [f for f in audit(urdf, Options(package_paths=(root,))) if f.code in ("GEOM030", "GEOM031")]
