"""Spec text stays data in every output (issue 18, part 3).

A payload built to break each output language (a line break followed by a Python statement,
``-->``, ``]]>``, quotes, ``|``, a backtick, ``${...}``, ``$(...)``, ``\\``, ``{{``, a tab and
U+2028) is planted in each free-text field and in the spec's file name. Either ``validate``
refuses it on the right line, or the package generates and every file parses back with its
own parser (lxml, xacro + yourdfpy, ``ast``, ``yaml``, Graphviz, the Markdown table rule)
into the same structure as the clean build, with the payload as a value.
"""

from __future__ import annotations

import ast
import json
import re
import shutil
import subprocess
from contextlib import nullcontext as _no_raise
from pathlib import Path
from typing import Any

import pytest
import yaml
import yourdfpy
from lxml import etree

from descgen.commands.generate import plan
from descgen.render import header
from descgen.render.formatting import mermaid, pyinner, pystr, yamlstr

from .helpers import EXAMPLE_TEXT, cli, line_of, plant
from .test_hostile_input import refused

PAYLOAD = "x\nimport os; os.system('id')\n# --> ]]> \" ' | ` ${1+1} $(find pkg) \\ {{ a }}\t\u2028 end"
# the same attack without line breaks, tabs or separators, for fields that are one line
ONE_LINE = "x; import os; os.system('id') # --> ]]> \" ' | ` ${1+1} $(find pkg) \\ {{ a }} end"
INJECTED = re.compile(r"^\s*import os", re.MULTILINE)


def quoted(value: str) -> str:
    """``value`` as a YAML double-quoted scalar (a JSON string is one)."""
    return json.dumps(value)


# field -> (text in the example, replacement with {v} for the quoted payload)
FIELDS: dict[str, tuple[str, str]] = {
    "description": ("description: WA-1 warehouse mobile manipulator", "description: {v}\nx_was: WA-1"),
    "link_description": (
        "description: chassis, frame at the wheel-axle centre",
        "description: {v}",
    ),
    "joint_description": ("description: zero at the column top", "description: {v}"),
    "part_description": ("description: differential-drive wheel; cylinder axis along y", "description: {v}"),
    "sensor_description": ("description: wrist camera, frame at the optical centre", "description: {v}"),
    "controller_param": ("        enable_odom_tf: true", "        enable_odom_tf: true\n        note: {v}"),
    "controller_param_key": ("        enable_odom_tf: true", "        enable_odom_tf: true\n        {v}: 1"),
    "link_source": ("    source: M14", "    source: {v}"),
    "origin_source": ("{xyz: [0, 0, 85 mm], source: M09}", "{{xyz: [0, 0, 85 mm], source: {v}}}"),
    "pose_source": ('source: "K3, K4"', "source: {v}"),
    "measurement_source": ("tolerance: 2 mm, source: K1}", "tolerance: 2 mm, source: {v}}}"),
    "visual_name": (
        "material: chassis_grey\n        source: M05",
        "material: chassis_grey\n        source: M05\n        name: {v}",
    ),
    "collision_name": ("200 mm]}}\n        source: M05", "200 mm]}}}}\n        source: M05\n        name: {v}"),
    "material_name": ("chassis_grey", "{v}"),
    "texture": (
        "{name: sensor_blue, rgba: [0.10, 0.25, 0.60, 1.0]}",
        "{{name: sensor_blue, rgba: [0.10, 0.25, 0.60, 1.0], texture: {v}}}",
    ),
    "mesh_filename": (
        "      - geometry: {sphere: {diameter: 60 mm}}\n        material: tyre_black",
        "      - geometry: {{mesh: {{filename: {v}}}}}\n        material: tyre_black",
    ),
    "disable_reason": (
        "  group_states:",
        "  disable_collisions:\n    - {{link1: base_link, link2: camera_link, reason: {v}}}\n  group_states:",
    ),
    "maintainer": ("maintainer: WA-1 integration team", "maintainer: {v}"),
    "license": ("license: Apache-2.0}", "license: {v}}}"),
    "hardware_param": (
        "    plugin: mock_components/GenericSystem",
        "    plugin: mock_components/GenericSystem\n    params: {{note: {v}}}",
    ),
}
MULTI_LINE = [
    "description",
    "link_description",
    "joint_description",
    "part_description",
    "sensor_description",
    "controller_param",
    "controller_param_key",
]
ONE_LINE_FIELDS = [f for f in FIELDS if f not in MULTI_LINE]


