"""``descgen report``: one page, ``evidence/README.md``, that links and summarises every proof.

The page is a pure function of the spec, the package on disk and the committed control
evidence, so ``descgen check`` rebuilds it in memory and compares it like a generated file.
What may differ between machines without the robot changing (MuJoCo's drift digits and wall
time, whether MuJoCo is installed) sits between ``<!-- volatile -->`` markers and is left out
of that comparison.

Building the page runs the tf scenario, the fault catalogue and validation again (about a
second), so its last line records the hash of everything it was built from and of its own
comparable text (descgen/infra/evidence_hash.py). ``check`` takes a page whose record matches as
current without building it; any other page is built and compared as before. The record
line itself is not compared: a page that reads the same is not stale because an input of its
key changed, it is only built again until ``descgen report`` records the new inputs. descgen's
part in the key is :data:`FORMAT` and its release (descgen/infra/keys.py EVIDENCE), not the bytes
of its source: an edit that changes no page leaves it current, and one that does is caught by
tests/test_evidence_recompute.py (the page built again and compared) until FORMAT is bumped.
"""

from __future__ import annotations

import functools
import json
import math
import re
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from descgen.commands import text as cli_format
from descgen.core.findings import Finding, InputError, Where
from descgen.core.record import record
from descgen.infra import evidence_hash, keys
from descgen.output import report
from descgen.write import pose_images

PAGE = "evidence/README.md"
_VOLATILE = re.compile(r"<!-- volatile -->.*?<!-- /volatile -->", re.S)
_RECORD = re.compile(r"^<!-- descgen input-sha256=[0-9a-f]{64} content-sha256=[0-9a-f]{64} -->\n?", re.M)
# what the page reads from the package besides the files it is given: verdict.json, which files
# exist (links), the plot names; the page itself, its pictures and the machine's frames.svg aside
_NOT_READ = ("evidence/README.md", "evidence/poses/", "evidence/frames.svg", "evidence/drift.svg")
# the libraries whose behaviour the page prints: xacro and lxml (proofs), pint and pydantic
# (validation), rosbags (the tf scenario's recording), numpy, PyYAML, Jinja2 (rendering), trimesh
_TOOLS = ("xacro", "lxml", "pint", "pydantic", "rosbags", "numpy", "PyYAML", "Jinja2", "trimesh")
# descgen's part in the page's key: bump when what the page says of the same inputs changes
# (a section, a sentence, a proof it runs); tests/test_evidence_recompute.py fails until then
# 2: sections 6-7 not applicable without a control run, BLIND SPOTS, cells escaped, both packages counted
FORMAT = 3
TARGET_FRAME = "odom"  # the tf-audit target: every sensor frame must reach the odometry frame


@record
class FieldFault:
    """A field-story mistake planted in a copy of the spec text, and the code that must catch it."""

    name: str
    story: str
    expected: str
    plant: Callable[[str], str]


def _camera_metres(text: str) -> str:
    """The wrist camera 25 m away: its 25 mm offset typed as metres."""
    return _replace_in(text, "name: camera", "xyz: [25 mm,", "xyz: [25 m,")


def _elbow_axis(text: str) -> str:
    """The elbow turning about z instead of y."""
    return _replace_in(text, "name: elbow_joint", "axis: +y", "axis: +z")


def _display_desired(text: str) -> str:
    """An operator display relay publishing the commanded positions on /joint_states."""
    extra = "  joint_state_sources:\n    - {node: operator_display_relay, kind: desired, source: field story}\n"
    if re.search(r"^frames:\s*$", text, re.M):
        return re.sub(r"^frames:\s*\n", lambda m: m.group(0) + extra, text, count=1, flags=re.M)
    return text.rstrip("\n") + "\n\nframes:\n" + extra


def _replace_in(text: str, anchor: str, old: str, new: str) -> str:
    """``old`` -> ``new`` at its first occurrence after ``anchor`` (unchanged text: not plantable)."""
    start = text.find(anchor)
    at = text.find(old, start) if start >= 0 else -1
    return text if at < 0 else text[:at] + new + text[at + len(old) :]


