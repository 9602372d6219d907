"""The example-robot-data corpus: real URDFs (and SRDFs) that nobody here wrote."""

from __future__ import annotations

from pathlib import Path


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
