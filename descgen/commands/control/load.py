"""The generated package's ros2_control block and controllers YAML -> a running model of
ros2_control (hardware with its limits and mimic joints, controllers spawned), refusing what
Jazzy's parser would refuse."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from descgen.codes.control import CTRL021
from descgen.commands.control.manager import ControllerManager
from descgen.commands.control.system import Hardware, HardwareSet, JointHw, MimicHw, Plant, Trace
from descgen.core.findings import InputError, Where
from descgen.core.model import HardwareBlock, Robot, Ros2Control
from descgen.physics.hardware_info import active_mimic
from descgen.read.controllers import read_controllers_text
from descgen.read.urdf import read_urdf_text
from descgen.read.xacro_file import expand


def find_package(spec: Path, robot: Robot, given: Path | None) -> Path:
    """The generated package: ``given`` is the package itself or the output root holding it
    (what ``generate --out`` was given); without it, the default output root. Nothing found
    is an input error that says where it looked."""
    from descgen.render.context import package_name
    from descgen.spec.files import default_out

    name = package_name(robot)
    root = given if given is not None else default_out(spec)
    tried = [root, root / name] if given is not None else [root / name]
    needed = (Path("config") / "ros2_controllers.yaml", Path("urdf") / f"{robot.name}.ros2_control.xacro")
    for folder in tried:
        if all((folder / rel).is_file() for rel in needed):
            return folder
    looked = " or ".join(str(f) for f in tried)
    raise InputError(
        [
            CTRL021.finding(
                f"no generated package of '{robot.name}' at {looked} "
                f"(it needs {needed[0].as_posix()} and {needed[1].as_posix()})",
                f"run descgen generate {spec}"
                + (f" --out {given}" if given is not None else "")
                + ", or pass --package with the folder generate --out wrote",
                "option" if given is not None else "file",
                Where(str(tried[-1])),
            )
        ]
    )


def load_system(package: Path, robot: Robot, plant: Plant) -> ControllerManager:
    """The hardware and controllers as the generated files describe them."""
    xacro = package / "urdf" / f"{robot.name}.ros2_control.xacro"
    model, _ = read_urdf_text(expand(xacro, str(xacro)), str(xacro))
    rc = model.ros2_control
    if rc is None:
        raise InputError([CTRL021.finding(f"{xacro} has no <ros2_control> block", "generate first", "file")])
    controllers, rate, _ = read_controllers_text(
        (package / "config" / "ros2_controllers.yaml").read_text(), str(package / "config" / "ros2_controllers.yaml")
    )
    _refuse_like_jazzy(robot, rc, xacro)
    trace = Trace()
    policies = {cj.name: cj.on_limit for cj in robot.ros2_control.joints} if robot.ros2_control else {}
    limits = {j.name: abs(j.limit.velocity) for j in robot.joints if j.limit is not None and j.limit.velocity}
    parts = []
    for block in rc.hardware_blocks():  # one GenericSystem per <ros2_control> block
        hw = Hardware(block.name, block.plugin, dict(block.params), _joints(rc, block, policies), trace, plant)
        hw.mimics = [mj for mj in mimic_joints(robot, rc) if any(j.name == mj.joint for j in hw.joints)]
        hw.vel_limit = {j.name: limits[j.name] for j in hw.joints if j.name in limits}
        parts.append(hw)
    if len(parts) == 1:
        hw = parts[0]
    else:
        hw = HardwareSet(parts, trace, plant)
        hw.kinds = {b.name: b.type for b in rc.hardware_blocks()}
    cm = ControllerManager(hw, rate or 100.0, trace)
    cm.start_hardware()
    for c in controllers:
        cm.spawn(c.name, c.type, {k: _plain(v) for k, v in c.params})
    return cm


def _joints(rc: Ros2Control, block: HardwareBlock, policies: dict[str, str]) -> list[JointHw]:
    """The joints of one block as its GenericSystem holds them: commands NaN until configured,
    states at their initial values, command limits from the interfaces' min/max."""
    several = len(rc.hardware_blocks()) > 1
    return [
        JointHw(
            cj.name,
            {i.name: math.nan for i in cj.command},
            {i.name: math.nan if i.initial_value is None else i.initial_value for i in cj.state},
            {i.name: (i.min, i.max) for i in cj.command},
            policies.get(cj.name, "reject"),
        )
        for cj in rc.joints
        if not several or cj.block == block.name
    ]


def _refuse_like_jazzy(robot: Robot, rc: Ros2Control, xacro: Path) -> None:
    """What Jazzy's component parser throws on (mimic rules, CTRL040-043), as an input error:
    the real controller_manager would load no hardware at all."""
    from descgen.audit import run as run_rules

    model = dataclasses.replace(robot, ros2_control=dataclasses.replace(rc, controllers=()))
    refused = [f for f in run_rules(model, codes=MIMIC_CODES) if f.severity == "error"]
    if refused:
        raise InputError(refused)


MIMIC_CODES = ("CTRL040", "CTRL041", "CTRL042", "CTRL043")


def mimic_joints(robot: Robot, rc: Ros2Control) -> list[MimicHw]:
    """HardwareInfo.mimic_joints as Jazzy's parser fills it: every ros2_control joint whose
    URDF joint has <mimic> and whose mimic attribute is not false, in block order."""
    out = []
    for cj in rc.joints:
        j = robot.joint(cj.name)
        if j is not None and j.mimic is not None and active_mimic(robot, cj):
            out.append(MimicHw(cj.name, j.mimic.joint, j.mimic.multiplier, j.mimic.offset))
    return out


def _plain(v: object) -> object:
    if isinstance(v, tuple) and v and all(isinstance(x, tuple) and len(x) == 2 for x in v):
        return {str(k): _plain(x) for k, x in v}
    if isinstance(v, tuple):
        return [_plain(x) for x in v]
    return v
