"""Comments and docs cite only files that are in the repository: a reader of a clone can open
every ``docs/...``, ``descgen/...``, ``tests/...`` path a comment names (the reference notes the
facts came from are vendored in docs/reference/, each with its upstream sources)."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CITED = re.compile(r"(?<![\w/.-])((?:docs|descgen|tests|benchmarks|scripts)/[\w./-]*\w\.(?:md|py|j2|yaml|sh|toml))")
RELATIVE = re.compile(r"(?<![\w/])reference/(\w+\.md)")
OUTSIDE = re.compile(r"/work/|\.\./shared/|(?<![\w/])DESIGN\.md|(?<![\w/])reference/\w+\.md")


def _texts() -> list[Path]:
    files = [*ROOT.glob("descgen/**/*.py"), *ROOT.glob("descgen/templates/*.j2"), *ROOT.glob("docs/*.md")]
    return sorted([*files, ROOT / "README.md"])


def test_every_cited_path_exists() -> None:
    missing = [
        f"{path.relative_to(ROOT)}: {cited}"
        for path in _texts()
        for cited in CITED.findall(path.read_text(encoding="utf-8"))
        if not any(c in cited for c in "*{}<>") and not (ROOT / cited).exists()
    ]
    assert missing == []


def _in_repo(line: str, path: Path) -> str:
    """The line without the citations that resolve inside the repository: docs/reference/...,
    and reference/... from a page in docs/ (a relative link)."""
    line = line.replace("docs/reference/", "")
    if path.parent == ROOT / "docs":
        line = RELATIVE.sub(lambda m: "" if (ROOT / "docs" / "reference" / m.group(1)).is_file() else m.group(0), line)
    return line


def test_nothing_cites_a_file_outside_the_repository() -> None:
    outside = [
        f"{path.relative_to(ROOT)}:{n}: {line.strip()[:120]}"
        for path in _texts()
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if OUTSIDE.search(_in_repo(line, path)) and "not in this repository" not in line  # README's drift note
    ]
    assert outside == []


def test_the_checks_see_a_bad_citation() -> None:
    assert CITED.findall("see descgen/audit/nowhere.py and docs/reference/urdf.md.") == [
        "descgen/audit/nowhere.py",
        "docs/reference/urdf.md",
    ]
    assert OUTSIDE.search("(reference/urdf.md)") and OUTSIDE.search("/work/shared/x") and OUTSIDE.search("DESIGN.md")
    code = ROOT / "descgen" / "x.py"
    assert not OUTSIDE.search(_in_repo("(docs/reference/urdf.md)", code))
    assert OUTSIDE.search(_in_repo("(reference/urdf.md)", code))  # from code, a bare reference/ is not ours
    assert not OUTSIDE.search(_in_repo("[u](reference/urdf.md)", ROOT / "docs" / "a.md"))
    assert OUTSIDE.search(_in_repo("[u](reference/none.md)", ROOT / "docs" / "a.md"))
