"""The one-pass box reader (descgen/meshes/bounds.py) against its oracle, trimesh's
``load(process=True)`` (what the audit measured meshes with before): on every mesh of the
corpus, and on made files for each case the reader decides (unused positions, index lists
in other forms, node transforms, polygons) or leaves to trimesh."""

from __future__ import annotations

import io
import math
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest
import trimesh

from descgen.meshes import load as meshes
from descgen.meshes.bounds import bounds

from .corpus import share

DATA = Path(__file__).parent / "data"
KINDS = ("stl", "obj", "dae")


def _corpus_meshes() -> dict[str, list[Path]]:
    """Every mesh of example-robot-data and of tests/data, by package folder (one test each)."""
    groups: dict[str, set[Path]] = defaultdict(set)
    root = share()
    folders = [DATA] + ([root / "example-robot-data" / "robots"] if root is not None else [])
    for folder in folders:
        for path in folder.rglob("*"):
            if path.suffix.lower().lstrip(".") in KINDS and path.is_file():
                groups[path.relative_to(folder).parts[0]].add(path.resolve())
    return {k: sorted(v) for k, v in sorted(groups.items())}


CORPUS = _corpus_meshes()


def _trimesh_box(data: bytes, kind: str) -> np.ndarray | None:
    try:
        facts = meshes._parse(data, kind).facts
    except meshes.MeshError:
        return None
    return np.array([facts.lower, facts.upper])


def _box(data: bytes, kind: str) -> np.ndarray | None:
    facts = bounds(data, kind)
    return None if facts is None else np.array([facts.lower, facts.upper])


def _same(got: np.ndarray, want: np.ndarray) -> bool:
    """Equal to float32 precision: pycollada reads a COLLADA file's numbers as float32 and
    composes its node transforms in float32 too; STL and OBJ give exactly equal boxes."""
    return bool(np.allclose(got, want, rtol=0, atol=4e-7 * max(1.0, float(np.abs(want).max()))))


def test_the_corpus_holds_every_kind() -> None:
    files = [p for group in CORPUS.values() for p in group]
    kinds = {p.suffix.lower() for p in files}
    assert kinds == {".stl", ".obj", ".dae"}
    assert len(files) > (600 if share() is not None else 200)


@pytest.mark.slow
@pytest.mark.parametrize("group", sorted(CORPUS))
def test_the_box_is_trimeshs_on_every_corpus_mesh(group: str) -> None:
    left = []
    for path in CORPUS[group]:
        data, kind = path.read_bytes(), path.suffix.lower().lstrip(".")
        got, want = _box(data, kind), _trimesh_box(data, kind)
        if got is None:
            left.append(path)  # trimesh decides: measure() asks it
            continue
        if want is None:
            continue  # trimesh reads nothing: test_a_collada_file_trimesh_drops_is_measured
        assert _same(got, want), (path, got.tolist(), want.tolist())
    # what the reader leaves to trimesh in a real corpus: ASCII STL only
    assert all(p.suffix.lower() == ".stl" and p.read_bytes()[:5].lower() == b"solid" for p in left), left


def test_a_collada_file_trimesh_drops_is_measured() -> None:
    """anymal_b's foot: pycollada refuses a broken texture reference, so trimesh drops the
    whole instance and sees no triangles, though RViz shows the foot. The oracle for its box
    is pycollada's own geometry (ignoring that error), moved by the node's matrix."""
    root = share()
    if root is None:
        pytest.fail("example-robot-data is not installed (the test extra installs it)")
    import collada

    path = root / "example-robot-data/robots/anymal_b_simple_description/meshes/foot/anymal_foot.dae"
    data = path.read_bytes()
    assert _trimesh_box(data, "dae") is None
    ignore = [collada.common.DaeBrokenRefError, collada.common.DaeUnsupportedError]
    c = collada.Collada(io.BytesIO(data), ignore=ignore)
    (geometry,) = c.geometries
    points = np.vstack([p.vertex[p.vertex_index].reshape(-1, 3) for p in geometry.primitives])
    (node,) = [n for n in c.scene.nodes if n.id == "_45634_00-ASM_Foot_V9"]
    placed = points @ node.matrix[:3, :3].T + node.matrix[:3, 3]
    got = _box(data, "dae")
    assert got is not None and _same(got, np.array([placed.min(axis=0), placed.max(axis=0)]))
    assert 0.03 < float(np.ptp(got[:, 0])) < 0.2  # a foot in metres: the node's 1e-3 scale applied


