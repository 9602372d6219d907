"""The package is switched as a whole, even when the run fails or is killed at any step, and
generate never writes (nor check reads) through a link out of the output root.

Expected file sets are written out by hand in the tests; the states after an interrupted
run are compared with them, never with what the writer reports."""

from __future__ import annotations

import builtins
import fcntl
import os
import shutil
import signal
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from descgen.cli import main
from descgen.commands import generate
from descgen.core.findings import InputError
from descgen.write import package as gen

from .conftest import ROOT
from .helpers import EXAMPLE_TEXT, plant

PKG = "warehouse_arm_description"
# Any text holding the header mark counts as a file generate wrote (that is how it finds
# its own stale files); the rest of the header does not matter to the writer.
MARK = "# descgen spec-sha256=" + "0" * 64 + "\n"

OLD = {
    "package.xml": MARK + "package v1\n",
    "urdf/a.urdf": MARK + "a v1\n",
    "urdf/b.urdf": MARK + "b v1\n",
    "config/gone.yaml": MARK + "stale after the change\n",
}
NEW = {
    "package.xml": MARK + "package v1\n",  # unchanged
    "urdf/a.urdf": MARK + "a v2\n",
    "urdf/b.urdf": MARK + "b v2 longer\n",
    "srdf/c.srdf": MARK + "c new\n",
    "launch/d.launch.py": MARK + "d new\n",
}
# Files that are not generate's: another command's evidence, the user's own notes, and a
# file that looks like ours but lies outside the folders generate owns.
USER = {
    "evidence/verdict.json": b'{"verdict": "pass"}\n',
    "evidence/control_run/joint_states.csv": b"t,q\n0,0\n",
    "notes.txt": b"my notes\n",
    "evidence/other.md": (MARK + "not ours: evidence/ is shared\n").encode(),
}
OLD_STATE = {**{k: v.encode() for k, v in OLD.items()}, **USER}
NEW_STATE = {**{k: v.encode() for k, v in NEW.items()}, **USER}


def files_of(folder: Path) -> dict[str, bytes]:
    """Every regular file under ``folder`` (links would be reported as such, never followed)."""
    out: dict[str, bytes] = {}
    for dirpath, dirnames, filenames in os.walk(folder):
        for name in filenames + dirnames:
            p = Path(dirpath) / name
            assert not p.is_symlink(), f"unexpected link {p}"
            if p.is_file():
                out[p.relative_to(folder).as_posix()] = p.read_bytes()
    return out


def scratch(root: Path) -> list[str]:
    return sorted(p.name for p in root.iterdir() if p.name.startswith(".descgen-"))


def old_package(root: Path) -> Path:
    pkg = root / PKG
    for rel, text in OLD.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text(text)
    for rel, data in USER.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_bytes(data)
    return pkg


def patch_fs(mp: pytest.MonkeyPatch, at: int, fire: Callable[[], None], exchange: bool) -> dict[str, int]:
    """Count every file-system change the writer can make; ``fire`` at call number ``at``.
    ``exchange=False`` makes the one-step swap unavailable, forcing the two-rename fallback."""
    seen = {"n": 0}

    def counted(real: Callable[..., Any]) -> Callable[..., Any]:
        def op(*args: Any, **kwargs: Any) -> Any:
            seen["n"] += 1
            if seen["n"] == at:
                fire()
            return real(*args, **kwargs)

        return op

    real_open = builtins.open

    def open_(file: Any, mode: str = "r", *args: Any, **kwargs: Any) -> Any:
        if any(c in mode for c in "wax+"):
            return counted(real_open)(file, mode, *args, **kwargs)
        return real_open(file, mode, *args, **kwargs)

    for mod, name in [
        (os, "mkdir"),
        (os, "link"),
        (os, "rename"),
        (os, "replace"),
        (os, "fsync"),
        (os, "unlink"),
        (os, "rmdir"),
        (shutil, "copy2"),
        (shutil, "copymode"),
        (shutil, "rmtree"),
    ]:
        mp.setattr(mod, name, counted(getattr(mod, name)))
    mp.setattr(builtins, "open", open_)
    real_exchange = gen.exchange
    mp.setattr(gen, "exchange", counted(real_exchange if exchange else lambda a, b: False))
    return seen


