"""Check 1: expanding ``<robot>.urdf.xacro`` with the xacro package gives ``<robot>.urdf``.

Every expansion of a rendered Xacro (here, and the MoveIt package's in moveit/proof.py) goes
through :func:`expand_packages`, which keeps the expanded XML in the result cache
(descgen/infra/result_cache.py) under the hash of every file the expansion can read, its arguments,
the environment variables the sandbox lets through, descgen's own source and xacro's
version: a ``check`` of an unchanged package compares the same XML without running xacro
again. The comparisons themselves run every time.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path

from lxml import etree

from descgen.codes.generate import GEN001
from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import Robot, Ros2Control
from descgen.core.xmlcompare import first_difference, parse
from descgen.infra import result_cache
from descgen.infra.evidence_hash import sha256

# what the sandbox lets an expansion read besides its files (readers/xacro_file.ENV_ALLOWED,
# spelled out here so a cache hit does not import xacro; tests/test_result_cache.py compares)
SANDBOX_ENV = ("ROS_DISTRO", "ROS_PYTHON_VERSION", "ROS_VERSION")
_KIND = "xacro-expansion"


def _read_by_xacro(rel: str) -> bool:
    """The files of a rendered package an expansion may read: Xacro, YAML, the manifest."""
    return rel.endswith((".xacro", ".yaml")) or rel == "package.xml"


def expand_packages(
    packages: Mapping[str, Mapping[str, str]], package: str, xacro_path: str, args: Mapping[str, str]
) -> tuple[str, str]:
    """Expand ``xacro_path`` of ``package`` with Xacro arguments ``args``, every package of
    ``packages`` (name -> rendered files) laid out in a scratch folder ``<scratch>/<name>/`` so
    that ``$(find <name>)`` resolves to it; returns the XML and the folder the package was
    expanded in (a value the XML may hold, e.g. a ``$(find)`` path). An InputError when the
    sandbox refuses or xacro fails (never cached: it is raised again every time)."""
    key = result_cache.key(
        _KIND,
        {
            "packages": {
                name: {
                    rel: sha256(text)
                    for rel, text in sorted(files.items())
                    if _read_by_xacro(rel) or (name, rel) == (package, xacro_path)
                }
                for name, files in sorted(packages.items())
            },
            "top": [package, xacro_path],
            "args": sorted(args.items()),
            "env": {name: os.environ.get(name) for name in SANDBOX_ENV},
        },
        ("xacro", "lxml", "PyYAML"),  # PyYAML: xacro.load_yaml, which a Xacro may call
    )
    hit = result_cache.get(_KIND, key)
    if isinstance(hit, dict) and isinstance(hit.get("xml"), str) and isinstance(hit.get("folder"), str):
        return hit["xml"], hit["folder"]
    with tempfile.TemporaryDirectory(prefix="descgen-xacro-") as tmp:
        root = Path(tmp)
        for name, files in packages.items():
            for rel, text in files.items():
                if _read_by_xacro(rel) or (name, rel) == (package, xacro_path):  # the top file: any name (an SRDF)
                    target = root / name / rel
                    target.parent.mkdir(parents=True, exist_ok=True)
                    target.write_text(text, encoding="utf-8")
        folder = root / package
        xml = expand_scratch(folder / xacro_path, xacro_path, args, [root])
    result_cache.put(_KIND, key, {"xml": xml, "folder": str(folder)})
    return xml, str(folder)


def expand_scratch(top: Path, display: str, args: Mapping[str, str], package_paths: Sequence[Path]) -> str:
    """The sandboxed expansion of ``top``, a file of a scratch folder, with its static parts set
    aside (readers/xacro_skeleton.py) when it has any: the skeleton is written beside it under a
    random name, so ``top`` stays what the file's own includes and ``load_yaml`` read. The
    whole file is expanded when nothing can be set aside, or when the skeleton fails (the
    whole file then fails too, and says why in its own terms)."""
    from descgen.read import xacro_skeleton
    from descgen.read.xacro_file import MAX_ELEMENTS, MAX_FILE_BYTES, MAX_TEXT
    from descgen.read.xacro_file import expand as sandboxed_expand

    skeleton = None
    whole = top.read_bytes()
    # over the sandbox's file bound, the whole file is refused as before; xacro reads the file
    # in the locale's encoding: a non-ASCII file is set aside only where that is UTF-8
    if len(whole) <= MAX_FILE_BYTES and (whole.isascii() or _utf8_locale()):
        with contextlib.suppress(UnicodeDecodeError):
            skeleton = xacro_skeleton.split(whole.decode("utf-8"))
    if skeleton is not None:
        beside = top.with_name(f".{secrets.token_hex(8)}.{top.name}")
        beside.write_text(skeleton.text, encoding="utf-8")
        try:
            expanded = sandboxed_expand(beside, display, dict(args), package_paths, symbolic_find=True).decode("utf-8")
            joined = xacro_skeleton.join(expanded, skeleton, MAX_ELEMENTS, MAX_TEXT)
        except InputError:
            joined = None
        finally:
            beside.unlink()
        if joined is not None:
            return joined
    return sandboxed_expand(top, display, dict(args), package_paths, symbolic_find=True).decode("utf-8")


def _utf8_locale() -> bool:
    import locale

    return locale.getpreferredencoding(False).lower().replace("-", "").replace("_", "") == "utf8"


def expand(files: dict[str, str], xacro_path: str) -> str:
    """Expand one rendered xacro file in a scratch folder (its includes are relative).

    It is expanded in the same sandbox as an audited Xacro: the Xacro is made from a
    spec, which is someone else's data, so it is never given xacro's own evaluator."""
    return expand_with(files, xacro_path, "package", {})[0]


def expand_with(files: dict[str, str], xacro_path: str, package: str, args: dict[str, str]) -> tuple[str, str]:
    """Expand with Xacro arguments, the package laid out as ``<scratch>/<package>/`` so that
    ``$(find <package>)`` resolves to it; returns the XML and the package folder."""
    return expand_packages({package: files}, package, xacro_path, args)


def xacro_matches_urdf(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    xacro_path = f"urdf/{robot.name}.urdf.xacro"
    urdf_path = f"urdf/{robot.name}.urdf"
    loc = Where(str(where / xacro_path))
    from descgen.render.context import package_name

    try:  # laid out under the package's name: $(find <package>) reads its own files (calibration)
        expanded = expand_with(files, xacro_path, package_name(robot), {})[0]
    except InputError as exc:  # the sandbox turns every xacro failure into one
        return [
            GEN001.finding(
                f"xacro failed to expand the generated Xacro: {'; '.join(f.message for f in exc.findings)}",
                "a template produced invalid Xacro; check --templates overrides",
                "file:" + xacro_path,
                loc,
            )
        ]
    try:
        diff = first_difference(parse(expanded), parse(files[urdf_path]))
    except etree.XMLSyntaxError as exc:
        return [
            GEN001.finding(
                f"generated XML does not parse: {exc}",
                "check the templates",
                "file:" + urdf_path,
                Where(str(where / urdf_path)),
            )
        ]
    if diff:
        return [
            GEN001.finding(
                f"xacro expansion differs from {urdf_path} at {diff}",
                "the Xacro and URDF templates disagree; fix the template that changed",
                "file:" + xacro_path,
                loc,
            )
        ]
    return []


def xacro_variants_match(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    """Every hardware variant but the default: ``xacro ... hardware:=<variant>`` gives the
    committed URDF (the default variant) with the variant's ``<hardware>`` and, for gazebo, the
    gz_ros2_control sim plugin whose ``<parameters>`` is the package's controllers file.

    The expectation is built from the URDF as data (lxml), not by rendering a template again,
    so a template that writes a variant wrongly cannot agree with itself."""
    from descgen.render.context import GZ_SIM_PLUGIN, package_name

    rc = robot.ros2_control
    if rc is None or len(rc.variants) < 2:
        return []
    xacro_path = f"urdf/{robot.name}.urdf.xacro"
    loc = Where(str(where / xacro_path))
    out: list[Finding] = []
    for variant in rc.variants[1:]:
        try:
            text, folder = expand_with(files, xacro_path, package_name(robot), {"hardware": variant.name})
        except InputError as exc:
            why = "; ".join(f.message for f in exc.findings)
            out.append(_gen001(f"xacro {xacro_path} hardware:={variant.name} failed: {why}", xacro_path, loc))
            continue
        expected = _variant_document(
            files[f"urdf/{robot.name}.urdf"], rc, variant.name, folder, GZ_SIM_PLUGIN, robot.namespace, robot.name
        )
        diff = first_difference(parse(text), expected)
        if diff:
            out.append(
                _gen001(
                    f"xacro {xacro_path} hardware:={variant.name} differs from the model at {diff}", xacro_path, loc
                )
            )
    return out


def _variant_document(
    urdf: str,
    rc: Ros2Control,
    variant: str,
    folder: str,
    sim: tuple[str, str],
    namespace: str | None = None,
    robot: str = "",
) -> etree._Element:
    """The default URDF with each block's hardware of ``variant`` (and Gazebo's sim plugin for
    gazebo, in the robot's namespace when it has one). A block of the file the model does not know
    keeps its hardware, so the comparison reports it; a block's ``<group>`` is every variant's."""
    doc = parse(urdf)
    chosen = {b.name: v for b in rc.hardware_blocks() for v in b.variants if v.name == variant}
    for block in doc.findall("ros2_control"):
        hw = block.find("hardware")
        v = chosen.get(block.get("name", ""))
        if hw is None or v is None:
            continue
        for child in list(hw):
            if child.tag != "group":
                hw.remove(child)
        etree.SubElement(hw, "plugin").text = v.plugin
        if variant == "mujoco":  # the model generate writes beside the URDF (render/mjcf.py), a plain path
            etree.SubElement(hw, "param", name="mujoco_model").text = f"{folder}/mujoco/{robot}.xml"
        for k, val in v.params:
            etree.SubElement(hw, "param", name=k).text = val
    if variant == "gazebo":
        # the sim plugin follows the model's blocks (the ros2_control Xacro writes it after them),
        # not the end of the robot: pass-through elements come after the include
        gazebo = etree.Element("gazebo")
        plugin = etree.SubElement(gazebo, "plugin", filename=sim[0], name=sim[1])
        etree.SubElement(plugin, "parameters").text = f"{folder}/config/ros2_controllers.yaml"
        if namespace:
            etree.SubElement(etree.SubElement(plugin, "ros"), "namespace").text = "/" + namespace.strip("/")
        names = {b.name for b in rc.hardware_blocks()}
        blocks = [e for e in doc.findall("ros2_control") if e.get("name", "") in names]
        if blocks:
            blocks[-1].addnext(gazebo)
        else:
            doc.append(gazebo)
    return doc


def _gen001(message: str, xacro_path: str, loc: Where) -> Finding:
    return GEN001.finding(
        message,
        "the Xacro's hardware variants disagree with the spec; fix the ros2_control templates",
        "file:" + xacro_path,
        loc,
    )


def xacro_calibration_nominal(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    """``xacro ... calibration:=<nominal.yaml>`` gives the committed URDF with every calibrated
    joint at the origin the spec states (the nominal model): the calibration is a layer that can
    be taken off. The expectation is the URDF with those origins set from the model's layer (as
    data), so a template that writes the layer wrongly cannot agree with itself."""
    from descgen.render.context import package_name
    from descgen.render.formatting import vec

    if not robot.calibration:
        return []
    xacro_path = f"urdf/{robot.name}.urdf.xacro"
    loc = Where(str(where / xacro_path))
    try:  # relative to the Xacro's folder, as xacro.load_yaml resolves it
        text, _ = expand_with(
            files, xacro_path, package_name(robot), {"calibration": "../config/calibration/nominal.yaml"}
        )
    except InputError as exc:
        why = "; ".join(f.message for f in exc.findings)
        return [_gen001(f"xacro {xacro_path} calibration:=nominal.yaml failed: {why}", xacro_path, loc)]
    expected = parse(files[f"urdf/{robot.name}.urdf"])
    nominal = {e.joint: e.nominal for e in robot.calibration}
    for joint in expected.findall("joint"):
        pose = nominal.get(joint.get("name", ""))
        origin = joint.find("origin")
        if pose is not None and origin is not None:
            origin.set("xyz", vec(pose.xyz))
            origin.set("rpy", vec(pose.rpy))
    diff = first_difference(parse(text), expected)
    if diff:
        return [
            GEN001.finding(
                f"xacro {xacro_path} calibration:=nominal.yaml differs from the nominal model at {diff}",
                "the calibration layer of the Xacro disagrees with the spec; fix the URDF Xacro template",
                "file:" + xacro_path,
                loc,
            )
        ]
    return []
