"""The JSON Schema of the spec, for editors (yaml-language-server).

Every property carries a ``description``: the attribute docstring of its model field (the
string literal written right under the field, PEP 257), read here from the source of the
module that defines the model, only when the schema is made. pydantic's
``use_attribute_docstrings`` would do the same on every import of the models (inspect and
ast at class build time), which descgen's cold start cannot afford.
"""

from __future__ import annotations

import ast
import functools
import inspect
import sys
from typing import Any

from pydantic import BaseModel
from pydantic.json_schema import GenerateJsonSchema, JsonSchemaValue
from pydantic_core import core_schema

from descgen.spec.models import RobotSpec


def json_schema() -> dict[str, Any]:
    schema = RobotSpec.model_json_schema(by_alias=True, schema_generator=DocumentedJsonSchema)
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "descgen robot spec"
    return schema


class DocumentedJsonSchema(GenerateJsonSchema):
    """pydantic's generator, with each model's field docstrings as property descriptions.

    Hooked where pydantic builds one model's schema, so a description is looked up by the
    model class itself, not by a ``$defs`` name, and two models with a field of the same name
    each get their own. A description pydantic already has (``Field(description=...)``)
    stays. A property that is a ``$ref`` gets it beside the ``$ref``, which JSON Schema
    2020-12 allows (and editors show)."""

    def model_schema(self, schema: core_schema.ModelSchema) -> JsonSchemaValue:
        json_schema = super().model_schema(schema)
        properties = json_schema.get("properties")
        if not isinstance(properties, dict):
            return json_schema
        cls: type[BaseModel] = schema["cls"]
        docs = field_docs(cls)
        # the schema's keys are the aliases with by_alias ("from" for InertialSpec.from_), else the names
        names = {name: name for name in cls.model_fields}
        names.update({f.alias: name for name, f in cls.model_fields.items() if f.alias is not None})
        for key, prop in list(properties.items()):
            doc = docs.get(names[key]) if key in names else None
            if doc and isinstance(prop, dict) and not prop.get("description"):
                properties[key] = {**prop, "description": doc}  # a new dict: a property schema may be shared
        return json_schema


def field_docs(cls: type[BaseModel]) -> dict[str, str]:
    """Field name -> its docstring, for ``cls`` and the models it inherits from (the class
    nearest ``cls`` that documents a field wins)."""
    out: dict[str, str] = {}
    for klass in reversed(cls.__mro__):
        if not issubclass(klass, BaseModel) or klass is BaseModel:
            continue
        out.update(_module_docs(klass.__module__).get(klass.__qualname__, {}))
    return out


@functools.cache
def _module_docs(module: str) -> dict[str, dict[str, str]]:
    """Class qualname -> {field: docstring} for every class of a module, from its source."""
    mod = sys.modules.get(module)
    if mod is None:
        return {}
    try:
        source = inspect.getsource(mod)
    except (OSError, TypeError):  # no source shipped (a frozen build): no descriptions
        return {}
    out: dict[str, dict[str, str]] = {}
    _classes(ast.parse(source).body, "", out)
    return out


def _classes(body: list[ast.stmt], prefix: str, out: dict[str, dict[str, str]]) -> None:
    for node in body:
        if not isinstance(node, ast.ClassDef):
            continue
        name = f"{prefix}{node.name}"
        docs: dict[str, str] = {}
        for stmt, after in zip(node.body, node.body[1:], strict=False):
            if (
                isinstance(stmt, ast.AnnAssign)
                and isinstance(stmt.target, ast.Name)
                and isinstance(after, ast.Expr)
                and isinstance(after.value, ast.Constant)
                and isinstance(after.value.value, str)
            ):
                docs[stmt.target.id] = _text(after.value.value)
        out[name] = docs
        _classes(node.body, f"{name}.", out)


def _text(doc: str) -> str:
    """A docstring as description text: indentation removed, each paragraph on one line."""
    paragraphs = inspect.cleandoc(doc).split("\n\n")
    return "\n\n".join(" ".join(p.split()) for p in paragraphs if p.strip())
