"""The example-robot-data corpus: real URDFs (and SRDFs) that nobody here wrote."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from descgen.commands.importer.run import Outcome
    from descgen.core.findings import InputError


def share() -> Path | None:
    """``.../cmeel.prefix/share``, where example-robot-data installs its robots."""
    import site
    import sys

    for base in [*site.getsitepackages(), *sys.path]:
        candidate = Path(base) / "cmeel.prefix" / "share"
        if (candidate / "example-robot-data" / "robots").is_dir():
            return candidate
    return None


def descriptions() -> list[tuple[str, Path, Path | None]]:
    """(id, urdf, srdf or None) for every URDF in the corpus; the SRDF is the one with the
    same file stem in the package's srdf/ folder."""
    root = share()
    if root is None:
        return []
    robots = root / "example-robot-data" / "robots"
    out = []
    for urdf in sorted(robots.rglob("*.urdf")):
        package = urdf.relative_to(robots).parts[0]
        srdf = robots / package / "srdf" / (urdf.stem + ".srdf")
        out.append((urdf.relative_to(robots).as_posix(), urdf, srdf if srdf.is_file() else None))
    return out


_IMPORTED: dict[tuple[Path, Path | None], Outcome | InputError] = {}


def imported(urdf: Path, srdf: Path | None) -> Outcome:
    """``descgen import`` of a corpus robot with its SRDF and the corpus as package path, as
    docs/import-corpus.md's rows are made: once per process (importing the corpus is minutes),
    for tests/test_import_corpus.py, tests/test_import_oracle.py and tests/test_import_multidof.py,
    which only read the outcome. An unusable robot's InputError is raised again, each time."""
    from descgen.commands.importer.run import ImportOptions, import_description
    from descgen.core.findings import InputError
    from descgen.read.description import Options

    if (urdf, srdf) not in _IMPORTED:
        root = share()
        try:
            outcome = import_description(urdf, ImportOptions(Options(srdf=srdf, package_paths=(root,) if root else ())))
        except InputError as exc:
            _IMPORTED[urdf, srdf] = exc
        else:
            _IMPORTED[urdf, srdf] = outcome
    done = _IMPORTED[urdf, srdf]
    if isinstance(done, InputError):
        raise InputError(done.findings)
    return done


def audit_all() -> dict[str, list[object]]:
    """Findings for every corpus description (with its SRDF and the corpus as package path)."""
    from descgen.read.description import Options, audit

    root = share()
    out: dict[str, list[object]] = {}
    for ident, urdf, srdf in descriptions():
        out[ident] = list(audit(urdf, Options(srdf=srdf, package_paths=(root,) if root else ())))
    return out


def counts(findings: list[object], severity: str) -> str:
    from collections import Counter

    c = Counter(f.code for f in findings if f.severity == severity)  # type: ignore[attr-defined]
    return ", ".join(f"{code}×{n}" for code, n in sorted(c.items())) or "—"


if __name__ == "__main__":
    # prints the counts columns of docs/audit-corpus.md
    for ident, found in audit_all().items():
        print(f"| `{ident}` | {counts(found, 'error')} | {counts(found, 'warning')} |")


# corpus robots the planted-fault tests use: legged, humanoid, mobile manipulators, some with prismatic joints
FAULT_ROBOTS = [
    "talos_data/robots/talos_reduced.urdf",
    "solo_description/robots/solo12.urdf",
    "go2_description/urdf/go2.urdf",
    "anymal_c_simple_description/urdf/anymal.urdf",
    "pr2_description/urdf/pr2.urdf",
    "tiago_description/robots/tiago.urdf",
]


# --- Xacro corpora (tests/data/xacro_corpus, tests/data/jazzy_corpus) ------------------------------

_ONCE: dict[tuple[str, str], tuple[Outcome, Path]] = {}


def imported_once(corpus: str, ident: str, path: Path, options: object) -> tuple[Outcome, Path]:
    """(``descgen import`` of ``path`` with ``options``, the spec file it was meant for): once
    per process and case. The spec belongs in a folder of its own away from this repository:
    import records the package folders relative to it (package_paths: may leave the project),
    so :func:`spec_of` writes it exactly there."""
    import atexit
    import shutil
    import tempfile

    from descgen.commands.importer.run import ImportOptions, import_description

    if (corpus, ident) not in _ONCE:
        folder = Path(tempfile.mkdtemp(prefix="descgen-import-"))
        atexit.register(shutil.rmtree, folder, True)
        spec = folder / "robot.yaml"
        outcome = import_description(path, ImportOptions(options, spec_name=str(spec)))  # type: ignore[arg-type]
        _ONCE[corpus, ident] = outcome, spec
    return _ONCE[corpus, ident]


def spec_of(done: tuple[Outcome, Path]) -> Path:
    """The imported spec, written where import meant it to be."""
    from descgen.write.spec_file import write_spec

    outcome, spec = done
    if not spec.exists():
        write_spec(spec, outcome.imported.spec_text)
    return spec
