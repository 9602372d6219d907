"""Fuzzing the spec loader: whatever the text, it is a valid spec or an InputError, never a crash.

Every property: ``load_spec_text`` returns a :class:`Loaded` or raises :class:`InputError`
whose findings are all located errors with a code and a message. Any other exception
(a ``ValueError`` from a YAML constructor, a ``KeyError`` in the builder, ...) is a bug.

A full load of the example spec takes about 0.1 s, so the mutation tests keep their
example counts small enough for the whole file to run in well under a minute.
"""

from __future__ import annotations

import copy
import gc
import re
from typing import Any

import yaml
from hypothesis import HealthCheck, Phase, example, given, settings
from hypothesis import strategies as st

from descgen.audit.spec import load_spec_text
from descgen.core.findings import InputError
from descgen.spec import Loaded

from .helpers import EXAMPLE_TEXT

FILE = "fuzz.yaml"
EXAMPLE_LINES = EXAMPLE_TEXT.splitlines(keepends=True)
EXAMPLE_DATA = yaml.safe_load(EXAMPLE_TEXT)

FAST = settings(
    max_examples=300,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
)
MEDIUM = settings(FAST, max_examples=150)
# Each example is a full load of the example spec (30-100 ms): fewer examples, and no shrinking
# (the inputs are already small: line numbers, one token) so that a failure is reported fast.
SLOW = settings(FAST, max_examples=80, phases=[Phase.explicit, Phase.reuse, Phase.generate])


def check(text: str, max_line: int | None = None) -> None:
    """The property: a Loaded, or an InputError of well-formed located findings, at least one
    of them an error that blocks (the refusal carries the spec's warnings too)."""
    try:
        result = load_spec_text(text, FILE)
    except InputError as exc:
        assert exc.findings, "InputError without findings"
        assert any(f.blocks for f in exc.findings), exc.findings
        for f in exc.findings:
            assert f.message and f.message.strip(), f
            assert f.code and re.fullmatch(r"[A-Z]+\d{3}", f.code), f
            assert f.severity in ("error", "warning", "info"), f
            assert f.where.line >= 0, f
            assert f.where.col >= 0, f
            if max_line is not None:
                assert f.where.line <= max_line, (f, max_line)
        return
    assert isinstance(result, Loaded)


def check_mutated(text: str) -> None:
    check(text, max_line=len(text.splitlines()) + 1)


# --------------------------------------------------------------------------- random text

YAML_CHARS = "abcxyz019 -_.:,#&*!|>'\"%@`[]{}?<=~\t\n\r\\/+^$()"
# Line starts that reach the odd corners of YAML: tags and implicit types on keys and values,
# merge keys, anchors and aliases, complex keys, flow collections.
LINE_STARTS = [
    "",
    "- ",
    "? ",
    ": ",
    "name: ",
    "links: ",
    "<<: ",
    "&a ",
    "*a ",
    "- *a",
    "- {",
    "- [",
    "--- ",
    "...",
    "!x ",
    "!x k: ",
    "!!str ",
    "!!int ",
    "!!int k: ",
    "!!float k: ",
    "!!bool k: ",
    "!!binary k: ",
    "!!null ",
    "!!timestamp k: ",
    "!!set ",
    "!!omap ",
    "!!python/object:os.system ",
    "2001-13-41: ",
    "2001-02-03: ",
    "0x1F: ",
    "1e400: ",
    ".nan: ",
    "~: ",
    "[a, b]: ",
    "{a: 1}: ",
    "? [a]\n: ",
]
yamlish_text = st.one_of(
    st.text(max_size=200),
    st.text(alphabet=YAML_CHARS, max_size=200),
    st.lists(
        st.tuples(
            st.integers(0, 6).map(lambda n: " " * n),
            st.sampled_from(LINE_STARTS),
            st.text(alphabet=YAML_CHARS, max_size=20),
        ).map("".join),
        max_size=12,
    ).map("\n".join),
)


@FAST
@given(yamlish_text)
# inputs that once broke the loader: explicit YAML types that cannot be built, on keys and values
@example("!0 a: 1")
@example("2001-13-01: x")
@example("!!int ;: 1")
@example("!!float x: 1")
@example("!!bool k: 1")
@example("!!timestamp k: 1")
@example("!!binary k: 1")
@example("name: !!int")
@example("name: !!float")
@example("name: !!timestamp soon")
@example("name: !!bool maybe")
def test_random_text_is_spec_or_input_error(text: str) -> None:
    check(text)


