"""What the commands print, shaped from finished results: text tables and trees, and the
JSON documents of ``--format json``. Formatting only: nothing here computes a verdict, reads
a file or chooses an exit code (findings go through :mod:`descgen.output.report`)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from descgen.core.display import mm
from descgen.output.report import printable

if TYPE_CHECKING:
    from descgen.commands.faults import Result
    from descgen.commands.fleet.identity import Identity, Mapping
    from descgen.commands.fleet.run import Outcome
    from descgen.commands.tf.bagaudit import Report
    from descgen.core.model import Robot
    from descgen.physics.frames import Edge
    from descgen.physics.poses import Row


def validated(path: str, robot: Robot) -> str:
    return (
        f"{printable(path)}: valid: robot '{printable(robot.name)}', {len(robot.links)} links, "
        f"{len(robot.joints)} joints, {len(robot.known_poses)} known poses"
    )


# -- poses -----------------------------------------------------------------------------


def poses_json(rows: Sequence[Row]) -> list[dict[str, Any]]:
    return [
        {
            "pose": r.pose.name,
            "frame": r.measurement.frame,
            "relative_to": r.relative_to,
            "measured_m": list(r.measurement.xyz),
            "model_m": None if r.model is None else list(r.model),
            "error_m": None if r.error is None else list(r.error),
            "worst_axis_error_m": None if r.error is None else r.worst,
            "tolerance_m": r.measurement.tolerance,
            "ok": r.ok,
            "source": r.measurement.source,
        }
        for r in rows
    ]


def _mm(v: Sequence[float] | None) -> str:
    return "n/a" if v is None else mm(v)


def poses_table(rows: Sequence[Row]) -> str:
    from descgen.physics.poses import worst_mm

    lines = [f"{'pose':<16} {'frame':<22} {'measured (mm)':<24} {'model (mm)':<24} {'worst':>7} {'tol':>5}  verdict"]
    for r in rows:
        worst = worst_mm(r.error, r.measurement.tolerance)
        lines.append(
            f"{printable(r.pose.name):<16} {printable(r.measurement.frame):<22} "
            f"{_mm(r.measurement.xyz):<24} {_mm(r.model):<24} "
            f"{worst:>7} {r.measurement.tolerance * 1000:>5g}  {'pass' if r.ok else 'FAIL'}"
        )
    return "".join(line + "\n" for line in lines)


# -- faults ----------------------------------------------------------------------------


def faults_json(path: str, results: Sequence[Result]) -> dict[str, Any]:
    return {
        "path": path,
        "faults": [
            {
                "fault": r.fault.name,
                "planted": r.planted,
                "applicable": r.applicable,
                "caught": r.caught,
                "by": None if r.by is None else r.by.as_dict(),
            }
            for r in results
        ],
        "caught": sum(r.caught for r in results),
        "missed": sum(r.applicable and not r.caught for r in results),
    }


def faults_text(results: Sequence[Result]) -> str:
    lines = []
    for r in results:
        verdict = "caught" if r.caught else "n/a" if not r.applicable else "MISSED"
        by = f" by {r.by.code}: {r.by.message}" if r.by else ""
        lines.append(f"{verdict:<7} {r.fault.name:<28} {printable(r.planted + by)}")
    caught = sum(r.caught for r in results)
    applicable = sum(r.applicable for r in results)
    lines.append(f"{caught} of {applicable} planted faults caught ({len(results) - applicable} not applicable)")
    return "".join(line + "\n" for line in lines)


# -- frames ----------------------------------------------------------------------------


def frames_json(edges: Sequence[Edge]) -> list[dict[str, Any]]:
    return [
        {
            "parent": e.parent,
            "child": e.child,
            "owner": e.owner,
            "topic": e.topic,
            "static": e.static,
            "joint": e.joint,
            "fed_by": e.via,
        }
        for e in edges
    ]


def frames_tree(edges: Sequence[Edge]) -> str:
    """Each root frame, then its children indented under it with their publisher; a frame
    seen again on the same branch (a cycle) is shown once and not descended into."""
    children: dict[str, list[Edge]] = {}
    for e in edges:
        children.setdefault(e.parent, []).append(e)
    roots = [p for p in children if p not in {e.child for e in edges}]
    lines: list[str] = []

    def show(frame: str, depth: int, seen: set[str]) -> None:
        for e in children.get(frame, []):
            kind = "static" if e.static else "dynamic"
            lines.append(f"{'  ' * depth}{printable(f'{e.child}  <- {e.owner} on {e.topic} ({kind}; {e.via})')}")
            if e.child not in seen:
                show(e.child, depth + 1, seen | {e.child})

    for r in roots:
        lines.append(printable(r))
        show(r, 1, {r})
    return "".join(line + "\n" for line in lines)


# -- tf-audit and control ----------------------------------------------------------------


_OUTCOMES = ("ok", "disconnected", "stale", "future")


def tf_audit_text(rep: Report, target: str) -> str:
    from descgen.commands.tf.bagaudit import shown

    c = rep.counts
    lines = [
        f"{rep.lookups} lookups into '{target}': {c['ok']} ok, {c['disconnected']} "
        f"disconnected, {c['stale']} stale, {c['future']} future-dated"
    ]
    for topic, n in sorted(rep.per_topic.items()):
        lines.append(
            f"  {shown(topic)}: " + ", ".join(f"{k} {n[k]}" for k in ("ok", "disconnected", "stale", "future"))
        )
    lines.append("latency (log time - stamp): " + ", ".join(f"{k} ms: {v}" for k, v in sorted(rep.latency.items())))
    for e in rep.examples:
        lines.append(
            f"  {e['outcome']}: {shown(e['topic'])} logged {e['log_time_ns'] / 1e9:.6f} stamped "
            f"{e['stamp_ns'] / 1e9:.6f} in '{shown(e['frame_id'])}': {shown(e['detail'], 300)}"
        )
    return "".join(line + "\n" for line in lines)


def _identities(o: Outcome, mappings: Sequence[Mapping]) -> list[Identity]:
    from descgen.commands.fleet.identity import resolve

    rep = o.report
    assert rep is not None
    versions = sorted({v for _, v in rep.spans}) or [-1]
    out: list[Identity] = []
    for v in versions:
        ident = resolve(o.path, rep.descriptions, v, tuple(mappings))
        if ident not in out:
            out.append(ident)
    return out


def _fleet_lines(o: Outcome, mappings: Sequence[Mapping]) -> str:
    from descgen.commands.tf.bagaudit import shown

    lines = [shown(i.said(), 300) for i in _identities(o, mappings)]
    if o.windows > 1 and not o.note:
        lines.append(f"audited in {o.windows} time windows, joined as one pass (their boundaries agree)")
    if o.note:
        lines.append(o.note)
    return "".join(line + "\n" for line in lines)


def tf_audit_texts(outcomes: Sequence[Outcome], target: str, mappings: Sequence[Mapping] = ()) -> str:
    """One recording's report as before; several, each readable one under its name (an
    unreadable one is an input error, printed as a finding). Each says which robot and
    description version it is of, or that it cannot tell."""
    if len(outcomes) == 1 and outcomes[0].report is not None:
        return tf_audit_text(outcomes[0].report, target) + _fleet_lines(outcomes[0], mappings)
    return "".join(
        f"== {printable(o.path)}\n" + tf_audit_text(o.report, target) + _fleet_lines(o, mappings)
        for o in outcomes
        if o.report is not None
    )


def tf_audit_json(outcomes: Sequence[Outcome], target: str, mappings: Sequence[Mapping] = ()) -> dict[str, Any]:
    """One recording's report as before; several as {"recordings": {folder: report}}, an
    unreadable one as {"errors": [finding, ...]} in its place. Each report adds "identity" (robot,
    description version, SHA-256 and where they came from) and "windows"."""

    def one(o: Outcome) -> dict[str, Any]:
        assert o.report is not None
        return (
            o.report.as_dict()
            | {
                "identity": [
                    {"robot": i.robot, "description": i.version, "description_sha256": i.sha256, "source": i.source}
                    for i in _identities(o, mappings)
                ],
                "windows": o.windows,
            }
            | ({"note": o.note} if o.note else {})
        )

    if len(outcomes) == 1 and outcomes[0].report is not None:
        return one(outcomes[0])
    return {
        "recordings": {
            o.path: one(o) if o.report is not None else {"errors": [f.as_dict() for f in o.findings]} for o in outcomes
        }
    }


def control_text(written: Sequence[str], folder: object, verdict: dict[str, Any]) -> str:
    lines = [f"wrote {', '.join(written)} to {folder}"]
    for joint, err in verdict["tracking"].items():
        tol = verdict["tolerance"][joint]
        lines.append(
            f"  {joint:<22} max |desired - measured| {err:.6g} (tolerance {tol:.6g}) {'ok' if err <= tol else 'FAILED'}"
        )
    for e in verdict["rejected"]:
        lines.append(
            f"  rejected {e['joint']}/{e['interface']} = {e['value']:.6g} beyond {e['limit']:.6g} at {e['time']:.2f} s"
        )
    return "".join(line + "\n" for line in lines)


def import_summary(result: object, written_to: str) -> str:
    """One line: what descgen import wrote and whether the round trip proved it."""
    imp = result.imported  # type: ignore[attr-defined]
    kept = len(imp.kept)
    verdict = "round trip proven" if result.proven else "round trip not run: the spec fails validate (see warnings)"  # type: ignore[attr-defined]
    return (
        f"imported {imp.robot.name}: {len(imp.robot.links)} links, {len(imp.robot.joints)} joints, "
        f"{kept} pass-through element(s) -> {written_to}; {verdict}"
    )


def simulate_text(path: str, rep: dict[str, Any]) -> str:
    """``descgen simulate``: the run's set-up, then each held joint's drift from the pose."""
    head = f"{printable(path)}: MuJoCo, base {rep['base']}, pose {printable(rep['pose'])}, {rep['seconds']:g} s"
    if not rep.get("compiled"):
        return head + ": MuJoCo refused the model (see the errors)\n"
    lines = [f"{head}: {rep['bodies']} bodies, {rep['steps']} steps in {rep['wall_s']:.3f} s wall"]
    for s in rep["servos"]:
        unit = "rad" if s["rotating"] else "m"
        lines.append(
            f"  {printable(s['joint']):<24} drift {rep['drift'][s['joint']]:.3g} {unit} "
            f"(tolerance {s['tolerance']:g}), kp {s['kp']:.4g}, kv {s['kv']:.4g}"
        )
    if rep["base"] == "floor":
        lines.append(f"  free base: largest tilt {rep['tilt_deg']:.3g} deg")
    return "".join(line + "\n" for line in lines)
