"""Where values came from: the sources cited inside spec elements, joined for the model."""

from __future__ import annotations

from pydantic import BaseModel

from descgen.infra.yamlsource import Document
from descgen.spec.quantity import Measured, Written


def _walk_sources(obj: object) -> list[str]:
    """Every source inside a spec element, in spec order."""
    out: list[str] = []
    _collect(obj, out)
    return out


# a list filled by plain recursion: nested generators cost ~0.3 s on a 1000-link spec. Types
# are told apart by identity first (an isinstance chain per value was most of the walk), and a
# model's field names are looked up once per class (``model_fields`` goes through pydantic's
# class property on every access; ``getattr(model, "source", None)`` on a model without that
# field goes through pydantic's __getattr__ and an exception, ~50 us each).
_LEAVES = frozenset({str, int, float, bool, type(None)})
_VALUES = frozenset({Measured, Written})
_FIELDS: dict[type, tuple[str, ...]] = {}


def _collect(obj: object, out: list[str]) -> None:
    kind = type(obj)
    if kind in _LEAVES:
        return
    if kind in _VALUES or isinstance(obj, Measured | Written):
        source = obj.source  # type: ignore[attr-defined]
        if source:
            out.append(source)
    elif isinstance(obj, BaseModel):
        names = _FIELDS.get(kind)
        if names is None:
            names = _FIELDS[kind] = tuple(n for n in kind.__pydantic_fields__ if n != "source")  # type: ignore[attr-defined]
        if len(names) < len(kind.__pydantic_fields__):  # type: ignore[attr-defined]
            src = obj.source  # type: ignore[attr-defined]
            if isinstance(src, str):
                out.append(src)
        for name in names:
            value = getattr(obj, name)
            if type(value) not in _LEAVES:
                _collect(value, out)
    elif kind is list or kind is tuple or isinstance(obj, list | tuple):
        for item in obj:  # type: ignore[attr-defined]
            if type(item) not in _LEAVES:
                _collect(item, out)
    elif isinstance(obj, dict):
        for item in obj.values():
            _collect(item, out)


def cites_sources(doc: Document) -> bool:
    """Whether the spec names a source anywhere. Every source (a model's ``source:``, a
    quantity's ``{value, source}``) is a YAML key ``source``, however the key is spelled or
    reached (quoted, escaped, through an alias: each path is in ``key_marks``); without one,
    every element's sources are None."""
    return any(path[-1] == "source" for path in doc.key_marks if path)


def sources(*objs: object) -> str | None:
    seen: list[str] = []
    for obj in objs:
        for src in [obj] if isinstance(obj, str) else _walk_sources(obj):
            for part in (p.strip() for p in src.split(",")):
                if part and part not in seen:
                    seen.append(part)
    return ", ".join(seen) if seen else None
