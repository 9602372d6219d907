"""A mesh's bounding box from one pass over its file, without building the mesh.

What the audit's mesh rules (GEOM030-033) read of a mesh is its bounding box, in the file's
units, and the unit a COLLADA file declares. Building the mesh as trimesh does (merging
vertices, walking edges, pycollada's object model) costs ~30x more than reading the positions,
and was 90 % of a first audit. The box is the one trimesh's ``load(process=True)`` gives (the
oracle: tests/test_mesh_bounds.py compares both on every mesh of the corpus):

- binary STL: every corner of every triangle (trimesh keeps all, merged);
- OBJ: the ``v`` positions the ``f`` faces use (trimesh drops unused ones);
- COLLADA: the positions of each ``<triangles>``, ``<polylist>`` and ``<polygons>`` of each
  geometry a ``<node>`` of the scene instances, moved by the nodes' transforms, as trimesh's
  COLLADA loader places them; every position of such a primitive's source counts (exporters
  write no unused ones; the corpus test holds every real file to trimesh's box).

Anything else (ASCII STL, non-finite numbers, negative OBJ indices, ``<instance_node>``, a
transform this reader does not take) returns None: the caller asks trimesh, as before.
The bytes were checked by the caller (size bound; no DTD in a COLLADA file).
"""

from __future__ import annotations

import math
import re
import struct
from typing import TYPE_CHECKING

from descgen.meshes.facts import MeshFacts

if TYPE_CHECKING:
    import numpy as np
    from lxml.etree import _Element

Box = tuple[tuple[float, float, float], tuple[float, float, float]]


class _TooLargeError(Exception):
    """A scene that places more points than :data:`MAX_PLACED`."""


# Points moved by node transforms, summed over a COLLADA scene's instances: a file of a few MB
# can instance one large geometry thousands of times (tens of minutes of work); the densest real
# robot mesh places ~2 M. trimesh would do the same work, so the mesh is refused instead.
MAX_PLACED = 20_000_000


def bounds(data: bytes, kind: str, unit_meter: float | None = None) -> MeshFacts | None:
    """The facts of a mesh from its bounding box; None where trimesh must decide."""
    if kind == "stl":
        box = _stl(data)
    elif kind == "obj":
        box = _obj(data)
    elif kind == "dae":
        try:
            box = _dae(data)
        except _TooLargeError:
            return MeshFacts(problem=f"the COLLADA scene places more than {MAX_PLACED:,} points; descgen reads fewer")
    else:
        return None
    if box is None:
        return None
    lo, hi = box
    return MeshFacts(lower=lo, upper=hi, unit_meter=unit_meter)


def _extremes(points: np.ndarray) -> np.ndarray:
    """(2, 3): the lowest and highest coordinate of (n > 0, 3) points along each axis, NaN
    propagated. One axis at a time: numpy reduces a 3-wide axis 0 ~7x slower than a column."""
    import numpy as np

    columns = [points[:, k] for k in range(3)]
    return np.array([[c.min() for c in columns], [c.max() for c in columns]], dtype=np.float64)


def _box(extremes: np.ndarray) -> Box | None:
    """The box from :func:`_extremes`; None when it is not finite (trimesh drops non-finite
    vertices, and what it then keeps is its decision)."""
    import numpy as np

    if not np.isfinite(extremes).all():
        return None
    lo, hi = extremes
    return (float(lo[0]), float(lo[1]), float(lo[2])), (float(hi[0]), float(hi[1]), float(hi[2]))


def _floats(text: bytes) -> np.ndarray:
    """Whitespace-separated numbers with numpy's C reader; empty when a token is not a number
    (numpy 2 refuses the text), so a caller that compares the count with what it expects
    falls back to trimesh."""
    import numpy as np

    try:
        return np.fromstring(text, dtype=np.float64, sep=" ")
    except ValueError:
        return np.empty(0)


def _ints(text: bytes) -> np.ndarray | None:
    """Whitespace-separated integers (numpy's C reader: ~4x its speed for floats); None when a
    token is not one."""
    import numpy as np

    try:
        return np.fromstring(text, dtype=np.int64, sep=" ")
    except ValueError:
        return None


# -- STL ------------------------------------------------------------------------------------------

_STL_RECORD = 50  # normal, three corners (little-endian float32), attribute byte count


