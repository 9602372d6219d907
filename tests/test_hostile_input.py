"""Hostile and broken input through the CLI: exit 2, one clear located message, no traceback, no hang.

``descgen validate`` must refuse every one of these with exit code 2 and a message of the
form ``FILE:LINE:COL: error[CODE]: ...`` (or ``FILE: error[CODE]: ...`` when there is no
position) followed by a ``  hint:`` line. The time limit of ``helpers.cli`` is the hang guard.
"""

from __future__ import annotations

import random
import re
import time
from pathlib import Path

import pytest

from .helpers import EXAMPLE_TEXT, Ran, cli, line_of

TIMEOUT = 60
QUICK = 20.0  # seconds; a refusal must not take anywhere near the hang guard
LOCATED = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<col>\d+): error\[(?P<code>[A-Z]+\d{3})\]: (?P<msg>.+)$")
UNLOCATED = re.compile(r"^(?P<file>.+?): error\[(?P<code>[A-Z]+\d{3})\]: (?P<msg>.+)$")


def validate(*paths: str | Path) -> tuple[Ran, float]:
    """``descgen validate PATHS`` in this process (the CLI, not the library: exit code and stderr)."""
    start = time.monotonic()
    r = cli("validate", *paths, timeout=TIMEOUT)
    return r, time.monotonic() - start


def errors_in(stderr: str) -> list[dict[str, str]]:
    """The parsed ``error[...]`` lines of stderr; each must be followed by a hint line."""
    lines = stderr.splitlines()
    out = []
    for i, line in enumerate(lines):
        m = LOCATED.match(line) or UNLOCATED.match(line)
        if m is None:
            continue
        assert i + 1 < len(lines) and lines[i + 1].startswith("  hint: ") and lines[i + 1][8:].strip(), stderr
        out.append({"line": "0", "col": "0", **m.groupdict()})
    return out


def refused(path: str | Path, code_prefix: str = "") -> dict[str, str]:
    """Run validate on one path, check the refusal, return its first error."""
    r, took = validate(path)
    assert took < QUICK, f"took {took:.1f} s"
    return check_refusal(r.returncode, r.stdout, r.stderr, path, code_prefix)


def check_refusal(code: int, stdout: str, stderr: str, path: str | Path, code_prefix: str) -> dict[str, str]:
    assert "Traceback" not in stderr, stderr
    assert code == 2, (code, stdout, stderr)
    found = errors_in(stderr)
    assert found, f"no 'FILE[:LINE:COL]: error[CODE]: ...' line in stderr:\n{stderr}"
    first = found[0]
    assert first["file"] == str(path), (first, str(path))
    assert first["msg"].strip()
    assert first["code"].startswith(code_prefix), first
    return first


def write(tmp_path: Path, name: str, content: str | bytes) -> Path:
    p = tmp_path / name
    if isinstance(content, bytes):
        p.write_bytes(content)
    else:
        p.write_text(content, encoding="utf-8")
    return p


def test_malformed_yaml_reports_the_parser_position(tmp_path: Path) -> None:
    text = "name: robot\ndescription: ok\nlinks:\n  - name: base: link\n"
    # "mapping values are not allowed here": the parser stops at the second ':' on line 4
    line = line_of(text, "base: link")
    col = text.splitlines()[line - 1].index("base: link") + len("base") + 1
    e = refused(write(tmp_path, "malformed.yaml", text), "YAML")
    assert (int(e["line"]), int(e["col"])) == (line, col), e
    assert "malformed YAML" in e["msg"]


def test_unclosed_flow_sequence_reports_a_line_in_the_file(tmp_path: Path) -> None:
    text = EXAMPLE_TEXT.replace("[0.35, 0.35, 0.38, 1.0]", "[0.35, 0.35, 0.38, 1.0", 1)
    e = refused(write(tmp_path, "unclosed.yaml", text), "YAML")
    start = line_of(text, "[0.35, 0.35, 0.38, 1.0")
    assert start <= int(e["line"]) <= start + 1, (e, start)


def test_tab_indentation_is_located(tmp_path: Path) -> None:
    text = "name: robot\nlinks:\n\t- name: a\n"
    e = refused(write(tmp_path, "tab.yaml", text), "YAML")
    assert (int(e["line"]), int(e["col"])) == (3, 1), e


def test_empty_file(tmp_path: Path) -> None:
    e = refused(write(tmp_path, "empty.yaml", ""))
    assert "empty" in e["msg"]


def test_whitespace_only_file(tmp_path: Path) -> None:
    e = refused(write(tmp_path, "blank.yaml", "\n   \n\n"))
    assert "empty" in e["msg"]


