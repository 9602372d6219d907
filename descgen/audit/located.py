"""A controller parameter as the element of a finding (``registry.at``): located at its value.

Audit rules about one parameter of a controller (a joint name in ``joints``, ``frame_id``,
``update_rate``) point at that value in the controllers file, not at the controller; a
parameter the file does not give (or a spec's controller, whose values carry no place)
falls back to the controller's own key (``Controller.where_of``)."""

from __future__ import annotations

from descgen.core.findings import Where
from descgen.core.model import Controller


class Param:
    def __init__(self, c: Controller, key: str, index: int | None = None) -> None:
        self.where: Where = c.where_of(key, index)
        self.subject = f"controller:{c.name}"
