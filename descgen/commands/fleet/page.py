"""The fleet report's page (Markdown) and its summary on the terminal, from a roll-up. Every
name on the page comes from recordings (robots, topics, frames, versions): each is written as
Markdown text or a table cell (descgen/render/formatting.py), never as markup."""

from __future__ import annotations

from descgen.commands.fleet.rollup import CLASSES, Regression, RollUp
from descgen.commands.tf.bagaudit import shown
from descgen.render.formatting import mdcell, mdspan, mdtext

PLOTS = ("failure_rate_by_robot.png", "failures_by_description.png")
MARK = "<!-- written by descgen fleet-report -->"  # a folder whose README.md starts so is ours to rewrite


def _pct(n: int, of: int) -> str:
    return f"{100 * n / of:.2f}%" if of else "-"


def _robot_line(r: Regression) -> str:
    if r.healthy_until is None:
        head = f"robot {r.subject} has failed on every day since it was first seen, {r.since}"
    else:
        head = f"robot {r.subject} regressed on {r.since} (passing until {r.healthy_until})"
    now = ", ".join(r.versions)
    if r.before and r.before != r.versions:
        head += f", on description {now} (was {', '.join(r.before)})"
    else:
        head += f", on description {now}"
    return head


def _version_line(r: Regression) -> str:
    return (
        f"description {r.subject} regressed from {', '.join(r.before)} on {r.since}: "
        f"robots {', '.join(r.versions)} pass on the version before and fail on it"
    )


def text(rollup: RollUp, page: str | None) -> str:
    """What fleet-report prints: the totals, each regression on one line, where the page is."""
    lines = [
        f"{rollup.recordings} recordings, {len({d.robot for d in rollup.days})} robots, "
        f"{rollup.lookups} lookups, {rollup.failures} failed ({_pct(rollup.failures, rollup.lookups)})"
    ]
    # names come from recordings: escaped, as tf-audit prints them (no control character reaches the terminal)
    lines += [shown(_robot_line(r), 400) for r in rollup.robots]
    lines += [shown(_version_line(r), 400) for r in rollup.versions]
    if not rollup.lookups:
        lines.append("the tables hold no audited lookup")
    elif not rollup.robots and not rollup.versions:
        lines.append("no robot and no description version regressed")
    if rollup.unaudited:
        lines.append(f"{len(rollup.unaudited)} recordings were not audited (see the page)")
    if rollup.repeated:
        lines.append(f"{len(rollup.repeated)} recordings are in more than one table: counted once (see the page)")
    if page:
        lines.append(f"wrote {page}")
    return "".join(line + "\n" for line in lines)


def markdown(rollup: RollUp) -> str:
    days = sorted({d.day for d in rollup.days})
    span = f"from {days[0]} to {days[-1]}" if days else "no day with a lookup"
    out = [
        MARK,
        "",
        "# Fleet report",
        "",
        mdtext(
            f"{rollup.recordings} recordings of {len({d.robot for d in rollup.days})} robots, {span}: "
            f"{rollup.lookups} lookups, {rollup.failures} failed ({_pct(rollup.failures, rollup.lookups)}). "
            f"A robot-day fails when more than {100 * rollup.threshold:g}% of its lookups failed."
        ),
        "",
        "## Regressions",
        "",
    ]
    if not rollup.robots and not rollup.versions:
        out += ["No robot and no description version regressed.", ""]
    for r in rollup.robots:
        out += [f"- {mdtext(_robot_line(r))}"]
        for topic, frame, cls, n, first in r.lookups:
            where = mdspan(frame) if frame else "an empty frame\\_id"  # `` would be no code span
            out.append(f"  - {mdspan(topic)} in {where}: {n} {mdtext(cls)} since {mdtext(first)} UTC")
    for r in rollup.versions:
        out.append(f"- {mdtext(_version_line(r))}")
    out += [
        "",
        "## Failure rate by robot and day",
        "",
        f"![failure rate by robot and day]({PLOTS[0]})",
        "",
        f"![failed lookups by description version]({PLOTS[1]})",
        "",
        "| robot | day | description | recordings | lookups | " + " | ".join(CLASSES) + " | failed |",
        "|---|---|---|---:|---:|" + "---:|" * len(CLASSES) + "---:|",
    ]
    for d in rollup.days:
        out.append(
            f"| {mdcell(d.robot)} | {d.day} | {mdcell(', '.join(d.versions))} | {len(d.recordings)} | {d.lookups} | "
            + " | ".join(str(d.failed[c]) for c in CLASSES)
            + f" | {_pct(d.failures, d.lookups)} |"
        )
    if rollup.unaudited:
        out += ["", "## Recordings not audited", "", "| recording | why |", "|---|---|"]
        out += [f"| {mdcell(r)} | {mdcell(w)} |" for r, w in rollup.unaudited]
    out += _listed(
        "Recordings of an unknown robot",
        "These hold no /robot_description and no --robot mapping matched them; each is counted as "
        "a robot of its own, named (unknown) and the recording:",
        rollup.unidentified,
    )
    out += _listed(
        "Robots named by their URDF",
        "These names are a URDF's <robot name>, the model: every unit of the model is one robot here, "
        "and a regression of one unit is diluted by the others. Name the units with tf-audit --robot:",
        rollup.models,
    )
    out += _listed(
        "Recordings in more than one table", "Counted once, from the first table that audited it:", rollup.repeated
    )
    return "\n".join(out) + "\n"


def _listed(title: str, said: str, names: list[str]) -> list[str]:
    """A section of the page listing names from recordings (nothing when there are none)."""
    if not names:
        return []
    return ["", f"## {title}", "", mdtext(said), "", *(f"- {mdtext(n)}" for n in names)]
