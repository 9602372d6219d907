"""evidence/drift.svg: the residual of ``calibration.drift``'s samples over time, drawn as SVG
text (no plotting library: the same samples give the same bytes on every machine, so check
compares the file itself).

A long recording is drawn as at most MAX_POINTS columns, each the largest residual in its time
bucket (a peak is never averaged away). The tolerance is a dashed line; a change point, a
vertical line. Only numbers reach the SVG, except the axis labels, which are escaped.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from xml.sax.saxutils import escape

from descgen.core.findings import Finding, Where

PATH = "evidence/drift.svg"
MAX_POINTS = 1000
W, H = 720, 280
LEFT, RIGHT, TOP, BOTTOM = 64, 16, 24, 40


def _buckets(t: Sequence[float], r: Sequence[float]) -> list[tuple[float, float]]:
    if len(t) <= MAX_POINTS:
        return list(zip(t, r, strict=True))
    span = (t[-1] - t[0]) or 1.0
    out: dict[int, tuple[float, float]] = {}
    for x, y in zip(t, r, strict=True):
        k = min(MAX_POINTS - 1, int((x - t[0]) / span * MAX_POINTS))
        if k not in out or y > out[k][1]:
            out[k] = (x, y)
    return [out[k] for k in sorted(out)]


def svg(
    t_s: Sequence[float], residual_mm: Sequence[float], tolerance_mm: float, change_s: float | None, label: str
) -> str:
    points = _buckets(t_s, residual_mm)
    if len(points) < len(t_s):
        label += f" (the largest of each of {len(points)} time buckets)"
    t_max = max((x for x, _ in points), default=1.0) or 1.0
    y_max = max([tolerance_mm * 1.2, *(y for _, y in points)]) or 1.0

    def px(x: float) -> float:
        return LEFT + (W - LEFT - RIGHT) * x / t_max

    def py(y: float) -> float:
        return H - BOTTOM - (H - TOP - BOTTOM) * y / y_max

    line = " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y in points)
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" '
        'font-family="sans-serif" font-size="12">',
        f'<rect x="0" y="0" width="{W}" height="{H}" fill="white"/>',
        f'<text x="{LEFT}" y="16">{escape(label)}</text>',
        f'<line x1="{LEFT}" y1="{H - BOTTOM}" x2="{W - RIGHT}" y2="{H - BOTTOM}" stroke="black"/>',
        f'<line x1="{LEFT}" y1="{TOP}" x2="{LEFT}" y2="{H - BOTTOM}" stroke="black"/>',
        f'<text x="{W - RIGHT}" y="{H - 8}" text-anchor="end">time (s), 0 to {t_max:.1f}</text>',
        f'<text x="8" y="{TOP + 4}">{y_max:.3g} mm</text>',
        f'<text x="8" y="{H - BOTTOM}">0 mm</text>',
        f'<line x1="{LEFT}" y1="{py(tolerance_mm):.1f}" x2="{W - RIGHT}" y2="{py(tolerance_mm):.1f}" '
        'stroke="firebrick" stroke-dasharray="6 4"/>',
        f'<text x="{W - RIGHT}" y="{py(tolerance_mm) - 4:.1f}" text-anchor="end" fill="firebrick">'
        f"tolerance {tolerance_mm:g} mm</text>",
    ]
    if change_s is not None:
        parts += [
            f'<line x1="{px(change_s):.1f}" y1="{TOP}" x2="{px(change_s):.1f}" y2="{H - BOTTOM}" stroke="darkorange"/>',
            f'<text x="{px(change_s) + 4:.1f}" y="{TOP + 12}" fill="darkorange">change at {change_s:.1f} s</text>',
        ]
    parts += [f'<polyline points="{line}" fill="none" stroke="steelblue" stroke-width="1"/>', "</svg>", ""]
    return "\n".join(parts)


def write(package: Path, text: str | None) -> list[str]:
    """Write evidence/drift.svg in one rename, or remove one a spec without a drift check left
    behind; the paths written."""
    target = package / PATH
    if text is None:
        if target.is_file() and not target.is_symlink():
            target.unlink()
        return []
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = target.with_name(f".{target.name}.tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(target)
    return [PATH]


def stale(package: Path, text: str | None) -> list[Finding]:
    """GEN006 when the plot is missing, GEN080 when it is not what the samples give now, and
    GEN080 for a plot left behind by a spec that has no drift check any more."""
    target = package / PATH
    if text is None:
        if not target.exists():
            return []
        what, code = "is left from a drift check the spec no longer has", "GEN080"
    elif not target.is_file() or target.is_symlink():
        what, code = "is missing", "GEN006"
    elif target.read_text(encoding="utf-8", errors="replace") == text:
        return []
    else:
        what, code = "is not the residual plot of the drift samples as they are now", "GEN080"
    return [
        Finding(
            code,
            "error",
            f"{PATH} {what}",
            "run descgen report SPEC and commit the result",
            f"file:{PATH}",
            Where(str(target)),
        )
    ]


__all__ = ["PATH", "stale", "svg", "write"]
