"""Hostile files for the readers and the printed output (issue 18).

Every path the user names is checked for type and size before it is read (a FIFO, a
device, a folder, a 1 GB file, a name longer than the OS allows), a non-finite number is
a finding, a value cannot forge a line of the text report, a closed pipe ends quietly,
and 10,000 welded links cost linear memory. Hostile inputs are built here, in tmp_path.

Tests that could hang on a regression (a FIFO, /dev/zero) run under ``deadline``: SIGALRM
interrupts a blocking open or read in this process and fails the test instead.
"""

from __future__ import annotations

import errno
import json
import os
import re
import signal
import subprocess
import sys
import time
import tracemalloc
import unicodedata
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

from descgen import cli
from descgen.core.findings import Finding, InputError, Where
from descgen.infra import yamlsource
from descgen.infra.safeio import read_bounded
from descgen.output import report
from descgen.read.controllers import read_controllers_text
from descgen.read.description import kind_of, load_description

from .corpus import descriptions
from .helpers import EXAMPLE_TEXT, ROOT

FINDING = re.compile(r"^[^\n]+?:\d+:\d+: (error|warning|info)\[([A-Z]+\d{3})\]: ")
UNLOCATED = re.compile(r"^[^\n]+: (error|warning|info)\[[A-Z]+\d{3}\]: ")
CONTROL = {"Cc", "Zl", "Zp"}  # unicodedata categories a terminal treats as control or line break

ROBOT = """<robot name="r">
  <link name="base"/>
  <link name="arm">
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    <inertial><origin xyz="0 0 0.05" rpy="0 0 0"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"""