@pytest.fixture(params=["exchange", "fallback"])
def swap(request: pytest.FixtureRequest) -> bool:
    if request.param == "exchange" and gen._renameat2() is None:
        pytest.skip("no renameat2 on this system")
    return bool(request.param == "exchange")


@pytest.mark.parametrize("raised", [OSError, KeyboardInterrupt, SystemExit])
def test_interrupted_at_every_step_leaves_old_or_new(
    tmp_path: Path, swap: bool, raised: type[BaseException], monkeypatch: pytest.MonkeyPatch
) -> None:
    steps = 0
    for at in range(1, 200):
        root = tmp_path / str(at)
        pkg = old_package(root)

        def fire() -> None:
            raise (raised(28, "No space left on device") if raised is OSError else raised())

        with monkeypatch.context() as mp:
            seen = patch_fs(mp, at, fire, swap)
            try:
                gen.write_package(pkg, NEW)
                returned = True
            except raised:
                returned = False
        state = files_of(pkg)
        assert state in (OLD_STATE, NEW_STATE), f"mixed package after a failure at step {at}"
        if returned:  # an OSError the writer may swallow (cleaning up), never half a switch
            assert state == NEW_STATE, at
        if seen["n"] < at:  # every step ran without the interruption: done
            assert returned and not scratch(root)
            steps = at - 1
            break
        # the next run cleans up and switches
        again = gen.write_package(pkg, NEW)
        assert files_of(pkg) == NEW_STATE and not scratch(root), at
        if state == OLD_STATE:
            assert sorted(again.written) == ["launch/d.launch.py", "srdf/c.srdf", "urdf/a.urdf", "urdf/b.urdf"]
            assert again.removed == ["config/gone.yaml"] and again.unchanged == ["package.xml"]
    # dirs, four writes, a link for each kept file, a switch and a clean-up: well over 15
    assert steps > 15, steps


MOVEIT = "warehouse_arm_moveit_config"


def _two_old_packages(root: Path) -> tuple[Path, Path]:
    """The old description package and a MoveIt package beside it, both in OLD_STATE."""
    os.rename(old_package(root), root / MOVEIT)
    return old_package(root), root / MOVEIT


@pytest.mark.parametrize("raised", [OSError, KeyboardInterrupt])
def test_two_packages_interrupted_at_every_step_are_both_old_or_both_new(
    tmp_path: Path, swap: bool, raised: type[BaseException], monkeypatch: pytest.MonkeyPatch
) -> None:
    # the description and its MoveIt config: a full disk while the second is built, or a
    # failed second switch, must not leave the first switched (generate said "nothing was
    # changed" while the description had been)
    for at in range(1, 400):
        root = tmp_path / str(at)
        first, second = _two_old_packages(root)

        def fire() -> None:
            raise (raised(28, "No space left on device") if raised is OSError else raised())

        with monkeypatch.context() as mp:
            seen = patch_fs(mp, at, fire, swap)
            try:
                gen.write_packages([(first, NEW), (second, NEW)])
                returned = True
            except raised:
                returned = False
        states = (files_of(first), files_of(second))
        assert states in ((OLD_STATE, OLD_STATE), (NEW_STATE, NEW_STATE)), f"mixed after a failure at step {at}"
        if returned:
            assert states == (NEW_STATE, NEW_STATE), at
        if seen["n"] < at:
            assert returned and not scratch(root)
            assert at > 30  # two packages' worth of steps
            return
        gen.write_packages([(first, NEW), (second, NEW)])
        assert (files_of(first), files_of(second)) == (NEW_STATE, NEW_STATE) and not scratch(root), at
    pytest.fail("the writer never completed")


