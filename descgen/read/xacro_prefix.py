"""The name prefix a Xacro declares: its top file's ``prefix`` or ``tf_prefix`` argument.

ROS 2 has no tf_prefix, so descriptions meant to share a graph take the prefix as a Xacro
argument (ros2_control_demos and the Kinova description call it ``prefix``, the UR description
``tf_prefix``) and write it before every name. The value is the one the expansion used: given
with ``--xacro-arg``, else the argument's default. Only a plain default is read; one built from
other substitutions (``$(arg ...)``) is left undeclared rather than guessed.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from descgen.core.findings import Where
from descgen.core.model import NamePrefix
from descgen.infra.safeio import read_bounded

ARGS = ("prefix", "tf_prefix")  # in this order when a file declares both


def declared(path: Path, shown: str, given: Mapping[str, str]) -> NamePrefix | None:
    """The prefix of the Xacro at ``path`` (None when it declares none, or an empty one)."""
    from lxml import etree

    try:
        data = read_bounded(path, "Xacro", display=shown)
        root = etree.fromstring(data, etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False))
    except Exception:  # the expansion that ran before has reported an unreadable file
        return None
    # xacro knows its elements by the qualified name "xacro:arg", whatever URI the prefix is bound
    # to (www.ros.org/wiki/xacro and wiki.ros.org/xacro are both in use)
    args = {
        e.get("name"): e for e in root.iter(etree.Element) if e.prefix == "xacro" and etree.QName(e).localname == "arg"
    }
    for name in ARGS:
        e = args.get(name)
        if e is None:
            continue
        value = given.get(name, e.get("default"))
        if value and "$(" not in value and "${" not in value:
            return NamePrefix(
                value, f"the Xacro argument {name}", Where(shown, e.sourceline if isinstance(e.sourceline, int) else 0)
            )
        return None
    return None
