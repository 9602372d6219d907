"""The Jazzy corpus (issue 28): real ROS 2 Jazzy-era description packages nobody here wrote,
vendored in tests/data/jazzy_corpus (its README.md: upstream, commit, licence, what was kept and
what replaced; corpus.yaml: the cases, their arguments and the audit findings reviewed by hand).

For each case, with the corpus folder as the only package path:

(a) descgen's expansion of the Xacro (and of an SRDF Xacro) is the one xacro's own ``process_file``
    gives with ``$(find)`` answered from the corpus, compared as canonical XML (comments kept);
(b) ``descgen audit`` reports exactly the error-severity codes reviewed by hand: the upstream
    package's real defects (``defects``) and the findings a launch file answers (``context``);
(c) ``import`` proves its round trip, keeps every controller of the controllers file and every
    group and group state of the SRDF;
(d) ``generate`` and ``check`` of the imported spec pass, or fail only at the reviewed codes;
(e) pinocchio builds the same robot from the original expansion and from the generated URDF: every
    frame placement at 5 random configurations, every body's mass, centre of mass and inertia,
    within 1e-9; the generated controllers file gives back every controller's parameters;
(f) ``audit`` of the imported spec reports the original's findings.

A step that a defect of descgen fails is a strict xfail naming it (corpus.yaml ``judged_false``
and ``xfail``): it fails once the defect is fixed, and the entry is then removed."""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
import yaml
from lxml import etree

from descgen.commands.importer.run import Outcome
from descgen.read.xacro_file import expand_located
from tests.corpus import imported_once, spec_of
from tests.helpers import ROOT, cli

CORPUS = ROOT / "tests" / "data" / "jazzy_corpus"
STEPS = ("import", "controllers", "check", "generated", "spec_audit")


@dataclass(frozen=True)
class Case:
    ident: str
    xacro: str
    args: dict[str, str] = field(default_factory=dict)
    controllers: str | None = None
    launch_args: dict[str, str] = field(default_factory=dict)
    srdf: str | None = None
    defects: dict[str, str] = field(default_factory=dict)
    context: dict[str, str] = field(default_factory=dict)
    judged_false: dict[str, str] = field(default_factory=dict)
    in_spec: dict[str, str] = field(default_factory=dict)
    xfail: dict[str, str] = field(default_factory=dict)
    slow: bool = False

    @property
    def reviewed(self) -> set[str]:
        """The error codes audit should report on the original."""
        return set(self.defects) | set(self.context)

    def xacro_arg_options(self) -> list[str]:
        return [x for k, v in self.args.items() for x in ("--xacro-arg", f"{k}:={v}")]


def _cases() -> tuple[Case, ...]:
    raw = yaml.safe_load((CORPUS / "corpus.yaml").read_text())["cases"]
    out = []
    for c in raw:
        case = Case(
            ident=c["id"],
            xacro=c["xacro"],
            args={k: str(v) for k, v in (c.get("args") or {}).items()},
            controllers=c.get("controllers"),
            launch_args={k: str(v) for k, v in (c.get("launch_args") or {}).items()},
            srdf=c.get("srdf"),
            defects=c.get("defects") or {},
            context=c.get("context") or {},
            judged_false=c.get("judged_false") or {},
            in_spec=c.get("in_spec") or {},
            xfail=c.get("xfail") or {},
            slow=bool(c.get("slow")),
        )
        assert set(case.xfail) <= set(STEPS), case.ident
        out.append(case)
    return tuple(out)


CASES = _cases()


def _params(step: str | None = None, only: Any = lambda c: True) -> list[Any]:
    """One param per case ``only`` keeps: slow cases marked, and a strict xfail where a descgen
    defect fails ``step`` (``audit``: the codes judged false; ``check``: those and the step's own)."""
    out = []
    for c in CASES:
        if not only(c):
            continue
        marks: list[Any] = [pytest.mark.slow] if c.slow else []
        reasons = []
        if step in ("audit", "check") and c.judged_false:
            reasons += [f"{code} judged false: {why}" for code, why in c.judged_false.items()]
        if step in c.xfail:
            reasons.append(c.xfail[step])
        if reasons:
            marks.append(pytest.mark.xfail(strict=True, reason="descgen defect: " + " | ".join(reasons)))
        out.append(pytest.param(c, id=c.ident, marks=marks))
    return out


# --------------------------------------------------------------------------- reading the originals


