"""``@record``: a frozen dataclass that costs a fraction of one to define.

``@dataclass(frozen=True)`` writes six methods per class as source text and ``exec()``s each
(``__init__``, ``__repr__``, ``__eq__``, ``__hash__``, ``__setattr__``, ``__delattr__``), and
calls ``inspect.signature`` for a class without a docstring: about 0.5 ms per class, paid
at import by every command for ~170 classes (issue 17). A record is the same dataclass
(``dataclasses.fields``, ``replace``, ``asdict`` and ``is_dataclass`` see it as one; its
``__dataclass_params__`` say init, repr, eq and frozen) with the same methods, and the same
answers: equal, hashed, printed and refused assignment exactly as the frozen dataclass.
What differs is how they are made: ``__eq__``, ``__hash__``, ``__repr__``, ``__setattr__``
and ``__delattr__`` are closures over the class's field names (no source to compile), and
``__init__`` is written and compiled the first time the class is instantiated (most
classes a command imports are never instantiated by it). tests/test_record.py compares each
record with a ``@dataclass(frozen=True)`` twin.

Supported: plain fields with or without a default or ``default_factory``. Not supported
(refused when the class is defined): ``init=False``/``kw_only`` fields, ``InitVar``,
``__post_init__``, a dataclass base class, methods the decorator would write.
"""

from __future__ import annotations

import dataclasses
import inspect
import reprlib
from collections.abc import Callable
from dataclasses import MISSING, FrozenInstanceError
from operator import attrgetter
from typing import Any, TypeVar, dataclass_transform

_T = TypeVar("_T")

_WRITTEN = ("__init__", "__repr__", "__eq__", "__hash__", "__setattr__", "__delattr__", "__post_init__")


class _HasFactory:
    """The default of a field with a ``default_factory``: the factory is called in ``__init__``."""

    def __repr__(self) -> str:
        return "<factory>"


_HAS_FACTORY = _HasFactory()


def _key(names: tuple[str, ...]) -> Callable[[Any], tuple[Any, ...]]:
    """A function giving the tuple ``(obj.a, obj.b, ...)``: what the dataclass methods compare and hash."""
    if len(names) > 1:
        return attrgetter(*names)  # a tuple for two names or more
    if names:
        one = attrgetter(names[0])
        return lambda obj: (one(obj),)
    return lambda obj: ()


def _init_source(cls: type, fields: tuple[dataclasses.Field[Any], ...]) -> tuple[str, dict[str, Any]]:
    """The source of ``__init__`` and its globals, as dataclasses writes it for a frozen class."""
    self_name = "__record_self__" if any(f.name == "self" for f in fields) else "self"
    scope: dict[str, Any] = {"__record_setattr__": object.__setattr__, "_HAS_FACTORY": _HAS_FACTORY}
    params, body = [self_name], []
    for f in fields:
        value = f.name
        if f.default_factory is not MISSING:
            scope[f"_factory_{f.name}"] = f.default_factory
            params.append(f"{f.name}=_HAS_FACTORY")
            value = f"_factory_{f.name}() if {f.name} is _HAS_FACTORY else {f.name}"
        elif f.default is not MISSING:
            scope[f"_default_{f.name}"] = f.default
            params.append(f"{f.name}=_default_{f.name}")
        else:
            params.append(f.name)
        body.append(f"    __record_setattr__({self_name}, {f.name!r}, {value})")
    return f"def __init__({', '.join(params)}):\n" + ("\n".join(body) or "    pass") + "\n", scope


def _compiled_init(cls: type, fields: tuple[dataclasses.Field[Any], ...]) -> Callable[..., None]:
    source, scope = _init_source(cls, fields)
    local: dict[str, Any] = {}
    exec(source, scope, local)  # source written above from the class's own field names
    init: Callable[..., None] = local["__init__"]
    init.__qualname__ = f"{cls.__qualname__}.__init__"
    init.__annotations__ = {f.name: f.type for f in fields} | {"return": None}
    return init


