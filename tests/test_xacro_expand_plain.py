"""``readers.xacro_file.expand`` (what the proofs call) skips recording where each element was
written; ``expand_located`` (audit, import) records it. Both must give the XML that xacro itself
gives, byte for byte: the oracle is ``xacro.process_file``."""

from __future__ import annotations

from pathlib import Path

import xacro

from descgen.read.xacro_file import expand, expand_located
from tests.corpus import share
from tests.helpers import ROOT

MACROS = """\
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="l" value="0.25"/>
  <xacro:macro name="seg" params="name parent *inertial">
    <link name="${name}"><xacro:insert_block name="inertial"/></link>
    <joint name="${name}_j" type="fixed"><parent link="${parent}"/><child link="${name}"/>
      <origin xyz="0 0 ${l * 2}"/></joint>
  </xacro:macro>
  <link name="base"/>
  <xacro:seg name="a" parent="base"><inertial><mass value="1"/></inertial></xacro:seg>
  <xacro:seg name="b" parent="a"><inertial><mass value="${l}"/></inertial></xacro:seg>
</robot>
"""


def _same_as_xacro(path: Path) -> None:
    theirs = xacro.process_file(str(path)).toxml().encode()
    plain = expand(path, str(path))
    located = expand_located(path, str(path))
    assert plain == located.xml
    assert plain.split(b"-->", 4)[-1] == theirs.split(b"-->", 4)[-1], path  # the banner names the path
    assert located.sources and located.sources[0] is not None  # the located run really located


def test_macros_expand_alike(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf.xacro"
    path.write_text(MACROS)
    _same_as_xacro(path)
    assert expand_located(path, "r").sources[2].line == 5  # the macro body's <link>


def test_the_generated_xacro_expands_alike() -> None:
    _same_as_xacro(ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf.xacro")


def test_example_robot_data_xacros_expand_alike() -> None:
    root = share()
    compared = 0
    for f in sorted(root.rglob("*.xacro")) if root is not None else []:
        try:
            xacro.process_file(str(f))
        except Exception:  # a macro library, not a robot
            continue
        _same_as_xacro(f)
        compared += 1
        if compared >= 5:
            break
    assert compared >= 1