@pytest.fixture
def deadline() -> Iterator[None]:
    """Fail (not hang) when the code under test blocks for more than 10 s."""

    def expired(signum: int, frame: object) -> None:
        raise TimeoutError("blocked: the file was read instead of refused")

    old = signal.signal(signal.SIGALRM, expired)
    signal.alarm(10)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def audit(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = cli.main(["audit", *args])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return code, out, err


def codes_of(stderr: str) -> list[str]:
    return re.findall(r"(?:error|warning|info)\[([A-Z]+\d{3})\]", stderr)


# --- files that are not regular files, or too large -------------------------------------------


@pytest.fixture
def fifo(tmp_path: Path) -> Path:
    path = tmp_path / "robot.urdf"
    os.mkfifo(path)
    return path


@pytest.mark.usefixtures("deadline")
@pytest.mark.parametrize("option", [None, "--srdf", "--controllers"])
def test_a_fifo_is_refused_without_opening_it_blocking(
    fifo: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str | None
) -> None:
    # a plain open() of a FIFO with no writer blocks forever; read_bytes() would hang here
    urdf = tmp_path / "ok.urdf"
    urdf.write_text(ROBOT)
    args = [str(fifo)] if option is None else [str(urdf), option, str(fifo)]
    code, _, err = audit(capsys, *args)
    assert code == 2
    assert f"{fifo}: error[READ040]: is a FIFO" in err


@pytest.mark.usefixtures("deadline")
def test_a_fifo_spec_is_refused(fifo: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = fifo.with_suffix(".yaml")
    fifo.rename(spec)
    assert cli.main(["validate", str(spec)]) == 2
    assert f"{spec}: error[YAML010]: is a FIFO" in capsys.readouterr().err


@pytest.mark.usefixtures("deadline")
@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero")
@pytest.mark.parametrize("option", [None, "--srdf", "--controllers"])
def test_an_endless_device_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str | None) -> None:
    # /dev/zero never ends: read_bytes() would fill memory until the machine gives up
    urdf = tmp_path / "ok.urdf"
    urdf.write_text(ROBOT)
    args = ["/dev/zero"] if option is None else [str(urdf), option, "/dev/zero"]
    code, _, err = audit(capsys, *args)
    assert code == 2
    assert "/dev/zero: error[READ040]: is a character device" in err


@pytest.mark.usefixtures("deadline")
def test_kind_of_does_not_read_a_whole_file_for_its_head(tmp_path: Path, fifo: Path) -> None:
    # a file without a known suffix is sniffed for xmlns:xacro: only its head may be read
    big = tmp_path / "robot"
    with big.open("wb") as fh:
        fh.truncate(200 * 1024 * 1024)  # sparse: no disk used
    tracemalloc.start()
    try:
        assert kind_of(big) == "urdf"
        assert kind_of(fifo.rename(tmp_path / "pipe")) == "urdf"
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1024 * 1024, peak


@pytest.mark.usefixtures("deadline")
@pytest.mark.parametrize(
    ("name", "command", "code"), [("big.urdf", "audit", "READ041"), ("big.yaml", "validate", "YAML003")]
)
def test_a_1_gb_file_is_refused_before_it_is_read(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str, command: str, code: str
) -> None:
    big = tmp_path / name
    with big.open("wb") as fh:
        fh.truncate(1024**3)  # sparse
    tracemalloc.start()
    try:
        status = cli.main([command, str(big)])
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert status == 2
    assert f"{big}: error[{code}]: file is 1073.7 MB" in capsys.readouterr().err
    assert peak < 20 * 1024 * 1024, peak  # nothing of the gigabyte was read


def test_a_directory_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "robot.urdf"
    folder.mkdir()
    code, _, err = audit(capsys, str(folder))
    assert code == 2
    assert f"{folder}: error[READ040]: is a directory, not a regular file" in err


def test_a_file_name_longer_than_the_os_allows(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    name_max = os.pathconf(tmp_path, "PC_NAME_MAX")
    path = tmp_path / ("r" * (name_max + 1) + ".urdf")
    code, _, err = audit(capsys, str(path))
    assert code == 2
    assert f"error[READ001]: cannot read the file: {os.strerror(errno.ENAMETOOLONG)}" in err


def test_a_mesh_name_longer_than_the_os_allows_is_a_missing_mesh(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    long = "m" * (os.pathconf(tmp_path, "PC_NAME_MAX") + 1) + ".stl"
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(
        ROBOT.replace('<box size="0.1 0.1 0.1"/></geometry></visual>', f'<mesh filename="{long}"/></geometry></visual>')
    )
    (tmp_path / "package.xml").write_text("<package><name>p</name></package>")
    code, _, err = audit(capsys, str(urdf))
    assert code == 1  # an error finding, not unusable input and not a crash
    assert "GEOM003" in codes_of(err)


def test_read_bounded_reads_at_most_the_limit(tmp_path: Path) -> None:
    path = tmp_path / "f"
    path.write_bytes(b"x" * 100)
    assert read_bounded(path, "test", 100) == b"x" * 100
    with pytest.raises(InputError) as exc:
        read_bounded(path, "test", 99)
    assert exc.value.findings[0].code == "READ041"


def test_a_symlink_to_a_regular_file_is_read_and_to_a_fifo_refused(tmp_path: Path, fifo: Path) -> None:
    (tmp_path / "real").write_bytes(b"data")
    (tmp_path / "to_real").symlink_to(tmp_path / "real")
    (tmp_path / "to_fifo").symlink_to(fifo)
    assert read_bounded(tmp_path / "to_real", "test") == b"data"
    with pytest.raises(InputError) as exc:
        read_bounded(tmp_path / "to_fifo", "test")
    assert exc.value.findings[0].code == "READ040"


# --- non-finite numbers -----------------------------------------------------------------------


NON_FINITE = ["nan", "inf", "-inf", "1e999", "NaN"]
FIELDS = [
    ('<origin xyz="0 0 0.1" rpy="0 0 0"/><axis', '<origin xyz="0 0 0.1" rpy="0 {} 0"/><axis'),  # joint rpy
    ('<origin xyz="0 0 0.1" rpy="0 0 0"/><axis', '<origin xyz="{} 0 0.1" rpy="0 0 0"/><axis'),  # joint xyz
    ('<axis xyz="0 0 1"/>', '<axis xyz="0 {} 1"/>'),
    ('<mass value="1"/>', '<mass value="{}"/>'),
    ('ixx="0.01"', 'ixx="{}"'),
    ('<origin xyz="0 0 0.05" rpy="0 0 0"/>', '<origin xyz="0 0 {}" rpy="0 0 0"/>'),  # centre of mass (gravity load)
    ('effort="10"', 'effort="{}"'),
    ('upper="1"', 'upper="{}"'),
    ('<box size="0.1 0.1 0.1"/></geometry></collision>', '<box size="0.1 {} 0.1"/></geometry></collision>'),
]


@pytest.mark.parametrize("value", NON_FINITE)
@pytest.mark.parametrize(("old", "new"), FIELDS, ids=[new.split("{}")[0][-12:] for _, new in FIELDS])
def test_a_non_finite_number_is_a_located_finding(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], old: str, new: str, value: str
) -> None:
    assert float(value) != float(value) or abs(float(value)) == float("inf")  # the oracle: Python reads it
    text = ROBOT.replace(old, new.format(value), 1)
    assert text != ROBOT
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(text)
    line = text[: text.index(new.format(value))].count("\n") + 1
    code, _, err = audit(capsys, str(urdf))
    assert code == 1
    assert f"{urdf}:{line}:1: error[READ042]: " in err and "is not a finite number" in err


def test_a_non_finite_value_is_treated_as_missing(tmp_path: Path) -> None:
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(ROBOT.replace('<mass value="1"/>', '<mass value="nan"/>'))
    robot, found = load_description(urdf)
    arm = robot.link("arm")
    assert arm is not None and arm.inertial is not None and arm.inertial.mass is None
    assert [f.code for f in found] == ["READ042"]


def test_a_non_finite_srdf_group_state_is_a_finding(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(ROBOT)
    srdf = tmp_path / "robot.srdf"
    srdf.write_text(
        '<robot name="r">\n<group name="arm"><joint name="shoulder"/></group>\n'
        '<group_state name="up" group="arm">\n<joint name="shoulder" value="inf"/>\n</group_state>\n</robot>\n'
    )
    code, _, err = audit(capsys, str(urdf), "--srdf", str(srdf))
    assert code == 1
    assert f"{srdf}:4:1: error[READ042]: " in err


# --- controllers YAML of the wrong shape: files ROS's parameter parser refuses (READ045) ------


@pytest.mark.parametrize(
    ("text", "code", "line"),
    [
        ("controller_manager:\n  - a\n  - b\n", "READ045", 2),
        ("controller_manager:\n  ros__parameters: [1, 2]\n", "READ045", 2),
        ("controller_manager:\n  ros__parameters: 5\n", "READ045", 2),
        ("arm:\n  ros__parameters: hello\n", "READ045", 2),
        ("controller_manager:\n  ros__parameters:\n    update_rate: .inf\n", "READ042", 3),
        ("arm:\n  ros__parameters:\n    type: x/Y\n    gain: .nan\n", "READ042", 4),
    ],
)
def test_controllers_of_the_wrong_shape_are_findings(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str, code: str, line: int
) -> None:
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(ROBOT)
    controllers = tmp_path / "controllers.yaml"
    controllers.write_text(text)
    status, _, err = audit(capsys, str(urdf), "--controllers", str(controllers))
    assert status == 1
    assert f"{controllers}:{line}:" in err and f"error[{code}]" in err


YAML_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
    lambda inner: (
        st.lists(inner, max_size=3)
        | st.dictionaries(st.sampled_from(["type", "ros__parameters", "update_rate", "a"]), inner, max_size=3)
    ),
    max_leaves=12,
)


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(
    cm=YAML_VALUES,
    params=YAML_VALUES,
    top=st.dictionaries(st.sampled_from(["arm", "controller_manager", "b"]), YAML_VALUES, max_size=2),
)
def test_controllers_reader_fuzz(cm: object, params: object, top: dict[str, object]) -> None:
    doc = {**top, "controller_manager": {"ros__parameters": cm}, "arm": {"ros__parameters": params}}
    text = yaml.safe_dump(doc)
    try:
        _, rate, found = read_controllers_text(text, "c.yaml")
    except InputError as exc:
        assert all(f.severity == "error" for f in exc.findings)
        return
    assert rate is None or (rate == rate and abs(rate) != float("inf"))
    assert all(isinstance(f, Finding) for f in found)


# --- one line per finding ----------------------------------------------------------------------


def test_printable_escapes_every_control_character() -> None:
    hostile = "".join(map(chr, [*range(0x20), 0x7F, *range(0x80, 0xA0), 0x2028, 0x2029, 0x202E]))
    out = report.printable("a" + hostile + "b")
    assert out.startswith("a") and out.endswith("b")
    assert not [c for c in out if unicodedata.category(c) in CONTROL or c == "\u202e"]
    assert "\\n" in out and "\\x1b" in out and "\\x85" in out and "\\u2028" in out


def test_text_report_is_one_line_per_finding_whatever_the_values() -> None:
    f = Finding(
        "NAME001",
        "error",
        "name 'x\nevil.urdf:1:1: error[TOPO001]: forged' \x1b[2J",
        "hint\r\nmore",
        "link:x",
        Where("a\nb.urdf", 3, 4),
    )
    lines = report.text([f]).splitlines()
    assert len(lines) == 2 and lines[1].startswith("  hint: ")
    assert FINDING.match(lines[0]) and lines[0].count("error[") == 2  # the forged one is inside the message


def test_long_quoted_values_are_cut() -> None:
    msg = f"link '{'x' * 5000}' is odd"
    line = report.text([Finding("NAME001", "error", msg)]).splitlines()[0]
    assert len(line) < 400 and line.endswith("…' is odd")


@pytest.mark.parametrize("fmt", ["text", "json"])
def test_a_link_name_cannot_forge_a_finding_line(tmp_path: Path, capsys: pytest.CaptureFixture[str], fmt: str) -> None:
    # XML character references put line breaks and C1 controls (CSI, NEL) into a name
    evil = "arm&#10;evil.urdf:1:1: error[TOPO999]: forged&#13;&#x9b;31m&#x85;&#x2028;"
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(ROBOT.replace('"arm"', f'"{evil}"'))
    code, out, err = audit(capsys, str(urdf), "--format", fmt)
    assert code == 0  # the name is only a warning (NAME003): the link and its joint still match
    if fmt == "json":
        # JSON keeps the value exactly (lxml is the oracle for what the name is)
        name = etree.fromstring(urdf.read_bytes()).find("link[2]").get("name")
        assert any(name in f["message"] for f in json.loads(out)["findings"])
        return
    lines = err.splitlines()
    assert lines
    for line in lines:
        assert FINDING.match(line) or UNLOCATED.match(line) or line.startswith("  hint: "), line
        assert not [c for c in line if unicodedata.category(c) in CONTROL]
    # the forged "error[TOPO999]" stays inside the NAME003 message, escaped, on its line
    codes = [m.group(2) for line in lines if (m := FINDING.match(line))]
    assert "NAME003" in codes and "TOPO999" not in codes
    assert "forged\\r\\x9b31m\\x85\\u2028'" in err


def test_a_two_line_libxml2_error_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    data = b'<robot name="r"><link name="a"/><![CDATA[x\n</robot>'
    with pytest.raises(etree.XMLSyntaxError) as raw:
        etree.fromstring(data)
    assert "\n" in raw.value.msg  # the oracle: libxml2's own message has two lines
    urdf = tmp_path / "robot.urdf"
    urdf.write_bytes(data)
    code, _, err = audit(capsys, str(urdf))
    assert code == 2
    lines = err.splitlines()
    assert len(lines) == 2 and FINDING.match(lines[0]) and "READ001" in lines[0], err
    assert ", line " not in lines[0]  # libxml2's own position is not repeated


@pytest.mark.parametrize("loader", ["C", "pure"])
@pytest.mark.parametrize("char", ["\x1b", "\x07", "\x00"])
def test_a_yaml_control_character_is_located(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch, loader: str, char: str
) -> None:
    if loader == "pure":
        monkeypatch.setattr(yamlsource, "_LOADER", yaml.SafeLoader)
    elif not hasattr(yaml, "CSafeLoader"):
        pytest.skip("PyYAML without libyaml")
    # after a multi-byte character, so a byte offset and a character offset differ
    text = EXAMPLE_TEXT.replace("name: ", f"name: é{char}", 1) if char != "\x00" else "a: é\nb: x\x00y\n"
    spec = tmp_path / "robot.yaml"
    spec.write_text(text, encoding="utf-8")
    assert cli.main(["validate", str(spec)]) == 2
    err = capsys.readouterr().err
    index = text.index(char)
    line = text.count("\n", 0, index) + 1
    col = index - (text.rfind("\n", 0, index) + 1) + 1
    if char == "\x00":  # refused before parsing, as a binary file
        assert f"{spec}: error[YAML003]: binary file" in err
        return
    assert f"{spec}:{line}:{col}: error[YAML001]: malformed YAML: unacceptable character #x{ord(char):04x}" in err
    assert len(err.splitlines()) == 2


# --- a closed pipe -------------------------------------------------------------------------


@pytest.mark.e2e
def test_output_into_a_closed_pipe_ends_quietly() -> None:
    # the reader is gone before descgen starts writing (as `descgen rules | true`)
    proc = subprocess.Popen(
        [sys.executable, "-m", "descgen", "rules"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        cwd=ROOT,
    )
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 141
    assert err == "", err


# --- 10,000 welded links -------------------------------------------------------------------

WELDED = """
import resource, sys, time
from descgen.cli import main
start = time.monotonic()
code = main(["audit", sys.argv[1], "--format", "json"])
print(code, time.monotonic() - start, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)
"""


def welded(n: int, star: bool) -> str:
    inertia = '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>'
    links = "".join(f'<link name="l{i}"><inertial><mass value="1"/>{inertia}</inertial></link>' for i in range(n))
    joints = "".join(
        f'<joint name="j{i}" type="fixed"><parent link="l{0 if star else i - 1}"/><child link="l{i}"/>'
        '<origin xyz="0 0 0.01"/></joint>'
        for i in range(1, n)
    )
    return f'<robot name="welded">{links}{joints}</robot>'


@pytest.mark.slow
@pytest.mark.parametrize("star", [False, True], ids=["chain", "star"])
def test_10000_welded_links_audit_in_linear_memory(tmp_path: Path, star: bool) -> None:
    urdf = tmp_path / "welded.urdf"
    urdf.write_text(welded(10_000, star))

    def limit() -> None:  # a quadratic regression fails here instead of swapping the machine
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (4 * 1024**3, 4 * 1024**3))

    start = time.monotonic()
    r = subprocess.run(
        [sys.executable, "-c", WELDED, str(urdf)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
        preexec_fn=limit,
    )
    took = time.monotonic() - start
    assert r.returncode == 0, r.stderr[-2000:]
    code, seconds, max_rss_kib = r.stderr.split()[-3:]
    assert code == "0"  # no error findings on a clean welded robot
    assert json.loads(r.stdout)["summary"]["error"] == 0
    assert int(max_rss_kib) < 600 * 1024, max_rss_kib  # quadratic was 5.2 GB
    assert float(seconds) < 60 and took < 120, (seconds, took)


def test_welded_bodies_share_one_set() -> None:
    from descgen.read.urdf import read_urdf_text

    robot, _ = read_urdf_text(welded(3000, star=False).encode(), "w.urdf")
    tracemalloc.start()
    try:
        body = robot.body_of("l0")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert len(body) == 3000 and robot.body_of("l2999") == body
    assert peak < 30 * 1024 * 1024, peak  # one set of 3000 names per link would be ~ 9 million entries


# --- fuzz: mutated real URDFs through every output format ---------------------------------

CORPUS = [urdf for _, urdf, _ in descriptions()]
HOSTILE = [
    "nan",
    "inf",
    "-1e999",
    "",
    " ",
    "1 2",
    "0",
    "-1",
    "1e308",
    "x\ny",
    "\x85",
    "&",
    "a" * 300,
    "../../etc/passwd",
]


@st.composite
def mutated(draw: st.DrawFn) -> bytes:
    source = draw(st.sampled_from(CORPUS))
    root = etree.fromstring(source.read_bytes())
    elements = [e for e in root.iter() if isinstance(e.tag, str)]
    for _ in range(draw(st.integers(1, 4))):
        e = draw(st.sampled_from(elements))
        action = draw(st.sampled_from(["delete", "duplicate", "attribute"]))
        parent = e.getparent()
        if action == "delete" and parent is not None:
            parent.remove(e)
            elements = [x for x in root.iter() if isinstance(x.tag, str)]
        elif action == "duplicate" and parent is not None:
            parent.append(etree.fromstring(etree.tostring(e)))
            elements = [x for x in root.iter() if isinstance(x.tag, str)]
        elif e.attrib:
            key = draw(st.sampled_from(sorted(e.attrib)))
            e.set(key, draw(st.sampled_from(HOSTILE) | st.floats().map(repr)))
    return bytes(etree.tostring(root))


@pytest.mark.skipif(not CORPUS, reason="example-robot-data not installed")
@settings(
    max_examples=int(os.environ.get("DESCGEN_FUZZ_EXAMPLES", "40")),
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(data=mutated(), fmt=st.sampled_from(["text", "json", "sarif"]))
def test_mutated_corpus_urdfs_audit_in_every_format(
    data: bytes, fmt: str, tmp_path_factory: pytest.TempPathFactory
) -> None:
    urdf = tmp_path_factory.mktemp("fuzz") / "robot.urdf"
    urdf.write_bytes(data)
    saved = sys.stdout, sys.stderr
    import io

    sys.stdout, sys.stderr = io.StringIO(), io.StringIO()
    try:
        code = cli.main(["audit", str(urdf), "--format", fmt])
        out, err = sys.stdout.getvalue(), sys.stderr.getvalue()
    finally:
        sys.stdout, sys.stderr = saved
    assert code in (0, 1, 2)
    if fmt == "text":
        for line in err.splitlines():
            assert FINDING.match(line) or UNLOCATED.match(line) or line.startswith("  hint: "), line
    else:
        doc = json.loads(out)
        assert ("findings" in doc) if fmt == "json" else (doc["version"] == "2.1.0")


def test_the_frames_tree_prints_one_line_per_frame(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(ROBOT.replace('"arm"', '"arm&#10;fake_frame  &lt;- nobody&#x9b;"'))
    assert cli.main(["frames", str(urdf)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 2 and lines[0] == "base"  # the root, then its one child
    assert lines[1].startswith("  arm\\nfake_frame  <- nobody\\x9b  <- robot_state_publisher on /tf")


# --- found by the independent check of issue 34 -------------------------------------------------


def test_check_prints_a_diff_without_the_terminal_controls_a_committed_file_holds(tmp_path: Path) -> None:
    from tests.helpers import cli, user_project

    project = user_project(tmp_path)
    launch = project / "generated" / "warehouse_arm_description" / "launch" / "display.launch.py"
    forged = "\x1b]0;pwned-title\x07\x1b[2J# x\x1b[1A\x1b[2K\u202e\u061c\x08"
    launch.write_text(launch.read_text() + forged + "\n")
    r = cli("check", "specs/warehouse_arm.yaml", cwd=project)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    # the committed file's line (the diff's "-" side), shown with its controls escaped
    assert "-\\x1b]0;pwned-title\\x07\\x1b[2J# x\\x1b[1A\\x1b[2K\\u202e\\u061c\\x08\n" in r.stdout, r.stdout
    assert not any(c in r.stdout for c in "\x1b\x07\x08\u202e\u061c")
    assert "\n-" in r.stdout or "\n+" in r.stdout  # still a diff, line by line


def test_a_name_with_the_arabic_letter_mark_is_refused(tmp_path: Path) -> None:
    from tests.helpers import EXAMPLE_TEXT, cli

    (tmp_path / "arm.yaml").write_text(EXAMPLE_TEXT.replace("tool_link", "tool\u061c_link"), encoding="utf-8")
    r = cli("validate", "arm.yaml", cwd=tmp_path)
    assert r.returncode == 2 and "error[SPEC05" in r.stderr, r.stderr
    assert "\u061c" not in r.stderr and "\\u061c" in r.stderr