FIELD_FAULTS = (
    FieldFault(
        "camera-25m", "the wrist camera 25 m away (a millimetre value typed as metres)", "UNIT004", _camera_metres
    ),
    FieldFault("elbow-axis", "the elbow turning about the wrong axis (+z for +y)", "POSE010", _elbow_axis),
    FieldFault(
        "display-desired",
        "an operator display fed by desired commands instead of measured state",
        "FRAME005",
        _display_desired,
    ),
)


@record
class Caught:
    fault: FieldFault
    planted: bool
    by: Finding | None


def field_faults(spec_text: str, shown: str) -> list[Caught]:
    """Plant each field-story fault in a copy of the spec text and validate it as ``validate``
    and ``poses`` would; the fault is caught by the first error of its expected code."""
    from descgen.audit.spec import load_spec_text
    from descgen.physics.poses import findings as pose_findings

    out = []
    for fault in FIELD_FAULTS:
        text = fault.plant(spec_text)
        if text == spec_text:
            out.append(Caught(fault, False, None))
            continue
        try:
            loaded = load_spec_text(text, shown)
            found = [*loaded.findings, *pose_findings(loaded.robot)]
        except InputError as exc:
            found = list(exc.findings)
        by = next((f for f in found if f.code == fault.expected and f.severity == "error"), None)
        out.append(Caught(fault, True, by))
    return out


# Everything the page quotes from its input (the spec's file name, names, messages, what the
# recorded control run says) is Markdown text, a code span or a fenced block that it cannot leave
# (descgen/render/formatting.py: mdtext, mdspan, mdfence, mddest); tests/test_markdown_escaping.py
# reads the page with a CommonMark parser. Imported when the page is built (descgen.render is
# not needed to take a recorded page as current).


def _md() -> Any:
    from descgen.render import formatting

    return formatting


def _block(text: str, lang: str = "") -> list[str]:
    return _md().mdfence(text, lang)  # type: ignore[no-any-return]


def _exists(package: Path, rel: str) -> bool:
    return (package / rel).is_file()


def _link(package: Path, rel: str, label: str | None = None) -> str:
    """A link relative to evidence/README.md; a missing file is said so, never linked blindly."""
    target = rel[len("evidence/") :] if rel.startswith("evidence/") else f"../{rel}"
    shown = _md().mdtext(label or rel)
    return f"[{shown}]({_md().mddest(target)})" if _exists(package, rel) else f"{shown} (missing)"


def _verdict(ok: bool, text: str) -> str:
    return f"**Verdict: {'PASS' if ok else 'FAIL'}**: {text}"


def _waivers(robot: Any) -> list[str]:
    """The spec's waivers, when it has any: what is accepted for now, and why (a section of its
    own, so a reviewer sees what is left to fix; every waived finding is also printed above)."""
    if not robot.waivers:
        return []
    md = _md()
    lines = [
        "## 10. Waivers",
        "",
        "Findings the spec accepts for now (`waivers:`); every command still reports each one, marked waived:",
        "",
        "| code | subject | reason |",
        "|---|---|---|",
    ]
    lines += [f"| {md.mdcode(w.code)} | {md.mdcode(w.subject)} | {md.mdcell(w.reason)} |" for w in robot.waivers]
    lines += [
        "",
        f"**Verdict: WAIVED**: {len(robot.waivers)} waiver(s); fix each finding and remove its waiver",
        "",
    ]
    return lines


def _drift_of(robot: Any) -> dict[str, Any]:
    """``descgen drift`` of the spec's ``calibration.drift`` samples, with the series to plot
    (the page and evidence/drift.svg are made from one run: kept per robot and file state)."""
    st = Path(robot.drift_check.samples).stat()
    return _drift_cached(robot, (st.st_ino, st.st_size, st.st_mtime_ns))


@functools.lru_cache(maxsize=4)
def _drift_cached(robot: Any, _file: tuple[int, int, int]) -> dict[str, Any]:
    from descgen.commands.drift import drift

    c = robot.drift_check
    return drift(
        robot,
        c.frame,
        base=c.base,
        samples=Path(c.samples),
        parameters=c.parameters,
        tolerance_m=c.tolerance,
        series=True,
    )


