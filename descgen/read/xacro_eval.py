"""A restricted evaluator for the expressions inside an untrusted Xacro.

xacro evaluates ``${...}`` and ``$(eval ...)`` with Python's ``eval`` (docs/reference/xacro.md,
"Security": not a sandbox). Here an expression is parsed with :mod:`ast` and interpreted
node by node: only literals, arithmetic, comparisons, boolean logic, conditional
expressions, containers, comprehensions, subscripts, f-strings, names from the symbol
table, and calls of the functions on an allow-list (math, a few builtins, xacro's own
helpers) are evaluated. Attribute access is limited to namespace members, YAML keys and a
few string/list/dict methods; no name or attribute may start with ``_``. Every number,
string and collection it makes is bounded, so ``9**9**9`` or ``'x' * 10**10`` is refused
instead of hanging. Nothing here touches files or the environment: the callables that
do are wrapped by :mod:`descgen.read.xacro_file` before they reach the allow-list.
"""

from __future__ import annotations

import ast
import builtins
import math
import operator
import re
import string
from collections.abc import Callable, Iterator, Mapping
from typing import Any

_PYTHON_BUILTINS = frozenset(vars(builtins))
MAX_INT_BITS = 4096  # 1234 decimal digits: far beyond any physical constant
MAX_EXPONENT = 4096
MAX_SIZE = 1_000_000  # characters of a string, items of a collection
MAX_STEPS = 2_000_000  # nodes evaluated in one expansion (loops included)
MAX_EXPRESSION = 20_000  # characters of one expression


class RefusedError(Exception):
    """An expression uses something the restricted evaluator does not allow."""

    def __init__(self, message: str, kind: str = "expression") -> None:
        super().__init__(message)
        self.message = message
        self.kind = kind  # expression | file | environment | limit


class Budget:
    """Steps left for one expansion (shared by every expression of it)."""

    def __init__(self, steps: int = MAX_STEPS) -> None:
        self.steps = steps

    def spend(self, n: int = 1) -> None:
        self.steps -= n
        if self.steps < 0:
            raise RefusedError(f"the expressions of this Xacro need more than {MAX_STEPS} evaluation steps", "limit")


# Methods of plain values an expression may call (none of them reaches an object's internals).
_STR_METHODS = frozenset(
    [
        "capitalize",
        "casefold",
        "center",
        "count",
        "endswith",
        "find",
        "format",
        "index",
        "isalnum",
        "isalpha",
        "isdigit",
        "islower",
        "isnumeric",
        "isspace",
        "isupper",
        "join",
        "ljust",
        "lower",
        "lstrip",
        "partition",
        "replace",
        "rfind",
        "rindex",
        "rjust",
        "rpartition",
        "rsplit",
        "rstrip",
        "split",
        "splitlines",
        "startswith",
        "strip",
        "swapcase",
        "title",
        "upper",
        "zfill",
    ]
)
_LIST_METHODS = frozenset(["count", "index"])
_DICT_METHODS = frozenset(["get", "items", "keys", "values"])
_PADDING_METHODS = frozenset(["center", "ljust", "rjust", "zfill"])

_BINOPS: dict[type[ast.operator], Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
    ast.Pow: operator.pow,
    ast.BitAnd: operator.and_,
    ast.BitOr: operator.or_,
    ast.BitXor: operator.xor,
    ast.LShift: operator.lshift,
    ast.RShift: operator.rshift,
}
_UNARY: dict[type[ast.unaryop], Callable[[Any], Any]] = {
    ast.UAdd: operator.pos,
    ast.USub: operator.neg,
    ast.Not: operator.not_,
    ast.Invert: operator.invert,
}
_COMPARE: dict[type[ast.cmpop], Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
    ast.Is: operator.is_,
    ast.IsNot: operator.is_not,
}