# -- STL ------------------------------------------------------------------------------------------


def test_binary_stl_box_equals_trimesh() -> None:
    mesh = trimesh.creation.icosphere(subdivisions=2, radius=0.05)
    mesh.apply_translation((1.0, -2.0, 3.0))
    data = mesh.export(file_type="stl")
    got, want = _box(data, "stl"), _trimesh_box(data, "stl")
    assert got is not None and want is not None and np.array_equal(got, want)
    assert got[0] == pytest.approx((0.95, -2.05, 2.95), abs=1e-6)  # hand value


def test_stl_the_reader_leaves_to_trimesh() -> None:
    box = trimesh.creation.box(extents=(1, 1, 1))
    binary = box.export(file_type="stl")
    assert bounds(trimesh.exchange.stl.export_stl_ascii(box).encode(), "stl") is None
    assert bounds(binary[:-10], "stl") is None  # length disagrees with the header's count
    assert bounds(binary[:84], "stl") is None  # zero triangles
    nan = bytearray(binary)
    nan[84 + 12 : 84 + 16] = b"\x00\x00\xc0\x7f"  # first corner x = NaN (float32)
    assert bounds(bytes(nan), "stl") is None


def test_measure_gives_trimeshs_box_where_the_reader_steps_aside(tmp_path: Path) -> None:
    box = trimesh.creation.box(extents=(0.2, 0.4, 0.6))
    path = tmp_path / "ascii.stl"
    path.write_text(trimesh.exchange.stl.export_stl_ascii(box), encoding="ascii")
    facts = meshes.measure(path)
    assert facts.lower == pytest.approx((-0.1, -0.2, -0.3)) and facts.upper == pytest.approx((0.1, 0.2, 0.3))


# -- OBJ ------------------------------------------------------------------------------------------

_SQUARE = "v 0 0 0\nv 1 0 0\nv 1 2 0\nv 0 2 0.5\n"


@pytest.mark.parametrize(
    "faces",
    [
        "f 1 2 3\nf 1 3 4\n",
        "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
        "f 1/1/1 2/2/1 3/3/1 4/4/1\n",  # a quad: trimesh triangulates it
        "f 1//1 2//1 3//1\r\nf 1//1 3//1 4//1\r\n",  # v//vn, Windows line ends
    ],
)
def test_obj_box_is_of_the_used_positions(faces: str) -> None:
    texture = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
    unused = "v 50 50 50\nv -9 -9 -9\n"  # positions no face uses: trimesh leaves them out
    data = ("# made\no part\n" + _SQUARE + unused + texture + "g side\n" + faces).encode()
    got, want = _box(data, "obj"), _trimesh_box(data, "obj")
    assert got is not None and want is not None and np.array_equal(got, want)
    assert got.tolist() == [[0, 0, 0], [1, 2, 0.5]]  # hand value


def test_obj_indented_lines_count_as_trimesh_counts_them() -> None:
    """trimesh counts an indented position line and skips an indented face line."""
    data = ("  v 7 7 7\n" + _SQUARE + "f 2 3 4\n  f 1 2 3\n").encode()
    got, want = _box(data, "obj"), _trimesh_box(data, "obj")
    assert got is not None and want is not None and np.array_equal(got, want)
    assert got.tolist() == [[0, 0, 0], [1, 2, 0]]  # positions 2-4: the indented one shifted them


def test_obj_the_reader_leaves_to_trimesh() -> None:
    assert bounds((_SQUARE + "f 1 2 3\nf 1 4\n").encode(), "obj") is None  # a face of two corners
    assert bounds((_SQUARE + "f -4 -3 -2\n").encode(), "obj") is None  # relative indices
    assert bounds((_SQUARE + "f 1 2 9\n").encode(), "obj") is None  # an index past the last position
    assert bounds((_SQUARE + "f 1/1 2/2 3/3\nf 1 3 4\n").encode(), "obj") is None  # two corner forms
    assert bounds(_SQUARE.encode(), "obj") is None  # no faces: a point cloud
    assert bounds(b"v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", "obj") is None  # not a number


