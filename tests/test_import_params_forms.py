"""``descgen import`` of a controllers file in the forms rcl accepts (issue 28): the ``/**:`` blocks
many Jazzy packages ship, with the key repeated. Expected values are the hand-written file below;
the generated file is read back with yaml.safe_load (not descgen's reader) and its parameters
compared by the names ROS gives them (docs/ros2_parameters.md)."""

from __future__ import annotations

from pathlib import Path

import yaml

from .test_import_control import _generated, _import, _write

WILDCARD = """\
/**:
  controller_manager:
    ros__parameters:
      update_rate: 1000
      use_sim_time: false
      jsb:
        type: joint_state_broadcaster/JointStateBroadcaster
      fwd:
        type: forward_command_controller/ForwardCommandController
/**:
  fwd:
    ros__parameters:
      joints: [j1]
      interface_name: position
      gains: {p: 10, d: 0.10}
      limits.max: 2.5
"""


def _flat(params: dict[str, object], prefix: str = "") -> dict[str, object]:
    """Nested mappings as ROS names their parameters: gains: {p: 10} is gains.p (hand rule of rcl)."""
    out: dict[str, object] = {}
    for k, v in params.items():
        if isinstance(v, dict):
            out.update(_flat(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out


def test_every_controller_of_a_wildcard_file_is_imported_and_comes_back(tmp_path: Path) -> None:
    ctl = tmp_path / "ctl.yaml"
    ctl.write_text(WILDCARD)
    outcome = _import(_write(tmp_path), ctl)  # asserts the round trip is proven
    rc = yaml.safe_load(outcome.imported.spec_text)["ros2_control"]
    assert rc["update_rate"] == "1000 Hz"  # not the default 100: the file's value reached the manager
    assert [c["name"] for c in rc["controllers"]] == ["jsb", "fwd"]
    assert rc["controllers"][1]["source"] == "ctl.yaml:11"  # the key 'fwd:' of its own entry
    written = yaml.safe_load(_generated(outcome.imported.spec_text)["config/ros2_controllers.yaml"])
    assert written["controller_manager"]["ros__parameters"]["update_rate"] == 1000
    assert (
        written["controller_manager"]["ros__parameters"]["fwd"]["type"]
        == "forward_command_controller/ForwardCommandController"
    )
    assert _flat(written["fwd"]["ros__parameters"]) == {
        "joints": ["j1"],
        "interface_name": "position",
        "gains.p": 10,
        "gains.d": 0.1,
        "limits.max": 2.5,
    }
    not_imported = sorted((f.subject, f.where.line) for f in outcome.imported.report if f.code == "IMP024")
    assert not_imported == [("controllers", 5)]  # use_sim_time: the spec has no field for it
