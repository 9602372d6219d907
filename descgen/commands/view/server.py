"""The viser scene of ``descgen view``: the robot (visual and collision), a slider per independent
joint, a button per known pose and SRDF state, link frames with names, joint axes as arrows, and
each known pose's measured positions as markers beside the model's frames with the error.

The server answers only its own page (docs/security.md, "descgen view"):

* it binds 127.0.0.1 unless ``--host`` says otherwise;
* every HTTP request and websocket handshake must carry a ``Host`` that names the address the
  request arrived on (or ``localhost`` on a loopback address), or the address it is bound to,
  with the server's port, or a name given to :func:`start` (``allowed``): a page of another
  site whose name was rebound to this address (DNS rebinding) sends its own name and is
  refused with 403;
* a websocket handshake must carry ``Origin: http://<that Host>``, and any other request that
  carries an ``Origin`` must carry that one: a page of another site cannot open the websocket
  through the user's browser and read the scene (403);
* viser's share button (a public tunnel through share.viser.studio) is hidden and its message
  ignored.

viser offers no hook for this: it builds its ``websockets`` server inside its own thread, with
its own ``process_request`` (the static client files). So while the ``ViserServer`` is made,
:func:`_guarded_serve` puts a wrapper in place of ``websockets.asyncio.server.serve`` that runs
:func:`refusal` before viser's ``process_request`` on every request; the original is restored
as soon as the server is listening (the server keeps the wrapped hook for its lifetime). If
viser stops building its server through that function the viewer refuses to start rather than
serve unguarded.
"""

from __future__ import annotations

import contextlib
import http
import io
import ipaddress
import math
import sys
import threading
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from descgen.commands.view import joint_axes, markers, mesh_plan, presets, sliders
from descgen.core.findings import Finding
from descgen.core.model import Robot

if TYPE_CHECKING:
    from descgen.meshes.load import Loaded

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
    findings: list[Finding] = field(default_factory=list)  # meshes not shown, and why
    _lock: threading.Lock = field(default_factory=threading.Lock)

    @property
    def url(self) -> str:
        host = str(self.server.get_host())
        return f"http://{f'[{host}]' if ':' in host else host}:{self.server.get_port()}"

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
            from descgen.physics import mimic

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
    from descgen.commands.view import frames

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
        v.server.scene.add_label(f"{base}/error", f"{m.frame}: {m.verdict}", position=m.measured)
        v.marker_nodes[base] = (np.array(m.model), np.array(m.measured))


def _preset(v: Viewer, values: dict[str, float], pose: str | None) -> Callable[[Any], None]:
    return lambda _: v.set_joints(values, pose)


# -- who may talk to the server --------------------------------------------------------------------


def allowed_hosts(local: str, port: int, extra: Sequence[str] = ()) -> frozenset[str]:
    """The ``Host`` values (lower case) of a request that arrived on ``local`` (an IP address)
    at ``port``: that address, ``localhost`` and the loopback addresses when it is one, and the
    names in ``extra``; each with ``:port`` (and bare on port 80, which browsers leave out)."""
    try:
        ip = ipaddress.ip_address(local.split("%", 1)[0])
    except ValueError:
        ip = None
    if isinstance(ip, ipaddress.IPv6Address) and ip.ipv4_mapped is not None:
        ip = ip.ipv4_mapped
    names: set[str] = set()
    if ip is not None:
        names.add(f"[{ip}]" if ip.version == 6 else str(ip))
        if ip.is_loopback:
            names |= {"localhost", "127.0.0.1", "[::1]"}
    names |= {n.lower().strip() for n in extra if n.strip()}
    out = {f"{n}:{port}" for n in names}
    if port == 80:
        out |= names
    return frozenset(out)