def drift_svg(robot: Any) -> str | None:
    """evidence/drift.svg of the robot's drift check; None without one."""
    from descgen.write import drift_plot

    if robot.drift_check is None:
        return None
    d = _drift_of(robot)
    change = d["change_point"]["after_s"] if d["change_point"] else None
    label = f"{d['frame']} in {d['base']}: position residual |measured - model| per sample"
    return drift_plot.svg(
        d["series"]["t_s"], [r * 1000 for r in d["series"]["residual_m"]], d["tolerance_m"] * 1000, change, label
    )


def write_drift(package: Path, robot: Any) -> list[str]:
    """evidence/drift.svg written (report), or removed for a spec without a drift check."""
    from descgen.write import drift_plot

    return drift_plot.write(package, drift_svg(robot))


def drift_stale(package: Path, robot: Any) -> list[Finding]:
    from descgen.write import drift_plot

    return drift_plot.stale(package, drift_svg(robot))


def _drift(robot: Any, package: Path) -> tuple[list[str], bool]:
    if robot.drift_check is None:
        return [], True
    md = _md()
    d = _drift_of(robot)
    r, a = d["residual"], d["after_fit"]
    c = robot.drift_check
    samples = Path(c.samples).name
    lines = [
        f"Drift: {md.mdcode(samples)} ({r['samples']} samples), {md.mdcode(d['frame'])} measured in "
        f"{md.mdcode(d['base'])}, against the model as calibrated (`descgen drift`); the residual over time "
        "(evidence/drift.svg):",
        "",
        "![residual over time](drift.svg)",
        "",
        f"- residual: median {r['median_m'] * 1000:.3f} mm, 95% {r['p95_m'] * 1000:.3f} mm, worst "
        f"{r['max_m'] * 1000:.3f} mm (tolerance {d['tolerance_m'] * 1000:g} mm)",
    ]
    ch = d["change_point"]
    lines.append(
        f"- the residual changed {ch['after_s']:.1f} s into the samples (median {ch['before_median_m'] * 1000:.3f} mm "
        f"before, {ch['after_median_m'] * 1000:.3f} mm after); the fit uses the samples after it"
        if ch
        else "- no change of the residual over the samples"
    )
    lines.append(
        f"- after fitting {len(d['identified'])} parameter(s): median {a['median_m'] * 1000:.3f} mm, 95% "
        f"{a['p95_m'] * 1000:.3f} mm; {len(d['unidentifiable'])} unidentifiable from this motion"
    )
    big = sorted(d["identified"], key=lambda p: -abs(p["value"]) / max(p["stderr"], 1e-300))[:5]
    lines += [
        f"- {md.mdcode(p['parameter'])} = {p['value']:.4g} ± {p['stderr']:.2g} (SI)" for p in big if p["stderr"] > 0
    ]
    return [*lines, ""], not d["drifted"]


def _calibration(robot: Any, package: Path, proofs: Proofs | None) -> list[str]:
    """The calibration layer beside the nominal model: each calibrated joint's nominal and
    calibrated origin, how far the correction moves and turns its child frame, and the source;
    then the drift check's residual over time, when the spec has one."""
    if not robot.calibration and robot.drift_check is None:
        return []
    from descgen.core import display
    from descgen.physics.calibration import correction_size

    md = _md()
    sources = {s.name: s for s in robot.calibration_sources}
    lines = [
        "## 11. Calibration and drift",
        "",
        f"The robot as measured, a layer on the nominal model: {_link(package, 'config/calibration/default.yaml')} "
        f"(the Xacro's `calibration:=`; {_link(package, 'config/calibration/nominal.yaml')} gives the nominal model).",
        "",
        "| joint | nominal xyz (mm), rpy (deg) | calibrated xyz (mm), rpy (deg) | zero offset | moves | turns "
        "| source |",
        "|---|---|---|---|---|---|---|",
    ]

    def shown(p: Any) -> str:
        return f"({display.mm(p.xyz, 3)}), ({', '.join(f'{math.degrees(a):.4f}' for a in p.rpy)})"

    for e in robot.calibration:
        j = robot.joint(e.joint)
        shift, turn = correction_size(j, e) if j is not None else (0.0, 0.0)
        offset = "" if not e.offset else (j.show(e.offset) if j is not None else f"{e.offset:.6g}")
        src = sources.get(e.source)
        cite = e.source + (f": {src.method}" if src else "") + (f", {src.date}" if src and src.date else "")
        who = e.joint + (f" (sensor {e.sensor})" if e.sensor else "")
        lines.append(
            f"| {md.mdcode(who)} | {shown(e.nominal)} | {shown(e.calibrated)} | {md.mdcell(offset)} | "
            f"{shift * 1000:.3f} mm | {math.degrees(turn):.4f} deg | {md.mdcell(cite)} |"
        )
    done = dict(proofs or ())
    name = "xacro calibration:=nominal.yaml expands to the nominal model"
    ok = not [f for f in done.get(name, ()) if f.blocks]
    drift_lines, within = _drift(robot, package)
    said = (
        f"{len(robot.calibration)} calibrated joint(s), each citing its source; the Xacro without the layer expands "
        "to the nominal model"
    )
    if robot.drift_check is not None:
        said += "; the drift samples are within tolerance" if within else "; the robot has DRIFTED beyond tolerance"
    lines += ["", *drift_lines, _verdict(ok and within, said), ""]
    return lines