def spec_with(field: str, value: str) -> str:
    old, new = FIELDS[field]
    count = EXAMPLE_TEXT.count(old) if field == "material_name" else 1
    text = plant(old, new.format(v=quoted(value)), count=count)
    if field == "description":
        text = text.replace("\nx_was: WA-1", "\n#", 1)  # keep the rest of the old line as a comment
    return text


def write_spec(tmp_path: Path, text: str, name: str = "robot.yaml") -> Path:
    (tmp_path / "specs").mkdir(exist_ok=True)
    path = tmp_path / "specs" / name
    path.write_text(text)
    # a mesh must exist beside the spec (SPEC060): give the caster's mesh a file of that name
    for link in yaml.safe_load(text).get("links", []) if "mesh:" in text else []:
        for shape in link.get("visual", []):
            mesh = shape.get("geometry", {}).get("mesh")
            if mesh and "/" not in mesh["filename"]:
                (tmp_path / "specs" / mesh["filename"]).write_text("solid x\nendsolid x\n")
    return path


def generated(spec: Path) -> dict[str, str]:
    """The package ``generate`` would write; it must pass every check."""
    p = plan(spec, spec.parent.parent / "generated")
    errors = [f"{f.code} {f.message}" for f in p.findings if f.severity == "error"]
    assert not errors, errors
    return p.files


def reference(field: str, tmp_path: Path) -> dict[str, str]:
    """The same spec with a harmless value in ``field``: the structure every output must keep."""
    (tmp_path / "plain").mkdir()
    return generated(write_spec(tmp_path / "plain", spec_with(field, "plain_value")))


