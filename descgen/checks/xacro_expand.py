"""Check 1: expanding ``<robot>.urdf.xacro`` with the xacro package gives ``<robot>.urdf``."""

from __future__ import annotations

import tempfile
from pathlib import Path

from lxml import etree

from ..findings import Finding, InputError, Where
from ..model import Robot
from ..readers.xacro_file import expand as sandboxed_expand
from ..xmlcompare import first_difference, parse


def expand(files: dict[str, str], xacro_path: str) -> str:
    """Expand one rendered xacro file in a scratch folder (its includes are relative).

    It is expanded in the same sandbox as an audited Xacro: the Xacro is made from a
    spec, which is someone else's data, so it is never given xacro's own evaluator."""
    with tempfile.TemporaryDirectory(prefix="descgen-xacro-") as tmp:
        root = Path(tmp)
        for rel, text in files.items():
            if rel.endswith(".xacro") or rel == "package.xml":
                target = root / rel
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(text, encoding="utf-8")
        return sandboxed_expand(root / xacro_path, xacro_path).decode("utf-8")


def xacro_matches_urdf(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    xacro_path = f"urdf/{robot.name}.urdf.xacro"
    urdf_path = f"urdf/{robot.name}.urdf"
    loc = Where(str(where / xacro_path))
    try:
        expanded = expand(files, xacro_path)
    except InputError as exc:  # the sandbox turns every xacro failure into one
        return [
            Finding(
                "GEN001",
                "error",
                f"xacro failed to expand the generated Xacro: {'; '.join(f.message for f in exc.findings)}",
                "a template produced invalid Xacro; check --templates overrides",
                "file:" + xacro_path,
                loc,
            )
        ]
    try:
        diff = first_difference(parse(expanded), parse(files[urdf_path]))
    except etree.XMLSyntaxError as exc:
        return [
            Finding(
                "GEN001",
                "error",
                f"generated XML does not parse: {exc}",
                "check the templates",
                "file:" + urdf_path,
                Where(str(where / urdf_path)),
            )
        ]
    if diff:
        return [
            Finding(
                "GEN001",
                "error",
                f"xacro expansion differs from {urdf_path} at {diff}",
                "the Xacro and URDF templates disagree; fix the template that changed",
                "file:" + xacro_path,
                loc,
            )
        ]
    return []
