"""``$(find pkg)`` inside a pass-through element stays symbolic (issue 28): a Gazebo plugin's
``<parameters>$(find bot_bringup)/config/controllers.yaml</parameters>`` is imported as written,
generated so that xacro evaluates it on the machine that launches the robot, and package.xml
depends on the package; no path of the importing machine reaches the spec or the package.
xacro itself (its ``_eval_find`` pointed at the workspace, as ament_index would) is the oracle."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from lxml import etree

from .helpers import cli

PLUGIN = (
    '<gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">'
    "<parameters>$(find bot_bringup)/config/controllers.yaml</parameters>"
    "<robot_param_node>$(find bot_bringup)</robot_param_node>"
    "<uri>file://$(find bot_bringup)/config/world.sdf</uri>"
    "</plugin></gazebo>"
)
XACRO = f"""<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  {PLUGIN}
  <gazebo reference="base_link"><note>costs $5, home is $$(env HOME)</note></gazebo>
</robot>
"""


def _workspace(tmp_path: Path) -> tuple[Path, Path]:
    src = tmp_path / "ws" / "src"
    bringup = src / "bot_bringup"
    (bringup / "config").mkdir(parents=True)
    (bringup / "package.xml").write_text("<package format='3'><name>bot_bringup</name></package>")
    (bringup / "config" / "controllers.yaml").write_text("controller_manager:\n  ros__parameters: {update_rate: 100}\n")
    desc = src / "bot_description"
    (desc / "urdf").mkdir(parents=True)
    (desc / "package.xml").write_text("<package format='3'><name>bot_description</name></package>")
    (desc / "urdf" / "bot.urdf.xacro").write_text(XACRO)
    return src, bringup


def _xacro(path: Path, packages: dict[str, Path], monkeypatch: pytest.MonkeyPatch) -> etree._Element:
    import xacro
    import xacro.substitution_args as sa

    monkeypatch.setattr(sa, "_eval_find", lambda pkg: str(packages[pkg]))
    doc = xacro.process_file(str(path))
    return etree.fromstring(doc.toxml().encode())


def test_find_in_passthrough_is_imported_and_generated_symbolic(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    src, _ = _workspace(tmp_path)
    spec = tmp_path / "project" / "specs" / "bot.yaml"
    ran = cli("import", src / "bot_description" / "urdf" / "bot.urdf.xacro", "-o", spec, "--package-path", src)
    assert ran.returncode == 0, ran.stderr
    text = spec.read_text()
    assert str(tmp_path) not in text and str(tmp_path.resolve()) not in text  # no path of this machine
    kept = [p["xml"] for p in yaml.safe_load(text)["passthrough"]]
    assert any("<parameters>$(find bot_bringup)/config/controllers.yaml</parameters>" in x for x in kept)
    assert any("<robot_param_node>$(find bot_bringup)</robot_param_node>" in x for x in kept)
    assert any("<uri>file://$(find bot_bringup)/config/world.sdf</uri>" in x for x in kept)  # file:// kept

    ran = cli("generate", spec, "--package-path", src)
    assert ran.returncode == 0, ran.stderr
    package = tmp_path / "project" / "generated" / "bot_description"
    manifest = etree.parse(str(package / "package.xml")).getroot()
    assert "bot_bringup" in [e.text for e in manifest.iter("exec_depend")]
    for rel in ("urdf/bot.urdf", "urdf/bot.urdf.xacro", "package.xml"):
        assert str(tmp_path.resolve()) not in (package / rel).read_text(), rel
    # the plain URDF keeps it as written; xacro evaluates it where the robot is launched
    plain = etree.parse(str(package / "urdf" / "bot.urdf")).getroot()
    assert plain.findtext("gazebo/plugin/parameters") == "$(find bot_bringup)/config/controllers.yaml"
    elsewhere = tmp_path / "other_machine" / "share" / "bot_bringup"
    expanded = _xacro(package / "urdf" / "bot.urdf.xacro", {"bot_bringup": elsewhere}, monkeypatch)
    assert expanded.findtext("gazebo/plugin/parameters") == f"{elsewhere}/config/controllers.yaml"
    assert expanded.findtext("gazebo/plugin/robot_param_node") == str(elsewhere)
    # every other dollar is still data: xacro evaluates nothing else of a pass-through
    assert expanded.findtext("gazebo/note") == "costs $5, home is $(env HOME)"
    assert cli("check", spec, "--package-path", src).returncode == 0


@pytest.mark.parametrize(
    "written",
    ["$(find ../etc)", "$(find bot_bringup extra)", "$(env HOME)", "${__import__('os').getcwd()}", "$(eval 1+1)"],
)
def test_only_find_with_a_package_name_stays_live(written: str, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.spec.passthrough import for_xacro

    escaped = for_xacro(f"<gazebo><p>{written}</p></gazebo>")
    assert "$(" not in escaped.replace("${'$'}(", "") and "${__" not in escaped
    assert for_xacro("<gazebo><p>$(find bot_bringup)/x</p></gazebo>") == "<gazebo><p>$(find bot_bringup)/x</p></gazebo>"


def test_a_path_outside_the_packages_is_left_as_it_is(tmp_path: Path) -> None:
    from descgen.commands.importer.packages import symbolic

    src, bringup = _workspace(tmp_path)
    assert symbolic(f"<p>{bringup.resolve()}/config/x.yaml</p>", [src]) == "<p>$(find bot_bringup)/config/x.yaml</p>"
    # a path outside the searched folders is not looked at, even when it is a package
    assert (
        symbolic(f"<p>{bringup.resolve()}/config</p>", [tmp_path / "elsewhere"]) == f"<p>{bringup.resolve()}/config</p>"
    )
    assert symbolic("<p>/etc/passwd</p>", [src]) == "<p>/etc/passwd</p>"
    # a folder whose package.xml names a package that $(find) finds elsewhere is not that package
    twin = tmp_path / "twin" / "bot_bringup"
    twin.mkdir(parents=True)
    (twin / "package.xml").write_text("<package><name>bot_bringup</name></package>")
    assert symbolic(f"<p>{twin.resolve()}/x</p>", [src, tmp_path / "twin"]) == f"<p>{twin.resolve()}/x</p>"


def test_a_find_of_the_generated_package_itself(tmp_path: Path) -> None:
    """``$(find bot_description)`` in the description of bot_description names the original
    package (its files), not what descgen generates: import names the generated package
    otherwise (IMP014) and keeps the reference; a spec that names its own generated package
    is refused at validate (SPEC066), not left to fail generate's proof."""
    src, _ = _workspace(tmp_path)
    xacro = src / "bot_description" / "urdf" / "bot.urdf.xacro"
    xacro.write_text(
        XACRO.replace("$(find bot_bringup)/config/controllers.yaml", "$(find bot_description)/config/c.yaml")
    )
    spec = tmp_path / "project" / "specs" / "bot.yaml"
    ran = cli("import", xacro, "-o", spec, "--package-path", src)
    assert ran.returncode == 0 and "IMP014" in ran.stderr, ran.stderr
    data = yaml.safe_load(spec.read_text())
    assert data["package"]["name"] != "bot_description"
    assert any("$(find bot_description)/config/c.yaml" in p["xml"] for p in data["passthrough"])
    assert cli("generate", spec, "--package-path", src).returncode == 0
    del data["package"]
    spec.write_text(yaml.safe_dump(data, sort_keys=False))
    refused = cli("validate", spec, "--package-path", src)
    assert refused.returncode == 2 and "error[SPEC066]" in refused.stderr, refused.stderr
