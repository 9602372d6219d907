"""The JSON Schema of the spec, for editors (yaml-language-server)."""

from __future__ import annotations

from typing import Any

from descgen.spec.models import RobotSpec


def json_schema() -> dict[str, Any]:
    schema = RobotSpec.model_json_schema(by_alias=True)
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "descgen robot spec"
    return schema