def test_comments_only_file(tmp_path: Path) -> None:
    e = refused(write(tmp_path, "comments.yaml", "# a robot\n# to be written\n"))
    assert "empty" in e["msg"]


def test_billion_laughs_alias_bomb(tmp_path: Path) -> None:
    lines = ["a0: &a0 [" + ", ".join(['"lol"'] * 9) + "]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 10)]
    e = refused(write(tmp_path, "lol.yaml", "\n".join(lines) + "\n"), "YAML")
    assert "alias" in e["msg"] or "nodes" in e["msg"], e


def test_alias_bomb_inside_a_spec_value(tmp_path: Path) -> None:
    bomb = ["x0: &x0 [" + ", ".join(["1 mm"] * 9) + "]"]
    bomb += [f"x{i}: &x{i} [" + ", ".join([f"*x{i - 1}"] * 9) + "]" for i in range(1, 9)]
    text = EXAMPLE_TEXT.replace("name: warehouse_arm\n", "name: warehouse_arm\n" + "\n".join(bomb) + "\n", 1)
    refused(write(tmp_path, "lol_spec.yaml", text))


def test_50_mb_file_is_refused_by_size(tmp_path: Path) -> None:
    p = tmp_path / "huge.yaml"
    chunk = ("# " + "x" * 1021 + "\n").encode() * 1024  # 1 MiB of valid YAML comments
    with p.open("wb") as f:
        for _ in range(50):
            f.write(chunk)
    assert p.stat().st_size >= 50 * 1024 * 1024
    e = refused(p, "YAML")
    assert "MB" in e["msg"], e


def test_binary_file(tmp_path: Path) -> None:
    rng = random.Random(1234)
    data = bytearray(rng.randbytes(4096))
    data[10] = data[2000] = 0
    refused(write(tmp_path, "robot.yaml", bytes(data)), "YAML")


def test_non_utf8_file(tmp_path: Path) -> None:
    text = "name: robot\ndescription: caf\xe9 \xb5m\n".encode("latin-1")
    e = refused(write(tmp_path, "latin1.yaml", text), "YAML")
    assert "UTF-8" in e["msg"], e


def test_utf8_bom_is_accepted(tmp_path: Path) -> None:
    p = write(tmp_path, "bom.yaml", b"\xef\xbb\xbf" + EXAMPLE_TEXT.encode())
    r, _ = validate(p)
    assert r.returncode == 0, r.stderr


def test_missing_file(tmp_path: Path) -> None:
    e = refused(tmp_path / "nope.yaml")
    assert "not found" in e["msg"], e


def test_directory_without_specs(tmp_path: Path) -> None:
    d = tmp_path / "specs.yaml"
    d.mkdir()
    (d / "notes.txt").write_text("not a spec\n")
    e = refused(d)
    assert "directory" in e["msg"] or "no .yaml" in e["msg"], e


def test_directory_with_a_broken_spec_names_the_file(tmp_path: Path) -> None:
    d = tmp_path / "specs"
    d.mkdir()
    write(d, "broken.yaml", "name: robot\nlinks: [\n")
    r, _ = validate(d)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    found = errors_in(r.stderr)
    assert found and all(e["file"] in (str(d / "broken.yaml"), str(d)) for e in found), r.stderr


@pytest.mark.parametrize(
    "text", ["- a\n- b\n", "just a string\n", "42\n", "null\n"], ids=["list", "str", "int", "null"]
)
def test_top_level_not_a_mapping(tmp_path: Path, text: str) -> None:
    e = refused(write(tmp_path, "notmap.yaml", text))
    assert "mapping" in e["msg"] or "empty" in e["msg"], e


def test_duplicate_key_reported_at_the_second_key(tmp_path: Path) -> None:
    text = "name: one\nlinks:\n  - name: a\n    source: M1\n    source: M2\nname: two\n"
    r, _ = validate(write(tmp_path, "dup.yaml", text))
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    found = errors_in(r.stderr)
    dups = [e for e in found if "duplicate" in e["msg"]]
    assert dups, r.stderr
    # the first duplicate met is 'source' on line 5 (the second 'source'), not line 4
    assert (int(dups[0]["line"]), int(dups[0]["col"])) == (5, 5), dups
    assert "line 4" in dups[0]["msg"], dups


def test_duplicate_key_in_the_example(tmp_path: Path) -> None:
    text = EXAMPLE_TEXT.replace("    type: prismatic\n", "    type: prismatic\n    type: revolute\n", 1)
    e = refused(write(tmp_path, "dup_example.yaml", text))
    assert int(e["line"]) == line_of(text, "    type: revolute\n"), e
    assert "duplicate" in e["msg"]


def test_duplicate_key_in_a_flow_mapping(tmp_path: Path) -> None:
    text = EXAMPLE_TEXT.replace("{lower: 0 mm, upper: 300 mm,", "{lower: 0 mm, upper: 300 mm, lower: 10 mm,", 1)
    e = refused(write(tmp_path, "dup_flow.yaml", text))
    line = line_of(text, "lower: 10 mm")
    assert (int(e["line"]), int(e["col"])) == (line, text.splitlines()[line - 1].index("lower: 10 mm") + 1), e


def test_merge_keys_are_refused(tmp_path: Path) -> None:
    text = "common: &c {type: fixed}\nname: robot\njoints:\n  - <<: *c\n    name: j\n"
    e = refused(write(tmp_path, "merge.yaml", text))
    assert (int(e["line"]), int(e["col"])) == (4, 5), e
    assert "<<" in e["msg"] or "merge" in e["msg"], e


@pytest.mark.parametrize("depth", [100, 10_000])
def test_deeply_nested_lists(tmp_path: Path, depth: int) -> None:
    e = refused(write(tmp_path, "deep.yaml", "name: robot\nlinks: " + "[" * depth + "]" * depth + "\n"), "YAML")
    assert "deep" in e["msg"], e


def test_deeply_nested_mappings(tmp_path: Path) -> None:
    text = "name: robot\nlinks: " + "{a: " * 5000 + "1" + "}" * 5000 + "\n"
    e = refused(write(tmp_path, "deep_map.yaml", text), "YAML")
    assert "deep" in e["msg"], e


def test_very_long_line(tmp_path: Path) -> None:
    text = EXAMPLE_TEXT.replace("description: WA-1", "description: " + "x" * 1_000_000 + " WA-1", 1)
    refused(write(tmp_path, "long.yaml", text))


def test_several_specs_one_broken(tmp_path: Path) -> None:
    broken = write(tmp_path, "broken.yaml", EXAMPLE_TEXT.replace("    type: prismatic\n", "    type: slider\n", 1))
    good = "specs/warehouse_arm.yaml"
    for order in ((good, broken), (broken, good)):
        r, took = validate(*order)
        assert r.returncode == 2, (r.returncode, r.stderr)
        assert "Traceback" not in r.stderr, r.stderr
        assert took < QUICK
        found = errors_in(r.stderr)
        assert found and all(e["file"] == str(broken) for e in found), r.stderr
        assert int(found[0]["line"]) == line_of(EXAMPLE_TEXT, "    type: prismatic\n"), found
        assert f"{good}: valid" in r.stdout, r.stdout


def test_several_specs_one_missing(tmp_path: Path) -> None:
    missing = tmp_path / "missing.yaml"
    r, _ = validate("specs/warehouse_arm.yaml", missing)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert any(e["file"] == str(missing) for e in errors_in(r.stderr)), r.stderr


# Found by tests/test_loader_fuzz.py: explicit YAML types that PyYAML cannot build, on keys and values.
YAML_TYPE_CORNERS = [
    ("timestamp-key-out-of-range", "name: robot\n2001-13-01: x\n", 2),
    ("unknown-tag-on-key", "name: robot\n!x links: []\n", 2),
    ("bad-int-key", "name: robot\n!!int links: []\n", 2),
    ("bad-float-key", "name: robot\n!!float links: []\n", 2),
    ("bad-bool-key", "name: robot\n!!bool links: []\n", 2),
    ("empty-tagged-int-value", "name: !!int\n", 1),
    ("empty-tagged-float-value", "name: !!float\n", 1),
    ("bad-timestamp-value", "name: !!timestamp soon\n", 1),
    ("bad-bool-value", "name: !!bool maybe\n", 1),
]


@pytest.mark.parametrize(("text", "line"), [c[1:] for c in YAML_TYPE_CORNERS], ids=[c[0] for c in YAML_TYPE_CORNERS])
def test_yaml_explicit_types_that_cannot_be_built(tmp_path: Path, text: str, line: int) -> None:
    e = refused(write(tmp_path, "typed.yaml", text))
    assert int(e["line"]) == line, e


def test_huge_integer_in_a_quantity(tmp_path: Path) -> None:
    text = EXAMPLE_TEXT.replace("{mass: 300 g, from: collision}", "{mass: " + "9" * 400 + " g, from: collision}", 1)
    e = refused(write(tmp_path, "huge_number.yaml", text))
    assert int(e["line"]) == line_of(text, "{mass: 999"), e
