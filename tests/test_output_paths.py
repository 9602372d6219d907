"""Outputs are written only where the user asked, and only as regular files (issue 34, items 4,
8 and the linked ``control --out``).

- a joint name never becomes a path: ``descgen control`` with a joint named ``../../../x``
  wrote its plot outside the evidence folder, and one named ``wrist/pitch`` was a traceback;
- ``control --out DIR`` with ``DIR/control_run`` (or any entry) a symbolic link, FIFO or device
  is CTRL035 before anything is written;
- ``import -o PATH --force`` replaces only a regular file: a FIFO, a symbolic link or a device
  node is IMP033 (exit 2) and stays as it was.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from descgen.infra.safeio import output_file, safe_file_name

from .helpers import EXAMPLE_TEXT, cli

ROOT = Path(__file__).resolve().parents[1]
READY = (ROOT / "specs" / "trajectories" / "ready.yaml").read_text()
PKG = "warehouse_arm_description"


def _project(root: Path, elbow: str = "elbow_joint") -> Path:
    """The example robot with its elbow joint renamed, generated into root/generated."""
    (root / "specs" / "trajectories").mkdir(parents=True)
    (root / "specs" / "warehouse_arm.yaml").write_text(EXAMPLE_TEXT.replace("elbow_joint", elbow))
    (root / "specs" / "trajectories" / "ready.yaml").write_text(READY.replace("elbow_joint", elbow))
    r = cli("generate", "specs/warehouse_arm.yaml", cwd=root)
    assert r.returncode == 0, r.stdout + r.stderr
    return root / "generated" / PKG


def _files(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def _control(root: Path, *more: str):  # type: ignore[no-untyped-def]
    return cli("control", "specs/warehouse_arm.yaml", "--trajectory", "specs/trajectories/ready.yaml", *more, cwd=root)


@pytest.mark.parametrize("elbow", ["../../../escaped_elbow", "wrist/elbow", ".."])
def test_a_joint_name_never_becomes_a_path(tmp_path: Path, elbow: str) -> None:
    root = tmp_path / "p"
    pkg = _project(root, elbow)
    before = _files(tmp_path)
    r = _control(root)
    # (a name with '/' may keep the controller from claiming its interface: exit 1, a finding)
    assert r.returncode in (0, 1), r.stdout + r.stderr
    assert "Traceback" not in r.stderr
    evidence = pkg / "evidence"
    made = _files(tmp_path) - before
    assert made and all(str(evidence.relative_to(tmp_path)) in m for m in made), made  # nothing elsewhere
    plots = sorted(p.name for p in evidence.glob("*.png"))
    assert len(plots) == 4 and safe_file_name(elbow, ".png") in plots
    assert "/" not in safe_file_name(elbow, ".png") and ".." not in safe_file_name(elbow, ".png")
    # and check takes the evidence as its own (the plot names agree with the reuse record)
    c = cli("check", "specs/warehouse_arm.yaml", cwd=root)
    assert "evidence/" not in c.stderr or "GEN00" not in c.stderr, c.stderr


def test_safe_file_names() -> None:
    assert safe_file_name("elbow_joint", ".png") == "elbow_joint.png"
    assert safe_file_name("link_0.0", ".png") == "link_0.0.png"
    odd = ["..", ".", "a/b", "a/../b", "../../x", "-rf", "é" * 128, "x" * 128, "a b"]
    names = [safe_file_name(n, ".png") for n in odd]
    assert len(set(names)) == len(names)  # two names never share a file
    for n in names:
        assert "/" not in n and not n.startswith((".", "-")) and len(n.encode()) < 255, n
    with pytest.raises(ValueError):
        output_file(Path("/tmp"), "../x")


# --------------------------------------------------------------------------- control --out


@pytest.fixture(scope="module")
def project(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("control") / "p"
    _project(root)
    return root


def _refused(root: Path, out: Path, entry: Path) -> None:
    before = {p: (p.lstat().st_mode, p.lstat().st_size) for p in out.parent.rglob("*")}
    r = _control(root, "--out", str(out))
    assert r.returncode == 2, r.stdout + r.stderr
    assert f"{entry}: error[CTRL035]:" in r.stderr and "hint:" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr
    after = {p: (p.lstat().st_mode, p.lstat().st_size) for p in out.parent.rglob("*")}
    assert after == before  # nothing written


def test_control_refuses_a_linked_recording_folder(project: Path, tmp_path: Path) -> None:
    out = tmp_path / "ev"
    out.mkdir()
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (out / "control_run").symlink_to(elsewhere)
    _refused(project, out, out / "control_run")


def test_control_refuses_a_link_inside_the_recording_folder(project: Path, tmp_path: Path) -> None:
    # found by the independent check of issue 34: the link was replaced, not refused
    out = tmp_path / "ev"
    (out / "control_run").mkdir(parents=True)
    victim = tmp_path / "victim.mcap"
    victim.write_text("keep me\n")
    (out / "control_run" / "control_run.mcap").symlink_to(victim)
    _refused(project, out, out / "control_run" / "control_run.mcap")
    assert victim.read_text() == "keep me\n"


def test_control_refuses_a_linked_evidence_file(project: Path, tmp_path: Path) -> None:
    out = tmp_path / "ev"
    out.mkdir()
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me\n")
    (out / "lifecycle.md").symlink_to(victim)
    _refused(project, out, out / "lifecycle.md")
    assert victim.read_text() == "keep me\n"


def test_control_refuses_a_fifo_plot_and_a_linked_folder(project: Path, tmp_path: Path) -> None:
    out = tmp_path / "ev"
    out.mkdir()
    os.mkfifo(out / "elbow_joint.png")
    _refused(project, out, out / "elbow_joint.png")
    (out / "elbow_joint.png").unlink()
    real = tmp_path / "real"
    real.mkdir()
    linked = tmp_path / "linked"
    linked.symlink_to(real)
    _refused(project, linked, linked)


def test_control_writes_into_a_plain_folder(project: Path, tmp_path: Path) -> None:
    out = tmp_path / "ev"
    r = _control(project, "--out", str(out))
    assert r.returncode == 0, r.stdout + r.stderr
    assert (out / "verdict.json").is_file() and (out / "control_run").is_dir()
    assert sorted(p.name for p in out.glob("*.png")) == [
        "elbow_joint.png",
        "lift_joint.png",
        "shoulder_lift_joint.png",
        "shoulder_pan_joint.png",
    ]


# --------------------------------------------------------------------------- import -o

URDF = '<robot name="r"><link name="a"/></robot>\n'


@pytest.fixture
def urdf(tmp_path: Path) -> Path:
    path = tmp_path / "m.urdf"
    path.write_text(URDF)
    return path


def _imported(urdf: Path, target: Path, *more: str):  # type: ignore[no-untyped-def]
    return cli("import", urdf, "-o", target, *more, cwd=urdf.parent)


@pytest.mark.parametrize("force", [(), ("--force",)])
def test_import_never_replaces_a_fifo(urdf: Path, tmp_path: Path, force: tuple[str, ...]) -> None:
    fifo = tmp_path / "spec.yaml"
    os.mkfifo(fifo)
    r = _imported(urdf, fifo, *force)
    assert r.returncode == 2 and f"{fifo}: error[IMP033]:" in r.stderr and "FIFO" in r.stderr, r.stderr
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and "Traceback" not in r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.urdf", "spec.yaml"]  # no temporary left


@pytest.mark.parametrize("dangling", [False, True])
def test_import_never_replaces_a_link(urdf: Path, tmp_path: Path, dangling: bool) -> None:
    victim = tmp_path / "victim.yaml"
    if not dangling:
        victim.write_text("keep: me\n")
    link = tmp_path / "spec.yaml"
    link.symlink_to(victim)
    for force in ((), ("--force",)):
        r = _imported(urdf, link, *force)
        assert r.returncode == 2 and f"{link}: error[IMP033]:" in r.stderr and "symbolic link" in r.stderr, r.stderr
        assert link.is_symlink() and os.readlink(link) == str(victim)
        assert victim.read_text() == "keep: me\n" if not dangling else not victim.exists()


def test_import_never_replaces_a_device(urdf: Path, tmp_path: Path) -> None:
    if os.geteuid() != 0:
        pytest.skip("making a device node needs root")
    node = tmp_path / "null"
    os.mknod(node, stat.S_IFCHR | 0o600, os.makedev(1, 3))  # a /dev/null of our own, in tmp_path
    try:
        r = _imported(urdf, node, "--force")
        assert r.returncode == 2 and f"{node}: error[IMP033]:" in r.stderr and "character device" in r.stderr
        st = os.lstat(node)
        assert stat.S_ISCHR(st.st_mode) and st.st_rdev == os.makedev(1, 3)
    finally:
        node.unlink()


def test_import_force_replaces_a_regular_file(urdf: Path, tmp_path: Path) -> None:
    spec = tmp_path / "spec.yaml"
    spec.write_text("old\n")
    r = _imported(urdf, spec)
    assert r.returncode == 2 and "error[IMP007]" in r.stderr and spec.read_text() == "old\n"
    r = _imported(urdf, spec, "--force")
    assert r.returncode == 0, r.stderr
    assert spec.read_text().startswith("#") and "name: r" in spec.read_text()
    assert not stat.S_ISLNK(os.lstat(spec).st_mode)


def test_import_under_a_file_is_a_located_error(urdf: Path, tmp_path: Path) -> None:
    (tmp_path / "afile").write_text("x")
    r = _imported(urdf, tmp_path / "afile" / "spec.yaml")
    assert r.returncode == 2 and f"{tmp_path / 'afile' / 'spec.yaml'}: error[IMP034]:" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr and (tmp_path / "afile").read_text() == "x"
