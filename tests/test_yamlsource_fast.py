"""The spec loader's shortcuts (descgen/infra/yamlsource.py: a per-document memo of scalar tags, plain
strings taken without the constructor) must give what PyYAML's own safe loader gives: the same
data, and for every node the same line and column as PyYAML's pure-Python composer."""

from __future__ import annotations

from typing import Any

import yaml

from descgen.infra import yamlsource
from tests.conftest import EXAMPLE

# the same texts plain and quoted: a memo keyed on the text alone would type them alike
TRICKY = """\
a: 1
b: "1"
c: yes
d: 'yes'
e: ~
f: "~"
g: 1.5
h: '1.5'
i: [1, "1", 1, '1', null, "null", true, "true", 0x10, "0x10", 1e3, "1e3", .inf, ".inf"]
j: !!str 12
k: 2024-01-01
l: "2024-01-01"
m: &x 40 mm
n: *x
o: ""
p:
q: "40 mm"
"""


def _marks(node: yaml.Node, path: tuple[Any, ...], out: dict[tuple[Any, ...], tuple[int, int]]) -> None:
    out.setdefault(path, (node.start_mark.line + 1, node.start_mark.column + 1))
    if isinstance(node, yaml.MappingNode):
        for k, v in node.value:
            _marks(v, (*path, yaml.safe_load(yaml.serialize(k)) if k.tag != "tag:yaml.org,2002:str" else k.value), out)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            _marks(item, (*path, i), out)


def test_data_equals_pyyaml_safe_load() -> None:
    doc = yamlsource.loads(TRICKY, "t.yaml")
    want = yaml.load(TRICKY, Loader=yaml.SafeLoader)  # the pure-Python loader, no shortcuts
    assert doc.data == want
    assert [type(v) for v in doc.data["i"]] == [type(v) for v in want["i"]]
    assert type(doc.data["b"]) is str and type(doc.data["a"]) is int


def test_every_mark_equals_the_pure_python_composer() -> None:
    for text in (TRICKY, EXAMPLE.read_text(encoding="utf-8")):
        doc = yamlsource.loads(text, "t.yaml")
        want: dict[tuple[Any, ...], tuple[int, int]] = {}
        _marks(yaml.compose(text, Loader=yaml.SafeLoader), (), want)
        assert doc.value_marks == want