def _not_applicable(why: str) -> str:
    """A section that does not apply to this robot: neither a pass nor a failure of the page."""
    return f"**Verdict: NOT APPLICABLE**: {why}"


# -- the sections ---------------------------------------------------------------------------


Proofs = Sequence[tuple[str, Sequence[Finding]]]


def _model(files: dict[str, str], robot: Any, package: Path, proofs: Proofs | None) -> list[str]:
    from descgen.prove import CHECKS, mujoco_model, xacro_calibration_nominal
    from descgen.render import mjcf

    # the results plan() already has (the same checks on the same files), else run them here
    done = dict(proofs) if proofs is not None else {name: check(files, robot, package) for name, check in CHECKS}

    urdf = next((rel for rel in files if rel.startswith("urdf/") and rel.endswith(".urdf")), "")
    xacro = next((rel for rel in files if rel.endswith(".urdf.xacro")), "")
    moving = [j for j in robot.joints if j.type != "fixed"]
    lines = [
        "## 1. Expanded model",
        "",
        f"{_link(package, urdf)} (expanded from {_link(package, xacro)}): {len(robot.links)} links, "
        f"{len(robot.joints)} joints ({len(moving)} moving).",
        "",
        "| proof | result |",
        "|---|---|",
    ]
    ok = True
    for name, check in CHECKS:
        if check is xacro_calibration_nominal and not robot.calibration:
            continue  # nothing to take off: the row would pass on nothing
        if check is mujoco_model and not mjcf.wanted(robot):
            continue  # no hardware:=mujoco, no model to prove
        found = done[name]
        bad = sorted({f.code for f in found if f.severity in ("error", "warning")})
        notes = sorted({f.code for f in found if f.severity == "info"})
        ok = ok and not bad
        result = "failed: " + ", ".join(bad) if bad else "passed" + (f" (notes: {', '.join(notes)})" if notes else "")
        lines.append(f"| {_md().mdcell(name)} | {_md().mdcell(result)} |")  # "gazebo|real" splits no cell
    lines += ["", _verdict(ok, "every round trip (xacro, yourdfpy, check_urdf, SRDF, ros2_control) agrees"), ""]
    return lines


def _validation(spec: Path, shown: str, package_paths: tuple[Path, ...]) -> tuple[list[str], Any]:
    from descgen.audit.spec import validate_spec

    loaded = validate_spec(spec, display=shown, package_paths=package_paths)
    found = list(loaded.findings)
    ok = not any(f.blocks for f in found)
    text = report.text(found) + (cli_format.validated(shown, loaded.robot) + "\n" if ok else "")
    lines = ["## 2. Validation", "", f"{_md().mdspan(f'descgen validate {shown}')} prints:", "", *_block(text, "text")]
    lines += [_verdict(ok, "the spec is valid"), ""]
    return lines, loaded.robot


def _poses(robot: Any, package: Path) -> list[str]:
    from descgen.audit.waivers import waive
    from descgen.physics.poses import evaluate, findings

    rows = evaluate(robot)
    bad = [f for f in waive(findings(robot, rows), robot.waivers) if f.blocks]
    lines = ["## 3. Known poses", "", f"Table: {_link(package, 'evidence/known_poses.md')}.", ""]
    lines += _block(cli_format.poses_table(rows), "text")
    # one picture per pose (model dots, measured crosses); check compares their inputs, not PNG bytes
    lines += [*pose_images.embeds(robot), ""] if robot.known_poses else []
    lines += [_verdict(not bad, f"{len(rows)} measured frame positions within tolerance of forward kinematics"), ""]
    return lines


