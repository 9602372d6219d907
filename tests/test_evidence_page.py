"""`descgen report`: the evidence page (nine sections, links that resolve, verdicts), the three
field-story faults it must show caught, check's staleness test, and experiments of `descgen
control` that must not overwrite the committed evidence."""

from __future__ import annotations

import dataclasses
import re
import shutil
from pathlib import Path

import pytest
import yaml

from descgen.commands import evidence_page
from descgen.commands.generate import check

from .conftest import ROOT
from .helpers import EXAMPLE_TEXT, cli

SPEC = "specs/warehouse_arm.yaml"
TRAJECTORY = "specs/trajectories/ready.yaml"
PKG = "generated/warehouse_arm_description"


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A project made from scratch, as a new user would: generate, the committed control run, report."""
    root = tmp_path_factory.mktemp("project")
    (root / "specs" / "trajectories").mkdir(parents=True)
    shutil.copy(ROOT / SPEC, root / SPEC)
    shutil.copy(ROOT / TRAJECTORY, root / TRAJECTORY)
    assert cli("generate", root / SPEC).returncode == 0
    ran = cli("control", root / SPEC, "--trajectory", root / TRAJECTORY)
    assert ran.returncode == 0, ran.stderr
    ran = cli("report", root / SPEC)
    assert ran.returncode == 0, ran.stderr
    return root


@pytest.fixture
def project(built: Path, tmp_path: Path) -> Path:
    shutil.copytree(built, tmp_path / "p")
    return tmp_path / "p"


def page_of(root: Path) -> str:
    return (root / PKG / evidence_page.PAGE).read_text()


def test_the_page_has_nine_sections_each_with_a_verdict_and_links_that_resolve(built: Path) -> None:
    page = page_of(built)
    headings = re.findall(r"^## (\d)\. ", page, re.M)
    assert headings == [str(i) for i in range(1, 10)]
    sections = re.split(r"^## \d\. ", page, flags=re.M)[1:]
    for text in sections:  # one verdict per section, and it passed for the example
        assert re.findall(r"^\*\*Verdict: (\w+)\*\*", text, re.M) == ["PASS"], text[:200]
    links = re.findall(r"\]\(([^)]+)\)", page)
    assert len(links) >= 12  # URDF, Xacro, poses, frames, lifecycle x2, interfaces, CSV, verdict, 4 plots
    evidence = built / PKG / "evidence"
    for target in links:
        assert (evidence / target).resolve().is_file(), target
    assert "(missing)" not in page
    # the validation section quotes what `descgen validate` prints, word for word
    ran = cli("validate", SPEC, cwd=built)
    assert ran.stdout.strip() in page
    # and the starter transcript holds all of it, warnings (stderr) first, as a terminal shows it
    printed = (ran.stderr + ran.stdout).rstrip("\n")
    assert f"$ descgen validate {SPEC}\n{printed}\n$ descgen generate" in page, printed


def test_the_starter_transcript_says_what_generate_prints(project: Path) -> None:
    """The page said "wrote 0 files, 15 unchanged" (the description package alone) where
    generate prints 33 (the MoveIt package too): the line must be the command's own."""
    ran = cli("generate", SPEC, cwd=project)
    assert ran.returncode == 0
    (line,) = [x for x in ran.stdout.splitlines() if x.startswith(f"{SPEC}: wrote")]
    assert line.startswith(f"{SPEC}: wrote 0 files, ")
    assert f"$ descgen generate {SPEC}\n{line}\n$ descgen check" in page_of(project)


def test_the_plots_and_mermaid_are_embedded(built: Path) -> None:
    page = page_of(built)
    assert "```mermaid\ngraph TD" in page
    for png in sorted((built / PKG / "evidence").glob("*.png")):
        assert f"![{png.name}]({png.name})" in page


def test_the_timestamp_section_counts_each_planted_fault_class(built: Path) -> None:
    # 10 s at 30 Hz camera_info = 300 lookups; each fault window is 1 s = 30 messages (hand count)
    assert "300 lookups into 'odom': 210 ok, 30 disconnected, 30 stale, 30 future-dated" in page_of(built)


def test_each_field_fault_is_planted_where_the_story_says() -> None:
    """The plantings checked with a YAML parser, not with the code that planted them."""
    base = yaml.safe_load(EXAMPLE_TEXT)
    by_name = {f.name: yaml.safe_load(f.plant(EXAMPLE_TEXT)) for f in evidence_page.FIELD_FAULTS}
    camera = next(s for s in by_name["camera-25m"]["sensors"] if s["name"] == "camera")
    assert camera["origin"]["xyz"][0] == "25 m"
    elbow = next(j for j in by_name["elbow-axis"]["joints"] if j["name"] == "elbow_joint")
    assert elbow["axis"] == "+z"
    sources = by_name["display-desired"]["frames"]["joint_state_sources"]
    assert [s["kind"] for s in sources] == ["desired"]
    for doc in by_name.values():  # nothing else changed
        assert set(doc) - {"frames"} == set(base) - {"frames"}


