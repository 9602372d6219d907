"""A rendered image per known pose for the evidence page, and the record that keeps it current.

Each image (``evidence/poses/<pose>.png``) is an offscreen matplotlib render: the link frames
as a stick figure along the kinematic tree, the model's positions of the pose's measured
frames as dots and the measured positions as crosses. PNG bytes depend on matplotlib's
version and fonts, so ``check`` never compares them: ``evidence/poses/poses.json`` records the
inputs each image was drawn from (and their hash), and check compares that record, rebuilt
from the spec, and that every image exists. matplotlib is imported only when drawing.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from descgen.core.findings import Finding, Where
from descgen.core.model import KnownPose, Robot
from descgen.infra import keys
from descgen.physics import poses as known_poses
from descgen.physics import zero_pose
from descgen.physics.calibration import for_pose
from descgen.physics.rigid import ORIGIN, apply

if TYPE_CHECKING:  # numpy only draws (with matplotlib): check rebuilds the record in plain floats
    import numpy as np

FOLDER = "evidence/poses"
SIDECAR = f"{FOLDER}/poses.json"
# Bump when the drawing changes in a way a reviewer should see: the record then reads stale.
RENDERER_VERSION = "2"  # 2: the label says the error as poses does, with the tolerance and verdict
_MAX_SIDECAR_BYTES = 1 << 20  # a record for hundreds of poses is a few kB; more is not ours


@dataclass(frozen=True)
class Marker:
    """One measured frame of a pose, in the measurement's base frame (as the spec states it)
    and in the root frame (where it is drawn)."""

    frame: str
    relative_to: str | None
    model: tuple[float, float, float] | None  # None: the frame is not in the tree
    measured: tuple[float, float, float]
    model_in_root: tuple[float, float, float] | None
    measured_in_root: tuple[float, float, float] | None
    tolerance: float  # metres, as the spec states it

    @property
    def verdict(self) -> str:
        """As poses, POSE010, the viewer and the page say it (descgen/physics/poses.py)."""
        error = None if self.model is None else tuple(a - b for a, b in zip(self.model, self.measured, strict=True))
        return known_poses.verdict(error, self.tolerance)  # type: ignore[arg-type]


@dataclass(frozen=True)
class Scene:
    """Everything one image is drawn from."""

    pose: KnownPose
    links: dict[str, tuple[float, float, float]]  # origin of every link frame, root frame
    bones: list[tuple[str, str]]  # (parent, child) link pairs along the tree
    markers: list[Marker]


def image_rel(pose: str) -> str:
    return f"{FOLDER}/{pose}.png"


def _point(m: tuple[float, float, float]) -> tuple[float, float, float]:
    return (m[0] + 0.0, m[1] + 0.0, m[2] + 0.0)


def scene(robot: Robot, kp: KnownPose) -> Scene:
    """Forward kinematics (mimic followers resolved) for one known pose, in plain floats
    (descgen/physics/zero_pose.py: check rebuilds the record without numpy's import)."""
    poses = zero_pose.forward(for_pose(robot, kp), dict(kp.joints))
    links = {name: _point(t[1]) for name, t in poses.items()}
    bones = [(j.parent, j.child) for j in robot.joints if j.child in poses and j.parent in poses]
    markers = []
    for fm in kp.frames:
        t = zero_pose.relative(poses, fm.frame, fm.relative_to)
        base = poses.get(fm.relative_to) if fm.relative_to is not None else ORIGIN
        measured_root = None if base is None else _point(apply(base, fm.xyz))
        markers.append(
            Marker(
                fm.frame,
                fm.relative_to,
                None if t is None else _point(t[1]),
                fm.xyz,
                links.get(fm.frame),
                measured_root,
                fm.tolerance,
            )
        )
    return Scene(kp, links, bones, markers)


def _mm(v: tuple[float, float, float] | None) -> list[float] | None:
    # micrometres: float noise between machines stays below the last digit kept
    return None if v is None else [round(c * 1000, 3) + 0.0 for c in v]


def _inputs(s: Scene) -> dict[str, Any]:
    """What the image shows, as data: the pose values, every drawn position, the renderer."""
    return {
        "joints": {name: round(value, 9) + 0.0 for name, value in sorted(s.pose.joints)},
        "links_mm": {name: _mm(p) for name, p in sorted(s.links.items())},
        "bones": sorted([list(b) for b in s.bones]),
        "markers": [
            {
                "frame": m.frame,
                "relative_to": m.relative_to,
                "model_mm": _mm(m.model),
                "measured_mm": _mm(m.measured),
                "tolerance_mm": round(m.tolerance * 1000, 6) + 0.0,  # the label shows the verdict
            }
            for m in s.markers
        ],
        "renderer": RENDERER_VERSION,
    }


def record(robot: Robot) -> str:
    """The sidecar's text: per pose its image, its inputs' hash, and the marker positions a
    reviewer (and check) can read without opening the PNG."""
    poses = {}
    for kp in robot.known_poses:
        inputs = _inputs(scene(robot, kp))
        # the key (descgen/infra/keys.py) of what the image shows: nothing of descgen but the
        # renderer's version and no library's, since check rebuilds and compares this record
        # every time (the PNG, which matplotlib's version changes, is never compared)
        digest = keys.key("pose image", RENDERER_VERSION, inputs, (), keys.NOTHING)
        poses[kp.name] = {
            "image": f"{kp.name}.png",
            "inputs_sha256": digest,
            "joints": inputs["joints"],
            "markers": inputs["markers"],
        }
    return json.dumps({"renderer": RENDERER_VERSION, "poses": poses}, indent=2, sort_keys=True) + "\n"


def embeds(robot: Robot) -> list[str]:
    """The page's Markdown for the images (relative to evidence/README.md); a pose name is an
    identifier (the schema's Name), escaped all the same as Markdown text and a link target."""
    from descgen.render.formatting import mddest, mdtext

    return [f"![{mdtext(kp.name)}]({mddest(f'poses/{kp.name}.png')})" for kp in robot.known_poses]


# -- drawing ------------------------------------------------------------------------------


def _draw(s: Scene, target: Path) -> None:
    import matplotlib
    import numpy as np

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(5.5, 5.0))
    ax: Any = fig.add_subplot(projection="3d")
    for parent, child in s.bones:
        a, b = s.links[parent], s.links[child]
        ax.plot(*zip(a, b, strict=True), color="0.35", linewidth=2)
    pts = np.array(list(s.links.values()) or [(0.0, 0.0, 0.0)])
    ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], s=8, color="0.35")
    for m in s.markers:
        if m.model_in_root is not None:
            ax.scatter(*m.model_in_root, marker="o", s=40, label=f"{m.frame} model")
        if m.measured_in_root is not None:
            ax.scatter(*m.measured_in_root, marker="x", s=60, label=f"{m.frame} measured ({m.verdict})")
        pts = np.vstack([pts, *(p for p in (m.model_in_root, m.measured_in_root) if p is not None)])
    _equal_axes(ax, pts)
    ax.view_init(elev=20, azim=-60)  # fixed: images of different poses compare at a glance
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_title(f"known pose '{s.pose.name}'")
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    tmp = target.with_name(f".{target.name}.tmp")
    fig.savefig(tmp, dpi=80, format="png")
    plt.close(fig)
    tmp.replace(target)