def _frames(package: Path, files: dict[str, str], robot: Any) -> list[str]:
    md = files.get("evidence/frames.md", "")
    m = re.search(r"```mermaid\n.*?```\n", md, re.S)
    lines = ["## 4. Frame ownership", "", f"Every edge and its publisher: {_link(package, 'evidence/frames.md')}.", ""]
    if robot.mounted:  # a spec's compose: the tree below holds every robot, each behind its prefix
        cell = _md().mdcell
        lines += [
            "Composed of (spec `compose:`; the tree below is all of them):",
            "",
            "| robot | spec | prefix | mounted on | by the fixed joint |",
            "|---|---|---|---|---|",
            *(
                f"| {cell(mt.robot)} | {cell(mt.spec)} | {cell(mt.prefix)} | {cell(mt.parent)} | {cell(mt.joint)} |"
                for mt in robot.mounted
            ),
            "",
        ]
    if m:
        lines += [m.group(0).rstrip("\n"), ""]
    lines += [_verdict(m is not None, "one owner per frame (FRAME rules pass in validation)"), ""]
    return lines


def _timestamps(robot: Any) -> list[str]:
    from descgen.commands.tf.bagaudit import audit
    from descgen.commands.tf.scenario import FAULTS, WINDOWS, plan, write

    if plan(robot).camera_frame is None:
        # the scenario's only stamped sensor message is the camera's: without one there is nothing
        # to look up, and the section says so instead of failing the page (tf-audit's BAG010)
        return [
            "## 5. Timestamp failures",
            "",
            "Not run: the robot has no camera (a `sensors:` entry of type camera), and the scenario's "
            "stamped sensor messages are a camera's. To run it, add the camera to the spec's `sensors:`; "
            f"for any sensor, record the robot and run `descgen tf-audit BAG --target {TARGET_FRAME}`.",
            "",
            _not_applicable("the robot has no camera to stamp messages with"),
            "",
        ]
    odom = plan(robot).odom
    # the odometry frame of a driving base; a robot without one (an arm, a composed cell whose
    # bases are fixed) is audited against its root, and has no odometry gap to plant
    target = odom[0] if odom is not None else (robot.root() or TARGET_FRAME)
    faults = FAULTS if odom is not None else tuple(f for f in FAULTS if f != "odom-gap")
    expected = {"disconnected", "future"} | ({"stale"} if odom is not None else set())
    with tempfile.TemporaryDirectory(prefix="descgen-report-") as tmp:
        bag = Path(tmp) / "scenario"
        write(robot, bag, faults, 10.0, "mcap")
        rep = audit(bag, target, (), 0, None)
        text = cli_format.tf_audit_text(rep, target)
    c = rep.counts
    failed = {k for k in ("disconnected", "stale", "future") if c[k]}
    planted = ", ".join(f"{_md().mdspan(f)} in [{a:g} s, {b:g} s)" for f, (a, b) in WINDOWS.items() if f in faults)
    flags = " ".join(f"--fault {f}" for f in faults)
    lines = [
        "## 5. Timestamp failures",
        "",
        f"`descgen tf-scenario SPEC --out BAG {flags}` "
        f"(10 s; planted: {planted}), then {_md().mdspan(f'descgen tf-audit BAG --target {target}')} "
        "(the recording is not committed; this is its audit):",
        "",
        *_block(text, "text"),
        _verdict(
            failed == expected,
            "each planted fault shows as its own failure class ("
            + ", ".join(
                k if k != "future" else "future-dated" for k in ("disconnected", "stale", "future") if k in expected
            )
            + ")",
        ),
        "",
    ]
    return lines


