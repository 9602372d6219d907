"""``evidence/frames.svg``: Graphviz's drawing of ``evidence/frames.dot``, made only when it
would change.

The svg is a pure function of the dot text and of the Graphviz that draws it, so the svg
records both in a comment (``<!-- descgen-source: ... -->``): the sha256 of the dot bytes
without the file's leading ``//`` comment lines (descgen's header, which names the spec's hash
and so changes with every edit of the spec, while dot draws nothing of it), and
the ``dot`` executable it came from (resolved path, size and modification time; a Graphviz
upgrade replaces the executable, and reading its identity costs no process, unlike
``dot -V``). When both match, ``dot`` is not run. Its bytes depend on the Graphviz version,
so the svg is not part of what check compares, and is not committed.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from descgen.codes.generate import GEN094, GEN095
from descgen.core.findings import Finding, Where
from descgen.infra.safeio import public_mode

_MARK = "<!-- descgen-source: "
_HEAD = 4096  # the stamp is in the first lines; never read a whole (possibly huge) svg to find it


def _dot_identity(dot: str) -> str:
    real = os.path.realpath(dot)
    st = os.stat(real)
    return f"{real}:{st.st_size}:{st.st_mtime_ns}"


def drawn(dot_source: bytes) -> bytes:
    """What of a dot file Graphviz draws from: all but its leading ``//`` comment lines."""
    rest = dot_source
    while rest.startswith(b"//"):
        _, _, rest = rest.partition(b"\n")
    return rest


def stamp(dot_source: bytes, dot: str) -> str:
    """The comment that says what an svg was made from."""
    digest = hashlib.sha256(drawn(dot_source)).hexdigest()
    return f"{_MARK}frames.dot sha256 {digest}, dot {_dot_identity(dot)} -->"


def _recorded(svg: Path) -> str | None:
    if svg.is_symlink() or not svg.is_file():
        return None
    with open(svg, "rb") as fh:
        head = fh.read(_HEAD).decode("utf-8", errors="replace")
    for line in head.splitlines():
        if line.startswith(_MARK):
            return line
    return None


def _stamped(svg_text: str, mark: str) -> str:
    """``mark`` as the line after the XML declaration (a comment is allowed there)."""
    first, nl, rest = svg_text.partition("\n")
    if first.startswith("<?xml"):
        return f"{first}\n{mark}\n{rest}" if nl else f"{first}\n{mark}\n"
    return f"{mark}\n{svg_text}"


# Above this many edges dot is not run: its layout grows faster than the tree (measured on
# this project's 2-core machine: a 10,000-link chain 14 s, a 10,000-link tree 48 s; 1,000 links
# under a second), and a drawing of thousands of frames is read by no one.
MAX_DRAWN_EDGES = 2000
DOT_SECONDS = 60  # a drawing that takes longer is given up (GEN094), never a traceback


def draw(package_dir: Path) -> list[Finding]:
    """Write ``evidence/frames.svg`` from ``frames.dot`` when Graphviz is installed and the svg
    does not already record this dot text and this ``dot``. Findings: a tree too large to draw
    (GEN095, and an old drawing removed: it shows another tree), dot failing or timing out (GEN094)."""
    dot = shutil.which("dot")
    source = package_dir / "evidence" / "frames.dot"
    if dot is None or source.is_symlink() or not source.is_file():
        return []
    data = source.read_bytes()
    svg = source.with_suffix(".svg")
    where = Where(str(svg))
    edges = drawn(data).count(b"->")
    if edges > MAX_DRAWN_EDGES:
        if svg.is_file() and not svg.is_symlink():
            svg.unlink()
        return [
            GEN095.finding(
                f"frames.svg not drawn: the tree has {edges:,} transforms, more than the {MAX_DRAWN_EDGES:,} "
                "descgen draws",
                "read evidence/frames.md, or draw frames.dot by hand (sfdp -Tsvg evidence/frames.dot)",
                "file",
                where,
            )
        ]
    mark = stamp(data, dot)
    if _recorded(svg) == mark:
        return []
    fd, tmp = tempfile.mkstemp(prefix=".frames-", suffix=".svg", dir=source.parent)
    os.close(fd)
    try:
        try:
            done = subprocess.run(
                [dot, "-Tsvg", str(source), "-o", tmp], check=False, capture_output=True, timeout=DOT_SECONDS
            )
        except subprocess.TimeoutExpired:
            return [_failed(f"Graphviz's dot did not finish in {DOT_SECONDS} s", where)]
        except OSError as exc:
            return [_failed(f"Graphviz's dot could not be run: {exc.strerror or exc}", where)]
        if done.returncode != 0:
            said = done.stderr.decode("utf-8", "replace").strip().splitlines()
            reason = f": {said[0][:200]}" if said else ""
            return [_failed(f"Graphviz's dot failed (exit {done.returncode}){reason}", where)]
        text = Path(tmp).read_text(encoding="utf-8", errors="replace")
        Path(tmp).write_text(_stamped(text, mark), encoding="utf-8")
        os.chmod(tmp, public_mode())  # mkstemp makes it private; the drawing is the package's, as its other files
        os.replace(tmp, svg)  # a reader sees the old drawing or the new one
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
    return []


def _failed(message: str, where: Where) -> Finding:
    return GEN094.finding(
        f"frames.svg not drawn: {message}", "frames.dot and frames.md are written; draw it by hand", "file", where
    )
