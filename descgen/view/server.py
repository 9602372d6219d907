"""The viser scene of ``descgen view``: the robot (visual and collision), a slider per independent
joint, a button per known pose and SRDF state, link frames with names, joint axes as arrows, and
each known pose's measured positions as markers beside the model's frames with the error."""

from __future__ import annotations

import io
import math
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..model import Robot
from . import joint_axes, markers, presets, sliders

MEASURED = (220, 40, 40)  # red: where the robot was measured
MODEL = (40, 110, 220)  # blue: where the model puts the frame


@dataclass
class Viewer:
    """A running viewer: the server, its handles and the joint values now shown."""

    server: Any
    robot: Robot
    q: dict[str, float] = field(default_factory=dict)
    sliders: dict[str, Any] = field(default_factory=dict)
    buttons: dict[str, Any] = field(default_factory=dict)
    marker_nodes: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)  # name -> (model, measured)
    pose: str | None = None
    urdf: Any = None
    _lock: threading.Lock = field(default_factory=threading.Lock)

    @property
    def url(self) -> str:
        return f"http://{self.server.get_host()}:{self.server.get_port()}"

    def set_joints(self, values: dict[str, float], pose: str | None = None) -> None:
        """Set sliders (and through them the robot) to ``values``; others to zero, within limits."""
        with self._lock:
            for name, handle in self.sliders.items():
                v = float(values.get(name, 0.0))
                handle.value = min(max(v, handle.min), handle.max)
        self.pose = pose
        self._refresh()

    def _refresh(self) -> None:
        self.q = {name: float(h.value) for name, h in self.sliders.items()}
        if self.urdf is not None:
            names = self.urdf.get_actuated_joint_names()
            from .. import mimic

            full = mimic.resolve(self.robot, self.q)
            self.urdf.update_cfg(np.array([full.get(n, 0.0) for n in names], dtype=float))
        _draw_frames(self)
        _draw_markers(self)

    def close(self) -> None:
        self.server.stop()


def _quat(r: np.ndarray) -> tuple[float, float, float, float]:
    """wxyz of a rotation matrix (Shepperd's method, stable for every rotation)."""
    m = r
    t = float(np.trace(m))
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        return (0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s)
    i = int(np.argmax(np.diag(m)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + m[i, i] - m[j, j] - m[k, k]) * 2
    q = [0.0, 0.0, 0.0, 0.0]
    q[0] = (m[k, j] - m[j, k]) / s
    q[i + 1] = 0.25 * s
    q[j + 1] = (m[j, i] + m[i, j]) / s
    q[k + 1] = (m[k, i] + m[i, k]) / s
    return (q[0], q[1], q[2], q[3])


def _draw_frames(v: Viewer) -> None:
    from . import frames

    show_axes = bool(v.buttons["frame axes"].value)
    show_names = bool(v.buttons["frame names"].value)
    for link, t in frames(v.robot, v.q).items():
        v.server.scene.add_frame(
            f"/frames/{link}",
            show_axes=show_axes,
            axes_length=0.08,
            axes_radius=0.004,
            wxyz=_quat(t[:3, :3]),
            position=tuple(t[:3, 3]),
        )
        v.server.scene.add_label(f"/frames/{link}/name", link, visible=show_names)
    axes = joint_axes(v.robot, v.q)
    if axes:
        pts = np.array([[o, np.add(o, np.multiply(d, 0.15))] for _, o, d in axes], dtype=float)
        v.server.scene.add_arrows(
            "/joint_axes",
            pts,
            (250, 200, 0),
            shaft_radius=0.004,
            head_radius=0.012,
            head_length=0.03,
            visible=bool(v.buttons["joint axes"].value),
        )


def _draw_markers(v: Viewer) -> None:
    for name in list(v.marker_nodes):
        v.server.scene.remove_by_name(name)
    v.marker_nodes.clear()
    if v.pose is None:
        return
    for m in markers(v.robot, v.pose):
        base = f"/markers/{m.frame}"
        v.server.scene.add_icosphere(f"{base}/measured", radius=0.012, color=MEASURED, position=m.measured)
        v.server.scene.add_icosphere(f"{base}/model", radius=0.009, color=MODEL, position=m.model)
        verdict = "ok" if m.error_mm <= m.tolerance_mm else "OFF"
        v.server.scene.add_label(
            f"{base}/error", f"{m.frame}: {m.error_mm:.1f} mm (tol {m.tolerance_mm:g}) {verdict}", position=m.measured
        )
        v.marker_nodes[base] = (np.array(m.model), np.array(m.measured))


def _preset(v: Viewer, values: dict[str, float], pose: str | None) -> Callable[[Any], None]:
    return lambda _: v.set_joints(values, pose)


def start(robot: Robot, urdf_text: str, host: str, port: int, urdf_dir: Path | None = None) -> Viewer:
    """Start the server (bound to ``host``) and build the scene and the controls."""
    import viser
    import yourdfpy
    from viser.extras import ViserUrdf

    server = viser.ViserServer(host=host, port=port, label=f"descgen view: {robot.name}", verbose=False)
    v = Viewer(server, robot)
    handler: Callable[[str], str] | None = None
    if urdf_dir is not None:
        from functools import partial

        handler = partial(yourdfpy.filename_handler_magic, dir=str(urdf_dir))
    model = yourdfpy.URDF.load(
        io.BytesIO(urdf_text.encode("utf-8")),
        filename_handler=handler,
        build_collision_scene_graph=True,
        load_collision_meshes=True,
    )
    v.urdf = ViserUrdf(server, model, root_node_name="/robot", load_collision_meshes=True)
    v.urdf.show_collision = False
    server.scene.add_grid("/grid", width=2.0, height=2.0, cell_size=0.1)
    server.initial_camera.position = (1.6, -1.6, 1.3)
    server.initial_camera.look_at = (0.0, 0.0, 0.4)
    gui = server.gui
    with gui.add_folder("show"):
        for label, initial in (("visual", True), ("collision", False), ("frame axes", True), ("frame names", False)):
            v.buttons[label] = gui.add_checkbox(label, initial)
        v.buttons["joint axes"] = gui.add_checkbox("joint axes", True)
    v.buttons["visual"].on_update(lambda _: setattr(v.urdf, "show_visual", bool(v.buttons["visual"].value)))
    v.buttons["collision"].on_update(lambda _: setattr(v.urdf, "show_collision", bool(v.buttons["collision"].value)))
    for label in ("frame axes", "frame names", "joint axes"):
        v.buttons[label].on_update(lambda _: _draw_frames(v))
    with gui.add_folder("joints"):
        for s in sliders(robot):
            step = 0.001 if s.prismatic else math.radians(0.5)
            h = gui.add_slider(
                s.joint, min=s.lower, max=s.upper, step=step, initial_value=min(max(0.0, s.lower), s.upper)
            )
            h.on_update(lambda _: v._refresh())
            v.sliders[s.joint] = h
    with gui.add_folder("poses"):
        for label, values in presets(robot).items():
            b = gui.add_button(label)
            pose = label.removeprefix("pose: ") if label.startswith("pose: ") else None
            b.on_click(_preset(v, values, pose))
            v.buttons[label] = b
    v._refresh()
    return v
