"""Registries by name: valve gears and governors, each read from a scene table."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any, Callable

from corliss.errors import InputError
from corliss.keys.declared import Key, KeyGroup, group


@dataclass(frozen=True)
class RegistryEntry:
    """How to read a scene table into a spec and build the object from it.

    Parameters
    ----------
    name : str
        The registry name a scene's ``type`` gives.
    summary : str
        One line about it.
    parse : callable
        :class:`corliss.keys.toml_table.Table` -> spec.
    build : callable
        Spec -> gear or governor.
    keys : KeyGroup
        The keys its table takes (the registry adds ``type``); the table is read
        through them, and the scene reference is printed from them.
    """

    name: str
    summary: str
    parse: Callable[..., Any]                # corliss.keys.toml_table.Table -> spec
    build: Callable[..., Any]                # spec -> gear or governor
    keys: KeyGroup | None = None


class Registry(dict):
    """Entries by name; an unknown name is an :class:`InputError` naming the scene key
    and listing what there is.

    Parameters
    ----------
    key : str
        The scene key that names an entry (``"valve_gear.type"``).
    noun : str
        What an entry is (``"gear"``).
    """

    def __init__(self, key: str, noun: str):
        super().__init__()
        self.key, self.noun = key, noun

    def register(self, entry: RegistryEntry) -> RegistryEntry:
        """Add an entry, its key group led by the ``type`` key.

        Parameters
        ----------
        entry : RegistryEntry
            The entry.

        Returns
        -------
        RegistryEntry
            The entry as registered.
        """
        if entry.keys is None:
            raise TypeError(f"{self.noun} {entry.name!r}: register it with the key group "
                            "its parser reads (corliss.keys.declared)")
        if "type" not in entry.keys:
            kind = Key("type", "string", f"The {self.noun}'s registry name, "
                       f"\"{entry.name}\" (corliss list {self.noun}s).")
            entry = replace(entry, keys=group(entry.keys.name, entry.keys.doc, kind,
                                              entry.keys))
        self[entry.name] = entry
        return entry

    def lookup(self, name: object) -> RegistryEntry:
        """The entry called ``name``.

        Parameters
        ----------
        name : object
            A registry name.

        Returns
        -------
        RegistryEntry
            Its entry.
        """
        if name not in self:
            raise InputError(self.key, name, f"a {self.noun} from the registry: "
                             + ", ".join(sorted(self)))
        return self[name]
