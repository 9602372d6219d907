"""Every property of the spec's JSON Schema has a description, from its model field's docstring,
so editors (yaml-language-server) show help on every key. That the committed
specs/descgen-spec.schema.json is what json_schema() gives is tests/test_schema_file.py's."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest
from pydantic import BaseModel, ConfigDict, Field

from descgen.spec import models
from descgen.spec.schema import DocumentedJsonSchema, field_docs, json_schema


def _properties(node: object, path: str = "#") -> Iterator[tuple[str, object]]:
    """(path, schema) of every property of every object schema inside ``node``: the root's,
    each $defs entry's, and the inline ones (a quantity's ``{value, source}``)."""
    if isinstance(node, dict):
        props = node.get("properties")
        if isinstance(props, dict):
            for key, prop in props.items():
                yield f"{path}/properties/{key}", prop
        for key, value in node.items():
            yield from _properties(value, f"{path}/{key}")
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from _properties(value, f"{path}/{i}")


def test_every_property_has_a_description() -> None:
    schema = json_schema()
    found = list(_properties(schema))
    assert len(found) > 300  # the walk reaches the $defs, not only the root's 19 keys
    assert any(path.startswith("#/$defs/") for path, _ in found)
    missing = [
        path
        for path, prop in found
        if not (isinstance(prop, dict) and isinstance(prop.get("description"), str) and prop["description"].strip())
    ]
    assert not missing, f"{len(missing)} of {len(found)} properties have no description: {missing[:20]}"


@pytest.mark.parametrize(
    ("where", "key", "says"),
    [
        # the same field name in two classes: each gets its own text
        ("$defs/LinkSpec", "name", "NAME001"),
        ("$defs/JointSpec", "name", "NAME002"),
        ("$defs/JointSpec", "type", "`prismatic`"),
        ("$defs/SensorSpec", "type", "`camera`"),
        ("$defs/VisualSpec", "origin", "Pose of the shape in the link frame"),
        ("$defs/InertialSpec", "origin", "The centre of mass"),
        # inherited fields: from the base class, in the subclass's $defs entry
        ("$defs/LinkSpec", "description", "A note about the link"),
        ("$defs/JointSpec", "description", "A note about the joint"),
        ("$defs/CylinderSpec", "diameter", "instead of `radius`"),
        # a field the subclass overrides: the subclass's text
        ("$defs/InterfaceSpec", "name", "`orientation.x`"),
        ("$defs/GpioInterfaceSpec", "name", "`Goal Position`"),
        # a field with an alias ('from_' in Python, 'from' in YAML)
        ("$defs/InertialSpec", "from", "at uniform density"),
        # the root (RobotSpec, not in $defs)
        ("", "require_sources", "SPEC010"),
        # a quantity's {value, source} form, from descgen/spec/quantity.py
        ("$defs/LimitSpec/properties/velocity/anyOf/2", "value", "unit"),
    ],
)
def test_a_field_docstring_reaches_its_own_property(where: str, key: str, says: str) -> None:
    node: Any = json_schema()
    for part in filter(None, where.split("/")):
        node = node[int(part)] if isinstance(node, list) else node[part]
    assert says in node["properties"][key]["description"]


def test_a_reference_property_carries_its_description_beside_the_ref() -> None:
    package = json_schema()["properties"]["package"]
    assert package["$ref"] == "#/$defs/PackageSpec"
    assert package["description"] == field_docs(models.RobotSpec)["package"]


def test_descriptions_are_the_docstrings_as_one_line() -> None:
    """A docstring wrapped over several source lines is one line of text in the schema."""
    doc = json_schema()["$defs"]["LimitSpec"]["properties"]["acceleration"]["description"]
    assert doc.startswith("Largest acceleration, for MoveIt's joint_limits.yaml")
    assert "\n" not in doc and "  " not in doc


def test_the_models_do_not_read_their_docstrings_at_import() -> None:
    """pydantic's use_attribute_docstrings would parse the source on every import (cold start);
    the schema reads the docstrings only when it is made."""
    assert not models.Base.model_config.get("use_attribute_docstrings")
    for cls in _model_classes():
        assert not cls.model_config.get("use_attribute_docstrings"), cls.__name__
        assert all(f.description is None for f in cls.model_fields.values()), cls.__name__


def _model_classes() -> list[type[BaseModel]]:
    return [
        c
        for c in vars(models).values()
        if isinstance(c, type) and issubclass(c, BaseModel) and c.__module__ == models.__name__
    ]


# Models of this module, for the generator alone: two classes with a field of the same name, a
# subclass that overrides a documented field, and a description given through Field().


class _Probe(BaseModel):
    model_config = ConfigDict(extra="forbid")

    name: str
    """the probe's name"""
    width: float = 0.0
    """how wide the probe is"""
    kept: int = Field(default=0, description="written with Field")
    """not this docstring"""
    bare: int = 0


class _Other(BaseModel):
    name: str
    """the other's name"""
    probe: _Probe
    """a probe inside the other"""


class _Narrow(_Probe):
    width: float = 1.0
    """how wide the narrow probe is"""


def test_the_generator_takes_each_class_s_own_docstrings() -> None:
    schema = _Other.model_json_schema(schema_generator=DocumentedJsonSchema)
    assert schema["properties"]["name"]["description"] == "the other's name"
    assert schema["properties"]["probe"]["description"] == "a probe inside the other"
    assert schema["properties"]["probe"]["$ref"] == "#/$defs/_Probe"
    probe = schema["$defs"]["_Probe"]["properties"]
    assert probe["name"]["description"] == "the probe's name"
    assert probe["kept"]["description"] == "written with Field"  # Field(description=...) stays
    assert "description" not in probe["bare"]  # nothing invented for an undocumented field

    narrow = _Narrow.model_json_schema(schema_generator=DocumentedJsonSchema)["properties"]
    assert narrow["width"]["description"] == "how wide the narrow probe is"
    assert narrow["name"]["description"] == "the probe's name"  # inherited