# --------------------------------------------------------------------------- random structured data

SPEC_KEYS = [  # keys the spec uses, so that random mappings sometimes get past the first check
    "name", "description", "links", "joints", "parts", "sensors", "materials", "ros2_control", "semantic",
    "known_poses", "plausibility", "require_sources", "visual", "collision", "inertial", "mass", "origin", "xyz",
    "rpy", "geometry", "box", "size", "cylinder", "sphere", "mesh", "radius", "diameter", "length", "type", "parent",
    "child", "axis", "limit", "lower", "upper", "effort", "velocity", "from", "inertia", "ixx", "iyy", "izz",
    "source", "value", "instances", "link", "joint", "frames", "frame", "tolerance", "package",
]  # fmt: skip
scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**20), max_value=10**20),
    st.floats(),
    st.text(max_size=30),
    st.sampled_from(["0", "1 mm", "-90 deg", "2 kg", "300 g", "19.1 in / 2", "1e400 m", "nan mm", "m", "", "+y"]),
)
keys = st.one_of(st.sampled_from(SPEC_KEYS), st.text(max_size=15))
structured = st.recursive(
    scalars,
    lambda children: st.one_of(
        st.lists(children, max_size=5),
        st.dictionaries(keys, children, max_size=6),
    ),
    max_leaves=40,
)


@MEDIUM
@given(structured)
def test_random_structured_data_is_spec_or_input_error(data: Any) -> None:
    check(yaml.safe_dump(data, allow_unicode=True))


@MEDIUM
@given(st.dictionaries(keys, structured, max_size=8))
def test_random_top_level_mapping_is_spec_or_input_error(data: dict[str, Any]) -> None:
    check(yaml.safe_dump(data, allow_unicode=True))


