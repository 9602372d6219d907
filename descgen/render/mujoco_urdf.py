"""The robot model as the URDF MuJoCo reads: mesh files resolved and handed over as assets.

MuJoCo opens mesh filenames as plain paths (``package://`` fails), so every collision mesh
is resolved here, within the folders the user named (the description's package and
``--package-path``), read with a size bound, and passed in memory under a neutral name.
Visual meshes keep their filenames: MuJoCo discards visuals of a URDF before it would load
them (``discardvisual``), which :mod:`.compile` reports.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from descgen.codes.simulate import SIM008
from descgen.core.findings import Finding
from descgen.core.model import Collision, Joint, Link, Mesh, Robot, Visual
from descgen.infra.safeio import read_bounded
from descgen.physics.urdf_xml import geometry, origin, xyz

# mesh formats MuJoCo's compiler reads (user_mesh.cc); Collada and others are refused
MESH_FORMATS = (".stl", ".obj", ".msh")
MAX_MESH_BYTES = 64 * 1024 * 1024


@dataclass
class Emitted:
    """The URDF text, its mesh assets (neutral name -> bytes) and what could not be handed over."""

    text: str
    assets: dict[str, bytes] = field(default_factory=dict)
    findings: list[Finding] = field(default_factory=list)
    dropped: int = 0  # collision shapes left out (their mesh could not be handed to MuJoCo)


def _collada_as_stl(path: Path) -> tuple[bytes | None, str | None]:
    """A COLLADA mesh as a binary STL in metres, for MuJoCo, which reads no COLLADA: read as the
    audit reads it (descgen/meshes/load.py: trimesh and pycollada, DTDs refused), its
    ``<unit meter>`` applied as RViz and Gazebo apply it (the URDF's ``scale`` is applied after,
    by MuJoCo). Returns (bytes, None), or (None, why not)."""
    import trimesh

    from descgen.meshes.load import MeshError, load

    try:
        loaded = load(path)
    except MeshError as exc:
        return None, f"is a COLLADA file that cannot be read ({exc})"
    unit = loaded.facts.unit_meter or 1.0
    stl = trimesh.Trimesh(loaded.vertices * unit, loaded.faces, process=False).export(file_type="stl")
    assert isinstance(stl, bytes)  # binary STL (trimesh's "stl" exporter)
    return stl, None


class _Writer:
    def __init__(self, robot: Robot) -> None:
        self.robot = robot
        # the files the one resolver accepted when the robot was read (descgen/meshes/paths.py),
        # as every command reads them: a spec's package_paths:, --package-path, the environment
        ok = {name for name, state in robot.mesh_status if state == "ok"}
        self.files = {name: Path(file) for name, file in robot.mesh_files if name in ok}
        self.out = Emitted("")
        self.names: dict[Path, str] = {}

    def mesh_asset(self, link: Link, shape: Collision, mesh: Mesh) -> str | None:
        path = self.files.get(mesh.filename)
        why = None
        converted: bytes | None = None
        if path is None:
            why = (
                "is not a file inside the description's package, a spec's package_paths:, a --package-path "
                "folder or the sourced environment's packages"
            )
        elif path.suffix.lower() == ".dae":
            converted, why = _collada_as_stl(path)
        elif path.suffix.lower() not in MESH_FORMATS:
            why = (
                f"is a {path.suffix or 'extensionless'} file; MuJoCo reads only {', '.join(MESH_FORMATS)}, and COLLADA"
            )
        if path is None or why is not None:
            self.out.findings.append(
                SIM008.finding(
                    f"link {link.name}: collision mesh {mesh.filename!a} {why}; the shape is left out of the "
                    "MuJoCo model, so it neither collides nor adds inertia there",
                    "give --package-path the folder holding the package, or convert the mesh to STL or OBJ",
                    link.subject,
                    shape.where,
                )
            )
            return None
        if path not in self.names:
            suffix = ".stl" if converted is not None else path.suffix.lower()
            self.names[path] = f"descgen_mesh_{len(self.names)}{suffix}"
            data = converted if converted is not None else read_bounded(path, "mesh", MAX_MESH_BYTES)
            self.out.assets[self.names[path]] = data
        return self.names[path]

    def link(self, root: etree._Element, lk: Link) -> None:
        el = etree.SubElement(root, "link", name=lk.name)
        i = lk.inertial
        if i is not None and i.mass is not None:
            ine = etree.SubElement(el, "inertial")
            origin(ine, i.origin)
            etree.SubElement(ine, "mass", value=repr(i.mass))
            t = i.inertia
            values = (t.ixx, t.ixy, t.ixz, t.iyy, t.iyz, t.izz) if t is not None else (0.0,) * 6
            keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
            etree.SubElement(ine, "inertia", {k: repr(v) for k, v in zip(keys, values, strict=True)})
        for v in lk.visuals:
            self.visual(el, v)
        for c in lk.collisions:
            self.collision(el, lk, c)

    def visual(self, el: etree._Element, v: Visual) -> None:
        if v.geometry is None:
            return
        vis = etree.SubElement(el, "visual")
        origin(vis, v.origin)
        geometry(vis, v.geometry)

    def collision(self, el: etree._Element, lk: Link, c: Collision) -> None:
        if c.geometry is None:
            return
        filename = None
        if isinstance(c.geometry, Mesh):
            filename = self.mesh_asset(lk, c, c.geometry)
            if filename is None:
                self.out.dropped += 1
                return
        col = etree.SubElement(el, "collision")
        origin(col, c.origin)
        geometry(col, c.geometry, filename)

    def joint(self, root: etree._Element, j: Joint) -> None:
        el = etree.SubElement(root, "joint", name=j.name, type=j.type)
        origin(el, j.origin)
        etree.SubElement(el, "parent", link=j.parent or "")
        etree.SubElement(el, "child", link=j.child or "")
        if j.axis is not None:
            etree.SubElement(el, "axis", xyz=xyz(j.axis))
        lm = j.limit
        if lm is not None:
            attrs = {k: repr(v) for k, v in (("lower", lm.lower), ("upper", lm.upper)) if v is not None}
            attrs |= {"effort": repr(lm.effort or 0.0), "velocity": repr(lm.velocity or 0.0)}
            etree.SubElement(el, "limit", attrs)
        if j.dynamics is not None:
            etree.SubElement(el, "dynamics", damping=repr(j.dynamics.damping), friction=repr(j.dynamics.friction))
        if j.mimic is not None:
            m = j.mimic
            etree.SubElement(el, "mimic", joint=m.joint, multiplier=repr(m.multiplier), offset=repr(m.offset))


def emit(robot: Robot) -> Emitted:
    """The URDF of ``robot`` for MuJoCo, with MuJoCo's own URDF defaults left in force (fixed
    links fused, visuals discarded): what a user who loads the URDF gets is what is checked."""
    w = _Writer(robot)
    root = etree.Element("robot", name=robot.name)
    for lk in robot.links:
        w.link(root, lk)
    for j in robot.joints:
        w.joint(root, j)
    w.out.text = etree.tostring(root, encoding="unicode")
    return w.out
