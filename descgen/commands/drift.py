"""``descgen drift SPEC (--recording BAG --pose-topic T | --samples CSV) --frame FRAME``: the
model against what the running robot reports (docs/calibration.md).

Per sample, the residual is the measured position of FRAME in BASE minus the model's at the
recorded joint values (and the rotation between them when the input has orientations). The
report gives its median, 95th percentile and worst over the samples, the range each joint
covered, the moment the residual changed (descgen/physics/drift.py: change_point), and the
calibration parameters fitted on the samples after that moment, with what the motion could
not tell apart reported unidentifiable. Exit 1 when the 95th percentile exceeds --tolerance.
"""

from __future__ import annotations

import fnmatch
import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from descgen.codes.command import CAL012
from descgen.core.findings import InputError, Where
from descgen.core.model import ONE_DOF, Robot
from descgen.physics import drift as fitting
from descgen.physics.calibration import split_parameter
from descgen.read.drift_samples import Samples, read_bag, read_csv
from descgen.read.drift_samples import refuse as read_refuse

MIN_SAMPLES = 10
SIGNIFICANT = 3.0  # standard errors a fitted value must clear to be suggested as a correction


def _refuse(why: str, hint: str, where: str = "<command line>") -> InputError:
    return InputError([CAL012.finding(why, hint, "option", Where(where))])


def _stats(values: np.ndarray) -> dict[str, float]:
    return {
        "median": float(np.median(values)),
        "p95": float(np.percentile(values, 95)),
        "max": float(np.max(values)),
    }


def _rotation_error(model_rot: np.ndarray, quat: np.ndarray) -> np.ndarray:
    x, y, z, w = (quat[:, k] for k in range(4))
    meas = np.empty((len(quat), 3, 3))
    meas[:, 0] = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=1)
    meas[:, 1] = np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=1)
    meas[:, 2] = np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=1)
    rel = np.einsum("nji,njk->nik", model_rot, meas)
    cos = np.clip((np.trace(rel, axis1=1, axis2=2) - 1) / 2, -1.0, 1.0)
    return np.asarray(np.arccos(cos))


def _residuals(
    model: fitting.Model, q: dict[str, np.ndarray], xyz: np.ndarray, quat: np.ndarray | None, theta: np.ndarray
) -> tuple[np.ndarray, np.ndarray | None]:
    """Position error (m) and rotation error (rad, when measured) per sample, a chunk at a time
    (the model's frames of every sample at once would be ten times the samples' own size)."""
    n = len(xyz)
    err = np.empty(n)
    ang = np.empty(n) if quat is not None else None
    for lo in range(0, n, fitting.CHUNK):
        hi = min(n, lo + fitting.CHUNK)
        pos, rot = model.forward({k: v[lo:hi] for k, v in q.items()}, theta, hi - lo)
        err[lo:hi] = np.linalg.norm(xyz[lo:hi] - pos, axis=1)
        if ang is not None and quat is not None:
            ang[lo:hi] = _rotation_error(rot, quat[lo:hi])
    return err, ang


def _unit(robot: Robot, name: str) -> tuple[float, str]:
    """(factor from SI, unit) a parameter is shown in: mm or deg."""
    split = split_parameter(name)
    assert split is not None
    joint, what = split
    j = robot.joint(joint)
    if what == "offset":
        return (1000.0, "mm") if j is not None and j.type == "prismatic" else (math.degrees(1.0), "deg")
    return (1000.0, "mm") if what in ("x", "y", "z") else (math.degrees(1.0), "deg")


def suggested_block(robot: Robot, identified: list[dict[str, Any]], source: str = "drift") -> str:
    """The spec's ``calibration:`` entries for the identified parameters (corrections on top of
    the model as it is), each value with its standard error in a comment."""
    joints: dict[str, dict[str, Any]] = {}
    for p in identified:
        split = split_parameter(p["parameter"])
        assert split is not None
        joint, what = split
        factor, unit = _unit(robot, p["parameter"])
        entry = joints.setdefault(joint, {})
        entry[what] = (p["value"] * factor, p["stderr"] * factor, unit)
    lines = [
        "calibration:",
        "  sources:",
        f"    {source}: {{method: descgen drift (least squares on a recording), tool: descgen drift}}",
        "  joints:" if joints else "  joints: {}  # nothing the recording determines beyond its noise",
    ]
    for joint, entry in joints.items():
        lines.append(f"    {json.dumps(joint)}:")  # a joint name may be anything YAML reads as syntax
        lines.append(f"      source: {source}")
        if "offset" in entry:
            v, e, u = entry["offset"]
            lines.append(f"      offset: {v:.6g} {u}  # ± {e:.2g} {u}")
        xyz = [entry.get(c) for c in ("x", "y", "z")]
        rpy = [entry.get(c) for c in ("roll", "pitch", "yaw")]
        if any(xyz) or any(rpy):
            lines.append("      origin:")
            for key, comps in (("xyz", xyz), ("rpy", rpy)):
                if any(comps):
                    shown = ", ".join(f"{c[0]:.6g} {c[2]}" if c else "0" for c in comps)
                    errs = ", ".join(f"{c[1]:.2g}" if c else "-" for c in comps)
                    lines.append(f"        {key}: [{shown}]  # ± [{errs}]")
    return "\n".join(lines) + "\n"