def _stl(data: bytes) -> Box | None:
    """Binary STL only: trimesh takes a file as binary exactly when its length is what the
    header's triangle count gives (whatever its first bytes say), else reads it as ASCII."""
    import numpy as np

    if len(data) < 84:
        return None
    (count,) = struct.unpack_from("<I", data, 80)
    if count == 0 or len(data) != 84 + _STL_RECORD * count:
        return None
    records = np.frombuffer(data, dtype=np.uint8, count=_STL_RECORD * count, offset=84).reshape(count, _STL_RECORD)
    corners = records[:, 12:48].copy().view("<f4").reshape(-1, 3)
    return _box(_extremes(corners))


# -- OBJ ------------------------------------------------------------------------------------------

# after a newline (the engine searches for it, not every offset), as trimesh reads them: a
# position line may be indented, a face line not (tests/test_mesh_bounds.py holds both to trimesh)
_OBJ_V = re.compile(rb"\n[ \t]*v[ \t]+([^\r\n]*)")
_OBJ_F = re.compile(rb"\nf[ \t]+([^\r\n]*)")
_OBJ_SHORT_F = re.compile(rb"\nf[ \t]+\S+(?:[ \t]+\S+)?[ \t]*\r?(?=\n|$)")  # a face of 1 or 2 corners


def _obj(data: bytes) -> Box | None:
    import numpy as np

    text = b"\n" + data
    rows = _OBJ_V.findall(text)
    if not rows:
        return None
    width = len(rows[0].split())
    if width < 3:
        return None
    values = _floats(b" ".join(rows))
    if len(values) != len(rows) * width:
        return None  # x y z [w] or x y z r g b: one form per file, else trimesh decides
    values = values.reshape(len(rows), width)[:, :3]
    corners = b" ".join(_OBJ_F.findall(text)).replace(b"//", b"/0/")  # v, v/vt, v/vt/vn, v//vn
    if not corners or _OBJ_SHORT_F.search(text):
        return None  # no faces, or a face trimesh drops: it decides
    per_corner = corners.split(None, 1)[0].count(b"/") + 1
    numbers = _ints(corners.replace(b"/", b" "))
    if numbers is None or len(numbers) % per_corner:
        return None
    if corners.count(b"/") * per_corner != (per_corner - 1) * len(numbers):
        return None  # corners written in more than one form
    used = numbers[::per_corner]
    if len(used) == 0 or used.min() < 1 or used.max() > len(values):
        return None  # relative (negative) or missing indices: trimesh decides
    mask = np.zeros(len(values), dtype=bool)
    mask[used - 1] = True
    return _box(_extremes(values[mask]))


# -- COLLADA --------------------------------------------------------------------------------------

_PRIMITIVES = ("triangles", "polylist")
# what pycollada also reads as triangles, or reads its own way: trimesh decides those files
_OTHER_PRIMITIVES = ("polygons", "tristrips", "trifans")
_TRANSFORMS = ("matrix", "translate", "rotate", "scale")
_MOST_LOOKS = 64  # occurrences of one index tried before its primitives' indices are read whole


def _dae(data: bytes) -> Box | None:
    """Positions placed as trimesh's COLLADA loader places them (trimesh/exchange/dae.py: each
    ``<node>``'s matrix applied to its children; ``<instance_geometry>`` of a node; triangle
    and polygon primitives; cameras and lights skipped there too)."""
    import numpy as np
    from lxml import etree

    try:
        root = etree.fromstring(data, etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=True))
    except etree.XMLSyntaxError:
        return None
    ns = root.tag[: root.tag.index("}") + 1] if root.tag.startswith("{") else ""
    by_id = {e.get("id"): e for e in root.iter() if e.get("id") is not None}
    found = root.find(f"{ns}scene/{ns}instance_visual_scene")
    scene = by_id.get(_ref(found, "url")) if found is not None else None  # pycollada's Collada.scene
    if scene is None:
        return None
    geometries: dict[str, list[_Positions] | None] = {}
    boxes: list[np.ndarray] = []
    placed = 0
    stack: list[tuple[etree._Element, np.ndarray]] = [(n, np.eye(4)) for n in scene.iterchildren(f"{ns}node")]
    while stack:
        node, parent = stack.pop()
        if node.find(f"{ns}instance_node") is not None or node.find(f"{ns}instance_controller") is not None:
            return None  # pycollada's node and controller instances: trimesh decides
        matrix = _matrix(node, ns)
        if matrix is None:
            return None
        here = parent @ matrix
        for inst in node.iterchildren(f"{ns}instance_geometry"):
            ref = _ref(inst, "url")
            if ref not in geometries:
                geometries[ref] = _geometry(by_id.get(ref), ns, by_id)
            sources = geometries[ref]
            if sources is None:
                return None
            for source in sources:
                placed += len(source.points)
                if placed > MAX_PLACED:
                    raise _TooLargeError
                box = source.placed_box(here)
                if box is None:
                    return None
                boxes.append(box)
        stack.extend((child, here) for child in node.iterchildren(f"{ns}node"))
    if not boxes:
        return None  # no triangles: trimesh says what the file holds
    return _box(np.array([np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)]))


