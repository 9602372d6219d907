"""Where values came from: the sources cited inside spec elements, joined for the model."""

from __future__ import annotations

from collections.abc import Iterator

from pydantic import BaseModel

from .quantity import Measured, Written


def _walk_sources(obj: object) -> Iterator[str]:
    """Every source inside a spec element, in spec order."""
    if isinstance(obj, Measured | Written):
        if obj.source:
            yield obj.source
    elif isinstance(obj, BaseModel):
        src = getattr(obj, "source", None)
        if isinstance(src, str):
            yield src
        for name in type(obj).model_fields:
            if name != "source":
                yield from _walk_sources(getattr(obj, name))
    elif isinstance(obj, list | tuple):
        for item in obj:
            yield from _walk_sources(item)
    elif isinstance(obj, dict):
        for item in obj.values():
            yield from _walk_sources(item)


def sources(*objs: object) -> str | None:
    seen: list[str] = []
    for obj in objs:
        for src in [obj] if isinstance(obj, str) else _walk_sources(obj):
            for part in (p.strip() for p in src.split(",")):
                if part and part not in seen:
                    seen.append(part)
    return ", ".join(seen) if seen else None
