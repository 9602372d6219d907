"""The committed JSON Schema is what `descgen schema` prints, and the example spec points editors at it."""

from __future__ import annotations

import json
import re

from descgen.spec.schema import json_schema

from .helpers import ROOT, cli

SCHEMA_FILE = ROOT / "specs" / "descgen-spec.schema.json"
EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
MODELINE = re.compile(r"^#\s*yaml-language-server:\s*\$schema=(?P<target>\S+)\s*$")


def test_cli_schema_equals_the_committed_file() -> None:
    r = cli("schema")
    assert r.returncode == 0, r.stderr
    printed = json.loads(r.stdout)
    committed = json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))
    assert printed == committed, (
        "specs/descgen-spec.schema.json is stale: regenerate it with "
        "`descgen schema > specs/descgen-spec.schema.json`; differing top-level keys: "
        f"{sorted(k for k in set(printed) | set(committed) if printed.get(k) != committed.get(k))}, "
        f"differing $defs: {sorted(_differing(printed.get('$defs', {}), committed.get('$defs', {})))}, "
        f"differing properties: {sorted(_differing(printed.get('properties', {}), committed.get('properties', {})))}"
    )


def _differing(a: dict[str, object], b: dict[str, object]) -> set[str]:
    return {k for k in set(a) | set(b) if a.get(k) != b.get(k)}


def test_schema_is_a_draft_2020_12_object_schema() -> None:
    schema = json_schema()
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema["type"] == "object"
    assert "name" in schema["required"]
    assert schema.get("additionalProperties") is False
    json.dumps(schema)  # serialisable


def test_example_spec_modeline_points_at_the_schema() -> None:
    first = EXAMPLE.read_text(encoding="utf-8").splitlines()[0]
    m = MODELINE.match(first)
    assert m, f"first line is not a yaml-language-server modeline: {first!r}"
    target = m["target"]
    assert not re.match(r"^[a-z]+://", target) and not target.startswith("/"), f"not a relative path: {target}"
    resolved = (EXAMPLE.parent / target).resolve()
    assert resolved.is_file(), f"{target} does not exist next to the spec"
    assert resolved == SCHEMA_FILE.resolve()
