"""No pydantic plugin lookup in descgen's command-line process.

pydantic looks for plugins (the ``pydantic`` entry points of every installed distribution)
the first time it builds a validator, and imports ``importlib.metadata`` for it (email,
zipfile, csv, ...) even when ``PYDANTIC_DISABLE_PLUGINS`` turns plugins off: ~25-30 ms of
every ``validate`` and ``check`` (issue 17), ~10% of ``validate``. descgen's spec validation
takes no plugins (they observe an application's validations, e.g. for tracing), so the
command line's process gets a loader that finds none, which is what
``PYDANTIC_DISABLE_PLUGINS=__all__`` means. The user's setting wins: when
``PYDANTIC_DISABLE_PLUGINS`` leaves some plugins on (it names the ones to leave out), pydantic's
own loader runs. Anything else pydantic asks of the loader loads the real one.

Only ``descgen.cli.main`` calls :func:`no_plugin_lookup`; importing descgen as a library
changes nothing in pydantic.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import sys
import types
from collections.abc import Iterator
from importlib.machinery import ModuleSpec
from typing import TYPE_CHECKING, Any, cast

if TYPE_CHECKING:  # importlib.abc itself costs a few ms of imports
    from importlib.abc import Loader

LOADER = "pydantic.plugin._loader"
_OFF = ("__all__", "1", "true")  # the values pydantic reads as "no plugins at all"


class _NoPlugins(types.ModuleType):
    """Stands for pydantic's plugin loader: ``get_plugins()`` finds none."""

    @staticmethod
    def get_plugins() -> tuple[()]:
        return ()

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):  # what the import system probes (__path__, ...): a plain module's answer
            raise AttributeError(name)
        # a name this stand-in does not have (a newer pydantic): the real loader from now on
        _stop()
        if sys.modules.get(LOADER) is self:
            del sys.modules[LOADER]
        return getattr(importlib.import_module(LOADER), name)


class _Finder:
    """On sys.meta_path: the stand-in when pydantic imports its loader and no plugin is wanted."""

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> ModuleSpec | None:
        if fullname != LOADER or os.environ.get("PYDANTIC_DISABLE_PLUGINS", "__all__") not in _OFF:
            return None
        return ModuleSpec(LOADER, cast("Loader", self))

    def create_module(self, spec: ModuleSpec) -> types.ModuleType:
        return _NoPlugins(spec.name)

    def exec_module(self, module: types.ModuleType) -> None:
        pass


_FINDER = _Finder()


def _stop() -> None:
    if _FINDER in sys.meta_path:
        sys.meta_path.remove(_FINDER)


@contextlib.contextmanager
def no_plugin_lookup() -> Iterator[None]:
    """Inside: pydantic's plugin loader, when first imported, finds none (see the module
    docstring). Nothing is imported now (``descgen --help`` loads no pydantic). Afterwards the
    stand-in is gone, so a process that runs ``cli.main`` and then validates on its own (the
    test suite, a library user) gets pydantic's own loader for every later validator."""
    installed = LOADER not in sys.modules and _FINDER not in sys.meta_path
    if installed:
        sys.meta_path.insert(0, _FINDER)
    try:
        yield
    finally:
        if installed:
            _stop()
            if isinstance(sys.modules.get(LOADER), _NoPlugins):
                del sys.modules[LOADER]