def test_each_field_fault_is_caught_and_the_page_says_by_what(built: Path) -> None:
    caught = evidence_page.field_faults(EXAMPLE_TEXT, SPEC)
    assert [(c.fault.name, c.planted, c.by.code if c.by else None) for c in caught] == [
        ("camera-25m", True, "UNIT004"),
        ("elbow-axis", True, "POSE010"),
        ("display-desired", True, "FRAME005"),
    ]
    rows = {line.split(" | ")[0].lstrip("| "): line for line in page_of(built).splitlines() if line.startswith("| ")}
    for c in caught:
        assert c.by is not None
        row = rows[c.fault.story]
        assert f"| yes | {c.by.code}: " in row and "MISSED" not in row
    # the camera's finding names the planted value, the elbow's the pose it broke
    assert '"25 m"' in rows[caught[0].fault.story]
    assert "known pose" in rows[caught[1].fault.story]


def test_a_fault_nothing_catches_fails_the_page_and_nothing_is_written(
    project: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A planted fault no finding catches (here: the camera 25 mm -> 26 mm, plausible and not
    measured) must show MISSED and fail the verdict; report then refuses (GEN081)."""
    harmless = evidence_page.FieldFault(
        "camera-26mm",
        "the camera 1 mm off",
        "UNIT004",
        lambda t: evidence_page._replace_in(t, "name: camera", "xyz: [25 mm,", "xyz: [26 mm,"),
    )
    monkeypatch.setattr(evidence_page, "FIELD_FAULTS", (harmless,))
    before = page_of(project)
    ran = cli("report", project / SPEC)
    assert ran.returncode == 1 and "error[GEN081]" in ran.stderr
    assert "every planted fault was caught" in ran.stderr
    assert page_of(project) == before


@pytest.mark.slow  # check rebuilds every proof (~7 s)
def test_check_finds_a_stale_page_but_not_a_different_machine(project: Path) -> None:
    target = project / PKG / evidence_page.PAGE
    page = target.read_text()
    assert not check(project / SPEC).failed
    # MuJoCo's lines (volatile) may differ between machines: not stale
    target.write_text(re.sub(r"drift [0-9.e-]+", "drift 0.5", page))
    assert not check(project / SPEC).failed
    # a verdict or a number that matters: stale
    target.write_text(page.replace("210 ok", "211 ok"))
    codes = [f.code for f in check(project / SPEC).findings if f.severity == "error"]
    assert codes == ["GEN080"]


@pytest.mark.slow  # check rebuilds every proof (~7 s)
def test_check_finds_the_page_stale_when_the_evidence_it_summarises_changes(project: Path) -> None:
    verdict = project / PKG / "evidence" / "verdict.json"
    verdict.write_text(verdict.read_text().replace('"state_echoes_command": true', '"state_echoes_command": false'))
    codes = {f.code for f in check(project / SPEC).findings if f.severity == "error"}
    assert "GEN080" in codes


@pytest.mark.slow  # check rebuilds every proof (~7 s)
def test_a_control_experiment_never_overwrites_the_committed_evidence(project: Path) -> None:
    evidence = project / PKG / "evidence"
    before = {p.name: p.read_bytes() for p in evidence.iterdir() if p.is_file()}
    ran = cli(
        "control", project / SPEC, "--trajectory", project / TRAJECTORY, "--plant", "sim",
        "--plant-fault", "elbow_joint:=reversed",
    )  # fmt: skip
    assert ran.returncode == 1  # the reversed elbow fails tracking
    assert {p.name: p.read_bytes() for p in evidence.iterdir() if p.is_file()} == before
    folder = Path(re.search(r" to (\S+)\n", ran.stdout).group(1))  # type: ignore[union-attr]
    try:
        assert folder.resolve() != evidence.resolve() and (folder / "verdict.json").is_file()
    finally:
        shutil.rmtree(folder)
    assert not check(project / SPEC).failed


def test_the_documented_mock_run_still_writes_the_package_evidence(project: Path) -> None:
    csv = project / PKG / "evidence" / "desired_vs_measured.csv"
    csv.write_text("stale\n")
    ran = cli("control", project / SPEC, "--trajectory", project / TRAJECTORY)
    assert ran.returncode == 0 and csv.read_text().startswith("time_s,joint,desired")


def test_a_robot_without_a_camera_gets_its_page(tmp_path: Path) -> None:
    """Issue 29: a robot with no camera has no stamped sensor message for the timestamp scenario
    (tf-audit would say BAG010) and no camera to move 25 m in the field story: the page is still
    written, those parts say why, and check takes it as current."""
    (tmp_path / "specs" / "trajectories").mkdir(parents=True)
    data = yaml.safe_load(EXAMPLE_TEXT)
    data["sensors"] = [s for s in data["sensors"] if s["type"] != "camera"]
    for pose in data["known_poses"]:
        pose["frames"] = [f for f in pose["frames"] if f["frame"] != "camera_link"]
    (tmp_path / SPEC).write_text(yaml.safe_dump(data, sort_keys=False))
    shutil.copy(ROOT / TRAJECTORY, tmp_path / TRAJECTORY)
    assert cli("generate", tmp_path / SPEC).returncode == 0
    assert cli("control", tmp_path / SPEC, "--trajectory", tmp_path / TRAJECTORY).returncode == 0
    ran = cli("report", tmp_path / SPEC)
    assert ran.returncode == 0, ran.stderr
    page = page_of(tmp_path)
    sections = dict(re.findall(r"^## (\d)\. (.*?)(?=^## \d\. |\Z)", page, re.M | re.S))
    verdicts = {n: re.findall(r"^\*\*Verdict: ([A-Z ]+)\*\*", text, re.M) for n, text in sections.items()}
    assert verdicts["5"] == ["NOT APPLICABLE"] and "no camera" in sections["5"]
    assert all(v == ["PASS"] for n, v in verdicts.items() if n != "5"), verdicts
    assert "not plantable" in sections["9"]  # the story's camera fault has no camera to move
    assert cli("check", tmp_path / SPEC).returncode == 0


def _tables(markdown: str) -> list[list[list[str]]]:
    """Every GFM table as markdown-it-py's table rule reads it: rows of cell texts."""
    import markdown_it

    tokens = markdown_it.MarkdownIt("commonmark").enable("table").parse(markdown)
    tables: list[list[list[str]]] = []
    inside = False
    for t in tokens:
        if t.type in ("table_open", "table_close"):
            inside = t.type == "table_open"
            tables += [[]] if inside else []
        elif inside and t.type == "tr_open":
            tables[-1].append([])
        elif inside and t.type == "inline":
            tables[-1][-1].append("".join(c.content for c in t.children or ()))
    return tables


def test_every_table_of_the_committed_page_keeps_its_cells() -> None:
    """A `|` in a cell (the proof 'xacro hardware:=gazebo|real') split the first table's row
    on GitHub: GFM drops the cells past the header's, so the proof's name was cut and its result
    lost. Every row keeps its header's cells, and the proof reads whole."""
    page = (ROOT / "generated" / "warehouse_arm_description" / "evidence" / "README.md").read_text()
    tables = _tables(page)
    assert len(tables) >= 2
    for rows in tables:
        assert len({len(r) for r in rows}) == 1, rows
    proofs = {row[0]: row[1] for row in tables[0][1:]}
    assert proofs["xacro hardware:=gazebo|real expands to the model's variants"] == "passed"


def test_a_robot_without_a_control_run_still_gets_its_page(tmp_path: Path) -> None:
    """No committed control run (an imported robot on its first day): sections 6 and 7 say so and
    how to make one, and the page is written; they used to FAIL it (GEN081, nothing written)."""
    (tmp_path / "specs").mkdir()
    shutil.copy(ROOT / SPEC, tmp_path / SPEC)
    assert cli("generate", tmp_path / SPEC).returncode == 0
    ran = cli("report", tmp_path / SPEC)
    assert ran.returncode == 0, ran.stderr
    page = page_of(tmp_path)
    for section in ("## 6. Interface and lifecycle traces", "## 7. Desired versus measured"):
        text = page.split(section, 1)[1].split("\n## ", 1)[0]
        assert "**Verdict: NOT APPLICABLE**: no control run is committed" in text
        assert "descgen control SPEC --trajectory" in text
    assert "**Verdict: FAIL**" not in page
    assert cli("check", tmp_path / SPEC).returncode == 0  # the page is current as written


def _story_with(monkeypatch: pytest.MonkeyPatch, story_caught: bool, catalogue_missed: bool) -> str:
    from descgen.audit.spec import load_spec
    from descgen.commands import faults

    spec = ROOT / SPEC
    robot = load_spec(spec).robot
    real = faults.plant_all(robot)
    assert all(r.caught for r in real if r.applicable)  # the example: every fault caught
    fake = [
        dataclasses.replace(r, caught=False, by=None) if catalogue_missed and i == 0 else r for i, r in enumerate(real)
    ]
    monkeypatch.setattr(faults, "plant_all", lambda robot: fake)
    if not story_caught:
        story = evidence_page.field_faults(spec.read_text(), SPEC)
        missed = [dataclasses.replace(c, by=None) if i == 0 else c for i, c in enumerate(story)]
        monkeypatch.setattr(evidence_page, "field_faults", lambda text, shown: missed)
    return "\n".join(evidence_page._field_story(spec, SPEC, robot))


def test_a_fault_the_catalogue_misses_is_a_blind_spot_not_a_failed_page(monkeypatch: pytest.MonkeyPatch) -> None:
    """A joint no known pose moves cannot show a wrong axis (kuka's base joint, imported with its
    SRDF's states): the page says so and is still written; a story fault missed still FAILs it."""
    spots = _story_with(monkeypatch, story_caught=True, catalogue_missed=True)
    assert "**Verdict: BLIND SPOTS**" in spots and not evidence_page.failed_verdicts(spots)
    monkeypatch.undo()
    assert evidence_page.failed_verdicts(_story_with(monkeypatch, story_caught=False, catalogue_missed=True))
    monkeypatch.undo()
    assert "**Verdict: PASS**" in _story_with(monkeypatch, story_caught=True, catalogue_missed=False)
