"""``generate`` and ``check``: render the package, prove it, then write it (all or nothing,
descgen/write/package.py) or compare it with what is committed.

A spec with ``moveit:`` has a second package, ``<robot>_moveit_config`` (descgen/render/moveit.py),
beside the description package. Both are built before either is switched
(``package_write.write_packages``), so a failure while building changes neither.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from descgen import prove as checks
from descgen.audit.spec import check_stage, load_spec
from descgen.audit.waivers import unused, waive
from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import Robot
from descgen.infra.safeio import read_bounded
from descgen.meshes.paths import MAX_MESH_BYTES, spec_folder
from descgen.render import header, render_package
from descgen.render.context import package_name
from descgen.spec.files import default_out
from descgen.write import package as package_write


@dataclass(frozen=True)
class Plan:
    robot: Robot
    files: dict[str, str]  # the rendered text files, the mesh package_write.manifest among them
    package_dir: Path
    findings: tuple[Finding, ...]  # warnings from the spec, errors and warnings from the checks
    # the robot's own meshes: package path -> (source file beside the spec, its bytes)
    meshes: dict[str, tuple[Path, bytes]] = field(default_factory=dict)
    # the MoveIt config package (spec ``moveit:``): its files and folder; empty and None without it
    moveit_files: dict[str, str] = field(default_factory=dict)
    moveit_dir: Path | None = None
    # each proof's findings by its name (checks.CHECKS order): the evidence page shows them
    proofs: tuple[tuple[str, tuple[Finding, ...]], ...] = ()
    # where the spec's other packages were looked for after its package_paths: (the page reads it again)
    package_paths: tuple[Path, ...] = ()

    def content(self) -> dict[str, str | bytes]:
        """Every file generate writes: the text files and the mesh copies."""
        every: dict[str, str | bytes] = {**self.files, **{rel: data for rel, (_, data) in self.meshes.items()}}
        return dict(sorted(every.items()))

    def file_count(self) -> int:
        """How many files generate writes or leaves unchanged in both packages, as it prints them."""
        return len(self.content()) + len(self.moveit_files)


def spec_display(spec: Path, out_root: Path) -> str:
    """How the header names the spec: relative to the project (the folder holding the
    output root), so it is the same from any working directory and on any machine."""
    try:
        return spec.resolve().relative_to(out_root.resolve().parent).as_posix()
    except ValueError:
        return spec.name


def plan(
    spec: Path,
    out_root: Path | None = None,
    templates: Path | None = None,
    package_paths: Sequence[Path] = (),
    thorough: bool = False,
    show_progress: bool = False,
) -> Plan:
    """Load, render and prove one spec. Raises InputError for invalid input.

    ``templates`` (--templates) overrides the folder the spec records (``templates:``); that
    one renders sandboxed, since the spec is someone else's data. ``package_paths``
    (--package-path) are searched for ``package://`` meshes after the spec's ``package_paths:``.
    ``show_progress``: a collision matrix's samples drawn on a terminal."""
    root = out_root or default_out(spec)
    loaded = load_spec(spec, package_paths=package_paths)
    robot = loaded.robot
    recorded = loaded.spec.templates
    sandboxed = templates is None and recorded is not None
    if sandboxed and recorded is not None:
        templates = spec_folder(spec, recorded)  # validated by load_spec (SPEC064)
    shown = spec_display(spec, root)
    meshes = package_write.mesh_copies(robot, root)
    if robot.semantic is not None and robot.semantic.collision_matrix is not None:
        # the matrix needs the URDF (rendered alone first: the rest would be rendered again), and
        # the SRDF and its evidence need the matrix
        urdf = f"urdf/{robot.name}.urdf"
        robot = _with_matrix(
            robot,
            render_package(robot, shown, templates, sandboxed, only={urdf}),
            meshes,
            root / package_name(robot),
            show_progress,
        )
    sweep = None
    if robot.semantic is not None and robot.semantic.matrix is not None:
        from descgen.prove import sweep as sweep_evidence  # imported only for a robot with a matrix

        sweep = sweep_evidence.context
    files = render_package(robot, shown, templates, sandboxed, sweep=sweep)
    if meshes:
        files[package_write.MANIFEST] = header.add(
            package_write.MANIFEST, package_write.manifest(meshes), shown, robot.spec_hash or "0" * 64
        )
    package_dir = root / package_name(robot)
    proofs = checks.run_named(files, robot, package_dir, thorough)  # by name for the evidence page
    # the check-stage rules' findings with the spec's waivers of their codes (validate judged the
    # input stage's); a proof of descgen's own output is never waived
    later = tuple(w for w in robot.waivers if check_stage(w.code))
    proofs = tuple((name, tuple(waive(done, later))) for name, done in proofs)
    found = [*loaded.findings, *(f for _, done in proofs for f in done)]
    found += unused(later, found, check_stage)
    moveit_files: dict[str, str] = {}
    moveit_dir = None
    if robot.moveit is not None:
        from descgen.prove import moveit as proof
        from descgen.render.moveit import moveit_package_name, render

        moveit_dir = root / moveit_package_name(robot)
        moveit_files = render(robot, files, shown, templates, sandboxed)
        found += proof.check(moveit_files, robot, moveit_dir, files)
    return Plan(
        robot,
        dict(sorted(files.items())),
        package_dir,
        tuple(found),
        meshes,
        moveit_files,
        moveit_dir,
        proofs,
        tuple(package_paths),
    )


