"""Check 3: urdfdom's ``check_urdf`` (Debian liburdfdom-tools) accepts the URDF.

Skipped (with an info finding that says so) when the tool is not installed, unless
``DESCGEN_REQUIRE_TOOLS=1``, where its absence is an error.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from ..findings import Finding, Where
from ..model import Robot


def check_urdf(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    rel = f"urdf/{robot.name}.urdf"
    loc = Where(str(where / rel))
    tool = shutil.which("check_urdf")
    if tool is None:
        required = os.environ.get("DESCGEN_REQUIRE_TOOLS") == "1"
        return [
            Finding(
                "GEN020",
                "error" if required else "info",
                "check_urdf (urdfdom) is not installed: the URDF was not checked by urdfdom",
                "install Debian's liburdfdom-tools",
                "file:" + rel,
                loc,
            )
        ]
    with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False, encoding="utf-8") as fh:
        fh.write(files[rel])
        path = fh.name
    try:
        r = subprocess.run([tool, path], capture_output=True, text=True, timeout=120)
    finally:
        os.unlink(path)
    # urdfdom logs some errors without failing (reference/urdf.md): treat them as failures
    logged = [ln for ln in (r.stdout + r.stderr).splitlines() if "Error" in ln or "error" in ln.split(":")[0]]
    if r.returncode != 0 or logged:
        detail = "; ".join(logged[:3]) or (r.stdout + r.stderr).strip()[:300]
        return [
            Finding(
                "GEN021",
                "error",
                f"check_urdf rejected the URDF (exit {r.returncode}): {detail}",
                "the URDF template or the model is broken",
                "file:" + rel,
                loc,
            )
        ]
    return []
