"""`descgen generate` and `descgen check` beside `xacro`, cold process against cold process,
interleaved (benchmarks/harness.py: A B A B …, CPU time of the process tree, median and min).

Robots: the example, and synthetic serial chains of 100 and 1000 links (benchmarks/synthetic.py;
no value cites a source, so the generated Xacro has no properties); ``--quick`` leaves out the
1000-link chain. Anchor of every cold row: a fresh `xacro` process on the plain generated URDF of
the same robot (the README's "generate / xacro on the URDF").

descgen's caches live in a folder of this run (DESCGEN_CACHE_DIR): pint definitions, compiled
templates and mesh facts are warm after the uncounted pair, as after any first run. The result
cache (descgen/infra/result_cache.py) is said per row:

- ``generate``: the package removed and the result cache emptied before each run: an edited
  spec gives new files, so nothing in it applies;
- ``check after generate``: with what generate left in it: the pre-commit flow (edit the
  spec, generate, commit);
- ``check, result cache empty``: emptied before each run: a CI job that keeps no results;
- ``generate after editing one value`` (the chains): the last length of the spec changed by a
  new amount before each run, package and caches as the previous run left them: what an
  engineer runs after correcting one measurement.

Warm rows, both sides in this process (CPU time, ``time.process_time``):
- ``generate in process`` (the example), package, result cache and the process's memo of
  sampled collision matrices emptied before each run,
  beside ``xacro.process_file(URDF).toxml()`` on its plain URDF;
- check 1's sandboxed expansion of the generated Xacro (``prove.xacro_expand.expand_scratch``,
  on a copy: it writes the file's skeleton beside it) beside ``xacro.process_file`` + ``toxml``
  on the same Xacro.

Run: .venv/bin/python benchmarks/bench_generate.py [--quick] [--pairs N]
"""

from __future__ import annotations

import os
import re
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
from harness import BIN, ROOT, FreshCache, in_process, process
from synthetic import chain_spec

CACHE = FreshCache()
ENV = harness.env(CACHE.path)
XACRO = str(BIN / "xacro") if (BIN / "xacro").is_file() else "xacro"


def edit_one_value(spec_text: str, n: int) -> str:
    """The spec with its last length in mm changed by n micrometres: a new value every call, as
    when an engineer corrects one measurement and runs generate again."""
    matches = list(re.finditer(r"(\d+(?:\.\d+)?) mm", spec_text))
    last = matches[-1]
    value = float(last.group(1)) + n / 1000
    return f"{spec_text[: last.start(1)]}{value:g}{spec_text[last.end(1) :]}"


def bench(label: str, spec_text: str, name: str, warm: bool = False, edit: bool = False) -> None:
    descgen = str(BIN / "descgen")
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        (tmp / "specs").mkdir()
        spec = tmp / "specs" / f"{name}.yaml"
        spec.write_text(spec_text)
        urdf = tmp / "generated" / f"{name}_description" / "urdf" / f"{name}.urdf"

        def fresh_generate() -> None:  # an edited spec: no package, nothing in the result cache
            shutil.rmtree(tmp / "generated", ignore_errors=True)
            CACHE.empty("results")

        def anchor() -> harness.Timing:
            return process([XACRO, str(urdf)], env=ENV, cwd=tmp)

        def cold(measure: str, argv: list[str], before: object = None) -> None:
            harness.compare(
                f"{measure}, {label}",
                lambda: process([descgen, *argv, str(spec)], env=ENV, cwd=tmp),
                anchor,
                kind="cold",
                anchor_name="xacro on its URDF",
                before_descgen=before or (lambda: None),  # type: ignore[arg-type]
            )

        cold("`generate`", ["generate"], fresh_generate)
        cold("`check` after generate", ["check"])
        cold("`check`, result cache empty", ["check"], lambda: CACHE.empty("results"))
        if edit:
            edits = iter(range(1, 10_000))
            cold(
                "`generate` after editing one value",
                ["generate"],
                lambda: spec.write_text(edit_one_value(spec_text, next(edits))),
            )
            spec.write_text(spec_text)
            process([descgen, "generate", str(spec)], env=ENV, cwd=tmp)
        sandbox_row(label, urdf.with_suffix(".urdf.xacro"))
        if warm:
            warm_rows(label, spec, urdf, tmp)


def warm_rows(label: str, spec: Path, urdf: Path, tmp: Path) -> None:
    import xacro

    from descgen.commands.generate import generate
    from descgen.physics import collision

    os.environ["DESCGEN_CACHE_DIR"] = str(CACHE.path)  # this process: the bench's caches too
    plain = tmp / "plain.urdf"
    shutil.copyfile(urdf, plain)  # generate removes the package before each run

    def again() -> None:  # nothing kept from the run before: package, result cache, sampled matrices
        shutil.rmtree(tmp / "generated", ignore_errors=True)
        CACHE.empty("results")
        collision._SAMPLED.clear()

    def ours() -> None:
        assert not generate(spec).failed

    harness.compare(
        f"`generate` in process, {label}",
        lambda: in_process(ours),
        lambda: in_process(lambda: xacro.process_file(str(plain)).toxml()),
        kind="warm",
        anchor_name="xacro.process_file on its URDF",
        before_descgen=again,
    )


def sandbox_row(label: str, path: Path) -> None:
    """Check 1's own cost: its sandboxed expansion beside ``xacro.process_file`` + ``toxml`` on
    the same file, both in this process after imports. The expansion runs on a copy."""
    import xacro

    from descgen.prove.xacro_expand import expand_scratch

    with tempfile.TemporaryDirectory() as scratch:
        copy = Path(scratch) / path.name
        shutil.copyfile(path, copy)
        for include in path.parent.glob("*.xacro"):  # the ros2_control include, if any
            shutil.copyfile(include, Path(scratch) / include.name)
        harness.compare(
            f"check 1's sandboxed expansion of the generated Xacro, {label}",
            lambda: in_process(lambda: expand_scratch(copy, path.name, {}, [Path(scratch)])),
            lambda: in_process(lambda: xacro.process_file(str(path)).toxml()),
            kind="warm",
            anchor_name="xacro.process_file",
        )


def main() -> None:
    harness.parse(__doc__)
    example = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
    try:
        bench("the example", example, "warehouse_arm", warm=True)
        bench("chain of 100 links", chain_spec(100, "chain100"), "chain100", edit=True)
        if not harness.QUICK:
            bench("chain of 1000 links", chain_spec(1000, "chain1000"), "chain1000", edit=True)
    finally:
        CACHE.close()
    harness.done()


if __name__ == "__main__":
    main()