def refusal(headers: Any, local: str, port: int, extra: Sequence[str] = ()) -> str | None:
    """Why a request (its headers: a ``websockets`` ``Headers`` or a mapping) that arrived on
    ``local``:``port`` is refused, or None when it is the viewer's own page talking."""
    hosts = headers.get_all("Host") if hasattr(headers, "get_all") else [headers.get("Host")]
    hosts = [h for h in hosts if h is not None]
    if len(hosts) != 1:
        return "a request needs exactly one Host header"
    host = hosts[0].strip().lower()
    if host not in allowed_hosts(local, port, extra):
        return f"Host {host[:100]!r} is not this viewer's address (DNS rebinding?)"
    origins = headers.get_all("Origin") if hasattr(headers, "get_all") else [headers.get("Origin")]
    origins = [o for o in origins if o is not None]
    websocket = str(headers.get("Upgrade") or "").strip().lower() == "websocket"
    if websocket and not origins:
        return "a websocket handshake needs the Origin header of the viewer's own page"
    if origins and (len(origins) != 1 or origins[0].strip().lower() != f"http://{host}"):
        return "Origin is not the viewer's own page (a page of another site?)"
    return None


def _guard(inner: Callable[..., Any] | None, extra: Sequence[str]) -> Callable[..., Any]:
    """``process_request`` that refuses with 403 what :func:`refusal` refuses, then runs ``inner``."""

    def process_request(connection: Any, request: Any) -> Any:
        local = connection.local_address  # the socket the request arrived on: (address, port, ...)
        why = refusal(request.headers, str(local[0]), int(local[1]), extra)
        if why is not None:
            return connection.respond(http.HTTPStatus.FORBIDDEN, f"descgen view: {why}\n")
        return inner(connection, request) if inner is not None else None

    return process_request


_SERVE_LOCK = threading.Lock()


@contextlib.contextmanager
def _guarded_serve(extra: Sequence[str]) -> Iterator[list[bool]]:
    """While a ViserServer is made: ``websockets.asyncio.server.serve`` wraps the
    ``process_request`` it is given with :func:`_guard`. Yields a list that holds True once
    a server was started through it."""
    import websockets.asyncio.server as wss

    real = wss.serve
    used: list[bool] = []

    def serve(handler: Any, host: Any = None, port: Any = None, *args: Any, **kwargs: Any) -> Any:
        kwargs["process_request"] = _guard(kwargs.get("process_request"), extra)
        used.append(True)
        return real(handler, host, port, *args, **kwargs)

    with _SERVE_LOCK:
        wss.serve = serve  # type: ignore[misc,assignment]
        try:
            yield used
        finally:
            wss.serve = real  # type: ignore[misc]


def _server(host: str, port: int, label: str, extra: Sequence[str]) -> Any:
    """A ViserServer listening on ``host``:``port`` whose every request passes :func:`refusal`."""
    import viser

    # the address it is bound to, as the URL it prints names it (http://0.0.0.0:8080 reaches it too):
    # an IP literal (cli_types.host), so no name lookup can move it
    extra = (*extra, f"[{host}]" if ":" in host else host)
    with _guarded_serve(extra) as used:
        server = viser.ViserServer(host=host, port=port, label=label, verbose=False)
    if not used:  # viser no longer serves through websockets.asyncio.server.serve: do not serve unguarded
        server.stop()
        raise RuntimeError(
            f"viser {getattr(viser, '__version__', '?')} does not build its server through "
            "websockets.asyncio.server.serve; descgen view cannot check Host and Origin with it"
        )
    # the share button opens a public tunnel (share.viser.studio) to this server: never
    with contextlib.suppress(Exception):
        server.gui.configure_theme(show_share_button=False)
    from viser import _messages

    for message in ("ShareUrlRequest", "ShareUrlDisconnect"):
        cls = getattr(_messages, message, None)
        if cls is not None and cls in server._websock_server._incoming_handlers:
            server._websock_server.unregister_handler(cls)
    return server


# -- the scene ------------------------------------------------------------------------------------