def _equal_axes(ax: Any, pts: np.ndarray) -> None:
    """One metre is as long on every axis, so a wrong offset looks as wrong as it is."""
    centre = (pts.max(axis=0) + pts.min(axis=0)) / 2
    half = max(float((pts.max(axis=0) - pts.min(axis=0)).max()) / 2, 0.05)
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre, strict=True):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))


def write(package: Path, robot: Robot) -> list[str]:
    """Every pose's image and the sidecar; old images of poses no longer in the spec go."""
    folder = package / FOLDER
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for kp in robot.known_poses:
        _draw(scene(robot, kp), package / image_rel(kp.name))
        written.append(image_rel(kp.name))
    keep = {f"{kp.name}.png" for kp in robot.known_poses}
    for old in folder.glob("*.png"):
        if old.name not in keep and not old.is_symlink():
            old.unlink()
    tmp = folder / ".poses.json.tmp"
    tmp.write_text(record(robot), encoding="utf-8")
    tmp.replace(package / SIDECAR)
    return [*written, SIDECAR]


# -- checking -----------------------------------------------------------------------------


def _finding(code: str, package: Path, rel: str, what: str) -> Finding:
    return Finding(
        code,
        "error",
        f"{rel} {what}",
        "run descgen report SPEC and commit the result",
        f"file:{rel}",
        Where(str(package / rel)),
    )


def stale(package: Path, robot: Robot) -> list[Finding]:
    """GEN006 for a missing image or record, GEN080 when the record differs from the inputs
    the spec gives now. PNG bytes are not read."""
    found = [
        _finding("GEN006", package, image_rel(kp.name), "is missing")
        for kp in robot.known_poses
        if not (package / image_rel(kp.name)).is_file()
    ]
    target = package / SIDECAR
    if not robot.known_poses and not target.exists():
        return found
    if not target.is_file() or target.is_symlink():
        return [*found, _finding("GEN006", package, SIDECAR, "is missing")]
    if target.stat().st_size > _MAX_SIDECAR_BYTES:
        return [*found, _finding("GEN080", package, SIDECAR, "is stale: not a record descgen wrote (too large)")]
    now = target.read_text(encoding="utf-8", errors="replace")
    if now != record(robot):
        what = "is stale: a known pose, the model or a measured position changed since the images were drawn"
        found.append(_finding("GEN080", package, SIDECAR, what))
    return found