# -- COLLADA --------------------------------------------------------------------------------------

# a triangle geometry: positions 0-3 used, 4 unused unless a case says; normals interleaved
_POSITIONS = [(0, 0, 0), (1, 0, 0), (0, 2, 0), (0, 0, 3), (40, -40, 40)]


def _dae(
    p: str,
    nodes: str,
    *,
    primitive: str = "triangles",
    positions: list[tuple[float, float, float]] = _POSITIONS,
) -> bytes:
    floats = " ".join(f"{c:g}" for point in positions for c in point)
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1" name="meter"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries>
    <geometry id="g" name="g"><mesh>
      <source id="g-pos"><float_array id="g-pos-array" count="{3 * len(positions)}">{floats}</float_array>
        <technique_common><accessor source="#g-pos-array" count="{len(positions)}" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <source id="g-nrm"><float_array id="g-nrm-array" count="15">0 0 1 1 0 0 0 1 0 0 0 1 1 0 0</float_array>
        <technique_common><accessor source="#g-nrm-array" count="5" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="g-vtx"><input semantic="POSITION" source="#g-pos"/></vertices>
      <{primitive} count="2">
        <input semantic="VERTEX" source="#g-vtx" offset="0"/>
        <input semantic="NORMAL" source="#g-nrm" offset="1"/>
        {p}
      </{primitive}>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s" name="s">{nodes}</visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>""".encode()


_PLAIN = '<node id="n"><instance_geometry url="#g"/></node>'
_TRIANGLES = "<p>0 0 1 0 2 0 0 1 2 1 3 1</p>"  # (vertex, normal) pairs: positions 0-3


def _check(data: bytes) -> np.ndarray:
    got, want = _box(data, "dae"), _trimesh_box(data, "dae")
    assert got is not None and want is not None
    assert _same(got, want), (got.tolist(), want.tolist())
    return got


def test_collada_box_leaves_out_positions_no_triangle_uses() -> None:
    assert _check(_dae(_TRIANGLES, _PLAIN)).tolist() == [[0, 0, 0], [1, 2, 3]]  # not position 4's 40s


def test_collada_an_unused_position_named_at_the_normal_offset_is_still_unused() -> None:
    """Normal index 4 sits beside position 0: the number 4 is in the list, not as a vertex."""
    normals = "<p>0 4 1 4 2 4 0 4 2 4 3 4</p>"
    assert _check(_dae(normals, _PLAIN)).tolist() == [[0, 0, 0], [1, 2, 3]]
    positions = "<p>0 0 1 0 2 0 0 1 2 1 4 1</p>"  # now position 4 is used, as a vertex
    assert _check(_dae(positions, _PLAIN)).tolist() == [[0, -40, 0], [40, 2, 40]]


def test_collada_index_lists_in_other_forms_are_read_whole() -> None:
    spread = "<p>\n  0 0  1 0\t2 0\n  0 1 2 1 3 1\n</p>"  # newlines, tabs, double spaces
    assert _check(_dae(spread, _PLAIN)).tolist() == [[0, 0, 0], [1, 2, 3]]


def test_collada_polylists_and_what_trimesh_decides() -> None:
    quad = "<vcount>4</vcount><p>0 0 1 0 2 0 3 1</p>"
    assert _check(_dae(quad, _PLAIN, primitive="polylist")).tolist() == [[0, 0, 0], [1, 2, 3]]
    # a polygon of two corners makes no triangle, a vcount that disagrees with the list: trimesh decides
    assert _box(_dae("<vcount>3 2</vcount><p>0 0 1 0 2 0 3 1 4 1</p>", _PLAIN, primitive="polylist"), "dae") is None
    assert _box(_dae("<vcount>3</vcount><p>0 0 1 0 2 0 3 1</p>", _PLAIN, primitive="polylist"), "dae") is None
    for other in ("polygons", "tristrips", "trifans"):  # pycollada's own readings
        assert _box(_dae("<p>0 0 1 0 2 0</p><p>0 1 2 1 3 1</p>", _PLAIN, primitive=other), "dae") is None