def drift(
    robot: Robot,
    frame: str,
    *,
    base: str | None = None,
    recording: Path | None = None,
    pose_topic: str | None = None,
    samples: Path | None = None,
    parameters: Sequence[str] = (),
    tolerance_m: float = 0.001,
    series: bool = False,
) -> dict[str, Any]:
    """The report (see the module doc); ``series``: with ``series: {t_s, residual_m}``, the
    residual of every sample in time order (t from the first sample), for a plot."""
    links = {lk.name for lk in robot.links}
    if frame not in links:
        raise _refuse(f"--frame {frame!r} is not a link of the robot", "name a link of the spec")
    if base is not None and base not in links:
        raise _refuse(f"--base {base!r} is not a link of the robot", "name a link of the spec")
    # the pose topic names its frame; else the root link
    chosen_base = base or robot.root() or ""
    if recording is not None:
        if pose_topic is None:
            raise _refuse("--recording needs --pose-topic", "name the topic of the measured pose")
        # read once with every moving joint from the root down: the poses' frame_id may pick a lower base
        probe = (
            fitting.chain(robot, robot.root() or chosen_base, frame) or fitting.chain(robot, chosen_base, frame) or []
        )
        data = read_bag(recording, [j.name for j in probe if j.type in ONE_DOF], pose_topic)
        if base is None and data.base in links and data.base != chosen_base:
            chosen_base = str(data.base)
    joints = fitting.chain(robot, chosen_base, frame)
    if joints is None:
        raise _refuse(f"{frame!r} is not below {chosen_base!r} in the tree", "give --base, an ancestor of --frame")
    moving = [j.name for j in joints if j.type in ONE_DOF]
    names = _parameters(joints, chosen_base, frame, parameters)  # before the samples: a bad option first
    if recording is not None:
        lacking = [j for j in moving if j not in data.q]
        if lacking:
            raise read_refuse(
                recording, f"/joint_states never gives joint {lacking[0]!r}", "record every joint of the chain"
            )
    if recording is None:
        assert samples is not None
        data = read_csv(samples, moving)
    return _report(robot, joints, moving, data, chosen_base, frame, names, tolerance_m, series)


def _parameters(joints: list[Any], base: str, frame: str, patterns: Sequence[str]) -> list[str]:
    names = fitting.parameters(joints)
    if not names:
        raise _refuse(
            f"no joint between {base!r} and {frame!r}: nothing to compare", "give --base an ancestor of --frame"
        )
    if patterns:
        names = [p for p in names if any(fnmatch.fnmatchcase(p, pat) for pat in patterns)]
        if not names:
            raise _refuse("--parameters matches no parameter of the chain", "e.g. 'joint:*:offset'")
    return names