def bounded(value: Any) -> Any:
    """``value`` if it is within the size limits; RefusedError otherwise."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int) and value.bit_length() > MAX_INT_BITS:
        raise RefusedError(f"an integer larger than {MAX_INT_BITS} bits", "limit")
    if isinstance(value, str | bytes | list | tuple | dict | set | frozenset) and len(value) > MAX_SIZE:
        raise RefusedError(f"a value longer than {MAX_SIZE} items", "limit")
    return value


def _size(value: Any) -> int:
    return len(value) if isinstance(value, str | bytes | list | tuple) else 0


def _check_binop(op: ast.operator, a: Any, b: Any) -> None:
    """Refuse an operation before it runs when its result would be too large."""
    numbers = (int, float)
    if isinstance(op, ast.Pow) and isinstance(a, numbers) and isinstance(b, numbers):
        if isinstance(b, int) and abs(b) > MAX_EXPONENT and abs(a) not in (0, 1):
            raise RefusedError(f"the exponent {b} is too large (at most {MAX_EXPONENT})", "limit")
        if isinstance(a, int) and isinstance(b, int) and b > 0 and a.bit_length() * b > MAX_INT_BITS:
            raise RefusedError(f"{a}**{b} is larger than {MAX_INT_BITS} bits", "limit")
    if isinstance(op, ast.LShift) and isinstance(b, int) and b > MAX_INT_BITS:
        raise RefusedError(f"a shift by {b} bits is too large", "limit")
    if isinstance(op, ast.Mult):
        for seq, n in ((a, b), (b, a)):
            if _size(seq) and isinstance(n, int) and _size(seq) * n > MAX_SIZE:
                raise RefusedError(f"a repetition longer than {MAX_SIZE} items", "limit")
    if isinstance(op, ast.Mod) and isinstance(a, str):
        _check_printf(a)
    if isinstance(op, ast.Add) and _size(a) + _size(b) > MAX_SIZE:
        raise RefusedError(f"a value longer than {MAX_SIZE} items", "limit")


_PRINTF_WIDTH = re.compile(r"%[-#0 +]*(\d+|\*)?(?:\.(\d+|\*))?")


def _check_printf(fmt: str) -> None:
    for m in _PRINTF_WIDTH.finditer(fmt):
        for group in m.groups():
            if group == "*" or (group and (len(group) > 4 or int(group) > 1000)):
                raise RefusedError("a %-format width or precision above 1000", "limit")


def check_format(fmt: str) -> None:
    """``str.format`` may only insert its arguments: ``'{0.__globals__}'`` and
    ``'{x[key]}'`` reach into objects, and a huge width allocates memory."""
    try:
        parts = list(string.Formatter().parse(fmt))
    except ValueError as exc:
        raise RefusedError(f"bad format string: {exc}") from None
    for _, field, spec, _ in parts:
        if field is None:
            continue
        if "." in field or "[" in field:
            raise RefusedError(f"format field '{{{field}}}' reaches into an object; only plain fields are allowed")
        if spec:
            if "{" in spec:
                raise RefusedError("nested format fields are not allowed")
            check_spec(spec)


def check_spec(spec: str) -> None:
    """A format spec may not ask for a width or precision that allocates megabytes."""
    for digits in re.findall(r"\d+", spec):
        if len(digits) > 4 or int(digits) > 1000:
            raise RefusedError("a format width or precision above 1000", "limit")


def _call_method(obj: Any, name: str) -> Callable[..., Any]:
    method = getattr(obj, name)
    if name == "format" and isinstance(obj, str):
        check_format(obj)
    if name in _PADDING_METHODS:

        def padded(width: Any, *rest: Any) -> Any:
            if isinstance(width, int) and width > MAX_SIZE:
                raise RefusedError(f"a padding width above {MAX_SIZE}", "limit")
            return method(width, *rest)

        return padded
    if name == "join" and isinstance(obj, str):
        return lambda items: method([bounded(x) for x in _limited(items)])
    return method  # type: ignore[no-any-return]


def _limited(items: Any) -> Iterator[Any]:
    for i, x in enumerate(items):
        if i >= MAX_SIZE:
            raise RefusedError(f"an iteration over more than {MAX_SIZE} items", "limit")
        yield x


class Evaluator:
    """Interprets one parsed expression against a symbol table.

    ``names`` is looked up with ``[]`` (xacro's Table resolves lazy properties there);
    ``allowed`` holds the ids of the callables an expression may call or pass on.
    """

    def __init__(self, names: Mapping[str, Any], allowed: frozenset[int], budget: Budget) -> None:
        self.names = names
        self.allowed = allowed
        self.budget = budget
        self.scopes: list[dict[str, Any]] = []

    def run(self, text: str) -> Any:
        if len(text) > MAX_EXPRESSION:
            raise RefusedError(f"an expression longer than {MAX_EXPRESSION} characters", "limit")
        tree = ast.parse(text.strip(), mode="eval")
        self.check(tree)
        return self.eval(tree.body)

    def check(self, tree: ast.AST) -> None:
        """Refuse the whole expression before any of it runs, branches not taken included."""
        for node in ast.walk(tree):
            if isinstance(node, ast.Name | ast.Attribute):
                name = node.id if isinstance(node, ast.Name) else node.attr
                if name.startswith("_"):
                    raise RefusedError(f"the name '{name}' is not allowed (names starting with _ reach internals)")
            elif isinstance(node, ast.expr) and not hasattr(self, "_n_" + type(node).__name__.lower()):
                raise RefusedError(f"{type(node).__name__} expressions are not allowed in an audited Xacro")

    def _value(self, v: Any, what: str) -> Any:
        """A value that came from a name or attribute: callables only from the allow-list."""
        # namespaces and YAML dicts are containers, not functions
        if callable(v) and not isinstance(v, dict | _Method) and id(v) not in self.allowed:
            raise RefusedError(f"'{what}' is not one of the functions an audited Xacro may call")
        return v

    def eval(self, node: ast.AST) -> Any:
        self.budget.spend()
        method = getattr(self, "_n_" + type(node).__name__.lower(), None)
        if method is None:
            raise RefusedError(f"{type(node).__name__} expressions are not allowed in an audited Xacro")
        return bounded(method(node))

    def _n_constant(self, node: ast.Constant) -> Any:
        if not isinstance(node.value, int | float | str | bool | type(None)):
            raise RefusedError(f"a {type(node.value).__name__} literal is not allowed")
        return node.value

    def _n_name(self, node: ast.Name) -> Any:
        name = node.id
        if name.startswith("_"):
            raise RefusedError(f"the name '{name}' is not allowed (names starting with '_' reach Python internals)")
        for scope in reversed(self.scopes):
            if name in scope:
                return scope[name]
        try:
            value = self.names[name]
        except KeyError:
            if name in _PYTHON_BUILTINS:
                raise RefusedError(f"'{name}' is not available to an audited Xacro") from None
            raise NameError(f"name '{name}' is not defined") from None
        return self._value(value, name)

    def _n_attribute(self, node: ast.Attribute) -> Any:
        attr = node.attr
        if attr.startswith("_"):
            raise RefusedError(
                f"the attribute '{attr}' is not allowed (names starting with '_' reach Python internals)"
            )
        obj = self.eval(node.value)
        if isinstance(obj, dict) and attr in obj:  # xacro namespaces, YAML mappings (dotify)
            return self._value(getattr(obj, attr), attr)
        if isinstance(obj, str) and attr in _STR_METHODS:
            return _Method(_call_method(obj, attr))
        if isinstance(obj, list | tuple) and attr in _LIST_METHODS:
            return _Method(getattr(obj, attr))
        if isinstance(obj, dict) and attr in _DICT_METHODS:
            return _Method(getattr(obj, attr))
        if isinstance(obj, dict):
            raise NameError(f"name '{attr}' is not defined")
        raise RefusedError(f"the attribute '{attr}' of a {type(obj).__name__} is not allowed in an audited Xacro")

    def _n_subscript(self, node: ast.Subscript) -> Any:
        obj = self.eval(node.value)
        key = self.eval(node.slice)
        if not isinstance(obj, str | list | tuple | dict | range):
            raise RefusedError(f"indexing a {type(obj).__name__} is not allowed")
        return obj[key]

    def _n_slice(self, node: ast.Slice) -> slice:
        parts = [None if p is None else self.eval(p) for p in (node.lower, node.upper, node.step)]
        return slice(*parts)

    def _n_binop(self, node: ast.BinOp) -> Any:
        a, b = self.eval(node.left), self.eval(node.right)
        op = _BINOPS.get(type(node.op))
        if op is None:
            raise RefusedError(f"the operator {type(node.op).__name__} is not allowed")
        _check_binop(node.op, a, b)
        return op(a, b)

    def _n_unaryop(self, node: ast.UnaryOp) -> Any:
        return _UNARY[type(node.op)](self.eval(node.operand))

    def _n_boolop(self, node: ast.BoolOp) -> Any:
        value: Any = None
        for sub in node.values:
            value = self.eval(sub)
            if isinstance(node.op, ast.And) and not value:
                return value
            if isinstance(node.op, ast.Or) and value:
                return value
        return value

    def _n_compare(self, node: ast.Compare) -> Any:
        left = self.eval(node.left)
        for op, right_node in zip(node.ops, node.comparators, strict=True):
            right = self.eval(right_node)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _n_ifexp(self, node: ast.IfExp) -> Any:
        return self.eval(node.body) if self.eval(node.test) else self.eval(node.orelse)

    def _n_tuple(self, node: ast.Tuple) -> Any:
        return tuple(self._items(node.elts))

    def _n_list(self, node: ast.List) -> Any:
        return self._items(node.elts)

    def _n_set(self, node: ast.Set) -> Any:
        return set(self._items(node.elts))

    def _items(self, elts: list[ast.expr]) -> list[Any]:
        out: list[Any] = []
        for e in elts:
            if isinstance(e, ast.Starred):
                out.extend(_limited(self.eval(e.value)))
            else:
                out.append(self.eval(e))
        return out

    def _n_dict(self, node: ast.Dict) -> Any:
        out: dict[Any, Any] = {}
        for k, v in zip(node.keys, node.values, strict=True):
            if k is None:
                out.update(self.eval(v))
            else:
                out[self.eval(k)] = self.eval(v)
        return out

    def _n_joinedstr(self, node: ast.JoinedStr) -> Any:
        parts = []
        for v in node.values:
            if isinstance(v, ast.Constant):
                parts.append(str(v.value))
                continue
            assert isinstance(v, ast.FormattedValue)
            value = self.eval(v.value)
            spec = "" if v.format_spec is None else self.eval(v.format_spec)
            check_spec(str(spec))
            if v.conversion == ord("r"):
                value = repr(value)
            elif v.conversion == ord("s"):
                value = str(value)
            parts.append(format(value, spec))
        return bounded("".join(parts))

    def _n_call(self, node: ast.Call) -> Any:
        fn = self.eval(node.func)
        args = self._items(node.args)
        kwargs: dict[str, Any] = {}
        for kw in node.keywords:
            if kw.arg is None:
                kwargs.update(self.eval(kw.value))
            else:
                kwargs[kw.arg] = self.eval(kw.value)
        for a in (*args, *kwargs.values()):
            if callable(a) and not isinstance(a, dict | _Method) and id(a) not in self.allowed:
                raise RefusedError("only allowed functions may be passed to a function")
        if isinstance(fn, _Method):
            return fn.fn(*args, **kwargs)
        if id(fn) not in self.allowed:
            raise RefusedError(f"calling a {type(fn).__name__} is not allowed in an audited Xacro")
        return fn(*args, **kwargs)

    def _comprehension(self, generators: list[ast.comprehension], emit: Callable[[], None]) -> None:
        def loop(i: int) -> None:
            if i == len(generators):
                emit()
                return
            gen = generators[i]
            if gen.is_async:
                raise RefusedError("async comprehensions are not allowed")
            for item in _limited(self.eval(gen.iter)):
                self.budget.spend()
                self._bind(gen.target, item)
                if all(self.eval(cond) for cond in gen.ifs):
                    loop(i + 1)

        self.scopes.append({})
        try:
            loop(0)
        finally:
            self.scopes.pop()

    def _bind(self, target: ast.expr, value: Any) -> None:
        if isinstance(target, ast.Name):
            if target.id.startswith("_"):
                raise RefusedError(f"the name '{target.id}' is not allowed")
            self.scopes[-1][target.id] = value
        elif isinstance(target, ast.Tuple | ast.List):
            values = list(_limited(value))
            if len(values) != len(target.elts):
                raise ValueError(f"cannot unpack {len(values)} values into {len(target.elts)} names")
            for t, v in zip(target.elts, values, strict=True):
                self._bind(t, v)
        else:
            raise RefusedError("only names can be bound in a comprehension")

    def _n_listcomp(self, node: ast.ListComp) -> Any:
        out: list[Any] = []
        self._comprehension(node.generators, lambda: out.append(self.eval(node.elt)))
        return out

    def _n_generatorexp(self, node: ast.GeneratorExp) -> Any:
        out: list[Any] = []  # evaluated eagerly: the budget applies where the loop runs
        self._comprehension(node.generators, lambda: out.append(self.eval(node.elt)))
        return iter(out)

    def _n_setcomp(self, node: ast.SetComp) -> Any:
        out: set[Any] = set()
        self._comprehension(node.generators, lambda: out.add(self.eval(node.elt)))
        return out

    def _n_dictcomp(self, node: ast.DictComp) -> Any:
        out: dict[Any, Any] = {}

        def emit() -> None:
            out[self.eval(node.key)] = self.eval(node.value)

        self._comprehension(node.generators, emit)
        return out


class _Method:
    """A bound method of a plain value that the allow-list admits."""

    __slots__ = ("fn",)

    def __init__(self, fn: Callable[..., Any]) -> None:
        self.fn = fn

    def __call__(self, *args: Any, **kwargs: Any) -> Any:  # so map(str.upper, ...) works
        return self.fn(*args, **kwargs)


def bounded_range(*args: int) -> range:
    r = range(*args)
    if len(r) > MAX_SIZE:
        raise RefusedError(f"a range of more than {MAX_SIZE} numbers", "limit")
    return r


# math functions whose cost grows without bound with their argument
_SLOW_MATH = frozenset({"factorial", "comb", "perm", "prod"})


def math_names() -> dict[str, Any]:
    return {k: v for k, v in vars(math).items() if not k.startswith("_") and k not in _SLOW_MATH}


BUILTINS: dict[str, Any] = {
    "abs": abs,
    "all": all,
    "any": any,
    "bool": bool,
    "chr": chr,
    "dict": dict,
    "divmod": divmod,
    "enumerate": enumerate,
    "filter": filter,
    "float": float,
    "int": int,
    "len": len,
    "list": list,
    "map": map,
    "max": max,
    "min": min,
    "ord": ord,
    "range": bounded_range,
    "repr": repr,
    "reversed": reversed,
    "round": round,
    "set": set,
    "sorted": sorted,
    "str": str,
    "sum": sum,
    "tuple": tuple,
    "zip": zip,
}
"""Builtins an expression may call: pure functions of their arguments."""
