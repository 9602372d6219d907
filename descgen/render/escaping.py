"""Autoescaped template output written as markupsafe escapes it, at a fifth of the cost.

With autoescape on, jinja2 compiles every ``{{ value }}`` into ``escape(value)``: markupsafe
builds a ``Markup`` object for each (four Python calls), only for the template to join the
pieces into one text. A 1000-link URDF and its Xacro write ~150,000 values (names, numbers
the filters formatted, indentation), and those calls were ~0.09 s of ``generate``.

:class:`TextEscaping` is the code generator jinja2 documents for changing the Python a
template compiles to (``Environment.code_generator_class``): an output expression calls
:func:`escape_text` instead, which gives the same characters as ``str(escape(value))``
(tests/test_render_escaping.py compares them on hostile values and on whole packages). The
escaping itself is unchanged: a text without ``& < > ' "`` is returned as it is (markupsafe
would return the same characters), anything else goes through markupsafe. Only output
expressions change; ``escape`` elsewhere (constants folded at compile time, filters) is
jinja2's own, and the value of an output expression is only ever joined into text.
"""

from __future__ import annotations

import re
from typing import Any

from jinja2.compiler import CodeGenerator, Frame
from jinja2.nodes import Expr
from markupsafe import escape

_SPECIAL = re.compile(r"[&<>'\"]")  # what markupsafe escapes (to &amp; &lt; &gt; &#39; &#34;)


def escape_text(value: Any) -> str:
    """``str(markupsafe.escape(value))``."""
    if type(value) is str and _SPECIAL.search(value) is None:
        return value
    return str(escape(value))


class TextEscaping(CodeGenerator):
    """jinja2's code generator, with autoescaped output written by the environment's
    ``escape_text`` (an attribute of the environment classes in render/__init__.py, the only
    name a compiled template module holds besides jinja2's runtime)."""

    def _output_child_pre(self, node: Expr, frame: Frame, finalize: Any) -> None:
        if frame.eval_ctx.volatile or not frame.eval_ctx.autoescape:
            super()._output_child_pre(node, frame, finalize)  # {% autoescape %} decided at run time, or none
            return
        self.write("environment.escape_text(")
        if finalize.src is not None:
            self.write(finalize.src)