def _report(
    robot: Robot,
    joints: list[Any],
    moving: list[str],
    data: Samples,
    base: str,
    frame: str,
    names: list[str],
    tolerance_m: float,
    series: bool = False,
) -> dict[str, Any]:
    n = len(data.t)
    if n < MIN_SAMPLES:
        raise _refuse(f"{n} usable samples; the fit needs at least {MIN_SAMPLES}", "record longer")
    order = np.argsort(data.t, kind="stable")
    t = data.t[order]
    q = {k: v[order] for k, v in data.q.items()}
    xyz = data.xyz[order]
    model = fitting.Model(joints, names)
    zero = np.zeros(len(names))
    quat = data.quat[order] if data.quat is not None else None
    err, ang = _residuals(model, q, xyz, quat, zero)
    residual: dict[str, Any] = {f"{k}_m": v for k, v in _stats(err).items()} | {"samples": n}
    if ang is not None:
        residual["rotation"] = {f"{k}_rad": v for k, v in _stats(ang).items()}
    change = fitting.change_point(model, q, xyz)
    start = change.index if change is not None else 0
    seg = slice(start, n)
    q_seg = {k: v[seg] for k, v in q.items()}
    fit = fitting.fit(model, q_seg, xyz[seg])
    after, _ = _residuals(model, q_seg, xyz[seg], None, fit.theta)
    unfitted = {p for i, p in enumerate(names) if not fit.fitted[i]}
    identified = [
        {
            "parameter": p,
            "value": float(fit.theta[i]),
            "stderr": float(fit.stderr[i]),
            # a value within SIGNIFICANT standard errors of zero is not evidence of a correction
            "significant": bool(abs(fit.theta[i]) >= SIGNIFICANT * fit.stderr[i]),
        }
        | ({"stands_for": absorbed} if (absorbed := [k for k in fit.confounded.get(p, []) if k in unfitted]) else {})
        for i, p in enumerate(names)
        if fit.fitted[i]
    ]
    unidentifiable = [p for i, p in enumerate(names) if not fit.fitted[i]]
    out = {
        "frame": frame,
        "base": base,
        "residual": residual,
        "spread": {j: [float(q[j].min()), float(q[j].max())] for j in moving},
        "dropped": data.dropped,
        "change_point": None
        if change is None
        else {
            "time": float(t[start]),
            "after_s": float(t[start] - t[0]),
            "f": change.f,
            "before_median_m": float(np.median(err[:start])),
            "after_median_m": float(np.median(err[start:])),
        },
        "fitted_on": {"first_time": float(t[start]), "samples": n - start},
        "identified": identified,
        "unidentifiable": unidentifiable,
        "confounded": fit.confounded,
        "after_fit": {f"{k}_m": v for k, v in _stats(after).items()},
        "noise_m": fit.sigma,
        "tolerance_m": tolerance_m,
        "drifted": bool(residual["p95_m"] > tolerance_m),
        "suggested": suggested_block(robot, [p for p in identified if p["significant"]]),
    }
    if series:
        out["series"] = {"t_s": [float(x) for x in t - t[0]], "residual_m": [float(x) for x in err]}
    return out


def text(report: dict[str, Any]) -> str:
    r = report["residual"]
    out = [
        f"drift of {report['frame']} in {report['base']}: {r['samples']} samples"
        + (f" ({report['dropped']} poses without joint states dropped)" if report["dropped"] else ""),
        f"  position residual: median {r['median_m'] * 1000:.3f} mm, 95% {r['p95_m'] * 1000:.3f} mm, "
        f"worst {r['max_m'] * 1000:.3f} mm (tolerance {report['tolerance_m'] * 1000:g} mm)",
    ]
    if "rotation" in r:
        rr = r["rotation"]
        out.append(
            f"  rotation residual: median {math.degrees(rr['median_rad']):.4f} deg, "
            f"95% {math.degrees(rr['p95_rad']):.4f} deg, worst {math.degrees(rr['max_rad']):.4f} deg"
        )
    out.append(
        "  joints covered: " + ", ".join(f"{j} [{lo:.3g}, {hi:.3g}]" for j, (lo, hi) in report["spread"].items())
    )
    c = report["change_point"]
    if c is not None:
        out.append(
            f"  the residual changed {c['after_s']:.2f} s into the recording (t = {c['time']:.3f}): median "
            f"{c['before_median_m'] * 1000:.3f} mm before, {c['after_median_m'] * 1000:.3f} mm after; "
            "the fit below uses the samples after it"
        )
    else:
        out.append("  no change of the residual over the recording")
    a = report["after_fit"]
    out.append(
        f"  after the fit: median {a['median_m'] * 1000:.3f} mm, 95% {a['p95_m'] * 1000:.3f} mm "
        f"(noise {report['noise_m'] * 1000:.3f} mm)"
    )
    for p in report["identified"]:
        also = (
            f" (also carries {', '.join(p['stands_for'])}: this motion cannot tell them apart)"
            if p.get("stands_for")
            else ""
        )
        weak = "" if p["significant"] else f" (within {SIGNIFICANT:g} standard errors of 0: not suggested)"
        out.append(f"  identified {p['parameter']} = {p['value']:.6g} ± {p['stderr']:.2g}{weak}{also}")
    if report["unidentifiable"]:
        out.append(
            f"  unidentifiable from this motion ({len(report['unidentifiable'])}): "
            + ", ".join(report["unidentifiable"])
        )
    out.append(
        f"  suggested calibration (the values beyond {SIGNIFICANT:g} standard errors, corrections on top of the spec "
        "as it is):"
    )
    out += ["    " + ln for ln in report["suggested"].splitlines()]
    return "\n".join(out) + "\n"


__all__ = ["drift", "suggested_block", "text"]
