"""descgen/infra/yamlsource.py's loader replaces PyYAML's per-node resolver calls (descend, ascend,
resolve) when no path resolver is registered: every node must get the tag PyYAML's own
pure-Python loader gives it, and a loader with a path resolver must keep PyYAML's methods."""

from __future__ import annotations

import yaml

from descgen.infra import yamlsource
from tests.test_yamlsource_fast import TRICKY

NESTED = TRICKY + "r: {s: [1, '2', {t: 3.0}], u: [[], {}]}\nv: !!python/none x\n"


def _tags(node: yaml.Node) -> list[str]:
    out = [node.tag]
    if isinstance(node, yaml.MappingNode):
        for k, v in node.value:
            out += _tags(k) + _tags(v)
    elif isinstance(node, yaml.SequenceNode):
        for item in node.value:
            out += _tags(item)
    return out


def test_every_tag_equals_the_pure_python_loader() -> None:
    ours = yaml.compose(NESTED, Loader=yamlsource._LOADER)
    want = yaml.compose(NESTED, Loader=yaml.SafeLoader)
    assert len(_tags(want)) > 60
    assert _tags(ours) == _tags(want)


def test_the_shortcut_is_what_the_composer_calls() -> None:
    loader = yamlsource._LOADER("a: [1]")
    assert "resolve" in vars(loader) and "descend_resolver" in vars(loader)
    assert loader.get_single_node().value[0][1].tag == "tag:yaml.org,2002:seq"


def test_a_path_resolver_keeps_pyyamls_methods() -> None:
    class WithPath(yamlsource._LOADER):  # type: ignore[misc,valid-type]
        pass

    WithPath.add_path_resolver("!point", ["p"], dict)
    loader = WithPath("p: {x: 1}\nq: {x: 1}\n")
    assert "resolve" not in vars(loader)
    node = loader.get_single_node()
    assert [v.tag for _, v in node.value] == ["!point", "tag:yaml.org,2002:map"]