def _real_xacro(path: Path, args: dict[str, str], monkeypatch: pytest.MonkeyPatch) -> bytes:
    """``path`` expanded by xacro's own ``process_file`` (no sandbox), ``$(find P)`` answered with
    the corpus's P/, as ament_index answers it in an install space's share/."""
    import xacro
    import xacro.substitution_args as sa

    with monkeypatch.context() as m:
        m.setattr(sa, "_eval_find", lambda pkg: str(CORPUS / pkg))
        return xacro.process_file(str(path), mappings=dict(args)).toxml().encode("utf-8")


def _canonical(xml: bytes) -> bytes:
    return etree.tostring(etree.fromstring(xml), method="c14n", with_comments=True)


def _srdf_root(case: Case, monkeypatch: pytest.MonkeyPatch) -> etree._Element:
    assert case.srdf is not None
    path = CORPUS / case.srdf
    data = _real_xacro(path, case.args, monkeypatch) if case.srdf.endswith(".xacro") else path.read_bytes()
    return etree.fromstring(data)


class _MergingLoader(yaml.SafeLoader):
    """YAML as rcl's parameter parser reads a file: a key written twice in one mapping (three
    top-level ``/**:`` in open_manipulator's file) adds to the first, not replaces it."""


def _merge(a: dict[Any, Any], b: dict[Any, Any]) -> dict[Any, Any]:
    out = dict(a)
    for k, v in b.items():
        out[k] = _merge(out[k], v) if isinstance(out.get(k), dict) and isinstance(v, dict) else v
    return out


def _mapping(loader: yaml.SafeLoader, node: yaml.MappingNode) -> dict[Any, Any]:
    out: dict[Any, Any] = {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        value = loader.construct_object(value_node, deep=True)
        out[key] = _merge(out[key], value) if isinstance(out.get(key), dict) and isinstance(value, dict) else value
    return out


_MergingLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _mapping)


def _nodes(text: str) -> dict[str, dict[str, Any]]:
    """node name -> its ``ros__parameters``; a namespace key (``/**``, ``/robot``) is looked into, as
    rcl matches its nodes (every node of the corpus runs in the namespace its file names)."""
    out: dict[str, dict[str, Any]] = {}

    def walk(d: dict[Any, Any]) -> None:
        for k, v in d.items():
            if not isinstance(v, dict):
                continue
            if "ros__parameters" in v:
                name = str(k).rsplit("/", 1)[-1]
                out[name] = _merge(out.get(name, {}), v["ros__parameters"] or {})
            else:
                walk(v)

    walk(yaml.load(text, Loader=_MergingLoader) or {})  # a SafeLoader subclass
    return out


def _controllers_text(case: Case) -> str:
    """The controllers file as the controller manager gets it: ``$(var NAME)`` replaced."""
    assert case.controllers is not None
    text = (CORPUS / case.controllers).read_text()
    for name, value in case.launch_args.items():
        text = text.replace(f"$(var {name})", value)
    return text


def _declared(nodes: dict[str, dict[str, Any]]) -> dict[str, str]:
    """controller name -> type, as controller_manager's parameters declare them (``name: {type: T}``
    or ``name.type: T``)."""
    cm = nodes.get("controller_manager", {})
    out = {k: v["type"] for k, v in cm.items() if isinstance(v, dict) and "type" in v}
    out.update({k[: -len(".type")]: v for k, v in cm.items() if isinstance(k, str) and k.endswith(".type")})
    return out


# --------------------------------------------------------------------------- descgen's side


def _options(case: Case) -> Any:
    from descgen.read.description import Options

    return Options(
        srdf=CORPUS / case.srdf if case.srdf else None,
        controllers=CORPUS / case.controllers if case.controllers else None,
        xacro_args=case.args,
        package_paths=(CORPUS,),
        launch_args=case.launch_args,
    )


def _import(case: Case) -> tuple[Outcome, Path]:
    return imported_once("jazzy", case.ident, CORPUS / case.xacro, _options(case))


def _imported(case: Case) -> Outcome:
    return _import(case)[0]


def _spec(case: Case) -> Path:
    return spec_of(_import(case))


def _error_codes(stderr: str) -> set[str]:
    return set(re.findall(r"error\[(\w+)\]", stderr))


