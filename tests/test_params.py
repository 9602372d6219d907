"""Parameter files read as rcl_yaml_param_parser and rclcpp read them (docs/ros2_parameters.md).
Every expected value is worked out by hand from rcl's parse.c (9.2.0) and rclcpp's
parameter_map.cpp (jazzy), quoted beside it; none comes from descgen."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from descgen.read.params import matches, nested, parse, resolve, typed
from descgen.render.formatting import yamlstr

from .helpers import cli

# the form many Jazzy packages ship: one /**: block per node, /**: repeated at the top level
WILDCARD_FILE = """\
/**:
  controller_manager:
    ros__parameters:
      update_rate: 1000
      base_controller:
        type: diff_drive_controller/DiffDriveController
/**:
  base_controller:
    ros__parameters:
      left_wheel_names: ["wheel_left_joint"]
      wheel_separation: 0.233
"""


def test_repeated_top_level_keys_are_one_file_of_two_nodes() -> None:
    pf = parse(WILDCARD_FILE, "c.yaml")
    assert pf.loads and pf.problems == ()
    # the keys above ros__parameters join with '/': /** + controller_manager
    assert [n.name for n in pf.nodes] == ["/**/controller_manager", "/**/base_controller"]
    cm = resolve(pf, "/controller_manager")
    assert {k: p.value for k, p in cm.items()} == {
        "update_rate": 1000,  # strtoll: an integer
        "base_controller.type": "diff_drive_controller/DiffDriveController",  # nested map -> dotted name
    }
    assert cm["update_rate"].where.line == 4 and cm["update_rate"].where.col == 20  # the value 1000
    base = resolve(pf, "/base_controller")
    assert base["left_wheel_names"].value == ("wheel_left_joint",)
    assert base["left_wheel_names"].items[0].line == 10
    assert base["wheel_separation"].value == 0.233


def test_a_node_named_twice_is_one_node_and_the_later_value_wins_in_place() -> None:
    text = """\
/**:
  cm:
    ros__parameters: {a: 1, b: 2}
/**:
  cm:
    ros__parameters: {a: 3}
"""
    pf = parse(text, "c.yaml")
    (node,) = pf.nodes  # find_node found /**/cm again
    # find_parameter: 'a' keeps its first place (index 0), parse_value overwrites its value
    assert [(p.name, p.value) for p in node.params] == [("a", 3), ("b", 2)]
    (twice,) = pf.problems
    assert twice.kind == "twice" and twice.where.line == 6 and "line 3" in twice.message
    assert pf.loads  # rcl loads it: a warning, not a refusal


def test_entries_reach_a_node_in_file_order_so_a_later_wildcard_wins() -> None:
    text = """\
controller_manager:
  ros__parameters: {update_rate: 100}
/**:
  ros__parameters: {update_rate: 50, use_sim_time: true}
"""
    pf = parse(text, "c.yaml")
    # both match /controller_manager; the /** entry comes later, so its value is assigned last
    assert {k: p.value for k, p in resolve(pf, "/controller_manager").items()} == {
        "update_rate": 50,
        "use_sim_time": True,
    }
    assert {k: p.value for k, p in resolve(pf, "/other").items()} == {"update_rate": 50, "use_sim_time": True}


@pytest.mark.parametrize(
    ("entry", "fqn", "expected"),
    [
        ("/**", "/controller_manager", True),  # (/\w+)*
        ("/**", "/robot1/arm/controller_manager", True),
        ("/**/controller_manager", "/controller_manager", True),  # (/\w+)*/controller_manager
        ("/**/controller_manager", "/robot1/controller_manager", True),
        ("/*/controller_manager", "/controller_manager", False),  # (/\w+)/controller_manager: one level
        ("/*/controller_manager", "/robot1/controller_manager", True),
        ("/controller_manager", "/robot1/controller_manager", False),  # regex_match: the whole name
        ("/*", "/robot1/controller_manager", False),
    ],
)
def test_node_names_match_as_rclcpp_matches_them(entry: str, fqn: str, expected: bool) -> None:
    assert matches(entry, fqn) is expected


