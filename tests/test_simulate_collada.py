"""``descgen simulate`` hands a COLLADA collision mesh to MuJoCo (which reads no COLLADA) as an
STL in metres (issue 28): the file's ``<unit meter>`` applied, as RViz and Gazebo apply it.
The COLLADA file is written by hand below; MuJoCo's compiled model is the oracle."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np

from descgen.read.description import load_description
from descgen.render.mujoco_urdf import emit

from .helpers import cli
from .test_simulate import _package, _with_mesh, _write


def _collada_cube(side: float, unit_meter: float) -> bytes:
    """A cube of ``side`` file units, centred on the origin, 12 triangles, in a minimal COLLADA 1.4."""
    h = side / 2
    v = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1)]
    faces += [(2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    floats = " ".join(f"{c:g}" for p in v for c in p)
    idx = " ".join(str(i) for f in faces for i in f)
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="{unit_meter}" name="u"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="cube"><mesh>
    <source id="pos"><float_array id="pos-a" count="24">{floats}</float_array>
      <technique_common><accessor source="#pos-a" count="8" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="verts"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles count="12"><input semantic="VERTEX" source="#verts" offset="0"/><p>{idx}</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n">
    <instance_geometry url="#cube"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
""".encode()


def test_a_collada_collision_mesh_reaches_mujoco_in_metres(tmp_path: Path) -> None:
    pkg = _package(tmp_path, "cube.dae", _collada_cube(5.0, 0.01))  # 5 cm written in centimetres
    path = _write(pkg, _with_mesh("package://bot_description/meshes/cube.dae"))
    ran = cli("simulate", path, "--package-path", tmp_path / "ws")
    assert ran.returncode == 0 and "[SIM008]" not in ran.stderr, ran.stderr
    emitted = emit(load_description(path)[0])
    model = mujoco.MjModel.from_xml_string(emitted.text, emitted.assets)
    assert model.nmesh == 1 and model.mesh_vertnum[0] == 8
    start = model.mesh_vertadr[0]
    verts = model.mesh_vert[start : start + 8]
    # MuJoCo re-centres a mesh at its centroid; the extent is the cube's side in metres: 5 cm
    np.testing.assert_allclose(verts.max(axis=0) - verts.min(axis=0), [0.05, 0.05, 0.05], rtol=1e-6)