@pytest.fixture(scope="module")
def clean(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    return generated(write_spec(tmp_path_factory.mktemp("clean"), EXAMPLE_TEXT))


# --------------------------------------------------------------------------- parse back


def xml_shape(text: str) -> list[str]:
    """Every node of the document in order (tags, comments, processing instructions), by lxml."""
    root = etree.fromstring(text.encode(), etree.XMLParser(resolve_entities=False, no_network=True))
    before = list(reversed(list(root.itersiblings(preceding=True))))

    def kind(n: Any) -> str:
        if isinstance(n, etree._Comment):
            return "<!--"
        if isinstance(n, etree._ProcessingInstruction):
            return "<?" + str(n.target)
        return str(n.tag)

    return [kind(n) for n in before] + [kind(n) for n in root.iter()]


def table_shape(text: str) -> list[int]:
    """Cells per Markdown table row: GitHub splits a row on every pipe not escaped by ``\\``."""
    return [len(re.findall(r"(?<!\\)\|", line)) for line in text.splitlines() if line.startswith("|")]


def dot_shape(text: str, tmp_path: Path) -> tuple[list[str], list[tuple[str, str, str]]]:
    """Nodes and labelled edges as Graphviz itself reads the file."""
    exe = shutil.which("dot")
    if exe is None:
        return [], []
    src = tmp_path / "frames.dot"
    src.write_text(text)
    r = subprocess.run([exe, "-Tjson", str(src)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    g = json.loads(r.stdout)
    names = [o["name"] for o in g.get("objects", [])]
    edges = [(names[e["tail"]], names[e["head"]], e.get("label", "")) for e in g.get("edges", [])]
    return names, edges


def body(text: str) -> str:
    stamp = header.read(text)
    assert stamp is not None and not stamp.hand_edited, text[:300]
    return stamp.body


def assert_outputs_are_data(files: dict[str, str], clean: dict[str, str], tmp_path: Path) -> None:
    """Every file parses with its language's parser into the clean build's structure."""
    assert sorted(files) == sorted(clean)
    for rel, text in files.items():
        ref = clean[rel]
        body(text)  # the header reads back and the content hash matches
        if rel.endswith((".xml", ".urdf", ".xacro", ".srdf")):
            # XML text may hold a line break as data (package.xml's description): the tree decides
            assert xml_shape(text) == xml_shape(ref), rel
            continue
        assert not INJECTED.search(text), f"{rel}: a spec line became a line of the file"
        if rel.endswith(".py"):
            # comments are not in the AST: a payload may only ever be a comment or a value
            assert ast.dump(ast.parse(text)) == ast.dump(ast.parse(ref)), rel
        elif rel.endswith((".yaml", ".rviz")):
            doc, want = yaml.safe_load(text), yaml.safe_load(ref)
            assert isinstance(doc, dict) and list(doc) == list(want), rel
        elif rel.endswith(".md"):
            assert len(text.splitlines()) == len(ref.splitlines()), rel
            assert table_shape(text) == table_shape(ref), rel
        elif rel.endswith(".dot"):
            assert len(text.splitlines()) == len(ref.splitlines()), rel
            assert dot_shape(text, tmp_path) == dot_shape(ref, tmp_path), rel
        elif rel.endswith(".sha256"):  # the mesh manifest: one line per mesh, whatever its name
            assert len(text.splitlines()) == len(ref.splitlines()), rel
        else:  # CMakeLists.txt: nothing from the spec but the header
            assert body(text).splitlines() == body(ref).splitlines(), rel


def expanded_urdf(files: dict[str, str], tmp_path: Path) -> yourdfpy.URDF:
    """The Xacro expanded by the xacro package, read by yourdfpy."""
    import xacro

    for rel, text in files.items():
        if rel.endswith(".xacro"):
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            (tmp_path / rel).write_text(text)
    doc = xacro.process_file(str(tmp_path / "urdf" / "warehouse_arm.urdf.xacro"))
    out = tmp_path / "expanded.urdf"
    out.write_text(doc.toxml())
    return yourdfpy.URDF.load(str(out), build_scene_graph=False, load_meshes=False, build_collision_scene_graph=False)


def read_back(field: str, files: dict[str, str], tmp_path: Path) -> list[str]:
    """Where ``field``'s value is data, the value as an independent parser reads it."""
    if field == "description":
        return [etree.fromstring(files["package.xml"].encode()).findtext("description") or ""]
    if field in ("maintainer", "license"):
        return [etree.fromstring(files["package.xml"].encode()).findtext(field) or ""]
    if field == "controller_param":
        return [
            yaml.safe_load(files["config/ros2_controllers.yaml"])["diff_drive_controller"]["ros__parameters"]["note"]
        ]
    if field == "controller_param_key":
        params = yaml.safe_load(files["config/ros2_controllers.yaml"])["diff_drive_controller"]["ros__parameters"]
        return [k for k, v in params.items() if type(v) is int and v == 1]
    if field == "disable_reason":
        srdf = etree.fromstring(files["srdf/warehouse_arm.srdf"].encode())
        return [
            d.get("reason")
            for d in srdf.iter("disable_collisions")
            if (d.get("link1"), d.get("link2")) == ("base_link", "camera_link")
        ]
    if field == "hardware_param":
        urdf = etree.fromstring(files["urdf/warehouse_arm.urdf"].encode())
        return [p.text or "" for p in urdf.iter("param") if p.get("name") == "note"]
    if field in ("visual_name", "collision_name", "material_name", "texture", "mesh_filename"):
        out = []
        for urdf in (
            yourdfpy.URDF.load(
                _written(files, tmp_path), build_scene_graph=False, load_meshes=False, build_collision_scene_graph=False
            ),
            expanded_urdf(files, tmp_path),
        ):
            links = {lk.name: lk for lk in urdf.robot.links}
            if field == "visual_name":
                out.append(links["base_link"].visuals[0].name)
            elif field == "collision_name":
                out.append(links["base_link"].collisions[0].name)
            elif field == "material_name":
                out += [urdf.robot.materials[0].name, links["base_link"].visuals[0].material.name]
            elif field == "texture":
                out.append(next(m.texture.filename for m in urdf.robot.materials if m.name == "sensor_blue"))
            else:
                # the spec's own mesh is copied into the package and named there
                name = links["caster_link"].visuals[0].geometry.mesh.filename
                out.append(name.removeprefix("package://warehouse_arm_description/meshes/"))
        return out
    return []


def _written(files: dict[str, str], tmp_path: Path) -> str:
    path = tmp_path / "written.urdf"
    path.write_text(files["urdf/warehouse_arm.urdf"])
    return str(path)


# --------------------------------------------------------------------------- the fields


@pytest.mark.parametrize("field", MULTI_LINE)
def test_free_text_with_line_breaks_stays_data(field: str, tmp_path: Path) -> None:
    files = generated(write_spec(tmp_path, spec_with(field, PAYLOAD)))
    assert_outputs_are_data(files, reference(field, tmp_path), tmp_path)
    values = read_back(field, files, tmp_path)
    assert values in ([], [PAYLOAD]), values
    if field in ("link_description", "joint_description", "sensor_description"):
        # only in comments: one line each, the line break shown as an escape
        xml = files["urdf/warehouse_arm.urdf"] + files["urdf/warehouse_arm.urdf.xacro"]
        assert "x import os; os.system('id') # - -> ]]>" in xml


@pytest.mark.parametrize("field", ONE_LINE_FIELDS)
def test_line_break_in_a_one_line_field_is_refused_on_its_line(
    field: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = spec_with(field, PAYLOAD)
    path = write_spec(tmp_path, text)
    first = refused(path, "SPEC021")
    assert int(first["line"]) == line_of(text, quoted(PAYLOAD))
    assert "\\n" in first["msg"] and "one line" in first["msg"]


@pytest.mark.parametrize("field", ONE_LINE_FIELDS)
def test_one_line_payload_stays_data(field: str, tmp_path: Path) -> None:
    files = generated(write_spec(tmp_path, spec_with(field, ONE_LINE)))
    assert_outputs_are_data(files, reference(field, tmp_path), tmp_path)
    values = read_back(field, files, tmp_path)
    assert all(v == ONE_LINE for v in values), values


def test_control_character_in_a_description_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # XML cannot hold U+0001 even in a comment (lxml refused the URDF with a traceback before)
    text = spec_with("link_description", "chassis\x01")
    first = refused(write_spec(tmp_path, text), "SPEC020")
    assert int(first["line"]) == line_of(text, "chassis\\u0001")


def test_carriage_return_in_a_hardware_param_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # XML reads \r back as \n, so generate's round trip refused what validate passed
    text = spec_with("hardware_param", "a\rb")
    first = refused(write_spec(tmp_path, text), "SPEC021")
    assert int(first["line"]) == line_of(text, '"a\\rb"')


# --------------------------------------------------------------------------- the spec's file name

HOSTILE_NAME = PAYLOAD.replace("/", "") + ".yaml"


def test_spec_file_name_stays_a_comment(tmp_path: Path, clean: dict[str, str]) -> None:
    files = generated(write_spec(tmp_path, EXAMPLE_TEXT, HOSTILE_NAME))
    assert_outputs_are_data(files, clean, tmp_path)
    for rel, text in files.items():
        assert body(text) == body(clean[rel]), rel  # only the header differs
        assert text.count("\n") == clean[rel].count("\n"), rel
    launch = files["launch/display.launch.py"]
    assert [type(n).__name__ for n in ast.parse(launch).body] == ["Expr"] + ["ImportFrom"] * 6 + ["FunctionDef"]


def test_spec_file_name_end_to_end(tmp_path: Path) -> None:
    """generate then check through the command; the launch file compiles to the clean module."""
    spec = write_spec(tmp_path, EXAMPLE_TEXT, HOSTILE_NAME)
    r = cli("generate", str(spec), "--out", str(tmp_path / "generated"), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = cli("check", str(spec), "--out", str(tmp_path / "generated"), cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    pkg = tmp_path / "generated" / "warehouse_arm_description"
    launch = (pkg / "launch" / "display.launch.py").read_text()
    compile(launch, "display.launch.py", "exec")
    assert not INJECTED.search(launch)
    assert yaml.safe_load((pkg / "config" / "ros2_controllers.yaml").read_text())["controller_manager"]


@pytest.mark.parametrize("suffix", ["x.xml", "x.urdf", "x.xacro", "x.md", "x.dot", "x.py", "x.yaml", "CMakeLists.txt"])
def test_header_round_trips_a_hostile_display(suffix: str) -> None:
    text = "first line\nsecond\n"
    stamped = header.add(suffix, text, PAYLOAD + "--\r\x00\u202e", "ab" * 32)
    assert stamped.count("\n") == text.count("\n") + 2
    stamp = header.read(stamped)
    assert stamp is not None and stamp.body == text and stamp.spec_hash == "ab" * 32 and not stamp.hand_edited


# --------------------------------------------------------------------------- validate vs generate


def test_spec_without_links_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    first = refused(write_spec(tmp_path, "name: empty\n"), "SPEC023")
    assert "no links" in first["msg"]


def test_duplicate_srdf_group_is_refused_at_the_second(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    group = "    - name: arm\n      chain: {base: arm_base_link, tip: tool_link}\n"
    text = plant(group, group + group)
    first = refused(write_spec(tmp_path, text), "SPEC024")
    assert int(first["line"]) == line_of(text, group) + 2
    assert "'arm'" in first["msg"]


def test_duplicate_group_state_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    state = "    - {name: ready, group: arm, pose: ready}\n"
    text = plant(state, state + "    - {name: ready, group: arm, pose: zero}\n")
    first = refused(write_spec(tmp_path, text), "SPEC024")
    assert int(first["line"]) == line_of(text, state) + 1


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("email: wa1-integration@example.com", "email: wa1|integration@example.com"),
        ("email: wa1-integration@example.com", "email: wa1@localhost"),
        ("version: 0.1.0", "version: 01.1.0"),
        ("license: Apache-2.0}", 'license: " "}'),
    ],
)
def test_package_metadata_catkin_refuses_is_refused_at_validate(
    old: str, new: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from catkin_pkg.package import InvalidPackage, Package, Person

    # the oracle: catkin_pkg (what colcon uses) refuses the value, or warns about it
    value = new.split(": ", 1)[1].rstrip("}").strip('"')
    fields = {"email": "a@example.com", "version": "0.1.0", "license": "Apache-2.0"}
    fields[old.split(":")[0]] = value
    pkg = Package(
        name="x_description",
        version=fields["version"],
        package_format=3,
        description="d",
        maintainers=[Person("m", fields["email"])],
        licenses=[fields["license"]],
    )
    warned: list[str] = []
    with pytest.raises(InvalidPackage) if "version" not in old else _no_raise():
        pkg.validate(warnings=warned)
    assert "version" not in old or warned
    text = plant(old, new)
    first = refused(write_spec(tmp_path, text), "SPEC025")
    assert int(first["line"]) == line_of(text, new)


def test_part_named_like_a_xacro_tag_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = plant("  - name: drive_wheel", "  - name: property")
    first = refused(write_spec(tmp_path, text), "SPEC022")
    assert int(first["line"]) == line_of(text, "  - name: property")


def test_xacro_property_names_from_different_elements_stay_distinct(tmp_path: Path) -> None:
    """Link ``base_link_collision``'s box and link ``base_link``'s collision box both want the
    property ``base_link_collision_size``; each keeps its own value in the expanded Xacro."""
    text = plant(
        "        geometry: {box: {size: [600 mm, 450 mm, 200 mm]}}\n        source: M05",
        "        geometry: {box: {size: [1 m, 1 m, 1 m]}}\n        source: M05",
    )
    text = plant(
        "  - name: caster_link\n",
        "  - name: base_link_collision\n    source: M05\n"
        "    visual:\n      - geometry: {box: {size: [2 m, 2 m, 2 m]}}\n\n  - name: caster_link\n",
        text,
    )
    text = plant(
        "joints:\n",
        "joints:\n  - name: extra_joint\n    type: fixed\n    parent: base_link\n    child: base_link_collision\n\n",
        text,
    )
    files = generated(write_spec(tmp_path, text))
    urdf = expanded_urdf(files, tmp_path)
    links = {lk.name: lk for lk in urdf.robot.links}
    assert list(links["base_link"].collisions[0].geometry.box.size) == [1.0, 1.0, 1.0]
    assert list(links["base_link_collision"].visuals[0].geometry.box.size) == [2.0, 2.0, 2.0]
    names = re.findall(r'<xacro:property name="([^"]+)"', files["urdf/warehouse_arm.urdf.xacro"])
    assert len(names) == len(set(names))


# --------------------------------------------------------------------------- the filters


@pytest.mark.parametrize("value", ["base_footprint", "null", "yes", "No", "1e3", "~", "a: b", "#x", " x", "", PAYLOAD])
def test_yamlstr_reads_back_as_the_same_string(value: str) -> None:
    written = yamlstr(value)
    assert "\n" not in written
    assert yaml.safe_load(f"key: {written}\nnext: 1\n") == {"key": value, "next": 1}


def test_python_literals_read_back(tmp_path: Path) -> None:
    assert ast.literal_eval(pystr(PAYLOAD)) == PAYLOAD
    assert ast.literal_eval('"""' + pyinner(PAYLOAD + '"""') + '"""') == PAYLOAD + '"""'


def test_mermaid_label_keeps_to_its_quotes() -> None:
    label = mermaid(PAYLOAD)
    assert not set('"|`<>\n\t\u2028') & set(label)
    # Mermaid entity codes (#quot; #124; #35; ...) decode back to the text, line breaks shown
    decoded = re.sub(
        r"#(quot|lt|gt|\d+);", lambda m: {"quot": '"', "lt": "<", "gt": ">"}.get(m[1]) or chr(int(m[1])), label
    )
    assert decoded == PAYLOAD.replace("\n", "\\n").replace("\t", "\\t").replace("\u2028", "\\u2028")


# --------------------------------------------------------------------------- link and joint names

# Names ROS accepts (urdfdom: any unique string; tf2: not empty, no leading '/'), as real robots
# have them (flange-tool0 in Universal Robots, link_0.0 in Allegro, 2dof_planar), and names that
# break each output language if written raw.
# (tool_link, elbow_joint, forearm_link) renamed at once, one spec per case to keep the test fast
ROS_NAMES = [
    ("flange-tool0", "link_0.0", "2dof_planar"),
    ("a|b`c<d>&'\"e#f*g_[h]", "é—ü🤖", "x:y/z.{{7}}"),
]
PLAIN_NAMES = ("plain_link", "plain_joint", "plain_forearm")


def renamed(names: tuple[str, str, str]) -> str:
    """The example with ``tool_link``, ``elbow_joint`` and ``forearm_link`` renamed everywhere."""
    text = EXAMPLE_TEXT
    for old, new in zip(("tool_link", "elbow_joint", "forearm_link"), names, strict=True):
        # a YAML double-quoted string (JSON without \\u escapes: PyYAML reads no surrogate pairs)
        text = re.sub(rf"\b{old}\b", lambda _, new=new: json.dumps(new, ensure_ascii=False), text)
    return text


@pytest.mark.parametrize("names", ROS_NAMES, ids=["ros-style", "markup"])
def test_names_ros_accepts_generate_and_every_output_parses_back(names: tuple[str, str, str], tmp_path: Path) -> None:
    link, joint, forearm = names
    files = generated(write_spec(tmp_path, renamed(names)))
    (tmp_path / "plain").mkdir()
    ref = generated(write_spec(tmp_path / "plain", renamed(PLAIN_NAMES)))
    dots = [rel for rel in files if rel.endswith(".dot")]
    assert_outputs_are_data(
        {k: v for k, v in files.items() if k not in dots}, {k: v for k, v in ref.items() if k not in dots}, tmp_path
    )
    # Graphviz reads the same graph, with the new names as node names
    back = dict(zip(names, PLAIN_NAMES, strict=True))
    for rel in dots:
        nodes, edges = dot_shape(files[rel], tmp_path)
        want_nodes, want_edges = dot_shape(ref[rel], tmp_path)
        assert [back.get(n, n) for n in nodes] == want_nodes
        assert [(back.get(a, a), back.get(b, b), lb) for a, b, lb in edges] == want_edges
    # the URDF and the Xacro expanded by xacro hold the names as data, read back by yourdfpy
    written = yourdfpy.URDF.load(
        _written(files, tmp_path), build_scene_graph=False, load_meshes=False, build_collision_scene_graph=False
    )
    for urdf in (written, expanded_urdf(files, tmp_path)):
        assert {link, forearm} <= {lk.name for lk in urdf.robot.links}
        assert joint in {j.name for j in urdf.robot.joints}
    # xacro property names stay identifiers xacro accepts, one definition each
    import xacro

    props = re.findall(r'<xacro:property name="([^"]+)"', files["urdf/warehouse_arm.urdf.xacro"])
    assert props and len(props) == len(set(props))
    assert all(xacro.is_valid_name(p) and not p.startswith("__") for p in props)
    # the SRDF chain, the ros2_control joint and the controllers YAML name the same elements
    srdf = etree.fromstring(files["srdf/warehouse_arm.srdf"].encode())
    assert link in {c.get("tip_link") for c in srdf.iter("chain")}
    urdf_xml = etree.fromstring(files["urdf/warehouse_arm.urdf"].encode())
    assert joint in {j.get("name") for rc in urdf_xml.iter("ros2_control") for j in rc.iter("joint")}
    ctrl = yaml.safe_load(files["config/ros2_controllers.yaml"])
    assert any(joint in (c["ros__parameters"].get("joints") or []) for c in ctrl.values() if isinstance(c, dict))


@pytest.mark.parametrize(
    ("name", "why"),
    [("/tool_link", "'/'"), ("tool link", "whitespace"), ("tool\tlink", "whitespace"), ("a${x}", "'$'"), ("", "empty")],
)
def test_names_no_consumer_can_take_are_refused_on_their_line(
    name: str, why: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # tf2 refuses a leading '/' (validateFrameId), MoveIt trims SRDF names (a space would not be the
    # same name), and the Xacro would evaluate '$'
    text = plant("  - name: tool_link\n", f"  - name: {quoted(name)}\n")
    first = refused(write_spec(tmp_path, text), "SPEC050")
    assert int(first["line"]) == line_of(text, f"  - name: {quoted(name)}\n")
    assert why.strip("'") in first["msg"] or why in first["msg"]


@pytest.mark.parametrize("stem", ["2dof_planar", "flange-tool0", "link_0.0", "__init__", "_x", "é", "a b", "class"])
def test_xacro_property_stems_become_names_xacro_accepts(stem: str) -> None:
    import xacro

    from descgen.render.views import Values

    v = Values(xacro=True)
    # a sourced value: only those become properties
    ref = v(stem + "_xyz", "1 2 3", "M1")
    name = ref.removeprefix("${").removesuffix("}")
    assert xacro.is_valid_name(name) and not name.startswith("__"), name
    # two stems made equal by sanitising keep their own values
    other = v(stem.replace("-", ".") + "_xyz", "4 5 6", "M2") if "-" in stem else None
    assert other is None or other != ref