def _ref(element: _Element, attribute: str) -> str:
    return (element.get(attribute) or "").removeprefix("#")


def _matrix(node: _Element, ns: str) -> np.ndarray | None:
    """The node's transform, its elements composed in document order (pycollada's
    ``Node.matrix``, float32 as pycollada reads them); None for one it does not take here
    (lookat, skew)."""
    import numpy as np

    m = np.eye(4)
    for child in node.iterchildren():
        tag = child.tag.removeprefix(ns) if isinstance(child.tag, str) else ""
        if tag in ("lookat", "skew"):
            return None
        if tag not in _TRANSFORMS:
            continue
        v = _floats((child.text or "").encode()).astype(np.float32).astype(np.float64)
        if tag == "matrix" and v.shape == (16,):
            m = m @ v.reshape(4, 4)
        elif tag == "translate" and v.shape == (3,):
            t = np.eye(4)
            t[:3, 3] = v
            m = m @ t
        elif tag == "scale" and v.shape == (3,):
            m = m @ np.diag([v[0], v[1], v[2], 1.0])
        elif tag == "rotate" and v.shape == (4,) and abs(math.hypot(v[0], v[1], v[2]) - 1) < 1e-6:
            m = m @ _rotation(v[:3], math.radians(v[3]))  # pycollada does not normalise another axis
        else:
            return None
    return m if np.isfinite(m).all() else None


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    import numpy as np

    r = np.eye(4)
    n = float(np.linalg.norm(axis))
    if n == 0:
        return r
    x, y, z = axis / n
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    r[:3, :3] = [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
    return r


class _Positions:
    """One positions ``<source>`` and the index lists (``<p>``) of the primitives that use it.

    A position no primitive names is not in trimesh's mesh (a file cut from a larger model
    keeps them all), but reading every index costs as much as the positions. So the box of
    all positions is taken when each of its six extreme points is named by some primitive
    (then the box of the named ones is the same), found by searching the index text for that
    number at the vertex offset; otherwise, and for index text not in the one-space form
    exporters write, every index is read."""

    def __init__(self, points: np.ndarray) -> None:
        self.points = points
        # (index text, inputs per corner, vertex offset, one space between numbers)
        self.lists: list[tuple[bytes, int, int, bool]] = []
        self._named: dict[int, bool] = {}
        self._mask: np.ndarray | None = None

    def placed_box(self, matrix: np.ndarray) -> np.ndarray | None:
        """(2, 3) box of the named positions moved by ``matrix``; None when an index is bad."""
        if len(self.points) == 0:
            return None  # indices into nothing: trimesh decides
        placed = self.points @ matrix[:3, :3].T + matrix[:3, 3]
        columns = [placed[:, k] for k in range(3)]
        ends = {int(c.argmin()) for c in columns} | {int(c.argmax()) for c in columns}
        if all(self._is_named(i) for i in ends):
            return _extremes(placed)
        mask = self.mask()
        if mask is None or not mask.any():
            return None
        return _extremes(placed[mask])

    def _is_named(self, i: int) -> bool:
        known = self._named.get(i)
        if known is None:
            known = any(spaced and _names(text, i, stride, at) for text, stride, at, spaced in self.lists)
            self._named[i] = known
        return known

    def mask(self) -> np.ndarray | None:
        import numpy as np

        if self._mask is None:
            mask = np.zeros(len(self.points), dtype=bool)
            for text, stride, at, _ in self.lists:
                index = _ints(text)
                if index is None or len(index) % stride or (len(index) and index.min() < 0):
                    return None
                named = index[at::stride]
                if len(named) and named.max() >= len(mask):
                    return None
                mask[named] = True
            self._mask = mask
        return self._mask


def _names(text: bytes, i: int, stride: int, at: int) -> bool:
    """Whether the index list ``text`` (one space between numbers, and one before and after
    them: :func:`_geometry` checks) names position ``i`` at the vertex offset ``at`` of its
    ``stride`` inputs per corner; False when unsure (then every index is read). bytes.find,
    not a regular expression: ~30x faster on the megabytes of a real list."""
    token = b" %d " % i
    before, counted, start = 0, 0, 0  # numbers before the match, counted up to this offset
    for _ in range(_MOST_LOOKS):
        found = text.find(token, start)
        if found < 0:
            return False
        if stride == 1:
            return True
        before += text.count(b" ", counted, found)
        counted = found
        if before % stride == at:
            return True
        start = found + 1
    return False


def _geometry(geometry: _Element | None, ns: str, by_id: dict[str | None, _Element]) -> list[_Positions] | None:
    """The positions sources of a ``<geometry>``'s triangle and polygon primitives, with their
    index lists; empty for a geometry without such primitives (lines only, or a spline:
    trimesh skips it); None where unsure."""
    if geometry is None:
        return None
    mesh = geometry.find(f"{ns}mesh")
    if mesh is None:
        return []
    if any(mesh.find(f"{ns}{tag}") is not None for tag in _OTHER_PRIMITIVES):
        return None
    sources: dict[str, _Positions] = {}
    for tag in _PRIMITIVES:
        for prim in mesh.iterchildren(f"{ns}{tag}"):
            inputs = list(prim.iterchildren(f"{ns}input"))
            vertex = next((i for i in inputs if i.get("semantic") == "VERTEX"), None)
            if vertex is None:
                continue  # pycollada's primitive.vertex is None: trimesh skips it
            vertices = by_id.get(_ref(vertex, "source"))
            if vertices is None:
                return None
            position = next((i for i in vertices.iterchildren(f"{ns}input") if i.get("semantic") == "POSITION"), None)
            if position is None:
                return None
            try:
                stride, at = max(int(i.get("offset", "0")) for i in inputs) + 1, int(vertex.get("offset", "0"))
            except ValueError:
                return None
            name = _ref(position, "source")
            if name not in sources:
                points = _source(by_id.get(name), ns)
                if points is None:
                    return None
                sources[name] = _Positions(points)
            text = _index_text(prim, ns, tag, stride)
            if text is None:
                return None
            # one space between numbers, as exporters write; a list in another form is read whole
            spaced = not (b"  " in text or b"\n" in text or b"\t" in text or b"\r" in text)
            sources[name].lists.append((text, stride, at, spaced))
    return [s for s in sources.values() if s.lists]


def _index_text(prim: _Element, ns: str, tag: str, stride: int) -> bytes | None:
    """The primitive's index list, padded with a space each side, as pycollada reads it: the
    first ``<p>`` only; a count of numbers that makes whole triangles (``<triangles>``) or the
    polygons ``<vcount>`` gives, each of at least 3 corners (``<polylist>``); else None."""
    first = prim.find(f"{ns}p")
    text = (first.text or "").strip().encode() if first is not None else b""
    numbers = len(text.split()) if text else 0
    if tag == "triangles":
        if numbers % (3 * stride):
            return None
    else:
        vcount = _ints((prim.findtext(f"{ns}vcount") or "").encode())
        if vcount is None or (len(vcount) and vcount.min() < 3) or int(vcount.sum()) * stride != numbers:
            return None
    return b" %s " % text


def _source(source: _Element | None, ns: str) -> np.ndarray | None:
    """A ``<source>``'s points through its accessor (count, stride, offset; x, y, z first),
    float32 as pycollada reads them (trimesh's box is of those values)."""
    import numpy as np

    if source is None:
        return None
    accessor = source.find(f"{ns}technique_common/{ns}accessor")
    array = source.find(f"{ns}float_array")
    if accessor is None or array is None or _ref(accessor, "source") != array.get("id"):
        return None
    try:
        count, stride, offset = (int(accessor.get(a, d)) for a, d in (("count", "0"), ("stride", "1"), ("offset", "0")))
    except ValueError:
        return None
    params = len(accessor.findall(f"{ns}param"))
    values = _floats((array.text or "").encode())
    # pycollada shapes the whole array by the accessor's params, whatever its count and offset say;
    # where those disagree, trimesh decides
    if stride < 3 or params != stride or offset != 0 or count * stride != len(values):
        return None
    return values[offset : offset + count * stride].reshape(count, stride)[:, :3].astype(np.float32).astype(np.float64)