def _lazy_init(cls: type, fields: tuple[dataclasses.Field[Any], ...]) -> Callable[..., None]:
    compiled: Callable[..., None] | None = None

    def first_init(self: Any, *args: Any, **kwargs: Any) -> None:
        nonlocal compiled
        if compiled is None:
            compiled = _compiled_init(cls, fields)
            if cls.__dict__.get("__init__") is first_init:  # not if wrapped meanwhile (a test's probe)
                type.__setattr__(cls, "__init__", compiled)  # from now on, instances call it directly
        compiled(self, *args, **kwargs)

    return first_init


@dataclass_transform(frozen_default=True, field_specifiers=(dataclasses.field, dataclasses.Field))
def record(cls: type[_T]) -> type[_T]:
    """Make ``cls`` a frozen dataclass (see the module docstring)."""
    if any(dataclasses.is_dataclass(base) for base in cls.__mro__[1:]):
        raise TypeError(f"record {cls.__name__}: a dataclass base class is not supported")
    own = [name for name in _WRITTEN if name in cls.__dict__]
    if own:
        raise TypeError(f"record {cls.__name__}: defines {', '.join(own)}, which a record writes")
    if not cls.__doc__:
        # what dataclasses would write, without inspect.signature (a third of its cost)
        cls.__doc__ = f"{cls.__name__}({', '.join(inspect.get_annotations(cls))})"
    dataclasses.dataclass(init=False, repr=False, eq=False)(cls)  # fields, defaults, __match_args__
    fields = dataclasses.fields(cls)  # type: ignore[arg-type]  # ClassVar and InitVar left out
    pseudo = cls.__dataclass_fields__.keys() - {f.name for f in fields}  # type: ignore[attr-defined]
    if any(not f.init or f.kw_only is True for f in fields) or any(
        "InitVar" in str(cls.__dataclass_fields__[name].type)  # type: ignore[attr-defined]
        for name in pseudo
    ):
        raise TypeError(f"record {cls.__name__}: init=False, kw_only and InitVar fields are not supported")
    seen_default = False
    for f in fields:
        if f.default is not MISSING or f.default_factory is not MISSING:
            seen_default = True
        elif seen_default:
            raise TypeError(f"non-default argument {f.name!r} follows default argument")
    params = cls.__dataclass_params__  # type: ignore[attr-defined]
    params.init = params.repr = params.eq = params.frozen = True  # what the class now is

    names = tuple(f.name for f in fields)
    compared = _key(tuple(f.name for f in fields if f.compare))
    hashed = _key(tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash)))
    shown = tuple(f.name for f in fields if f.repr)

    def eq(self: Any, other: Any) -> Any:
        if other.__class__ is self.__class__:
            return compared(self) == compared(other)
        return NotImplemented

    def hash_(self: Any) -> int:
        return hash(hashed(self))

    @reprlib.recursive_repr()
    def repr_(self: Any) -> str:
        return f"{self.__class__.__qualname__}({', '.join(f'{n}={getattr(self, n)!r}' for n in shown)})"

    def setattr_(self: Any, name: str, value: Any) -> None:
        if type(self) is cls or name in names:
            raise FrozenInstanceError(f"cannot assign to field {name!r}")
        super(cls, self).__setattr__(name, value)

    def delattr_(self: Any, name: str) -> None:
        if type(self) is cls or name in names:
            raise FrozenInstanceError(f"cannot delete field {name!r}")
        super(cls, self).__delattr__(name)

    methods: dict[str, Callable[..., Any]] = {
        "__init__": _lazy_init(cls, fields),
        "__eq__": eq,
        "__hash__": hash_,
        "__repr__": repr_,
        "__setattr__": setattr_,
        "__delattr__": delattr_,
    }
    for name, fn in methods.items():
        fn.__name__, fn.__qualname__ = name, f"{cls.__qualname__}.{name}"
        type.__setattr__(cls, name, fn)
    return cls
