"""`descgen view` serves its own page only (issue 34, item 5): a websocket handshake from another
site's page (its Origin) and a request with another host name (DNS rebinding) are refused; a
mesh the resolver refuses (absolute, file://, ``..``, a package that is not found) is never
opened, and a malformed or over-bound mesh is a finding, not a traceback, read within bounds.
Every server here listens on 127.0.0.1 at a port the OS picks."""

from __future__ import annotations

import http.client
import os
import struct
import sys
import tracemalloc
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from descgen.commands.view import load, mesh_plan

from .conftest import ROOT
from .helpers import view_until_url_then_ctrl_c

SPEC = ROOT / "specs" / "warehouse_arm.yaml"
SECRET = 777.0  # a coordinate only the file outside the package has


def _stl(path: Path, at: float = 0.0, size: float = 0.1) -> Path:
    """A binary STL of one tetrahedron with a corner at (at, at, at)."""
    p = [(at, at, at), (at + size, at, at), (at, at + size, at), (at, at, at + size)]
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    data = bytearray(b"\0" * 80 + struct.pack("<I", len(faces)))
    for f in faces:
        data += struct.pack("<3f", 0, 0, 0)
        for i in f:
            data += struct.pack("<3f", *p[i])
        data += b"\0\0"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(bytes(data))
    return path


def _urdf(meshes: dict[str, str]) -> str:
    """A robot whose link ``l_<key>`` has the visual mesh ``filename``, on a fixed joint to base."""
    parts = ['<robot name="r">', '<link name="base"/>']
    for key, filename in meshes.items():
        parts.append(
            f'<link name="l_{key}"><visual><geometry><mesh filename="{filename}"/></geometry></visual></link>'
            f'<joint name="j_{key}" type="fixed"><parent link="base"/><child link="l_{key}"/></joint>'
        )
    parts.append("</robot>")
    return "\n".join(parts)


@pytest.fixture
def tree(tmp_path: Path) -> dict[str, Path]:
    """pkg/ (package.xml, urdf/, meshes/ok.stl), outside/secret.stl beside it, and a sibling
    package sibling/ (package.xml, meshes/secret.stl) that no package path names."""
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    _stl(pkg / "meshes" / "ok.stl")
    secret = _stl(tmp_path / "outside" / "secret.stl", SECRET)
    (tmp_path / "sibling").mkdir()
    (tmp_path / "sibling" / "package.xml").write_text("<package><name>sibling</name></package>")
    sibling = _stl(tmp_path / "sibling" / "meshes" / "secret.stl", SECRET)
    return {"root": tmp_path, "pkg": pkg, "secret": secret, "sibling": sibling}


def _viser() -> None:
    if os.environ.get("DESCGEN_REQUIRE_TOOLS") != "1":
        pytest.importorskip("viser")


@pytest.fixture
def viewer() -> Iterator[Any]:
    _viser()
    from descgen.commands.view.server import start

    robot, urdf = load(SPEC)
    view = start(robot, urdf, "127.0.0.1", 0)
    try:
        yield view
    finally:
        view.close()


