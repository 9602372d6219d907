"""Check 3: urdfdom's ``check_urdf`` (Debian liburdfdom-tools) accepts the URDF.

Skipped (with an info finding that says so) when the tool is not installed, unless
``DESCGEN_REQUIRE_TOOLS=1``, where its absence is an error.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from collections.abc import Callable
from pathlib import Path

from descgen.codes.generate import GEN020, GEN021
from descgen.core.findings import Finding, Where
from descgen.core.model import Robot


def check_urdf(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    return start_check_urdf(files, robot, where)()


def start_check_urdf(files: dict[str, str], robot: Robot, where: Path) -> Callable[[], list[Finding]]:
    """Start ``check_urdf`` and return what waits for it and judges its output: the caller
    runs its in-process proofs meanwhile (a second core is not idle while urdfdom loads)."""
    rel = f"urdf/{robot.name}.urdf"
    loc = Where(str(where / rel))
    tool = shutil.which("check_urdf")
    if tool is None:
        required = os.environ.get("DESCGEN_REQUIRE_TOOLS") == "1"
        missing = GEN020.finding(
            "check_urdf (urdfdom) is not installed: the URDF was not checked by urdfdom",
            "install Debian's liburdfdom-tools",
            "file:" + rel,
            loc,
            severity="error" if required else "info",
        )
        return lambda: [missing]
    with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False, encoding="utf-8") as fh:
        fh.write(files[rel])
        path = fh.name
    # urdfdom writes its errors to stderr (console_bridge logs warnings and errors there, and
    # check_urdf its own failure); stdout is the tree, indented by depth (~2 MB for a 1000-link
    # chain), where a link named "ErrorLink" is no error: it is not read
    try:
        proc = subprocess.Popen([tool, path], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    except BaseException:
        os.unlink(path)
        raise

    def collect() -> list[Finding]:
        try:
            _, err = proc.communicate(timeout=120)
        except subprocess.TimeoutExpired:
            proc.kill()
            _, err = proc.communicate()
        finally:
            os.unlink(path)
        return _judged(proc.returncode, err.decode("utf-8", "replace"), rel, loc)

    return collect


def _judged(code: int, err: str, rel: str, loc: Where) -> list[Finding]:
    # urdfdom logs some errors without failing (docs/reference/urdf.md): treat them as failures
    logged = [ln for ln in err.splitlines() if "Error" in ln or "error" in ln.split(":")[0]]
    if code != 0 or logged:
        detail = "; ".join(logged[:3]) or err.strip()[:300]
        return [
            GEN021.finding(
                f"check_urdf rejected the URDF (exit {code}): {detail}",
                "the URDF template or the model is broken",
                "file:" + rel,
                loc,
            )
        ]
    return []
