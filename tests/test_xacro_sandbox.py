"""An audited Xacro is data: the restricted evaluator refuses code, file and environment
access and unbounded work, at the file and line that asked, and expands real descriptions
exactly as xacro itself does.

Each hostile payload is checked twice: with ``--trust-xacro`` (xacro's own evaluator) the
payload really does what it says (a canary file appears, a secret is printed), which proves
the payload is live; in the sandbox the same file is refused and nothing happens.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest
import xacro

from descgen.cli import main
from descgen.core.findings import InputError
from descgen.read.xacro_file import expand
from tests.corpus import share
from tests.helpers import ROOT

HEAD = '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'


def write(folder: Path, body: str, name: str = "robot.urdf.xacro") -> Path:
    path = folder / name
    path.write_text(HEAD + body + "\n</robot>\n")
    return path


def refusal(path: Path, **kw: object) -> tuple[str, int, str]:
    with pytest.raises(InputError) as info:
        expand(path, str(path), **kw)  # type: ignore[arg-type]
    (f,) = info.value.findings
    return f.code, f.where.line, f.message


def line_of(path: Path, needle: str) -> int:
    text = path.read_text()
    return text[: text.index(needle)].count("\n") + 1


# --- code execution -------------------------------------------------------------------------

CODE_PAYLOADS = [
    "${__import__('os').system('touch {canary}')}",
    "${python.type(1).__subclasses__}",
    "$(eval open)",  # $(...) ends at the first ')', so no call fits; a name is enough to refuse
    "${python.vars(python)}",
    "${(lambda: 1)()}",
    "${open('{canary}', 'w')}",
    "${python.type(python.abs)}",
]


@pytest.mark.parametrize("payload", CODE_PAYLOADS)
def test_code_in_an_expression_is_refused_at_its_line(tmp_path: Path, payload: str) -> None:
    canary = tmp_path / "canary"
    body = payload.replace("{canary}", str(canary))
    path = write(tmp_path, f'  <link name="base"/>\n  <link name="x{body}"/>')
    code, line, message = refusal(path)
    assert code == "READ030", message
    assert line == line_of(path, body[:6])
    assert not canary.exists()


def test_the_code_payload_is_live_under_trust_xacro(tmp_path: Path) -> None:
    """The oracle that the payloads above are real: xacro's own evaluator runs them."""
    # xacro refuses dunder names in expressions itself, so use a route it allows: str.format
    path = write(
        tmp_path,
        '  <xacro:property name="f" value="{0.__globals__[os]}"/>\n  <link name="x${f.format(xacro.load_yaml)}"/>',
    )
    out = expand(path, "r", trusted=True).decode()
    assert "module 'os'" in out  # xacro leaked the os module through str.format
    code, line, message = refusal(path)
    assert code == "READ030" and "reaches into an object" in message
    assert line == line_of(path, "f.format")


def test_format_attribute_access_is_refused(tmp_path: Path) -> None:
    path = write(
        tmp_path,
        '  <xacro:property name="f" value="{0.__class__.__mro__}"/>\n  <link name="x${f.format(1)}"/>',
    )
    assert refusal(path)[0] == "READ030"


# --- files and environment ---------------------------------------------------------------------


def test_load_yaml_outside_the_package_is_refused_and_not_printed(tmp_path: Path) -> None:
    secret = tmp_path / "secret.yaml"
    secret.write_text("token: hunter2\n")
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    (pkg / "urdf").mkdir()
    path = write(pkg / "urdf", f"  <link name=\"x${{xacro.load_yaml('{secret}')['token']}}\"/>")
    assert "hunter2" in expand(path, "r", trusted=True).decode()  # the payload is live
    code, line, message = refusal(path)
    assert code == "READ031" and "outside the folders" in message
    assert "hunter2" not in message
    assert line == line_of(path, "xacro.load_yaml")