def _with_matrix(
    robot: Robot, files: Mapping[str, str], meshes: dict[str, tuple[Path, bytes]], pkg: Path, show_progress: bool
) -> Robot:
    """The robot with its sampled self-collision matrix, taken from the committed SRDF when
    that records the same input hash (so ``check`` does not sample again)."""
    from dataclasses import replace

    from descgen.physics import collision

    sem = robot.semantic
    assert sem is not None and sem.collision_matrix is not None
    srdf = pkg / "srdf" / f"{robot.name}.srdf"
    committed = None
    if srdf.is_file() and not srdf.is_symlink():
        try:
            committed = read_bounded(srdf, "SRDF").decode("utf-8", errors="replace")
        except InputError:
            committed = None  # unreadable: sample again, check reports the file
    from descgen.render import header

    urdf = files[f"urdf/{robot.name}.urdf"]
    stamp = header.read(urdf)  # the key leaves out the header: it names the spec's path and hash
    matrix = collision.compute(
        robot,
        stamp.body if stamp is not None else urdf,
        {rel: data for rel, (_, data) in meshes.items()},
        pkg.name,
        sem.collision_matrix,
        committed,
        show_progress,
    )
    from descgen.prove import sweep as sweep_evidence

    out = replace(robot, semantic=replace(sem, matrix=matrix))
    sweep_evidence.reuse_committed(out, pkg)  # check: the committed sweep's collision runs, when still valid
    return out


def generate(
    spec: Path,
    out_root: Path | None = None,
    templates: Path | None = None,
    force: bool = False,
    package_paths: Sequence[Path] = (),
    show_progress: bool = False,
) -> package_write.Outcome:
    p = plan(spec, package_write.output_root(spec, out_root), templates, package_paths, show_progress=show_progress)
    outcome = package_write.Outcome(findings=list(p.findings))
    if outcome.failed:
        return outcome
    package_write.refuse_unsafe(p.package_dir)  # before reading any file of the package
    if p.moveit_dir is not None:
        package_write.refuse_unsafe(p.moveit_dir)
    edited = (
        [] if force else [(p.package_dir, rel) for rel in package_write.hand_edited(p.package_dir, p.files, p.meshes)]
    )
    if p.moveit_dir is not None and not force:
        edited += [(p.moveit_dir, rel) for rel in package_write.hand_edited(p.moveit_dir, p.moveit_files)]
    if edited:
        for folder, rel in edited:
            how = (
                f"is neither its source nor what {package_write.MANIFEST} recorded"
                if folder == p.package_dir and rel in p.meshes
                else "its content no longer matches its header"
            )
            shown = rel if folder == p.package_dir else f"{folder.name}/{rel}"
            outcome.findings.append(
                Finding(
                    "GEN004",
                    "error",
                    f"{shown} was edited by hand ({how}); not overwritten",
                    "move the change into the spec or a template, or run with --force to discard it",
                    f"file:{shown}",
                    Where(str(folder / rel)),
                )
            )
        return outcome
    try:
        packages: list[tuple[Path, Mapping[str, str | bytes]]] = [(p.package_dir, p.content())]
        if p.moveit_dir is not None:  # built before either is switched (see the module docstring)
            packages.append((p.moveit_dir, dict(p.moveit_files)))
        written, *more = package_write.write_packages(packages)
        for second in more:
            assert p.moveit_dir is not None
            written.written += [f"{p.moveit_dir.name}/{rel}" for rel in second.written]
            written.unchanged += [f"{p.moveit_dir.name}/{rel}" for rel in second.unchanged]
            written.removed += [f"{p.moveit_dir.name}/{rel}" for rel in second.removed]
    except OSError as exc:  # a full disk, a read-only --out: the old package is still in place
        raise InputError(
            [
                Finding(
                    "GEN045",
                    "error",
                    f"could not write the package: {exc.strerror or exc}"
                    + (f": {exc.filename}" if exc.filename else ""),
                    "check free space and permissions of the output folder (--out); nothing was changed",
                    "file",
                    Where(str(p.package_dir)),
                )
            ]
        ) from None
    written.findings = [*outcome.findings, *draw_frames(p.package_dir)]
    return written