@pytest.mark.parametrize(
    ("text", "quoted", "expected"),
    [
        ("y", False, True),  # rcl's true set holds Y/y; PyYAML reads 'y' as a string
        ("Off", False, False),
        ("010", False, 8),  # strtoll(..., 0): octal
        ("0x1F", False, 31),
        ("-7", False, -7),
        ("1e3", False, 1000.0),  # strtod
        (".5", False, 0.5),
        ("9223372036854775808", False, 9.223372036854775808e18),  # past int64: ERANGE, then strtod
        ("1_000", False, "1_000"),  # strtod stops at '_': not whole, a string
        ("'5'", True, "'5'"),  # quoted: a string whatever it holds
        ("true", True, "true"),
        ("abc", False, "abc"),
    ],
)
def test_values_are_typed_as_rcl_types_them(text: str, quoted: bool, expected: object) -> None:
    got = typed(text, quoted, False)
    assert got == expected and type(got) is type(expected)


def test_special_floats_and_the_str_tag() -> None:
    assert math.isnan(typed(".nan", False, False))  # type: ignore[arg-type]
    assert typed("-.inf", False, False) == -math.inf
    assert typed("5", False, True) == "5"  # !!str


def test_yaml_text_types_as_rcl_not_as_pyyaml() -> None:
    text = "n:\n  ros__parameters:\n    a: y\n    b: '1'\n    c: !!str 2\n    d: 010\n    e: [1, 2]\n"
    pf = parse(text, "c.yaml")
    assert {p.name: p.value for p in pf.nodes[0].params} == {"a": True, "b": "1", "c": "2", "d": 8, "e": (1, 2)}


@pytest.mark.parametrize(
    ("text", "line", "what"),
    [
        ("n:\n  ros__parameters:\n    a: &x 1\n    b: *x\n", 4, "alias"),  # Will not support aliasing
        ("n:\n  a: 1\n", 2, "no ros__parameters"),  # Cannot have a value before ros__parameters
        ("n:\n  ros__parameters:\n    a:\n", 3, "no value"),  # No value at line
        ("n:\n  ros__parameters:\n    a: [1, x]\n", 3, "mixes"),  # Sequence should be of same type
        ("n:\n  ros__parameters:\n    a: [{b: 1}]\n", 3, "list of"),
        ('n:\n  ros__parameters:\n    "": 1\n', 3, "empty parameter name"),  # No key at line
        ("ros__parameters:\n  a: 1\n", 1, "no node name"),  # There are no node names before
        ("9n:\n  ros__parameters:\n    a: 1\n", 2, "not a valid node name"),
    ],
)
def test_what_rcl_refuses_is_an_error_and_the_file_reads_as_nothing(text: str, line: int, what: str) -> None:
    pf = parse(text, "c.yaml")
    assert not pf.loads and pf.nodes == ()
    errors = [p for p in pf.problems if p.kind == "error"]
    assert errors and errors[0].where.line == line and what in errors[0].message, errors


def test_nested_rebuilds_the_shape_the_file_wrote() -> None:
    text = "c:\n  ros__parameters:\n    gains:\n      j1: {p: 1.5, i: 0}\n    joints: [a, b]\n    linear.x.max: 1.0\n"
    pf = parse(text, "c.yaml")
    # gains and gains.j1 were opened as mappings; linear.x.max was written with its dots
    assert {space for space, _, _ in pf.nodes[0].spaces} == {"gains", "gains.j1"}
    assert sorted(resolve(pf, "/c")) == ["gains.j1.i", "gains.j1.p", "joints", "linear.x.max"]  # one name each to ROS
    assert nested(resolve(pf, "/c"), {"gains", "gains.j1"}) == {
        "gains": {"j1": {"p": 1.5, "i": 0}},
        "joints": ["a", "b"],
        "linear.x.max": 1.0,
    }


def test_positions_map_back_through_substitutions() -> None:
    pf = parse("n:\n  ros__parameters:\n    a: 1\n", "c.yaml", position=lambda line, col: (line + 10, col))
    assert pf.nodes[0].params[0].where.line == 13


# -- what descgen writes into parameter files reads back as the string it meant ------------------


@given(st.text(alphabet=st.characters(blacklist_categories=("Cs",)), min_size=1, max_size=12))
@settings(max_examples=400, deadline=None)
def test_a_string_written_by_yamlstr_is_a_string_to_rcl_and_to_pyyaml(text: str) -> None:
    scalar = yamlstr(text)  # the templates write it in block context: a value, or a "- " item
    pf = parse(f"n:\n  ros__parameters:\n    k: {scalar}\n    l:\n      - {scalar}\n      - {scalar}\n", "c.yaml")
    assert pf.loads, (text, scalar, pf.problems)
    got = {p.name: p.value for p in pf.nodes[0].params}
    assert got == {"k": text, "l": (text, text)}, (text, scalar)
    assert yaml.safe_load(f"k: {scalar}") == {"k": text}