def test_collada_triangles_are_read_from_their_first_list_as_pycollada_reads_them() -> None:
    two = "<p>0 0 1 0 2 0</p><p>0 1 4 1 3 1</p>"  # pycollada reads the first <p> alone
    assert _check(_dae(two, _PLAIN)).tolist() == [[0, 0, 0], [1, 2, 0]]
    assert _box(_dae("<p>0 0 1 0 2 0 3 1</p>", _PLAIN), "dae") is None  # not whole triangles


def test_collada_an_accessor_pycollada_reads_otherwise_is_left_to_trimesh() -> None:
    data = _dae(_TRIANGLES, _PLAIN)
    assert _box(data.replace(b'count="5" stride="3"', b'count="4" stride="3"'), "dae") is None
    rotated = '<node id="n"><rotate>0 0 2 90</rotate><instance_geometry url="#g"/></node>'
    assert _box(_dae(_TRIANGLES, rotated), "dae") is None  # an axis pycollada does not normalise


def test_collada_a_scene_past_the_work_bound_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.meshes import bounds as box_reader

    monkeypatch.setattr(box_reader, "MAX_PLACED", 9)  # two instances of the 5-position geometry
    twice = _PLAIN + '<node id="m"><translate>1 0 0</translate><instance_geometry url="#g"/></node>'
    facts = bounds(_dae(_TRIANGLES, twice), "dae")
    assert facts is not None and facts.problem is not None and "places more than 9 points" in facts.problem
    assert bounds(_dae(_TRIANGLES, _PLAIN), "dae") is not None


def test_collada_node_transforms_compose_as_pycollada_composes_them() -> None:
    nested = (
        '<node id="a"><translate>1 2 3</translate><rotate>0 0 1 90</rotate>'
        '<node id="b"><scale>2 2 2</scale><rotate>1 0 0 30</rotate><instance_geometry url="#g"/></node>'
        '<node id="c"><matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix><instance_geometry url="#g"/></node>'
        "</node>"
    )
    got = _check(_dae(_TRIANGLES, nested))
    # hand values. Node b: scale 2, then about x by 30 degrees, about z by 90, + (1, 2, 3):
    # corner (0, 0, 3) -> (0, 0, 6) -> (0, -3, 6 cos 30) -> (3, 0, 6 cos 30) -> (4, 2, 3 + 6 cos 30);
    # corner (0, 2, 0) -> (0, 4, 0) -> (0, 4 cos 30, 2) -> (-4 cos 30, 0, 2) -> (1 - 4 cos 30, 2, 5).
    # Node c: (1, 0, 0) + (10, 0, 0) -> about z (0, 11, 0) -> (1, 13, 3)
    c30 = math.cos(math.radians(30))
    assert got[0][0] == pytest.approx(1 - 4 * c30, abs=1e-6)
    assert got[1].tolist() == pytest.approx([4, 13, 3 + 6 * c30], abs=1e-6)


def test_collada_what_the_reader_leaves_to_trimesh() -> None:
    instance_node = '<node id="n"><instance_node url="#lib"/></node>'
    lookat = '<node id="n"><lookat>0 0 1 0 0 0 0 1 0</lookat><instance_geometry url="#g"/></node>'
    assert _box(_dae(_TRIANGLES, instance_node), "dae") is None
    assert _box(_dae(_TRIANGLES, lookat), "dae") is None
    assert _box(_dae("<p>0 0 1 0 9 0 0 1 2 1 3 1</p>", _PLAIN), "dae") is None  # index past the end
    assert _box(_dae(_TRIANGLES, _PLAIN).replace(b"0 0 3 40", b"0 0 nan 40"), "dae") is None
    assert _box(b"<COLLADA><scene/></COLLADA>", "dae") is None  # no visual scene
    assert _box(b"<COLLADA><unclosed></COLLADA>", "dae") is None  # not XML


def test_collada_lines_only_and_cameras_hold_no_triangles() -> None:
    lines = _dae("<p>0 0 1 0</p>", _PLAIN, primitive="lines")
    assert _box(lines, "dae") is None  # nothing to measure: trimesh says what the file holds
    camera = '<node id="cam"><matrix>1 0 0 99 0 1 0 99 0 0 1 99 0 0 0 1</matrix><instance_camera url="#c"/></node>'
    assert _check(_dae(_TRIANGLES, camera + _PLAIN)).tolist() == [[0, 0, 0], [1, 2, 3]]