def draw_frames(package_dir: Path) -> list[Finding]:
    """evidence/frames.svg from frames.dot when Graphviz's dot is installed, and only when the
    svg does not already record this dot text and this dot (see frames_svg); findings when the
    tree is too large to draw or dot fails."""
    from descgen.write.frames_svg import draw

    return draw(package_dir)


def check(
    spec: Path,
    out_root: Path | None = None,
    templates: Path | None = None,
    write_page: bool = False,
    package_paths: Sequence[Path] = (),
    thorough: bool = False,
) -> package_write.Outcome:
    """Regenerate in memory and compare with the files on disk; run every check. The evidence
    page (``descgen report``) is compared when it exists, and written with ``write_page``.
    ``thorough`` adds the slow-to-start proofs (checks.THOROUGH: yourdfpy)."""
    root = package_write.output_root(spec, out_root)
    p = plan(spec, root, templates, package_paths, thorough)
    package_write.refuse_unsafe(p.package_dir)  # a link would let the diff print a file from elsewhere
    outcome = package_write.Outcome(findings=list(p.findings))
    diffs: list[str] = []
    _compare(p.package_dir, p.files, p.robot.spec_hash, "", set(p.meshes), outcome, diffs)
    outcome.findings += _stale_meshes(p)
    if p.moveit_dir is not None:  # the MoveIt package is compared like the description package
        package_write.refuse_unsafe(p.moveit_dir)
        _compare(p.moveit_dir, p.moveit_files, p.robot.spec_hash, f"{p.moveit_dir.name}/", set(), outcome, diffs)
    outcome.diff = "".join(diffs)
    outcome.findings += _stale_evidence(spec, p, root or default_out(spec), write_page)
    outcome.findings += _evidence_page(spec, p, root or default_out(spec), outcome, write_page)
    return outcome


def _compare(
    package_dir: Path,
    files: Mapping[str, str],
    spec_hash: str | None,
    prefix: str,
    other: set[str],
    outcome: package_write.Outcome,
    diffs: list[str],
) -> None:
    """Each rendered file against the one on disk (GEN004-GEN006, with a diff), and files of
    package_write.ours no longer rendered (GEN007; ``other`` are generated files compared elsewhere).
    ``prefix`` names the package in messages when it is not the description package."""
    for rel, fresh in files.items():
        shown = f"{prefix}{rel}"
        target = package_dir / rel
        where = Where(str(target))
        if not target.is_file():
            outcome.findings.append(
                Finding("GEN006", "error", f"{shown} is missing", "run descgen generate", f"file:{shown}", where)
            )
            continue
        current = target.read_text(encoding="utf-8", errors="replace")
        if current == fresh:
            continue
        stamp = header.read(current)
        if stamp is not None and stamp.hand_edited:
            what, hint, code = "was edited by hand", "move the change into the spec or a template", "GEN004"
        elif stamp is not None and stamp.spec_hash != spec_hash:
            what, hint, code = "is stale: the spec changed", "run descgen generate and commit the result", "GEN005"
        else:
            what, hint, code = (
                "is stale: templates or descgen changed",
                "run descgen generate and commit the result",
                "GEN005",
            )
        outcome.findings.append(Finding(code, "error", f"{shown} {what}", hint, f"file:{shown}", where))
        diffs.append(
            "".join(
                difflib.unified_diff(
                    current.splitlines(keepends=True),
                    fresh.splitlines(keepends=True),
                    fromfile=f"a/{shown}",
                    tofile=f"b/{shown}",
                )
            )
        )
    for rel in package_write.ours(package_dir):
        if rel not in files and rel not in other:
            outcome.findings.append(
                Finding(
                    "GEN007",
                    "error",
                    f"{prefix}{rel} is no longer generated",
                    "run descgen generate",
                    f"file:{prefix}{rel}",
                    Where(str(package_dir / rel)),
                )
            )


