"""Where values came from: the sources cited inside spec elements, joined for the model."""

from __future__ import annotations

from pydantic import BaseModel

from .quantity import Measured, Written


def _walk_sources(obj: object) -> list[str]:
    """Every source inside a spec element, in spec order."""
    out: list[str] = []
    _collect(obj, out)
    return out


# a list filled by plain recursion: nested generators cost ~0.3 s on a 1000-link spec
_LEAVES = (str, int, float, type(None))


def _collect(obj: object, out: list[str]) -> None:
    if isinstance(obj, _LEAVES):
        return
    if isinstance(obj, Measured | Written):
        if obj.source:
            out.append(obj.source)
    elif isinstance(obj, BaseModel):
        src = getattr(obj, "source", None)
        if isinstance(src, str):
            out.append(src)
        for name in type(obj).model_fields:
            if name != "source":
                _collect(getattr(obj, name), out)
    elif isinstance(obj, list | tuple):
        for item in obj:
            _collect(item, out)
    elif isinstance(obj, dict):
        for item in obj.values():
            _collect(item, out)


def sources(*objs: object) -> str | None:
    seen: list[str] = []
    for obj in objs:
        for src in [obj] if isinstance(obj, str) else _walk_sources(obj):
            for part in (p.strip() for p in src.split(",")):
                if part and part not in seen:
                    seen.append(part)
    return ", ".join(seen) if seen else None
