"""The fleet report's folder (``descgen fleet-report --out DIR``): the one place it is written.

``README.md`` and two plots drawn with matplotlib (offscreen): the failure rate of each robot by
day, and the failed lookups of each description version by class. The folder is new, empty, or
one a fleet-report wrote (it holds nothing but these files); each file is written beside its
place and renamed into it, so a reader never sees half a page. Names on the plots are drawn as
text (matplotlib's mathtext is off for them: a ``$`` in a robot name is a dollar sign).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from descgen.codes.recording import BAG021
from descgen.core.findings import InputError, Where
from descgen.infra.safeio import output_kind, public_mode

PAGE = "README.md"


def _refuse(folder: Path, message: str) -> InputError:
    return InputError([BAG021.finding(message, "choose another --out", "option", Where(str(folder)))])


def check_folder(folder: Path, files: Sequence[str], mark: str) -> None:
    """A new or empty folder, or one a fleet-report wrote (only its files, the page starting
    with ``mark``); BAG021 otherwise, before any table is read."""
    kind = output_kind(folder)
    if kind is not None and kind != "a directory":
        raise _refuse(folder, f"--out names {kind}; the report is written to a folder")
    if folder.exists() and not folder.is_dir():
        raise _refuse(folder, "--out names a file; the report is written to a folder")
    if not folder.is_dir():
        return
    other = sorted(p.name for p in folder.iterdir() if p.name not in files)
    if other:
        raise _refuse(
            folder,
            f"{folder} holds other files ({', '.join(other[:3])}); the report is written to a new or empty folder",
        )
    page = folder / PAGE
    if page.exists() or page.is_symlink():
        try:
            ours = output_kind(page) is None and page.read_bytes()[: len(mark)] == mark.encode()
        except OSError:
            ours = False
        if not ours:
            raise _refuse(folder, f"{page} is not a page fleet-report wrote; it is never replaced")


def _write(path: Path, data: bytes) -> None:
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.chmod(tmp, public_mode())
        if output_kind(path) is not None:  # a link or folder swapped in meanwhile
            raise OSError(f"{path} is no longer a regular file")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_report(
    folder: Path,
    page: str,
    rates: dict[str, list[tuple[str, float]]],
    by_version: dict[str, dict[str, int]],
    plots: Sequence[str],
) -> Path:
    """Write the page and its plots; returns the page's path. ``rates``: robot -> [(day, failed
    share)]; ``by_version``: version -> {class: failed lookups}."""
    check_folder(folder, [PAGE, *plots], page.splitlines()[0] if page else "")
    try:
        folder.mkdir(parents=True, exist_ok=True)
        _write(folder / plots[0], _rate_plot(rates))
        _write(folder / plots[1], _version_plot(by_version))
        _write(folder / PAGE, page.encode("utf-8"))
    except OSError as exc:
        raise _refuse(folder, f"cannot write the report there: {exc.strerror or exc}") from None
    return folder / PAGE


def _figure(width: float, height: float) -> tuple[Any, Any]:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), dpi=100)
    FigureCanvasAgg(fig)
    return fig, fig.add_subplot(1, 1, 1)


def _png(fig: Any) -> bytes:
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()


MAX_LINES = 20  # robots and versions drawn (the worst); the table on the page has every one
MAX_LABEL = 40


def _label(name: str) -> str:
    """A name as a plot label: escaped, shortened, and never one matplotlib hides (a leading _)."""
    text = "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii") for c in name)
    text = text if len(text) <= MAX_LABEL else text[: MAX_LABEL - 3] + "..."
    return " " + text if text.startswith("_") else text


def _rate_plot(rates: dict[str, list[tuple[str, float]]]) -> bytes:
    import importlib
    import warnings
    from datetime import date

    fig, ax = _figure(8, 4)
    worst = sorted(rates, key=lambda r: (-max((v for _, v in rates[r]), default=0.0), r))[:MAX_LINES]
    days = {d for pts in rates.values() for d, _ in pts}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a glyph a font lacks: the label shows a box, not a warning
        for robot in sorted(worst):
            pts = [(date.fromisoformat(d), v) for d, v in rates[robot] if d[:1].isdigit()]
            ax.plot([d for d, _ in pts], [100 * v for _, v in pts], marker="o", label=_label(robot))
        ax.set_ylabel("failed lookups (%)")
        ax.set_title("failure rate by robot and day (UTC)")
        if worst:
            leg = ax.legend(fontsize="small", loc="upper left")
            for t in leg.get_texts():
                t.set_usetex(False)
                t.set_parse_math(False)
        dates: Any = importlib.import_module("matplotlib.dates")  # untyped: its calls stay out of mypy's way
        ax.xaxis.set_major_locator(dates.DayLocator(interval=max(1, len(days) // 8)))
        ax.xaxis.set_major_formatter(dates.DateFormatter("%Y-%m-%d"))
        fig.autofmt_xdate()
        fig.tight_layout()
        return _png(fig)


def _version_plot(by_version: dict[str, dict[str, int]]) -> bytes:
    import warnings

    fig, ax = _figure(8, 4)
    versions = sorted(by_version, key=lambda v: (-sum(by_version[v].values()), v))[:MAX_LINES]
    bottom = [0] * len(versions)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for cls in ("disconnected", "stale", "future"):
            values = [by_version[v].get(cls, 0) for v in versions]
            ax.bar(range(len(versions)), values, bottom=bottom, label=cls)
            bottom = [b + v for b, v in zip(bottom, values, strict=True)]
        ax.set_xticks(range(len(versions)))
        labels = ax.set_xticklabels([_label(v) for v in versions], rotation=30, ha="right", fontsize="small")
        for t in labels:
            t.set_parse_math(False)
        ax.set_ylabel("failed lookups")
        ax.set_title("failed lookups by description version (the most failed first)")
        ax.legend(fontsize="small")
        fig.tight_layout()
        return _png(fig)