def _ctrl_c_after_each_rename(tmp_path: Path, swap: bool) -> None:
    """Run by the test below in a fresh interpreter: a signal is held only in the main thread,
    and pytest-xdist runs tests in another one."""
    import signal

    for at in range(1, 400):
        root = tmp_path / str(at)
        first, second = _two_old_packages(root)
        seen = {"n": 0, "at": at}

        def after(real: Callable[..., Any], seen: dict[str, int] = seen) -> Callable[..., Any]:
            def op(*args: Any, **kwargs: Any) -> Any:
                result = real(*args, **kwargs)
                seen["n"] += 1
                if seen["n"] == seen["at"]:
                    os.kill(os.getpid(), signal.SIGINT)
                return result

            return op

        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(os, "rename", after(os.rename))
            mp.setattr(gen, "exchange", after(gen.exchange if swap else lambda a, b: False))
            try:
                gen.write_packages([(first, NEW), (second, NEW)])
                interrupted = False
            except KeyboardInterrupt:
                interrupted = True
        states = (files_of(first), files_of(second))
        assert states in ((OLD_STATE, OLD_STATE), (NEW_STATE, NEW_STATE)), f"mixed after Ctrl-C at rename {at}"
        if not interrupted:
            assert states == (NEW_STATE, NEW_STATE) and seen["n"] < at
            return
        gen.write_packages([(first, NEW), (second, NEW)])
        assert (files_of(first), files_of(second)) == (NEW_STATE, NEW_STATE) and not scratch(root), at
    raise AssertionError("the writer never completed")


