"""Turning pydantic's errors into findings at the YAML line that holds the bad value."""

from __future__ import annotations

import difflib
import types
import typing
from typing import Any

from pydantic import BaseModel, ValidationError

from descgen.codes import Code, raisable
from descgen.codes.spec import SPEC001, SPEC002, SPEC003, SPEC050
from descgen.core.findings import Finding
from descgen.infra.yamlsource import Document, Path_


def _strip_annotated(tp: Any) -> Any:
    while typing.get_origin(tp) is typing.Annotated:
        tp = typing.get_args(tp)[0]
    return tp


def _model_of(tp: Any) -> type[BaseModel] | None:
    tp = _strip_annotated(tp)
    if isinstance(tp, type) and issubclass(tp, BaseModel):
        return tp
    if typing.get_origin(tp) in (typing.Union, types.UnionType):
        for arg in typing.get_args(tp):
            found = _model_of(arg)
            if found is not None:
                return found
    return None


def _item_of(tp: Any, key: str | int) -> Any:
    """The annotation one step into ``tp`` along ``key``."""
    tp = _strip_annotated(tp)
    model = _model_of(tp)
    if model is not None and isinstance(key, str):
        for name, info in model.model_fields.items():
            if key in (name, info.alias):
                return info.annotation
        return None
    if typing.get_origin(tp) in (typing.Union, types.UnionType):
        for arg in typing.get_args(tp):
            if arg is not type(None):
                return _item_of(arg, key)
    origin = typing.get_origin(tp)
    args = typing.get_args(tp)
    if origin in (list, tuple) and args:
        return args[0]
    if origin is dict and len(args) == 2:
        return args[1]
    return None


def allowed_keys(root: type[BaseModel], path: Path_) -> list[str]:
    tp: Any = root
    for key in path:
        tp = _item_of(tp, key)
        if tp is None:
            return []
    model = _model_of(tp)
    if model is None:
        return []
    return [info.alias or name for name, info in model.model_fields.items()]


def data_path(data: Any, loc: tuple[Any, ...]) -> Path_:
    """pydantic's loc reduced to keys and indexes that exist in the YAML data."""
    out: list[str | int] = []
    cur = data
    for i, part in enumerate(loc):
        last = i == len(loc) - 1
        if isinstance(cur, dict) and isinstance(part, str) and (part in cur or last):
            out.append(part)
            cur = cur.get(part)
        elif isinstance(cur, list) and isinstance(part, int) and 0 <= part < len(cur):
            out.append(part)
            cur = cur[part]
        elif isinstance(cur, dict) and isinstance(part, str) and part not in cur:
            continue  # a validator's name, a union branch, ...
        else:
            continue
    return tuple(out)


_TYPE_CODES: dict[str, Code] = {
    "missing": SPEC002,
    "extra_forbidden": SPEC001,
    "string_pattern_mismatch": SPEC050,
    "literal_error": SPEC003,
}


def findings_from(exc: ValidationError, doc: Document, root: type[BaseModel], prefix: Path_ = ()) -> list[Finding]:
    out: list[Finding] = []
    seen: set[tuple[str, Path_]] = set()
    for err in exc.errors(include_url=False):
        loc = tuple(err["loc"])
        path = data_path(doc.data, prefix + loc)
        etype = err["type"]
        ctx = err.get("ctx") or {}
        # a descgen error's type is its finding code; pydantic's own types map to SPEC codes
        code = raisable(etype) if etype[:4].isupper() and etype[4:].isdigit() else _TYPE_CODES.get(etype, SPEC003)
        message = str(ctx.get("message") or err["msg"])
        hint = str(ctx.get("hint") or "")
        key_pos = False
        subject = ".".join(str(p) for p in path) or "spec"
        if etype == "extra_forbidden":
            key = str(loc[-1]) if loc else "?"
            parent = path[:-1] if path and path[-1] == key else path
            choices = allowed_keys(root, parent[len(prefix) :] if prefix else parent)
            close = difflib.get_close_matches(key, choices, n=1, cutoff=0.6)
            message = f"unknown key '{key}'"
            hint = (
                f"did you mean '{close[0]}'?"
                if close
                else (f"allowed here: {', '.join(choices)}" if choices else "remove it")
            )
            key_pos = True
        elif etype == "missing":
            key = str(loc[-1]) if loc else "?"
            path = path[:-1] if path and path[-1] == key else path
            message = f"missing required key '{key}'"
            hint = f"add {key}: ..."
        elif etype == "string_pattern_mismatch":
            message = f"'{err.get('input')}' is not a valid name"
            hint = "use letters, digits and _, starting with a letter (e.g. elbow_joint)"
        elif etype == "literal_error":
            message = f"{err.get('input')!r} is not allowed here"
            hint = f"use {ctx.get('expected', 'one of the listed values')}"
        elif not hint:
            message = f"{err['msg']} (got {err.get('input')!r})" if "input" in err else err["msg"]
            hint = "see `descgen schema` for what this field takes"
        where = doc.where(path, key=key_pos)
        dedup = (message, path)
        if dedup in seen:
            continue
        seen.add(dedup)
        out.append(code.finding(message, hint, subject, where))
    return out