def _written(case: Case, tmp_path: Path) -> dict[str, str]:
    """What generate writes for the imported spec: its URDF and config files (path in the package
    -> text). Where generate refuses the spec at the reviewed defects, the same renderer without
    validate's rules, as import's own proof renders it (descgen.render.render_package)."""
    spec = _spec(case)
    out = tmp_path / "gen"
    ran = cli("generate", spec, "--out", out, "--package-path", CORPUS, cwd=tmp_path)
    if ran.returncode == 0:
        (package,) = out.iterdir()
        wanted = [*package.glob("urdf/*.urdf"), *package.glob("config/*.yaml")]
        return {p.relative_to(package).as_posix(): p.read_text() for p in wanted}
    assert ran.returncode == 2, ran.stderr[-2000:]
    from descgen.audit.spec import load_spec_text
    from descgen.render import render_package

    loaded = load_spec_text(spec.read_text(), str(spec), rules=False)
    return dict(render_package(loaded.robot, str(spec)))


# --------------------------------------------------------------------------- (a) expansion


@pytest.mark.parametrize("case", _params())
def test_descgen_expands_as_xacro_does(case: Case, monkeypatch: pytest.MonkeyPatch) -> None:
    files = [case.xacro] + ([case.srdf] if case.srdf and case.srdf.endswith(".xacro") else [])
    for name in files:
        theirs = _real_xacro(CORPUS / name, case.args, monkeypatch)
        mine = expand_located(CORPUS / name, name, case.args, (CORPUS,), False).xml
        assert _canonical(mine) == _canonical(theirs), name


# --------------------------------------------------------------------------- (b) audit


def _audit_args(case: Case) -> list[str | Path]:
    args: list[str | Path] = [CORPUS / case.xacro, "--package-path", CORPUS, *case.xacro_arg_options()]
    if case.controllers:
        args += ["--controllers", CORPUS / case.controllers]
    args += [x for k, v in case.launch_args.items() for x in ("--launch-arg", f"{k}:={v}")]
    if case.srdf:
        args += ["--srdf", CORPUS / case.srdf]
    return args


@pytest.mark.parametrize("case", _params("audit"))
def test_audit_reports_the_reviewed_errors(case: Case, tmp_path: Path) -> None:
    """The error-severity codes (warnings and infos are not compared) of ``descgen audit``."""
    ran = cli("audit", *_audit_args(case), "--format", "json", cwd=tmp_path)
    assert ran.returncode in (0, 1), ran.stderr[-2000:]
    found = json.loads(ran.stdout)["findings"]
    errors = {f["code"] for f in found if f["severity"] == "error"}
    assert errors == case.reviewed, [f for f in found if f["severity"] == "error"][:5]
    assert ran.returncode == (1 if errors else 0)


# --------------------------------------------------------------------------- (c) import


@pytest.mark.parametrize("case", _params("import"))
def test_import_is_proven(case: Case) -> None:
    outcome = _imported(case)
    assert not outcome.imported.differences, outcome.imported.differences[:5]
    assert not outcome.invalid, outcome.invalid[:5]
    assert outcome.proven


@pytest.mark.parametrize("case", _params(only=lambda c: c.srdf))
def test_import_keeps_the_srdf_groups(case: Case, monkeypatch: pytest.MonkeyPatch) -> None:
    root = _srdf_root(case, monkeypatch)
    semantic = yaml.safe_load(_imported(case).imported.spec_text).get("semantic") or {}
    assert [g["name"] for g in semantic.get("groups", [])] == [g.get("name") for g in root.iterfind("group")]
    states = {(s.get("name"), s.get("group")) for s in root.iterfind("group_state")}
    assert {(s["name"], s["group"]) for s in semantic.get("group_states", [])} == states


@pytest.mark.parametrize("case", _params("controllers", only=lambda c: c.controllers))
def test_import_keeps_every_controller(case: Case) -> None:
    nodes = _nodes(_controllers_text(case))
    expected = set(_declared(nodes)) | (set(nodes) - {"controller_manager"})
    spec = yaml.safe_load(_imported(case).imported.spec_text)
    rc = spec.get("ros2_control") or {}
    imported = {c["name"]: c for c in rc.get("controllers", [])}
    assert set(imported) == expected
    for name, type_ in _declared(nodes).items():
        assert imported[name]["type"] == type_, name


# --------------------------------------------------------------------------- (d) generate and check