def _paths(node: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    out = [prefix]
    if isinstance(node, dict):
        for k, v in node.items():
            out += _paths(v, (*prefix, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += _paths(v, (*prefix, i))
    return out


EXAMPLE_PATHS = [p for p in _paths(EXAMPLE_DATA) if p]


@SLOW
@given(st.sampled_from(EXAMPLE_PATHS), structured)
def test_example_with_a_subtree_replaced_is_spec_or_input_error(path: tuple[Any, ...], value: Any) -> None:
    data = copy.deepcopy(EXAMPLE_DATA)
    node = data
    for part in path[:-1]:
        node = node[part]
    node[path[-1]] = value
    check_mutated(yaml.safe_dump(data, allow_unicode=True, sort_keys=False))


# --------------------------------------------------------------------------- mutations of the example text

NUMBER = re.compile(r"(?<![A-Za-z0-9_.])-?\d+(?:\.\d+)?")
NUMBER_SPANS = [m.span() for m in NUMBER.finditer(EXAMPLE_TEXT)]
_MASS = EXAMPLE_TEXT.index("{mass: 300 g") + len("{mass: ")
MASS_SPAN = (_MASS, _MASS + len("300"))  # the caster's mass, a quantity with a fixed kind
UNIT_TOKENS = ["mm", "deg", "kg", "g", "in", "rpm", "N*m", "m/s", "Hz"]
UNIT = re.compile(r"(?<=\d )(N\*m|m/s|mm|deg|kg|rpm|Hz|in|g)(?![A-Za-z])")
UNIT_SPANS = [m.span() for m in UNIT.finditer(EXAMPLE_TEXT)]

numbers = st.one_of(
    st.integers(-(10**9), 10**9).map(str),
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
    st.sampled_from(
        ["0", "-0", "0.0", "1e400", "-1e400", "1e-400", "nan", ".inf", "-.inf", "1_000", "0x1F", "1/0", "9" * 400]
    ),
)


def _replace(text: str, span: tuple[int, int], new: str) -> str:
    return text[: span[0]] + new + text[span[1] :]


def test_mutation_tables_cover_the_example() -> None:
    assert len(EXAMPLE_LINES) > 100
    assert len(NUMBER_SPANS) > 50
    assert MASS_SPAN in NUMBER_SPANS and EXAMPLE_TEXT[slice(*MASS_SPAN)] == "300"
    found = {EXAMPLE_TEXT[a:b] for a, b in UNIT_SPANS}
    assert set(UNIT_TOKENS) <= found, set(UNIT_TOKENS) - found
    check(EXAMPLE_TEXT, max_line=len(EXAMPLE_LINES) + 1)  # the unmutated example loads


@SLOW
@given(st.integers(0, len(EXAMPLE_LINES) - 1))
def test_delete_a_line(i: int) -> None:
    check_mutated("".join(EXAMPLE_LINES[:i] + EXAMPLE_LINES[i + 1 :]))


@SLOW
@given(st.integers(0, len(EXAMPLE_LINES) - 1))
def test_duplicate_a_line(i: int) -> None:
    check_mutated("".join(EXAMPLE_LINES[: i + 1] + EXAMPLE_LINES[i:]))


@SLOW
@given(st.integers(0, len(EXAMPLE_LINES) - 1), st.integers(0, len(EXAMPLE_LINES) - 1))
def test_swap_two_lines(i: int, j: int) -> None:
    lines = list(EXAMPLE_LINES)
    lines[i], lines[j] = lines[j], lines[i]
    check_mutated("".join(lines))


@SLOW
@given(st.sampled_from(NUMBER_SPANS), numbers)
@example(MASS_SPAN, "9" * 400)  # an integer too large for a float
@example(MASS_SPAN, "1e400")
def test_replace_a_number(span: tuple[int, int], new: str) -> None:
    check_mutated(_replace(EXAMPLE_TEXT, span, new))


@SLOW
@given(
    st.sampled_from(UNIT_SPANS),
    st.one_of(st.sampled_from(UNIT_TOKENS), st.sampled_from(["m", "s", "rad", "J", "N", "%", "furlong", "", "kg*m^2"])),
)
def test_replace_a_unit(span: tuple[int, int], new: str) -> None:
    check_mutated(_replace(EXAMPLE_TEXT, span, new))


@SLOW
@given(
    st.integers(0, len(EXAMPLE_TEXT)),
    st.one_of(st.text(min_size=1, max_size=6), st.text(YAML_CHARS, min_size=1, max_size=8)),
)
def test_insert_random_characters(pos: int, chars: str) -> None:
    check_mutated(EXAMPLE_TEXT[:pos] + chars + EXAMPLE_TEXT[pos:])


@SLOW
@given(
    st.lists(
        st.one_of(
            st.tuples(st.just("del"), st.integers(0, 10**6)),
            st.tuples(st.just("dup"), st.integers(0, 10**6)),
            st.tuples(st.just("num"), st.integers(0, 10**6)),
            st.tuples(st.just("unit"), st.integers(0, 10**6)),
        ),
        min_size=2,
        max_size=5,
    ),
    st.data(),
)
def test_several_mutations_at_once(ops: list[tuple[str, int]], data: st.DataObject) -> None:
    text = EXAMPLE_TEXT
    for op, k in ops:
        lines = text.splitlines(keepends=True)
        if op == "del" and lines:
            i = k % len(lines)
            text = "".join(lines[:i] + lines[i + 1 :])
        elif op == "dup" and lines:
            i = k % len(lines)
            text = "".join(lines[: i + 1] + lines[i:])
        elif op == "num":
            spans = [m.span() for m in NUMBER.finditer(text)]
            if spans:
                text = _replace(text, spans[k % len(spans)], data.draw(numbers))
        elif op == "unit":
            spans = [m.span() for m in UNIT.finditer(text)]
            if spans:
                text = _replace(text, spans[k % len(spans)], data.draw(st.sampled_from(UNIT_TOKENS)))
    check_mutated(text)


def test_loading_does_not_keep_yaml_nodes_alive() -> None:
    """Fuzzing loads thousands of documents in one process: each load's YAML nodes must be freed."""

    def live_nodes() -> int:
        gc.collect()
        return sum(isinstance(o, yaml.Node) for o in gc.get_objects())

    load_spec_text(EXAMPLE_TEXT, FILE)
    before = live_nodes()
    for _ in range(5):
        load_spec_text(EXAMPLE_TEXT, FILE)
    after = live_nodes()
    assert after - before < 100, f"{after - before} YAML nodes kept alive by 5 loads"
