"""Python's cyclic collector paused where descgen makes objects that all stay alive.

Parsing a spec or an expanded Xacro, and a whole ``validate``, ``generate`` or ``check``, make
hundreds of thousands of objects (YAML nodes, the spec, the model, DOM and lxml trees) and
next to no cyclic garbage, so a collection during them traverses everything and frees nothing:
at 1000 links ~60 passes were ~140 ms of loading a spec, two passes ~0.1 s of expanding its
Xacro, and the rest of a ``generate`` ~0.12 s, with the same peak memory. Reference counting
still frees whatever is dropped; a cycle made meanwhile waits for the next pass.
"""

from __future__ import annotations

import contextlib
import gc
from collections.abc import Iterator


@contextlib.contextmanager
def paused(pause: bool = True, ending: bool = False) -> Iterator[None]:
    """The collector off inside (when ``pause``), and left as it was found afterwards, also when
    the body raises: callers run inside the test suite's process too.

    ``ending``: the process ends after the body (the console script, ``python -m descgen``).
    Then everything alive is frozen instead and the collector is not switched back on: switching
    it on starts a pass over every object the command made, and the interpreter's last
    collection at exit traverses them all again, to free memory the exit frees anyway (together
    ~0.15 s of a 1000-link ``generate``, 15 % of it)."""
    was = gc.isenabled()
    if pause:
        gc.disable()
    try:
        yield
    finally:
        if ending:
            gc.freeze()
        elif was and pause:
            gc.enable()
