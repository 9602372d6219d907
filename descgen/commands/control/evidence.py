"""A control run's evidence on disk: lifecycle.jsonl/.md, interfaces.md,
desired_vs_measured.csv, a plot per joint, an MCAP recording and verdict.json."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path
from typing import Any

from descgen.codes.control import CTRL034, CTRL035
from descgen.commands.control.verdict import Outcome
from descgen.core.findings import InputError, Where
from descgen.core.model import Robot
from descgen.infra.safeio import output_file, output_kind, safe_file_name


def evidence_folder(package: Path, plant: str, faults: object) -> Path:
    """Where a run without ``--out`` writes. The committed evidence belongs to the documented
    mock run; an experiment (a simulated plant, planted faults) goes to a new scratch folder
    so it can never silently replace what ``check`` and the evidence page vouch for."""
    if plant == "mock" and not faults:
        return package / "evidence"
    import tempfile

    return Path(tempfile.mkdtemp(prefix="descgen-control-"))


FILES = (
    "lifecycle.jsonl",
    "lifecycle.md",
    "interfaces.md",
    "desired_vs_measured.csv",
    "control_run",
    "verdict.json",
)


def plot_name(joint: str) -> str:
    """The plot of a joint: its name as one plain file name (safeio.safe_file_name), so a joint
    named ``../../x`` or ``wrist/pitch`` never becomes a path."""
    return safe_file_name(joint, ".png")


def plot_names(out: Outcome) -> list[str]:
    return [plot_name(joint) for joint in out.tracking]


def _refuse_unsafe(folder: Path, names: list[str]) -> None:
    """CTRL035 (exit 2) when the evidence folder is a link or not a folder, or an entry control
    writes in it is a link, FIFO, device or socket (control_run/ must be a real folder): the
    evidence is written only as regular files inside the folder named, and nothing is written
    when any is refused."""
    bad: list[tuple[Path, str]] = []
    kind = output_kind(folder)  # a regular file in the way is mkdir's CTRL034, below
    if kind is not None and kind != "a directory":
        bad.append((folder, kind))
    elif folder.is_dir():
        for name in names:
            entry = folder / name
            kind = output_kind(entry)
            if name == "control_run":
                if kind == "a directory":
                    # the recording's own files too: a link there is refused, not replaced
                    for inner in sorted(entry.iterdir()):
                        inner_kind = output_kind(inner)
                        if inner_kind is not None:
                            bad.append((inner, inner_kind))
                    continue
                if kind is None and entry.exists():
                    kind = "a regular file"
            if kind is not None:
                bad.append((entry, kind))
    if bad:
        raise InputError(
            [
                CTRL035.finding(
                    f"{'the evidence folder' if path == folder else path.name + ' in the evidence folder'} is {kind}, "
                    f"not {'a folder' if path == folder or path.name == 'control_run' else 'a regular file'}: "
                    "control writes its evidence only inside the folder named, and wrote nothing",
                    "remove it, or choose another --out",
                    "option",
                    Where(str(path)),
                )
                for path, kind in bad
            ]
        )


def _write_plain(path: Path, data: bytes) -> None:
    """Write a regular file, never through a link that appeared since the check (O_NOFOLLOW),
    never blocking on a FIFO (O_NONBLOCK: no reader is an error)."""
    import os
    import stat

    flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0)
    fd = os.open(path, flags, 0o644)
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise OSError(f"{path} is not a regular file")
        os.set_blocking(fd, True)
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view) :]
    finally:
        os.close(fd)


def write_evidence(
    out: Outcome, folder: Path, robot: Robot, plots: bool = True, package: Path | None = None
) -> list[str]:
    """lifecycle.jsonl/.md, interfaces.md, desired_vs_measured.csv, plots, MCAP, verdict.json.
    ``plots=False``: all but the plots (``descgen check`` compares their data, not their bytes).
    ``package``: the package the run loaded; verdict.json then records the hash of the run's
    inputs and of the files written, so ``check`` can take them without running again
    (record.reuse_record). verdict.json is written last, when every file it vouches for is."""
    _refuse_unsafe(folder, [*FILES, *plot_names(out)])  # before anything is written
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:  # a file in the way, no permission
        raise InputError(
            [
                CTRL034.finding(
                    f"cannot create the evidence folder {folder}: {exc.strerror or exc}",
                    "choose another --out",
                    "option",
                    Where(str(folder)),
                )
            ]
        ) from None
    from descgen.render.formatting import mdfence, mdtext

    cm = out.cm
    written = []

    def put(name: str, text: str) -> None:
        _write_plain(output_file(folder, name), text.encode("utf-8"))
        written.append(name)

    put("lifecycle.jsonl", "".join(json.dumps(e, sort_keys=True) + "\n" for e in cm.trace.events))
    lines = [
        "# ros2_control lifecycle and claims, in order",
        "",
        "| t (s) | event | who | detail |",
        "|---|---|---|---|",
    ]
    for e in cm.trace.events:
        who = e.get("name") or e.get("controller") or e.get("joint", "")
        detail = ", ".join(f"{k}={v}" for k, v in e.items() if k not in ("t", "event", "name", "controller", "kind"))
        # names come from the spec: escaped so that none becomes HTML, a link or a new cell
        lines.append(f"| {e['t']:.2f} | {mdtext(e['event'])} | {mdtext(who)} | {mdtext(detail)} |")
    put("lifecycle.md", "\n".join(lines) + "\n")
    cmds = [f"{j.name}/{i}" for j in cm.hardware.joints for i in j.commands]
    states = [f"{j.name}/{i}" for j in cm.hardware.joints for i in j.states]
    listing = ["command interfaces"]
    listing += [f"\t{k} [available] [{'claimed' if k in cm.resources.owner else 'unclaimed'}]" for k in cmds]
    listing += ["state interfaces"] + [f"\t{k}" for k in states]
    controllers = [f"{n:<26} {c.type:<55} {c.state}" for n, c in cm.controllers.items()]
    text = ["# Interfaces and controllers (as `ros2 control list_hardware_interfaces` / `list_controllers`)", ""]
    # fenced by more backticks than any name holds: a name cannot close the block
    text += mdfence("\n".join(listing)) + mdfence("\n".join(controllers))
    put("interfaces.md", "\n".join(text))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["time_s", "joint", "desired", "commanded", "measured", "error"])
    for t, name, d, c, m in out.rows:
        w.writerow([f"{t:.3f}", name, f"{d:.9g}", f"{c:.9g}", f"{m:.9g}", f"{d - m:.9g}"])
    put("desired_vs_measured.csv", buf.getvalue())
    verdict = out.verdict()
    if plots:
        written += _plots(out, folder)
    written += _recording(out, folder)
    if package is not None:
        from descgen.commands.control.record import reuse_record

        record = reuse_record(folder, package, robot, verdict)
        verdict = {**verdict, **({} if record is None else {"reuse": record})}
    put("verdict.json", json.dumps(verdict, indent=2) + "\n")
    return written


def _plots(out: Outcome, folder: Path) -> list[str]:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    names = []
    for joint in out.tracking:
        rows = [r for r in out.rows if r[1] == joint]
        fig, ax = plt.subplots(figsize=(7, 3.2))
        ax.plot([r[0] for r in rows], [r[2] for r in rows], label="desired (controller)")
        ax.plot([r[0] for r in rows], [r[3] for r in rows], "--", label="commanded (after limits)")
        ax.plot([r[0] for r in rows], [r[4] for r in rows], label="measured (state interface)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("position (SI: m or rad)")
        ax.set_title(f"{joint}: " + ("state echoes the command (mock)" if out.echo else "simulated plant"))
        ax.legend(fontsize=7)
        fig.tight_layout()
        name = plot_name(joint)
        buf = io.BytesIO()
        fig.savefig(buf, dpi=80, format="png")
        _write_plain(output_file(folder, name), buf.getvalue())
        plt.close(fig)
        names.append(name)
    return names


def _recording(out: Outcome, folder: Path) -> list[str]:
    import shutil

    import numpy as np
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    types: dict[str, Any] = dict(ts.types)
    js, header, time_ = (
        types["sensor_msgs/msg/JointState"],
        types["std_msgs/msg/Header"],
        types["builtin_interfaces/msg/Time"],
    )
    bag = folder / "control_run"
    shutil.rmtree(bag, ignore_errors=True)
    start = 1_700_000_000 * 1_000_000_000
    by_time: dict[float, list[tuple[str, float, float]]] = {}
    for t, name, d, _, m in out.rows:
        by_time.setdefault(t, []).append((name, d, m))
    with Writer(bag, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        measured = w.add_connection("/joint_states", "sensor_msgs/msg/JointState", typestore=ts)
        desired = w.add_connection("/arm_controller/desired_state", "sensor_msgs/msg/JointState", typestore=ts)
        for t, entries in sorted(by_time.items()):
            ns = start + round(t * 1e9)
            stamp = time_(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)
            names = [e[0] for e in entries]
            for conn, values in ((measured, [e[2] for e in entries]), (desired, [e[1] for e in entries])):
                msg = js(
                    header=header(stamp=stamp, frame_id=""),
                    name=names,
                    position=np.array(values),
                    velocity=np.zeros(0),
                    effort=np.zeros(0),
                )
                w.write(conn, ns, ts.serialize_cdr(msg, "sensor_msgs/msg/JointState"))
    return ["control_run/"]