def _control(package: Path, robot: Any) -> tuple[list[str], list[str]]:
    ev = package / "evidence"
    if not (ev / "verdict.json").is_file():
        return _no_control_run(robot)
    try:
        verdict = json.loads((ev / "verdict.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        verdict = {}
    traces = [
        "## 6. Interface and lifecycle traces",
        "",
        f"{_link(package, 'evidence/lifecycle.md')} (and {_link(package, 'evidence/lifecycle.jsonl')}), "
        f"{_link(package, 'evidence/interfaces.md')}.",
        "",
    ]
    active = not verdict.get("controllers_not_active", ["?"])
    traces += [_verdict(bool(verdict) and active, "every controller reached active; no claim was refused"), ""]
    plots = sorted(p.name for p in ev.glob("*.png")) if ev.is_dir() else []
    run = verdict.get("run", {})
    trajectory = run.get("trajectory", "?")
    dvm = [
        "## 7. Desired versus measured",
        "",
        f"{_link(package, 'evidence/desired_vs_measured.csv')} and {_link(package, 'evidence/verdict.json')}, "
        f"from {_md().mdspan(f'descgen control SPEC --trajectory {trajectory}')} "
        f"(plant {_md().mdtext(run.get('plant', {}).get('kind', '?'))}).",
        "",
    ]
    dvm += [f"![{_md().mdtext(p)}]({_md().mddest(p)})" for p in plots] + [""]
    echo = verdict.get("state_echoes_command")
    dvm += [
        _verdict(
            bool(verdict.get("ok")),
            f"tracking within tolerance; {_md().mdspan(f'state_echoes_command: {str(echo).lower()}')}",
        ),
        "",
    ]
    if echo:
        dvm += [f"> {_md().mdtext(verdict.get('note', ''))}", ""]
    return traces, dvm


def _no_control_run(robot: Any) -> tuple[list[str], list[str]]:
    """Sections 6 and 7 without a committed control run: they say why and how to make one (a
    section that does not apply is no failure of the page: issue 29, a report for every robot)."""
    if robot.ros2_control is None:
        why = "the robot has no ros2_control: no controllers to start, no commands to follow"
    else:
        why = (
            "no control run is committed: "
            + _md().mdspan("descgen control SPEC --trajectory TRAJECTORY.yaml")
            + " starts the controllers against a simulated plant and writes the evidence these sections summarise"
        )
    traces = ["## 6. Interface and lifecycle traces", "", _not_applicable(why), ""]
    dvm = ["## 7. Desired versus measured", "", _not_applicable(why), ""]
    return traces, dvm


def _transcript(
    spec: Path,
    shown: str,
    check_out: tuple[str, str],
    unchanged: int,
    simulate: bool,
    robot: Any,
    package_paths: tuple[Path, ...],
) -> list[str]:
    from descgen.audit.spec import validate_spec

    # what `descgen validate SPEC` prints (cli._cmd_validate): the findings on stderr, then the
    # one-line verdict; tests/test_evidence_page.py holds it to the command's real output
    loaded = validate_spec(spec, package_paths=package_paths)
    validated = report.text(loaded.findings) + cli_format.validated(str(spec), loaded.robot) + "\n"
    steps = [
        (f"descgen validate {shown}", validated.replace(str(spec), shown)),
        (f"descgen generate {shown}", f"{shown}: wrote 0 files, {unchanged} unchanged\n"),
        (f"descgen check {shown}", check_out[1] + check_out[0]),
    ]
    lines = [
        "## 8. Starter output",
        "",
        "What `make demo` prints on a fresh clone after installing (the package is committed and up to date, "
        "so generate rewrites nothing):",
        "",
    ]
    shell: list[str] = []
    for cmd, out in steps:
        shell += [f"$ {cmd}", *out.rstrip("\n").splitlines()]
    # MuJoCo's digits and its presence vary by machine: check leaves this part out (and skips the run)
    shell += ["<!-- volatile -->", *(_simulate(spec, shown, package_paths) if simulate else []), "<!-- /volatile -->"]
    images = [*(pose_images.image_rel(kp.name) for kp in robot.known_poses), pose_images.SIDECAR]
    wrote = [f"wrote {rel}" for rel in images]
    shell += [f"$ descgen report {shown}", *wrote, f"wrote {PAGE}"]
    lines += _block("\n".join(shell), "text")
    lines += [_verdict("every check passed" in check_out[0], "validate, generate and check succeed"), ""]
    return lines


def _simulate(spec: Path, shown: str, package_paths: tuple[Path, ...]) -> list[str]:
    from descgen.commands.simulate import Settings, simulate_description

    lines = [f"$ descgen simulate {shown} --pose ready"]
    try:
        from descgen.read.description import Options

        outcome = simulate_description(spec, Options(package_paths=package_paths), Settings(pose="ready"))
    except InputError as exc:
        return lines + report.text(exc.findings).replace(str(spec), shown).splitlines()
    text = cli_format.simulate_text(shown, outcome.report)
    text = re.sub(r" in [0-9.]+ s wall", "", text)
    return lines + text.splitlines()


def _field_story(spec: Path, shown: str, robot: Any) -> list[str]:
    from descgen.commands.faults import plant_all

    caught = field_faults(spec.read_text(encoding="utf-8"), shown)
    lines = [
        "## 9. Three-fault audit",
        "",
        "The field story's three faults, each planted in a copy of the spec and validated:",
        "",
        "| fault | planted | caught by |",
        "|---|---|---|",
    ]
    for c in caught:
        # a fault with no place in this spec (a composed robot's camera is in its own spec) is
        # neither caught nor missed
        absent = "**MISSED**" if c.planted else "n/a"
        by = _md().mdtext(f"{c.by.code}: {report.printable(c.by.message)}") if c.by else absent
        lines.append(f"| {_md().mdcell(c.fault.story)} | {'yes' if c.planted else 'not plantable'} | {by} |")
    results = plant_all(robot)
    applicable = [r for r in results if r.applicable]
    lines += ["", "`descgen faults SPEC`, the whole catalogue:", "", *_block(cli_format.faults_text(results), "text")]
    # a fault this robot has no place for (no camera to move 25 m) is listed as not plantable; it is
    # neither caught nor missed
    planted = [c for c in caught if c.planted]
    missed = [r for r in applicable if not r.caught]
    if not planted and not applicable:
        lines += [_not_applicable("no fault of the story or the catalogue can be planted in this robot"), ""]
    elif any(c.by is None for c in planted) or not missed:
        ok = all(c.by is not None for c in planted) and not missed
        lines += [_verdict(ok, "every planted fault was caught by its expected finding"), ""]
    else:
        # the story's faults are caught; what the catalogue misses on this robot is a blind spot of its
        # evidence (a joint no known pose moves cannot show a wrong axis), said so, not a failed package
        spots = "; ".join(f"{r.fault.name} ({r.planted})" for r in missed)
        lines += [
            f"**Verdict: BLIND SPOTS**: the story's faults are caught; the audit misses {len(missed)} of the "
            f"catalogue's on this robot: {_md().mdtext(spots)}. A known pose that moves the joint, or the "
            "missing element, lets it catch them",
            "",
        ]
    return lines


# -- the page -------------------------------------------------------------------------------


def build(
    spec: Path,
    shown: str,
    files: dict[str, str],
    robot: Any,
    package: Path,
    check_out: tuple[str, str],
    n: int,
    simulate: bool = True,
    proofs: Proofs | None = None,
    key: str | None = None,
    package_paths: tuple[Path, ...] = (),
) -> str:
    """The whole page. ``check_out`` is (stdout, stderr) of ``descgen check`` for the transcript,
    ``n`` the number of files generate writes, ``proofs`` the results of checks.CHECKS by name
    when the caller has them, ``key`` the :func:`input_key` to record on the last line."""
    validation, _ = _validation(spec, shown, package_paths)
    traces, dvm = _control(package, robot)
    parts = [
        f"# Evidence for {_md().mdtext(robot.name)}",
        "",
        f"Written by {_md().mdspan(f'descgen report {shown}')}; `descgen check` verifies it is current. "
        "Each section links the committed files it summarises and ends with a verdict.",
        "",
        *_model(files, robot, package, proofs),
        *validation,
        *_poses(robot, package),
        *_frames(package, files, robot),
        *_timestamps(robot),
        *traces,
        *dvm,
        *_transcript(spec, shown, check_out, n, simulate, robot, package_paths),
        *_field_story(spec, shown, robot),
        *_waivers(robot),
        *_calibration(robot, package, proofs),
    ]
    page = _relative("\n".join(parts).rstrip("\n") + "\n", package)
    return page if key is None else page + f"<!-- {evidence_hash.stamp(key, comparable(page))} -->\n"


def input_key(
    spec: Path,
    shown: str,
    files: dict[str, str],
    meshes: dict[str, bytes],
    package: Path,
    check_out: tuple[str, str],
    n: int,
    drift: Any = None,
) -> str:
    """The key (descgen/infra/keys.py) of everything the page's comparable text is a function
    of: the spec's bytes, the rendered files and meshes, what the page reads from the package,
    what check printed (paths as the project sees them), with :data:`FORMAT`, descgen's release
    and the versions of the libraries it prints the work of."""
    import shutil

    check_urdf = shutil.which("check_urdf")
    urdfdom = None
    if check_urdf is not None:  # its identity as frames_svg names dot's: no process started
        st = Path(check_urdf).resolve().stat()
        urdfdom = [str(Path(check_urdf).resolve()), st.st_size, st.st_mtime_ns]
    inputs = {
        "check_urdf": urdfdom,
        "spec": evidence_hash.sha256(spec.read_bytes()),
        "shown": shown,
        "files": {rel: evidence_hash.sha256(text) for rel, text in files.items()},
        "meshes": {rel: evidence_hash.sha256(data) for rel, data in meshes.items()},
        "package": evidence_hash.package_files(package, _NOT_READ),
        "check_out": [_relative(text, package) for text in check_out],
        "n": n,
    }
    if drift is not None:  # the samples the page's drift section is made from (spec calibration.drift)
        inputs["drift"] = evidence_hash.sha256(Path(drift.samples).read_bytes())
    return keys.key(PAGE, FORMAT, inputs, _TOOLS, keys.EVIDENCE)


def current(package: Path, key: str) -> bool:
    """True when the committed page records ``key`` and its text is what was recorded with it
    (check then takes it as current without building it)."""
    target = package / PAGE
    if target.is_symlink() or not target.is_file():
        return False
    now = target.read_text(encoding="utf-8", errors="replace")
    found = list(_RECORD.finditer(now))
    if len(found) != 1:
        return False
    body = now[: found[0].start()] + now[found[0].end() :]
    return evidence_hash.reusable(evidence_hash.recorded(found[0].group(0)), key, comparable(body))


def _relative(page: str, package: Path) -> str:
    """Paths as the project sees them (``specs/...``, ``generated/...``): findings name files by
    the path they were read from, and the page must read the same on any machine."""
    for folder in {package.resolve().parent.parent, package.parent.parent}:
        page = page.replace(f"{folder}/", "")
    return page


def comparable(page: str) -> str:
    """The page without its volatile parts and its input record (what check compares)."""
    return _VOLATILE.sub("<!-- volatile -->", _RECORD.sub("", page))


def stale(package: Path, fresh: str) -> list[Finding]:
    """GEN080 when the committed page is missing or differs from ``fresh`` (volatile parts aside)."""
    target = package / PAGE
    where = Where(str(target))
    if not target.is_file():
        return []  # no report written yet: nothing to keep current (generate does not write it)
    now = target.read_text(encoding="utf-8", errors="replace")
    if comparable(now) == comparable(fresh):
        return []
    return [
        Finding(
            "GEN080",
            "error",
            f"{PAGE} is stale: the proofs it summarises changed",
            "run descgen report SPEC and commit the result",
            f"file:{PAGE}",
            where,
        )
    ]


def failed_verdicts(page: str) -> list[str]:
    return [line for line in page.splitlines() if line.startswith("**Verdict: FAIL**")]


def write(package: Path, page: str) -> Path:
    """The page, replaced in one rename so a reader never sees half of it."""
    target = package / PAGE
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = target.with_name(f".{target.name}.tmp")
    tmp.write_text(page, encoding="utf-8")
    tmp.replace(target)
    return target


def check_lines(spec_shown: str, findings: Sequence[Finding], diff: str) -> tuple[str, str]:
    """(stdout, stderr) that ``descgen check`` prints for this outcome, as in cli._cmd_check."""
    failed = any(f.blocks for f in findings)
    out = diff + ("" if failed else f"{spec_shown}: generated files are up to date and every check passed\n")
    return out, report.text(findings)
