"""``@record`` (descgen/core/record.py) behaves exactly as ``@dataclass(frozen=True)``.

The oracle is the standard library: every record class descgen defines is compared with a
frozen dataclass twin built by ``dataclasses.make_dataclass`` from the same fields, on the
instances a real robot model holds (the example spec, loaded and built): same repr, equality,
hash, refused assignment and deletion, ``replace``/``asdict``/``astuple``, ``__match_args__``,
``__init__`` signature and error messages, pickling."""

from __future__ import annotations

import copy
import dataclasses
import inspect
import math
import pickle
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import FrozenInstanceError, field
from typing import Any

import pytest

from descgen.core import record as record_module
from descgen.core.record import record
from tests.conftest import EXAMPLE, ROOT


def _is_record(cls: type) -> bool:
    init = cls.__dict__.get("__eq__")
    return (
        init is not None
        and getattr(init, "__code__", None) is not None
        and (init.__code__.co_filename == record_module.__file__)
    )


def _twin(cls: type) -> type:
    """A ``@dataclass(frozen=True)`` with the same name, fields and defaults."""
    spec = []
    for f in dataclasses.fields(cls):
        kw: dict[str, Any] = {"repr": f.repr, "compare": f.compare, "hash": f.hash}
        if f.default is not dataclasses.MISSING:
            kw["default"] = f.default
        if f.default_factory is not dataclasses.MISSING:
            kw["default_factory"] = f.default_factory
        spec.append((f.name, f.type, field(**kw)))
    twin = dataclasses.make_dataclass(cls.__name__, spec, frozen=True)
    twin.__qualname__ = cls.__qualname__
    return twin


def _records_in(value: Any, seen: set[int]) -> Iterator[Any]:
    """Every record instance reachable from ``value`` (fields, tuples, dicts)."""
    if id(value) in seen:
        return
    seen.add(id(value))
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        if _is_record(type(value)):
            yield value
        for f in dataclasses.fields(value):
            yield from _records_in(getattr(value, f.name), seen)
    elif isinstance(value, (tuple, list, frozenset, set)):
        for v in value:
            yield from _records_in(v, seen)
    elif isinstance(value, dict):
        for k, v in value.items():
            yield from _records_in(k, seen)
            yield from _records_in(v, seen)


