"""``descgen tf-audit``'s work, with or without the findings table: the recordings on their
engine, and with ``out`` every recording's rows written to the table as it is done."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from descgen.commands.fleet.identity import Mapping
from descgen.commands.fleet.run import Outcome, audit_fleet
from descgen.core.findings import InputError


def tf_audit(
    bags: list[str],
    target: str,
    *,
    out: Path | None = None,
    force: bool = False,
    mappings: tuple[Mapping, ...] = (),
    **kwargs: Any,
) -> list[Outcome]:
    """Every recording's outcome (``kwargs``: audit_fleet's). With ``out``, the table is written
    whole or not at all: nothing when no recording was audited (InputError, exit 2)."""
    if out is None:
        return audit_fleet(bags, target, **kwargs)
    from descgen.commands.fleet.table import rows, schema, table
    from descgen.infra.workers import sigterm_raises
    from descgen.write.findings_table import TableFile, check_out, pyarrow_modules

    pa, _ = pyarrow_modules()
    check_out(out, force)
    # SIGTERM (a CI runner's timeout) ends the run as Ctrl-C does: the table's temporary file goes
    with sigterm_raises(), TableFile(out, schema(pa), force) as written:

        def each(i: int, outcome: Outcome) -> None:
            written.write(table(pa, rows(outcome, target, mappings)))
            if outcome.report is not None:
                outcome.report.failures = []  # written: one recording's rows are held at a time

        outcomes = audit_fleet(bags, target, each=each, keep_failures=True, **kwargs)
        if not any(o.report is not None for o in outcomes):  # nothing audited: nothing written
            raise InputError([f for o in outcomes for f in o.findings])
    return outcomes