def _evidence_page(spec: Path, p: Plan, root: Path, outcome: package_write.Outcome, write_page: bool) -> list[Finding]:
    """The evidence page rebuilt from the proofs just run: compared (GEN080), or written when
    asked and every proof passed (else GEN081: a page must not show a failed package as current)."""
    from descgen.commands import evidence_page as page
    from descgen.write import pose_images

    if not write_page and not (p.package_dir / page.PAGE).is_file():
        return []
    shown = spec_display(spec, root)
    lines = page.check_lines(shown, outcome.findings, outcome.diff)
    meshes = {rel: data for rel, (_, data) in p.meshes.items()}
    key = page.input_key(spec, shown, p.files, meshes, p.package_dir, lines, p.file_count(), p.robot.drift_check)
    if not write_page and page.current(p.package_dir, key):  # built from these very inputs: not again
        return pose_images.stale(p.package_dir, p.robot) + page.drift_stale(p.package_dir, p.robot)
    fresh = page.build(
        spec,
        shown,
        p.files,
        p.robot,
        p.package_dir,
        lines,
        p.file_count(),
        write_page,
        p.proofs,
        key,
        p.package_paths,
    )
    if not write_page:
        return (
            page.stale(p.package_dir, fresh)
            + pose_images.stale(p.package_dir, p.robot)
            + page.drift_stale(p.package_dir, p.robot)
        )
    bad = page.failed_verdicts(fresh)
    if outcome.failed or bad:
        why = bad[0] if bad else "the package is stale or a check failed"
        return [
            Finding(
                "GEN081",
                "error",
                f"{page.PAGE} not written: {why}",
                "fix what check reports, then run descgen report again",
                f"file:{page.PAGE}",
                Where(str(p.package_dir / page.PAGE)),
            )
        ]
    outcome.written += pose_images.write(p.package_dir, p.robot)  # before the page that embeds them
    outcome.written += page.write_drift(p.package_dir, p.robot)
    outcome.written.append(page.PAGE)
    page.write(p.package_dir, fresh)
    return []


def _stale_meshes(p: Plan) -> list[Finding]:
    """Every mesh copy compared byte for byte with its source beside the spec."""
    found: list[Finding] = []
    for rel, (src, data) in p.meshes.items():
        target = p.package_dir / rel
        where = Where(str(target))
        if not target.is_file():
            found.append(Finding("GEN006", "error", f"{rel} is missing", "run descgen generate", f"file:{rel}", where))
            continue
        now = read_bounded(target, "mesh", MAX_MESH_BYTES)
        if now != data:
            found.append(
                Finding(
                    "GEN060",
                    "error",
                    f"{rel} differs from its source {package_write.shown_source(src, p.package_dir.parent)} "
                    f"(package_write.sha256 {package_write.sha256(now)[:12]}... in the package, "
                    f"{package_write.sha256(data)[:12]}... at the source)",
                    "run descgen generate and commit the result; to change a mesh, edit the file beside the spec",
                    f"file:{rel}",
                    where,
                )
            )
    return found


def _stale_evidence(spec: Path, p: Plan, root: Path, refresh: bool = False) -> list[Finding]:
    """The committed control evidence (written by ``descgen control``, not by generate) run
    again from what verdict.json records, and compared like a generated file."""
    from descgen.commands.control.evidence_check import check_evidence

    return check_evidence(p.package_dir, p.robot, spec_display(spec, root), refresh)