def _as_twin(value: Any, twins: dict[type, type]) -> Any:
    """``value`` with every record replaced by its twin, recursively."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type) and _is_record(type(value)):
        twin = twins.setdefault(type(value), _twin(type(value)))
        return twin(*(_as_twin(getattr(value, f.name), twins) for f in dataclasses.fields(value)))
    if isinstance(value, tuple):
        return tuple(_as_twin(v, twins) for v in value)
    return value


@pytest.fixture(scope="module")
def robot_records() -> list[Any]:
    from descgen import codes
    from descgen.audit.spec import load_spec
    from descgen.physics import frames
    from descgen.read import urdf_readback

    loaded = load_spec(EXAMPLE)
    urdf = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"
    roots = (
        loaded.robot,
        urdf_readback.read(urdf.read_text()),
        frames.edges(loaded.robot),
        tuple(codes.CODES.values()),
    )
    found = list(_records_in(roots, set()))
    assert len({type(r) for r in found}) >= 25  # the walk really reached the model's classes and the others
    return found


def test_model_records_match_frozen_dataclasses(robot_records: list[Any]) -> None:
    twins: dict[type, type] = {}
    for rec in robot_records:
        twin = _as_twin(rec, twins)
        assert repr(rec) == repr(twin)
        assert hash(rec) == hash(twin)  # the same tuple of field values is hashed
        assert dataclasses.astuple(rec) == dataclasses.astuple(twin)
        assert dataclasses.asdict(rec) == dataclasses.asdict(twin)
        same = dataclasses.replace(rec)
        assert same == rec and same is not rec and hash(same) == hash(rec)
        assert rec != twin and twin != rec  # a dataclass of another class is never equal, as before
        name = dataclasses.fields(rec)[0].name
        with pytest.raises(FrozenInstanceError, match=f"cannot assign to field '{name}'"):
            setattr(rec, name, None)
        with pytest.raises(FrozenInstanceError, match="cannot assign to field 'other'"):
            rec.other = 1
        with pytest.raises(FrozenInstanceError, match=f"cannot delete field '{name}'"):
            delattr(rec, name)
        assert pickle.loads(pickle.dumps(rec)) == rec
        assert copy.deepcopy(rec) == rec
    for cls, twin in twins.items():
        assert cls.__match_args__ == twin.__match_args__  # type: ignore[attr-defined]
        assert [(f.name, f.type, f.default) for f in dataclasses.fields(cls)] == [
            (f.name, f.type, f.default) for f in dataclasses.fields(twin)
        ]
        ours, theirs = cls.__dataclass_params__, twin.__dataclass_params__  # type: ignore[attr-defined]
        assert (ours.init, ours.repr, ours.eq, ours.order, ours.unsafe_hash, ours.frozen) == (
            theirs.init,
            theirs.repr,
            theirs.eq,
            theirs.order,
            theirs.unsafe_hash,
            theirs.frozen,
        )
        assert str(inspect.signature(cls)) == str(inspect.signature(twin))  # compiled by now: instances exist


def test_a_changed_field_is_unequal_and_differently_hashed(robot_records: list[Any]) -> None:
    checked = 0
    for rec in robot_records:
        for f in dataclasses.fields(rec):
            value = getattr(rec, f.name)
            if isinstance(value, str):
                other = dataclasses.replace(rec, **{f.name: value + "x"})
                assert other != rec
                assert not other.__eq__(rec)
                assert hash(other) != hash(rec)  # tuples of distinct strings: a collision would be a bug
                checked += 1
    assert checked > 50


def _pair(body: str) -> tuple[type, type]:
    """The same class body as a record and as a frozen dataclass."""
    made = []
    for deco in (record, dataclasses.dataclass(frozen=True)):
        scope: dict[str, Any] = {"field": field, "deco": deco}
        exec(f"@deco\nclass K:\n{body}", scope)  # test-built source only
        made.append(scope["K"])
    return made[0], made[1]


def test_defaults_factories_and_init_errors_as_dataclasses() -> None:
    body = (
        "    a: int\n    b: str = 'x'\n    c: tuple = field(default_factory=tuple)\n"
        "    d: list = field(default_factory=list, compare=False, hash=False, repr=False)\n"
    )
    rec, dc = _pair(body)
    assert rec.__init__.__code__.co_name == "first_init"  # written on first use
    r1, r2 = rec(1), rec(1)
    d1 = dc(1)
    assert str(inspect.signature(rec)) == str(inspect.signature(dc))
    assert r1.d is not r2.d  # a factory is called per instance
    assert repr(r1) == repr(d1) == "K(a=1, b='x', c=())"
    r1.d.append(5)
    assert r1 == r2 and hash(r1) == hash(r2)  # compare=False, hash=False fields left out, as dataclasses does
    assert hash(r1) == hash(d1)
    assert rec(1, "y", (2,)) == rec(a=1, c=(2,), b="y")
    for args, kwargs in (((), {}), ((1, 2, 3, 4, 5), {}), ((1,), {"a": 2}), ((1,), {"zz": 2})):
        with pytest.raises(TypeError) as ours:
            rec(*args, **kwargs)
        with pytest.raises(TypeError) as theirs:
            dc(*args, **kwargs)
        assert str(ours.value) == str(theirs.value)


def test_one_field_and_nan_compare_as_tuples() -> None:
    rec, dc = _pair("    v: float\n")
    nan = math.nan
    assert (rec(nan) == rec(nan)) == (dc(nan) == dc(nan))  # the same nan object: equal in a tuple
    assert (rec(nan) == rec(float("nan"))) == (dc(nan) == dc(float("nan")))
    assert hash(rec(2.5)) == hash(dc(2.5)) == hash((2.5,))
    empty, dc_empty = _pair("    pass\n")
    assert empty() == empty() and hash(empty()) == hash(dc_empty()) == hash(())
    assert repr(empty()) == repr(dc_empty()) == "K()"


def test_match_statement_and_subclass_setattr() -> None:
    rec, _ = _pair("    a: int\n    b: int = 2\n")
    match rec(1):
        case rec(a, b):  # type: ignore[misc]
            assert (a, b) == (1, 2)
        case _:
            raise AssertionError("positional pattern did not match")

    class Sub(rec):  # type: ignore[misc, valid-type]  # a plain subclass may set its own attributes
        pass

    s = Sub(1)
    s.extra = 3
    assert s.extra == 3
    with pytest.raises(FrozenInstanceError):
        s.a = 5


@pytest.mark.parametrize(
    "body",
    [
        "    a: int = 1\n    b: int\n",  # non-default after default
        "    a: int = field(init=False, default=1)\n",
        "    a: int = field(kw_only=True, default=1)\n",
        "    a: int\n    def __eq__(self, other): return True\n",
        "    a: int\n    def __post_init__(self): pass\n",
    ],
)
def test_refused_class_bodies(body: str) -> None:
    with pytest.raises(TypeError):
        _pair(body)  # record refuses first; dataclasses would accept some of these
    if "b: int\n" in body:  # dataclasses refuses the same with the same words
        with pytest.raises(TypeError, match="non-default argument 'b' follows default argument"):
            exec(f"@deco\nclass K:\n{body}", {"deco": dataclasses.dataclass(frozen=True), "field": field})


def test_init_compiled_once_and_shared() -> None:
    rec, _ = _pair("    a: int\n")
    stub = rec.__init__
    rec(1)
    compiled = rec.__init__
    assert compiled is not stub and compiled.__qualname__ == "K.__init__"
    rec(2)
    assert rec.__init__ is compiled


def test_defining_model_records_compiles_no_init() -> None:
    """Importing descgen.core.model writes no ``__init__`` source: instantiation does (fresh process)."""
    probe = (
        "import descgen.core.model as m, dataclasses\n"
        "stubs = [c for c in vars(m).values() if isinstance(c, type) and dataclasses.is_dataclass(c)"
        " and c.__init__.__code__.co_name == 'first_init']\n"
        "print(len(stubs))"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert done.returncode == 0, done.stderr
    assert int(done.stdout.strip()) >= 30  # of 42: a few are instantiated at import (defaults)


def test_a_wrapped_init_stays_wrapped() -> None:
    """Replacing ``__init__`` before the first instance (as tests/codes_seen.py does for
    Finding) keeps the replacement; the original still works and is compiled once."""
    rec, _ = _pair("    a: int\n")
    original = rec.__init__
    calls = []

    def wrapped(self: Any, *args: Any, **kwargs: Any) -> None:
        original(self, *args, **kwargs)
        calls.append(self.a)

    rec.__init__ = wrapped
    rec(1)
    rec(2)
    assert calls == [1, 2] and rec.__init__ is wrapped