def _urdf_model(urdf_text: str, shown: dict[str, Loaded]) -> Any:
    """yourdfpy's model of the URDF without a single file read by yourdfpy or trimesh: its
    primitives, and the meshes of ``shown`` (already read and bounded by descgen.meshes.load)."""
    import trimesh
    import yourdfpy

    from descgen.read.urdf import parse_xml

    # yourdfpy parses with lxml's defaults (entities resolved): the text passes descgen's own
    # parser first (no DTD, no entity; READ002 at exit 2). The readers refused one already.
    parse_xml(urdf_text.encode("utf-8"), "the URDF shown by descgen view")
    model = yourdfpy.URDF.load(
        io.BytesIO(urdf_text.encode("utf-8")),
        filename_handler=lambda fname: "",  # no name reaches the file system (no mesh is loaded by yourdfpy)
        build_scene_graph=True,
        build_collision_scene_graph=True,
        load_meshes=False,
        load_collision_meshes=False,
    )
    materials = {m.name: m for m in model.robot.materials if m.name is not None}
    for link in model.robot.links:
        for kind, shapes, scene in (
            ("visual", link.visuals, model.scene),
            ("collision", link.collisions, model.collision_scene),
        ):
            for i, shape in enumerate(shapes):
                mesh = shape.geometry.mesh if shape.geometry is not None else None
                if mesh is None or mesh.filename not in shown or scene is None:
                    continue
                loaded = shown[mesh.filename]
                geom = trimesh.Trimesh(loaded.vertices.copy(), loaded.faces.copy(), process=False)
                unit = loaded.facts.unit_meter or 1.0
                scale = np.ones(3) if mesh.scale is None else np.broadcast_to(np.asarray(mesh.scale, float), (3,))
                geom.apply_scale(scale * unit)  # type: ignore[no-untyped-call]
                if kind == "visual":
                    _colour(geom, shape, materials)
                name = f"{link.name}/{kind}/{i}"
                while name in scene.geometry or name in scene.graph.nodes:
                    name += "_"
                origin = shape.origin if shape.origin is not None else np.eye(4)
                scene.add_geometry(geom, node_name=name, geom_name=name, parent_node_name=link.name, transform=origin)
    return model


def _colour(geom: Any, visual: Any, materials: dict[str, Any]) -> None:
    material = visual.material
    color = None
    if material is not None:
        color = material.color
        if color is None and material.name in materials:
            color = materials[material.name].color
    if color is not None and color.rgba is not None:
        geom.visual.face_colors = [int(255 * min(max(float(c), 0.0), 1.0)) for c in color.rgba]


def _print(findings: Sequence[Finding]) -> None:
    from descgen.output.report import text

    sys.stderr.write(text(findings))
    sys.stderr.flush()


def start(
    robot: Robot,
    urdf_text: str,
    host: str = "127.0.0.1",
    port: int = 8080,
    urdf_dir: Path | None = None,
    *,
    allowed: Sequence[str] = (),
    report: Callable[[Sequence[Finding]], None] = _print,
) -> Viewer:
    """Start the server (bound to ``host``, loopback by default) and build the scene and the
    controls. The meshes shown are those the resolver accepted for ``robot``
    (:func:`descgen.commands.view.mesh_plan`); ``urdf_dir`` is not searched (kept for callers). Every mesh
    not shown is a finding: given to ``report`` (printed) and listed on the page. ``allowed``:
    further host names a browser may use in ``Host`` (e.g. the machine's name when bound to
    another address with ``--host``)."""
    from viser.extras import ViserUrdf

    del urdf_dir  # meshes come from robot.mesh_files only: no search beside the file
    shown, findings = mesh_plan(robot)
    model = _urdf_model(urdf_text, shown)
    if findings:
        report(findings)
    server = _server(host, port, f"descgen view: {robot.name}", allowed)
    v = Viewer(server, robot, findings=list(findings))
    v.urdf = ViserUrdf(server, model, root_node_name="/robot", load_collision_meshes=True)
    v.urdf.show_collision = False
    server.scene.add_grid("/grid", width=2.0, height=2.0, cell_size=0.1)
    server.initial_camera.position = (1.6, -1.6, 1.3)
    server.initial_camera.look_at = (0.0, 0.0, 0.4)
    gui = server.gui
    if findings:
        from descgen.output.report import printable

        # plain text fields (never Markdown or HTML: a mesh name is someone else's text)
        with gui.add_folder(f"meshes not shown ({len(findings)})"):
            for f in findings:
                gui.add_text(f"{f.severity}[{f.code}]", printable(f.message), multiline=True, disabled=True)
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