def test_load_yaml_inside_the_package_and_package_paths_works(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    (pkg / "config").mkdir(parents=True)
    (pkg / "urdf").mkdir()
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    (pkg / "config" / "dims.yaml").write_text("length: !millimeters 250\nname: arm\n")
    other = tmp_path / "shared" / "other_pkg"
    other.mkdir(parents=True)
    (other / "package.xml").write_text("<package><name>other_pkg</name></package>")
    (other / "joint.yaml").write_text("upper: 1.5\n")
    path = write(
        pkg / "urdf",
        '  <xacro:property name="d" value="${xacro.load_yaml(\'../config/dims.yaml\')}"/>\n'
        '  <xacro:property name="j" value="${xacro.load_yaml(\'$(find other_pkg)/joint.yaml\')}"/>\n'
        '  <link name="${d.name}"><visual><geometry><box size="${d.length} ${j.upper} 1"/></geometry></visual></link>',
    )
    kw = {"package_paths": [tmp_path / "shared"]}
    ours = expand(path, "r", **kw)  # type: ignore[arg-type]
    assert ours == expand(path, "r", trusted=True, **kw)  # type: ignore[arg-type]
    assert b'name="arm"' in ours and b'size="0.25 1.5 1"' in ours


def test_include_outside_the_package_is_refused(tmp_path: Path) -> None:
    outside = tmp_path / "outside.xacro"
    outside.write_text(HEAD + '  <link name="stolen"/>\n</robot>\n')
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    path = write(pkg, '  <xacro:include filename="../outside.xacro"/>')
    assert b"stolen" in expand(path, "r", trusted=True)
    code, line, _ = refusal(path)
    assert code == "READ031" and line == line_of(path, "../outside.xacro")
    glob = write(pkg, '  <xacro:include filename="/etc/*.conf"/>', "glob.urdf.xacro")
    assert refusal(glob)[0] == "READ031"


def test_find_cannot_walk_out_of_the_package_paths(tmp_path: Path) -> None:
    path = write(tmp_path, '  <xacro:include filename="$(find ..)/etc/hostname"/>')
    with pytest.raises(InputError) as info:
        expand(path, "r", package_paths=[tmp_path])
    assert "not a package name" in info.value.findings[0].message


def test_environment_is_an_allow_list(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DESCGEN_SECRET", "hunter2")
    monkeypatch.setenv("ROS_DISTRO", "jazzy")
    path = write(tmp_path, '  <link name="x$(env DESCGEN_SECRET)"/>')
    assert b"hunter2" in expand(path, "r", trusted=True)
    code, line, message = refusal(path)
    assert code == "READ032" and line == line_of(path, "env DESCGEN_SECRET") and "hunter2" not in message
    # optenv of a variable not on the allow-list reads as unset: the file's default applies
    opt = write(tmp_path, '  <link name="a_$(optenv DESCGEN_SECRET dflt)_$(optenv ROS_DISTRO none)"/>', "o.urdf.xacro")
    assert b'name="a_dflt_jazzy"' in expand(opt, "r")
    cwd = write(tmp_path, '  <link name="x$(cwd)"/>', "c.urdf.xacro")
    assert refusal(cwd)[0] == "READ032"


def test_a_fifo_include_is_refused_without_blocking(tmp_path: Path) -> None:
    os.mkfifo(tmp_path / "pipe.xacro")
    path = write(tmp_path, '  <xacro:include filename="pipe.xacro"/>')
    result: list[object] = []
    worker = threading.Thread(target=lambda: result.append(refusal(path)), daemon=True)
    worker.start()
    worker.join(10)
    assert result, "expanding a Xacro that includes a FIFO blocked"
    assert result[0][0] == "READ031"  # type: ignore[index]


def test_a_doctype_include_is_refused(tmp_path: Path) -> None:
    (tmp_path / "inc.xacro").write_text(
        '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY a "aaaaaaaaaa">]>\n'
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="&a;"/></robot>\n'
    )
    path = write(tmp_path, '  <xacro:include filename="inc.xacro"/>')
    assert refusal(path)[0] == "READ030"


# --- bounded work ----------------------------------------------------------------------------

LIMIT_PAYLOADS = [
    "${9**9**9}",
    "${'x' * 10**10}",
    "${[0] * 10**9}",
    "${2 &lt;&lt; 10**9}",
    "${python.range(10**12)}",
]


@pytest.mark.parametrize("payload", ["${'x' * 3000000}", "${3000000 * 'x'}", "${[0] * 3000000}", "${3000000 * [0]}"])
def test_a_repetition_is_refused_before_it_is_built(tmp_path: Path, payload: str) -> None:
    # whichever side the sequence is on; 3 MB, so a missed bound is caught by the size check of
    # the built value (another message) instead of exhausting memory
    path = write(tmp_path, f'  <link name="x{payload}"/>')
    code, line, message = refusal(path)
    assert (code, line) == ("READ033", 3) and "a repetition longer than" in message, message


@pytest.mark.parametrize("payload", LIMIT_PAYLOADS)
def test_unbounded_values_are_refused_quickly(tmp_path: Path, payload: str) -> None:
    path = write(tmp_path, f'  <link name="x{payload}"/>')
    code, line, _ = refusal(path)
    assert code == "READ033" and line == 3


def test_macro_bomb_is_refused(tmp_path: Path) -> None:
    macros = ['  <xacro:macro name="m0"><link name="x"/></xacro:macro>']
    macros += [f'  <xacro:macro name="m{i}"><xacro:m{i - 1}/><xacro:m{i - 1}/></xacro:macro>' for i in range(1, 18)]
    path = write(tmp_path, "\n".join([*macros, "  <xacro:m17/>"]))
    code, _, message = refusal(path)
    assert code == "READ033" and "macro calls" in message


def test_text_doubling_is_refused(tmp_path: Path) -> None:
    props = ['  <xacro:property name="p0" value="xxxxxxxxxxxxxxxx"/>']
    props += [f'  <xacro:property name="p{i}" value="${{p{i - 1}}}${{p{i - 1}}}"/>' for i in range(1, 40)]
    path = write(tmp_path, "\n".join([*props, '  <link name="${p39}"/>']))
    assert refusal(path)[0] == "READ033"


# --- same expansion as xacro on real descriptions ----------------------------------------------

FEATURES = """\
  <xacro:arg name="prefix" default="p_"/>
  <xacro:property name="w" value="0.5"/>
  <xacro:property name="fmt" value="a_{0}_{1:.2f}"/>
  <xacro:property name="joints" value="${dict(shoulder=1.5, elbow=-0.25)}"/>
  <xacro:macro name="lk" params="name *origin ln:=1 **extra">
    <link name="$(arg prefix)${name}"><visual><xacro:insert_block name="origin"/>
      <geometry><box size="${ln} ${w*2} ${radians(90)}"/></geometry></visual><xacro:insert_block name="extra"/></link>
  </xacro:macro>
  <xacro:lk name="base"><origin xyz="0 0 ${sin(pi/2)}"/>
    <extra><inertial><mass value="${2**3}"/></inertial></extra></xacro:lk>
  <xacro:lk name="arm" ln="${joints['shoulder'] + python.abs(-1) + math.sqrt(4)}">
    <origin xyz="${'%d %d %d' % (1, 2, 3)}"/><extra/></xacro:lk>
  <xacro:if value="${w > 0.1 and len([x * 2 for x in python.range(3)]) == 3}">
    <link name="${fmt.format(w, w)}"/></xacro:if>
  <xacro:unless value="${w in (0.5, 1)}"><link name="never"/></xacro:unless>
  <link name="e_$(eval 1+2)_${max(1, 2)}_${python.abs(-3)}_${' '.join(str(v) for v in sorted(joints.values()))}"/>
  <link name="s_${'-'.join(['a', 'b']).upper()}_${int(7 // 2)}_${round(3.14159, 2)}_${w if w else 0}"/>
"""


def test_realistic_features_expand_as_xacro_does(tmp_path: Path) -> None:
    path = write(tmp_path, FEATURES)
    ours = expand(path, "r")
    assert ours == expand(path, "r", trusted=True)
    assert b'name="a_0.5_0.50"' in ours and b'size="4.5 1.0 1.5707963267948966"' in ours


def _erd_xacros() -> list[Path]:
    root = share()
    return sorted(root.rglob("*.xacro")) if root is not None else []


def test_example_robot_data_xacros_expand_as_xacro_does() -> None:
    files = _erd_xacros()
    assert files, "example-robot-data ships Xacros (installed with the test extras)"
    compared = 0
    for f in files:
        try:
            theirs = xacro.process_file(str(f)).toxml().encode()
        except Exception:  # a macro library, not a robot: xacro itself cannot expand it alone
            continue
        ours = expand(f, str(f))
        assert ours.split(b"-->", 4)[-1] == theirs.split(b"-->", 4)[-1], f  # banner names the path
        compared += 1
    assert compared >= 1


def test_generated_xacro_expands_as_xacro_does() -> None:
    path = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf.xacro"
    assert expand(path, "r") == expand(path, "r", trusted=True)


# --- the command line ----------------------------------------------------------------------------


def test_audit_refuses_with_exit_2_and_trust_xacro_opts_in(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(
        tmp_path,
        '  <xacro:property name="f" value="{0.__globals__[os]}"/>\n'
        '  <link name="base"/>\n'
        '  <link name="x${f.format(xacro.load_yaml)}"/>',
    )
    assert main(["audit", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}:{line_of(path, 'f.format')}:" in err and "error[READ030]" in err
    assert main(["audit", str(path), "--trust-xacro"]) in (0, 1)
    assert "module 'os'" in capsys.readouterr().err  # trusted: xacro's evaluator leaks, as documented


@pytest.mark.parametrize("command", ["faults", "frames"])
def test_every_command_that_reads_a_xacro_uses_the_sandbox(
    tmp_path: Path, command: str, capsys: pytest.CaptureFixture[str]
) -> None:
    secret = tmp_path / "secret.yaml"
    secret.write_text("token: hunter2\n")
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    path = write(pkg, f"  <link name=\"x${{xacro.load_yaml('{secret}').token}}\"/>")
    assert main([command, str(path)]) == 2
    captured = capsys.readouterr()
    assert "error[READ031]" in captured.err
    assert "hunter2" not in captured.out + captured.err