def _request(port: int, headers: dict[str, str]) -> tuple[int, bytes]:
    """GET / on 127.0.0.1:port with exactly these headers (Host included)."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    try:
        conn.putrequest("GET", "/", skip_host=True, skip_accept_encoding=True)
        for k, v in headers.items():
            conn.putheader(k, v)
        conn.endheaders()
        resp = conn.getresponse()
        return resp.status, resp.read()
    finally:
        conn.close()


# -- (a) Origin, (b) Host ------------------------------------------------------------------------


def _handshake(port: int, origin: str | None, host: str | None = None) -> int:
    """The HTTP status of a websocket handshake (101: accepted): made by the websockets client,
    or by hand when ``host`` is given (the client writes its own Host header)."""
    import viser

    protocol = f"viser-v{viser.__version__}"
    if host is not None:
        headers = {
            "Host": host,
            "Upgrade": "websocket",
            "Connection": "Upgrade",
            "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ==",
            "Sec-WebSocket-Version": "13",
            "Sec-WebSocket-Protocol": protocol,
        }
        if origin is not None:
            headers["Origin"] = origin
        return _request(port, headers)[0]
    from websockets.exceptions import InvalidStatus
    from websockets.sync.client import connect

    try:
        with connect(
            f"ws://127.0.0.1:{port}",
            origin=origin,  # type: ignore[arg-type]
            subprotocols=[protocol],  # type: ignore[list-item]
            open_timeout=10,
        ) as ws:
            assert ws.response is not None
            return ws.response.status_code
    except InvalidStatus as exc:
        return exc.response.status_code


def test_a_websocket_from_another_sites_page_is_refused_the_viewers_own_accepted(viewer: Any) -> None:
    port = viewer.server.get_port()
    assert _handshake(port, "http://evil.example") == 403
    assert _handshake(port, f"http://evil.example:{port}") == 403
    assert _handshake(port, "null") == 403  # a sandboxed frame or a file:// page
    assert _handshake(port, None) == 403  # browsers always send one; without it, no page vouches
    assert _handshake(port, f"http://127.0.0.1:{port}") == 101
    # the page as opened through localhost: its origin is http://localhost:PORT
    assert _handshake(port, f"http://localhost:{port}", host=f"localhost:{port}") == 101
    # an origin of the right host but another port (another local server's page) is another site
    assert _handshake(port, f"http://127.0.0.1:{port + 1}") == 403


def test_a_request_naming_another_host_is_refused_dns_rebinding(viewer: Any) -> None:
    port = viewer.server.get_port()
    status, body = _request(port, {"Host": "evil.example"})
    assert status == 403 and b"<html" not in body.lower()
    status, _ = _request(port, {"Host": f"evil.example:{port}"})  # evil.example rebound to 127.0.0.1
    assert status == 403
    status, _ = _request(port, {"Host": f"127.0.0.1:{port + 1}"})
    assert status == 403
    status, _ = _request(port, {})  # no Host at all
    assert status in (400, 403)
    status, body = _request(port, {"Host": f"127.0.0.1:{port}"})
    assert status == 200 and b"<html" in body.lower()
    status, _ = _request(port, {"Host": f"localhost:{port}"})
    assert status == 200
    status, _ = _request(port, {"Host": f"LOCALHOST:{port}"})  # host names are case-insensitive
    assert status == 200
    # a same-host request carrying another site's Origin (a cross-site fetch) is refused too
    status, _ = _request(port, {"Host": f"127.0.0.1:{port}", "Origin": "http://evil.example"})
    assert status == 403
    # the websocket handshake is held to Host as well
    assert _handshake(port, f"http://evil.example:{port}", host=f"evil.example:{port}") == 403


def test_the_guard_is_gone_from_websockets_after_the_server_started(viewer: Any) -> None:
    """The wrapper is in place only while viser builds its server: websockets is left as it was."""
    import websockets.asyncio.server as wss

    assert wss.serve.__module__.startswith("websockets")


def test_the_share_button_cannot_open_a_public_tunnel(viewer: Any) -> None:
    from viser import _messages

    assert _messages.ShareUrlRequest not in viewer.server._websock_server._incoming_handlers


def test_allowed_hosts_by_hand() -> None:
    from descgen.commands.view.server import allowed_hosts, refusal

    assert allowed_hosts("127.0.0.1", 8080) == {"127.0.0.1:8080", "localhost:8080", "[::1]:8080"}
    assert allowed_hosts("::1", 80) >= {"[::1]:80", "localhost", "[::1]", "127.0.0.1"}
    assert allowed_hosts("192.168.1.5", 8080) == {"192.168.1.5:8080"}  # not loopback: no localhost
    assert allowed_hosts("::ffff:10.0.0.2", 9000) == {"10.0.0.2:9000"}
    assert "robot-pc:8080" in allowed_hosts("192.168.1.5", 8080, ["Robot-PC"])
    ok = {"Host": "127.0.0.1:8080", "Origin": "http://127.0.0.1:8080", "Upgrade": "websocket"}
    assert refusal(ok, "127.0.0.1", 8080) is None
    assert refusal({**ok, "Origin": "https://127.0.0.1:8080"}, "127.0.0.1", 8080) is not None
    assert refusal({**ok, "Host": "127.0.0.1.evil.example:8080"}, "127.0.0.1", 8080) is not None


# -- (c) meshes the resolver refuses are never opened --------------------------------------------


def _opened_during(fn: Any) -> tuple[Any, list[str]]:
    """``fn()`` and every path this process opened meanwhile (Python's audit hook sees open()
    and os.open() of every library, trimesh's and yourdfpy's included)."""
    seen: list[str] = []
    live = [True]

    def hook(event: str, args: tuple[Any, ...]) -> None:
        if live[0] and event == "open" and args and isinstance(args[0], (str, bytes, os.PathLike)):
            seen.append(os.fsdecode(args[0]))

    sys.addaudithook(hook)  # hooks cannot be removed: this one goes quiet after fn
    try:
        return fn(), seen
    finally:
        live[0] = False


def _vertices(scene: Any) -> np.ndarray:
    arrays = [np.asarray(g.vertices) for g in scene.geometry.values()] if scene is not None else []
    return np.concatenate(arrays) if arrays else np.zeros((0, 3))


def test_meshes_outside_the_package_are_not_opened_nor_served(tree: dict[str, Path]) -> None:
    _viser()
    from descgen.commands.view.server import start

    secret, sibling = tree["secret"], tree["sibling"]
    urdf = tree["pkg"] / "urdf" / "robot.urdf"
    (tree["pkg"] / "meshes" / "link.stl").symlink_to(secret)  # a link out of the package
    urdf.write_text(
        _urdf(
            {
                "ok": "../meshes/ok.stl",
                "link_out": "../meshes/link.stl",
                "absolute": str(secret),
                "file_uri": f"file://{secret}",
                "dotdot": "../../outside/secret.stl",
                "sibling_relative": "../../sibling/meshes/secret.stl",
                "sibling_package": "package://sibling/meshes/secret.stl",  # not on any package path
                "etc": "/etc/passwd",
            }
        )
    )
    robot, text = load(urdf)
    printed: list[Any] = []
    view, opened = _opened_during(lambda: start(robot, text, "127.0.0.1", 0, urdf.parent, report=printed.extend))
    try:
        outside = {str(secret), str(sibling), "/etc/passwd"}
        assert not outside & {os.path.realpath(p) for p in opened}, opened
        codes = {f.message.split("'")[1]: f.code for f in view.findings}
        assert codes == {
            "l_link_out": "GEOM004",
            "l_absolute": "GEOM004",
            "l_file_uri": "GEOM004",
            "l_dotdot": "GEOM004",
            "l_sibling_relative": "GEOM004",
            "l_sibling_package": "GEOM005",
            "l_etc": "GEOM004",
        }
        assert [f.code for f in printed] == [f.code for f in view.findings]  # printed too
        # what the scene holds: the one mesh inside the package, nothing of the outside file
        model = view.urdf._urdf
        seen = _vertices(model.scene)
        assert len(model.scene.geometry) == 1 and seen.max() == pytest.approx(0.1, abs=1e-6)
        assert not np.any(np.isclose(_vertices(model.collision_scene), SECRET))
        # and the link without its mesh is still drawn (its frame is in the scene graph)
        assert "l_dotdot" in model.scene.graph.nodes
    finally:
        view.close()


def test_a_spec_with_a_mesh_outside_its_folder_is_refused_before_serving(tmp_path: Path) -> None:
    """A spec's meshes are resolved by validate's rules: one outside its folder stops view at load."""
    from descgen.core.findings import InputError

    text = SPEC.read_text(encoding="utf-8")
    _stl(tmp_path / "outside.stl")
    (tmp_path / "specs").mkdir()
    spec = tmp_path / "specs" / "arm.yaml"
    marker = "        geometry: {box: {size: [600 mm, 450 mm, 200 mm]}}"
    assert marker in text
    spec.write_text(text.replace(marker, "        geometry: {mesh: {filename: ../outside.stl}}", 1))
    with pytest.raises(InputError) as caught:
        load(spec)
    assert "SPEC061" in {f.code for f in caught.value.findings}


# -- (d) malformed and over-bound meshes ---------------------------------------------------------


def test_malformed_and_over_bound_stl_are_findings_read_within_bounds(tree: dict[str, Path]) -> None:
    _viser()
    from descgen.commands.view.server import start

    meshes = tree["pkg"] / "meshes"
    (meshes / "garbage.stl").write_bytes(b"\x00\x01not a mesh" * 20)
    huge_count = bytearray(b"\0" * 80 + struct.pack("<I", 0xFFFFFFFF) + b"\0" * 50)
    (meshes / "count.stl").write_bytes(bytes(huge_count))
    with open(meshes / "sparse.stl", "wb") as f:  # 125 MB, no block on disk: over the 64 MiB bound
        f.write(b"\0" * 80 + struct.pack("<I", 2_500_000))
        f.truncate(125 * 1000 * 1000)
    urdf = tree["pkg"] / "urdf" / "robot.urdf"
    urdf.write_text(
        _urdf(
            {
                "ok": "../meshes/ok.stl",
                "garbage": "../meshes/garbage.stl",
                "count": "../meshes/count.stl",
                "sparse": "package://pkg/meshes/sparse.stl",
            }
        )
    )
    robot, text = load(urdf)
    tracemalloc.start()
    try:
        _, found = mesh_plan(robot)
        view = start(robot, text, "127.0.0.1", 0, report=lambda _: None)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    try:
        by_link = {f.message.split("'")[1]: f for f in view.findings}
        assert set(by_link) == {"l_garbage", "l_count", "l_sparse"}
        assert all(f.code == "GEOM033" for f in by_link.values())
        assert "4294967295 triangles" in by_link["l_count"].message
        assert "125.0 MB" in by_link["l_sparse"].message and "64 MiB" in by_link["l_sparse"].message
        assert [f.message for f in found] == [f.message for f in view.findings]
        assert peak < 64 * 1024 * 1024, peak  # not the 125 MB file, nor an array of 4 G triangles
        assert len(view.urdf._urdf.scene.geometry) == 1
    finally:
        view.close()


@pytest.mark.e2e
def test_view_prints_the_mesh_findings_and_serves_without_a_traceback(tree: dict[str, Path]) -> None:
    meshes = tree["pkg"] / "meshes"
    (meshes / "garbage.stl").write_bytes(b"\x00\x01not a mesh" * 20)
    urdf = tree["pkg"] / "urdf" / "robot.urdf"
    urdf.write_text(_urdf({"ok": "../meshes/ok.stl", "garbage": "../meshes/garbage.stl", "out": "/etc/passwd"}))
    code, err = view_until_url_then_ctrl_c(urdf)
    assert code == 0 and "Traceback" not in err, err
    assert "info[GEOM033]" in err and "garbage.stl" in err
    assert "error[GEOM004]" in err and "/etc/passwd" in err