@pytest.mark.parametrize("name", ["x", "y", "z", "n", "on", "1e3", "inf"])
def test_a_gantry_joint_named_y_stays_a_string(name: str) -> None:
    # PyYAML reads a plain y as a string, rcl as true: a joint list [x, y, z] would be a list of
    # mixed types, which rcl refuses, so the controller manager would load nothing
    scalar = yamlstr(name)
    pf = parse(f"c:\n  ros__parameters:\n    joints: [x_joint, {scalar}]\n", "c.yaml")
    assert pf.loads and pf.nodes[0].params[0].value == ("x_joint", name)


@given(st.lists(st.text(alphabet=st.characters(blacklist_categories=("Cs",)), min_size=1, max_size=8), min_size=1))
@settings(max_examples=300, deadline=None)
def test_the_controllers_yaml_dumper_writes_strings_rcl_reads_as_strings(names: list[str]) -> None:
    from descgen.render.context import _Dumper

    doc = {"c": {"ros__parameters": {"joints": names, "one": names[0]}}}
    text = yaml.dump(doc, Dumper=_Dumper, sort_keys=False, default_flow_style=False, width=100)
    pf = parse(text, "c.yaml")
    assert pf.loads, (names, text)
    got = {p.name: p.value for p in pf.nodes[0].params}
    assert got == {"joints": tuple(names), "one": names[0]}, text


# -- descgen audit reads a controllers file as ROS loads it ----------------------------------------

RULES = Path(__file__).resolve().parent / "rules"


def test_audit_reports_a_parameter_given_twice_where_the_dead_line_is(tmp_path: Path) -> None:
    yaml_file = tmp_path / "c.yaml"
    yaml_file.write_text(
        (RULES / "CTRL009" / "good3.controllers.yaml").read_text() + "      joints: [shoulder_joint]\n"
    )
    ran = cli("audit", RULES / "CTRL009" / "good3.urdf", "--controllers", yaml_file)
    # line 17 repeats 'joints' (line 14) inside the same arm_controller block: a warning, exit 0
    assert ran.returncode == 0, ran.stderr
    assert f"{yaml_file}:17:7: warning[READ046]: parameter 'joints' of node '/**/arm_controller'" in ran.stderr


def test_audit_reports_a_file_ros_refuses_and_reads_nothing_from_it(tmp_path: Path) -> None:
    yaml_file = tmp_path / "c.yaml"
    text = (RULES / "CTRL009" / "bad5.controllers.yaml").read_text().replace("update_rate: 100", "update_rate:")
    yaml_file.write_text(text)
    ran = cli("audit", RULES / "CTRL009" / "bad5.urdf", "--controllers", yaml_file)
    assert ran.returncode == 1
    assert f"{yaml_file}:7:" in ran.stderr and "error[READ045]" in ran.stderr and "has no value" in ran.stderr
    assert "[CTRL009]" not in ran.stderr  # the file reads as nothing: no controller is judged


def test_check_catches_a_controllers_file_ros_reads_otherwise_than_yaml() -> None:
    from descgen.prove.controllers import _as_ros_loads, safe_load

    def found(text: str) -> list[tuple[int, str]]:
        return [(f.where.line, f.message) for f in _as_ros_loads(text, "c.yaml", safe_load(text), "config/x.yaml")]

    # [x, y]: a string and a boolean to rcl, a list of one type only, so ROS loads nothing
    ((line, message),) = found("c:\n  ros__parameters:\n    joints: [x, y]\n")
    assert line == 3 and "does not load in ROS" in message and "mixes" in message
    # 1e3: a string to PyYAML (YAML 1.1 floats need a dot), the double 1000 to rcl's strtod
    ((line, message),) = found("c:\n  ros__parameters:\n    rate: 1e3\n")
    assert line == 3 and "c.rate reads as 1000.0 in ROS but '1e3' in YAML" in message
    assert found("c:\n  ros__parameters:\n    joints: [x, 'y']\n    rate: '1e3'\n") == []


def test_an_empty_list_loads_but_no_node_it_reaches_starts() -> None:
    # rcl keeps 'a' with no value (no parse_value call between the sequence's start and end);
    # rclcpp's parameter_value_from throws "No parameter value set" for each node it reaches
    pf = parse("n:\n  ros__parameters:\n    a: []\n    b: 1\n", "c.yaml")
    assert pf.loads and {p.name: p.value for p in pf.nodes[0].params} == {"a": (), "b": 1}
    (empty,) = pf.problems
    assert empty.kind == "empty" and empty.where.line == 3 and "No parameter value set" in empty.message