def test_ctrl_c_just_after_any_rename_leaves_both_old_or_both_new(tmp_path: Path, swap: bool) -> None:
    # a signal arriving while a rename runs is raised by Python just after it returns, before
    # the writer records what it did: the switch holds SIGINT until both packages are in place
    code = (
        "import sys; from pathlib import Path; from tests.test_atomic_write import _ctrl_c_after_each_rename; "
        "_ctrl_c_after_each_rename(Path(sys.argv[1]), sys.argv[2] == 'exchange')"
    )
    mode = "exchange" if swap else "fallback"
    done = subprocess.run([sys.executable, "-c", code, str(tmp_path), mode], capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr[-2000:]


def test_generate_that_cannot_build_the_moveit_package_changes_neither(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    project = tmp_path / "project"
    for rel in ("specs/warehouse_arm.yaml", "specs/trajectories/ready.yaml"):
        (project / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / rel, project / rel)
    for pkg in (PKG, MOVEIT):
        shutil.copytree(ROOT / "generated" / pkg, project / "generated" / pkg)
    spec = project / "specs" / "warehouse_arm.yaml"
    before = {pkg: files_of(project / "generated" / pkg) for pkg in (PKG, MOVEIT)}
    text = spec.read_text()
    assert "velocity: 90 deg/s" in text  # shoulder_lift_joint: in the URDF and MoveIt's joint_limits.yaml
    spec.write_text(text.replace("velocity: 90 deg/s", "velocity: 80 deg/s", 1))
    real = gen._build

    def full_disk(new: Path, package_dir: Path, files: Any, out: Any) -> None:
        if package_dir.name == MOVEIT:
            raise OSError(28, "No space left on device", str(new))
        real(new, package_dir, files, out)

    monkeypatch.setattr(gen, "_build", full_disk)
    with pytest.raises(InputError) as caught:
        generate.generate(spec, project / "generated")
    assert caught.value.findings[0].code == "GEN045" and "nothing was changed" in caught.value.findings[0].hint
    assert {pkg: files_of(project / "generated" / pkg) for pkg in (PKG, MOVEIT)} == before
    assert not scratch(project / "generated")


def _killed_child(pkg: Path, at: int, swap: bool) -> int:
    """Run the writer in a forked child that SIGKILLs itself at step ``at`` (no finally, no
    clean-up runs, as with a real kill). Returns the child's wait status."""
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        code = 1
        try:
            mp = pytest.MonkeyPatch()
            patch_fs(mp, at, lambda: os.kill(os.getpid(), signal.SIGKILL), swap)
            gen.write_package(pkg, NEW)
            code = 0
        finally:
            os._exit(code)
    _, status = os.waitpid(pid, 0)
    return status


def test_killed_at_every_step_leaves_old_or_new(tmp_path: Path, swap: bool) -> None:
    for at in range(1, 200):
        root = tmp_path / str(at)
        pkg = old_package(root)
        status = _killed_child(pkg, at, swap)
        if os.WIFEXITED(status):
            assert os.WEXITSTATUS(status) == 0
            assert files_of(pkg) == NEW_STATE and not scratch(root)
            assert at > 15
            return
        assert os.WIFSIGNALED(status) and os.WTERMSIG(status) == signal.SIGKILL
        if pkg.exists():
            assert files_of(pkg) in (OLD_STATE, NEW_STATE), f"mixed package after a kill at step {at}"
        else:
            # only the fallback has this window: moved aside, not yet replaced. The old
            # package is whole, under the name that says so, and the next run puts it back.
            assert not swap, f"package missing after a kill at step {at}"
            (old,) = [root / n for n in scratch(root) if n.startswith(f".descgen-old-{PKG}-")]
            assert files_of(old) == OLD_STATE
            assert gen.recover(root) == [PKG]
            assert files_of(pkg) == OLD_STATE
        gen.write_package(pkg, NEW)
        assert files_of(pkg) == NEW_STATE and not scratch(root), at
    pytest.fail("the writer never completed")


def test_next_run_restores_a_package_moved_aside_and_cleans_scratch(tmp_path: Path) -> None:
    root = tmp_path / "generated"
    old_package(root)
    # what a kill between the two fallback renames leaves, plus a half-built new folder,
    # a half-deleted one, and a scratch folder from the earlier writer's naming
    os.rename(root / PKG, root / f".descgen-old-{PKG}-0a1b2c3d")
    (root / f".descgen-new-{PKG}-00000000" / "urdf").mkdir(parents=True)
    (root / f".descgen-new-{PKG}-00000000" / "urdf" / "a.urdf").write_text("half")
    (root / f".descgen-trash-{PKG}-11111111").mkdir()
    (root / ".descgen-k2j_x9q1").mkdir()
    out = gen.write_package(root / PKG, NEW)
    # the user's files exist only in the moved-aside package: they prove it was put back
    assert files_of(root / PKG) == NEW_STATE
    assert not scratch(root)
    assert out.removed == ["config/gone.yaml"]


def test_unchanged_package_is_not_touched(tmp_path: Path) -> None:
    pkg = old_package(tmp_path / "generated")
    gen.write_package(pkg, NEW)
    inode = pkg.stat().st_ino
    out = gen.write_package(pkg, NEW)
    assert out.written == [] and out.removed == [] and sorted(out.unchanged) == sorted(NEW)
    assert pkg.stat().st_ino == inode and files_of(pkg) == NEW_STATE


def test_a_second_writer_is_refused(tmp_path: Path) -> None:
    pkg = old_package(tmp_path / "generated")
    fd = os.open(pkg.parent, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        with pytest.raises(InputError) as exc:
            gen.write_package(pkg, NEW)
    finally:
        os.close(fd)
    assert [f.code for f in exc.value.findings] == ["GEN044"]
    assert files_of(pkg) == OLD_STATE and not scratch(pkg.parent)


def listing(*folders: Path) -> dict[Path, tuple[int, int, int, int]]:
    """What each entry is, without following links (atimes change on reading: left out)."""
    out = {}
    for folder in folders:
        for dirpath, dirnames, filenames in os.walk(folder):
            for name in [*dirnames, *filenames]:
                st = (Path(dirpath) / name).lstat()
                out[Path(dirpath) / name] = (st.st_mode, st.st_ino, st.st_size, st.st_mtime_ns)
    return out


@pytest.mark.parametrize("kind", ["dir", "file", "package", "fifo"])
def test_links_and_special_files_are_refused_before_writing(tmp_path: Path, kind: str) -> None:
    root = tmp_path / "generated"
    pkg = old_package(root)
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "a.urdf").write_text("victim\n")
    if kind == "dir":
        shutil.rmtree(pkg / "urdf")
        (pkg / "urdf").symlink_to(outside, target_is_directory=True)
        link, code = pkg / "urdf", "GEN040"
    elif kind == "file":
        (pkg / "urdf" / "a.urdf").unlink()
        (pkg / "urdf" / "a.urdf").symlink_to(outside / "a.urdf")
        link, code = pkg / "urdf" / "a.urdf", "GEN040"
    elif kind == "package":
        shutil.rmtree(pkg)
        pkg.symlink_to(outside, target_is_directory=True)
        link, code = pkg, "GEN041"
    else:
        os.mkfifo(pkg / "evidence" / "pipe")
        link, code = pkg / "evidence" / "pipe", "GEN043"
    before = listing(root, outside)
    with pytest.raises(InputError) as exc:
        gen.write_package(pkg, NEW)
    (finding,) = exc.value.findings
    assert finding.code == code and finding.where.file == str(link) and finding.hint
    assert (outside / "a.urdf").read_text() == "victim\n" and sorted(os.listdir(outside)) == ["a.urdf"]
    assert listing(root, outside) == before
    assert not scratch(root)


# --- the whole command, on the example robot ---


def project(tmp: Path, text: str = EXAMPLE_TEXT) -> Path:
    (tmp / "specs").mkdir(parents=True)
    shutil.copytree(ROOT / "specs" / "trajectories", tmp / "specs" / "trajectories")
    spec = tmp / "specs" / "warehouse_arm.yaml"
    spec.write_text(text)
    return spec


HEAVIER = plant("{value: 1200 g, source: M03}", "{value: 1250 g, source: M03}")


@pytest.fixture(scope="module")
def baseline(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Path, dict[str, bytes], dict[str, bytes]]]:
    """The example package before and after a change of the spec (each generated once)."""
    base = tmp_path_factory.mktemp("baseline")
    spec = project(base / "old")
    assert main(["generate", str(spec), "--out", str(base / "old" / "generated")]) == 0
    spec2 = project(base / "new", HEAVIER)
    assert main(["generate", str(spec2), "--out", str(base / "new" / "generated")]) == 0
    old = {k: v for k, v in files_of(base / "old" / "generated" / PKG).items() if not k.endswith(".svg")}
    new = {k: v for k, v in files_of(base / "new" / "generated" / PKG).items() if not k.endswith(".svg")}
    assert old != new
    yield base / "old" / "generated", old, new


def copy_baseline(tmp: Path, baseline_root: Path) -> tuple[Path, Path]:
    spec = project(tmp, HEAVIER)
    shutil.copytree(baseline_root, tmp / "generated", symlinks=True)
    return spec, tmp / "generated"


def without_svg(folder: Path) -> dict[str, bytes]:
    return {k: v for k, v in files_of(folder).items() if not k.endswith(".svg")}


def test_generate_keeps_user_files(
    tmp_path: Path, baseline: tuple[Path, dict[str, bytes], dict[str, bytes]], capsys: pytest.CaptureFixture[str]
) -> None:
    spec, out = copy_baseline(tmp_path, baseline[0])
    for rel, data in USER.items():
        (out / PKG / rel).parent.mkdir(parents=True, exist_ok=True)
        (out / PKG / rel).write_bytes(data)
    assert main(["generate", str(spec), "--out", str(out)]) == 0
    assert without_svg(out / PKG) == {**baseline[2], **USER}
    assert "urdf/warehouse_arm.urdf" in capsys.readouterr().out
    assert not scratch(out)


def test_generate_refuses_a_directory_link_out_of_the_root(
    tmp_path: Path, baseline: tuple[Path, dict[str, bytes], dict[str, bytes]], capsys: pytest.CaptureFixture[str]
) -> None:
    spec, out = copy_baseline(tmp_path, baseline[0])
    outside = tmp_path / "elsewhere"
    shutil.move(out / PKG / "urdf", outside)
    (out / PKG / "urdf").symlink_to(outside, target_is_directory=True)
    before = files_of(outside)
    assert main(["generate", str(spec), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{out / PKG / 'urdf'}: error[GEN040]: urdf in {PKG} is a symbolic link (to {outside})" in err
    assert "hint:" in err and "Traceback" not in err
    assert files_of(outside) == before
    assert not scratch(out)


def test_check_does_not_print_a_linked_file(
    tmp_path: Path, baseline: tuple[Path, dict[str, bytes], dict[str, bytes]], capsys: pytest.CaptureFixture[str]
) -> None:
    spec, out = copy_baseline(tmp_path, baseline[0])
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET-LINE\n")
    (out / PKG / "package.xml").unlink()
    (out / PKG / "package.xml").symlink_to(secret)
    assert main(["check", str(spec), "--out", str(out)]) == 2
    captured = capsys.readouterr()
    assert "TOP-SECRET-LINE" not in captured.out + captured.err
    assert "error[GEN040]: package.xml" in captured.err


def test_default_output_root_that_is_a_link_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = project(tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "generated").symlink_to(elsewhere, target_is_directory=True)
    assert main(["generate", str(spec)]) == 2
    assert "error[GEN042]" in capsys.readouterr().err
    assert os.listdir(elsewhere) == []


def test_output_root_that_is_a_file_is_refused(tmp_path: Path) -> None:
    (tmp_path / "generated").write_text("not a folder")
    with pytest.raises(InputError) as exc:
        gen.write_package(tmp_path / "generated" / PKG, NEW)
    assert [f.code for f in exc.value.findings] == ["GEN042"]
    assert (tmp_path / "generated").read_text() == "not a folder"


_KILL_AT = """
import os, signal, sys
from descgen.write import package as gen
from descgen.cli import main
real = gen.exchange
def exchange(a, b):
    if sys.argv[1] == "before":
        os.kill(os.getpid(), signal.SIGKILL)
    done = real(a, b)
    os.kill(os.getpid(), signal.SIGKILL)
gen.exchange = exchange
main(["generate", sys.argv[2], "--out", sys.argv[3]])
"""


@pytest.mark.slow
@pytest.mark.skipif(gen._renameat2() is None, reason="the one-step swap needs renameat2")
def test_generate_killed_around_the_switch(
    tmp_path: Path, baseline: tuple[Path, dict[str, bytes], dict[str, bytes]]
) -> None:
    """A real ``descgen generate`` process, SIGKILLed just before and just after the swap."""
    spec, out = copy_baseline(tmp_path, baseline[0])
    _, old, new = baseline
    for when, expected in (("before", old), ("after", new)):
        r = subprocess.run(
            [sys.executable, "-c", _KILL_AT, when, str(spec), str(out)], cwd=ROOT, capture_output=True, timeout=60
        )
        assert r.returncode == -signal.SIGKILL, r.stderr
        assert without_svg(out / PKG) == expected, when
        assert scratch(out), "the kill should leave a scratch folder for the next run"
    r = subprocess.run(
        [sys.executable, "-m", "descgen", "generate", str(spec), "--out", str(out)], cwd=ROOT, capture_output=True
    )
    assert r.returncode == 0, r.stderr
    assert without_svg(out / PKG) == new and not scratch(out)


def test_a_write_error_is_exit_2_not_a_traceback(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """A full disk during the write: a located message and exit 2, no traceback."""
    specs = tmp_path / "specs"
    specs.mkdir()
    shutil.copy(ROOT / "specs" / "warehouse_arm.yaml", specs / "robot.yaml")

    def full(*args: object, **kw: object) -> object:
        raise OSError(28, "No space left on device", str(tmp_path / "generated"))

    monkeypatch.setattr(gen, "write_packages", full)
    assert main(["generate", str(specs / "robot.yaml")]) == 2
    err = capsys.readouterr().err
    assert "error[GEN045]: could not write the package: No space left on device" in err
    assert "Traceback" not in err