@pytest.mark.parametrize("case", _params("check"))
def test_generate_and_check_pass_with_the_reviewed_defects_waived(case: Case, tmp_path: Path) -> None:
    """Import writes a waiver for each defect of the original (IMP038), so generate and check
    pass at once; every error they print is waived, and of a code reviewed by hand above."""
    spec = _spec(case)
    allowed = case.reviewed | set(case.in_spec)
    waivers = yaml.safe_load(spec.read_text()).get("waivers", [])
    assert {w["code"] for w in waivers} <= allowed
    assert all(w["reason"] == "imported as is" for w in waivers)
    out = tmp_path / "gen"
    for command in ("generate", "check"):
        ran = cli(command, spec, "--out", out, "--package-path", CORPUS, cwd=tmp_path)
        assert ran.returncode == 0, (command, ran.stderr[-2000:])
        assert _error_codes(ran.stderr) <= allowed, command
        assert ran.stderr.count("  waived: imported as is") == len(re.findall(r"error\[\w+\]", ran.stderr)), command
    # one verdict: the audit of what generate wrote (its descgen-waivers.yaml read) passes as check did
    (package,) = [p for p in out.iterdir() if p.name.endswith("_description")]
    (urdf,) = package.glob("urdf/*.urdf")
    audit = ["audit", urdf, "--package-path", CORPUS]
    audit += [x for srdf in package.glob("srdf/*.srdf") for x in ("--srdf", srdf)]
    audit += [x for c in package.glob("config/ros2_controllers.yaml") for x in ("--controllers", c)]
    ran = cli(*audit, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    raw = cli(*audit, "--no-waivers", cwd=tmp_path)
    waived_errors = len(re.findall(r"error\[\w+\].*\n  waived: imported as is \(descgen-waivers.yaml\)", ran.stderr))
    assert raw.returncode == (1 if waived_errors else 0), raw.stderr[-2000:]
    assert len(re.findall(r"error\[\w+\]", raw.stderr)) == waived_errors


# --------------------------------------------------------------------------- (e) the same robot


@pytest.mark.parametrize("case", _params("generated"))
def test_the_generated_robot_is_the_original(case: Case, tmp_path: Path, pin: Any) -> None:
    from tests.test_import_oracle import _pinocchio, _random_configs, _same

    original = tmp_path / "original.urdf"
    original.write_bytes(expand_located(CORPUS / case.xacro, case.xacro, case.args, (CORPUS,), False).xml)
    files = _written(case, tmp_path)
    (name,) = [p for p in files if p.startswith("urdf/") and p.endswith(".urdf")]
    written = tmp_path / "written.urdf"
    written.write_text(files[name])
    configs = _random_configs(pin.buildModelFromUrdf(str(original)), case.ident)
    poses_a, bodies_a = _pinocchio(original, configs)
    poses_b, bodies_b = _pinocchio(written, configs)
    _same(bodies_a, bodies_b, "masses and inertias")
    for k, (a, b) in enumerate(zip(poses_a, poses_b, strict=True)):
        _same(a, b, f"frame placements at configuration {k}")


@pytest.mark.parametrize("case", _params("controllers", only=lambda c: c.controllers))
def test_the_written_controllers_are_the_originals(case: Case, tmp_path: Path) -> None:
    """Every controller's parameters (its type under controller_manager) as yaml reads them back
    from the generated config/ros2_controllers.yaml."""
    original = _nodes(_controllers_text(case))
    written = _nodes(_written(case, tmp_path)["config/ros2_controllers.yaml"])
    assert _declared(written) == _declared(original)
    for name, params in original.items():
        if name == "controller_manager":
            continue
        mine = {k: v for k, v in params.items() if k != "type"}
        assert {k: v for k, v in written.get(name, {}).items() if k != "type"} == mine, name


# --------------------------------------------------------------------------- (f) audit of the spec


@pytest.mark.parametrize("case", _params("spec_audit"))
def test_audit_of_the_spec_reports_the_originals_findings(case: Case, tmp_path: Path) -> None:
    """(code, subject) of every finding, but the reader's (READ) on the original and the spec's
    own (IMP, SPEC and the reviewed ``in_spec``) on the spec; and GEOM006 (an absolute mesh path
    into a package) of the original, which import writes package://, saying so (IMP036)."""
    from descgen.read.description import audit

    spec = _spec(case)
    ran = cli("audit", spec, "--package-path", CORPUS, "--format", "json", cwd=tmp_path)
    own = set(case.in_spec)
    mine = {
        (f["code"], f["subject"])
        for f in json.loads(ran.stdout)["findings"]
        if f["code"][:3] not in ("IMP", "SPE") and f["code"] not in own
    }
    fixed = {"GEOM006"} if "IMP036" in {f.code for f in _imported(case).imported.report} else set()
    original = {
        (f.code, f.subject)
        for f in audit(CORPUS / case.xacro, _options(case))
        if f.code[:4] != "READ" and f.code not in fixed
    }
    assert mine == original, (sorted(original - mine)[:10], sorted(mine - original)[:10])


# --------------------------------------------------------------------------- the corpus itself


def test_the_corpus_is_as_its_readme_says() -> None:
    """Every package has its package.xml and licence and a row in README.md; every case names
    files that are there; the folder stays small (meshes are stand-ins)."""
    readme = (CORPUS / "README.md").read_text()
    packages = sorted(p.name for p in CORPUS.iterdir() if p.is_dir())
    for name in packages:
        assert (CORPUS / name / "package.xml").is_file(), name
        assert any(p.name.startswith(("LICENSE", "LICENCE")) for p in (CORPUS / name).iterdir()), name
        assert f"`{name}`" in readme, name
    for case in CASES:
        for f in (case.xacro, case.controllers, case.srdf):
            assert f is None or (CORPUS / f).is_file(), (case.ident, f)
        assert f"`{case.ident}`" in readme, case.ident
    files = [p for p in CORPUS.rglob("*") if p.is_file()]
    assert sum(p.stat().st_size for p in files) < 3_000_000
    meshes = [p for p in files if p.suffix.lower() in (".stl", ".dae")]
    assert meshes and all(p.stat().st_size < 10_000 for p in meshes)


@pytest.mark.parametrize("case", _params(), ids=lambda c: c.ident)
def test_the_imported_spec_validates_against_the_json_schema(case: Case) -> None:
    """Issue 29: the published JSON Schema (what editors check a spec with) accepts every spec
    import writes, checked by a real JSON Schema validator."""
    import jsonschema

    schema = json.loads((ROOT / "specs" / "descgen-spec.schema.json").read_text())
    data = yaml.safe_load(_imported(case).imported.spec_text)
    errors = [
        f"{list(e.absolute_path)}: {e.message[:200]}" for e in jsonschema.Draft202012Validator(schema).iter_errors(data)
    ]
    assert errors == []


@pytest.mark.parametrize("case", _params("fix", only=lambda c: "CTRL045" in c.reviewed))
def test_import_fix_renames_the_plugin_jazzy_renamed_and_nothing_else(case: Case, tmp_path: Path) -> None:
    """fake_components/GenericSystem, the packages' use_fake_hardware plugin, and its
    fake_sensor_commands are what a fix may touch: import --fix writes mock_components/GenericSystem,
    no CTRL045 waiver, and the robot generate writes is the same one (its URDF differs from the
    unfixed import's only in those two names)."""
    from descgen.commands.importer.run import ImportOptions, import_description

    options = ImportOptions(_options(case), spec_name=str(tmp_path / "r.yaml"), fix=True)
    fixed = import_description(CORPUS / case.xacro, options)
    assert [f.code for f in fixed.imported.report if f.code == "IMP039"] == ["IMP039"]
    spec = tmp_path / "r.yaml"
    spec.write_text(fixed.imported.spec_text)
    assert "fake_components/GenericSystem" not in fixed.imported.spec_text.split("waivers:")[0]
    waivers = yaml.safe_load(spec.read_text()).get("waivers", [])
    assert "CTRL045" not in {w["code"] for w in waivers}
    ran = cli("validate", spec, "--package-path", CORPUS, cwd=tmp_path)
    assert ran.returncode == 0 and "CTRL045" not in ran.stderr, ran.stderr[-2000:]
    plain_spec = spec_of(_import(case))
    out_a, out_b = tmp_path / "a", tmp_path / "b"
    assert cli("generate", spec, "--out", out_a, "--package-path", CORPUS, cwd=tmp_path).returncode == 0
    assert cli("generate", plain_spec, "--out", out_b, "--package-path", CORPUS, cwd=tmp_path).returncode == 0
    (a,) = out_a.glob("*_description/urdf/*.urdf")
    (b,) = out_b.glob("*_description/urdf/*.urdf")
    renames = {"fake_components/GenericSystem": "mock_components/GenericSystem"}
    renames |= {'"fake_sensor_commands"': '"mock_sensor_commands"', '"fake_gpio_commands"': '"mock_gpio_commands"'}

    def body(urdf: Path, renamed: bool = False) -> list[str]:
        lines = [x for x in urdf.read_text().splitlines() if "spec-sha256" not in x and "generated from" not in x]
        for old, new in renames.items() if renamed else ():
            lines = [x.replace(old, new) for x in lines]
        return lines

    assert body(a) == body(b, renamed=True)
