"""Registries by name: valve gears and governors, each read from a scene table."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from corliss.errors import InputError


@dataclass(frozen=True)
class RegistryEntry:
    """How to read a scene table into a spec and build the object from it."""

    name: str
    summary: str
    parse: Callable[[object], object]        # corliss.tables.Table -> spec
    build: Callable[[object], object]        # spec -> gear or governor


class Registry(dict):
    """Entries by name; an unknown name is an :class:`InputError` naming the scene key
    and listing what there is."""

    def __init__(self, key: str, noun: str):
        super().__init__()
        self.key, self.noun = key, noun

    def register(self, entry: RegistryEntry) -> RegistryEntry:
        """Add an entry."""
        self[entry.name] = entry
        return entry

    def lookup(self, name: object) -> RegistryEntry:
        """The entry called ``name``."""
        if name not in self:
            raise InputError(self.key, name, f"a {self.noun} from the registry: "
                             + ", ".join(sorted(self)))
        return self[name]
