"""Reading one TOML table of a scene: typed getters that name the key on error.

Every getter records the key it read; :meth:`Table.finish` then refuses any key that
was not read, so a misspelt key is an error instead of a silent default.

A table bound to a :class:`corliss.keys.declared.KeyGroup` reads only the keys the group
declares (any other read is a :class:`corliss.keys.declared.UndeclaredKeyError`, a
programming error), and :meth:`Table.get` reads a key by its declaration: its kind,
default and range written once, where the scene reference is printed from.
"""

from __future__ import annotations

import math

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.declared import MICRON_m, REQUIRED, Derived, KeyGroup, UndeclaredKeyError

_MISSING = object()
#: The getter each plain kind is read with (a quantity kind is read by its units).
_GETTERS = {"number": "number", "integer": "integer", "string": "string", "choice": "choice"}
#: A port's or a pipe's coefficient of discharge [-]: valve ports have 0.6 to 0.9, a
#: perfect nozzle 1; below a tenth no port passes steam (1e-12 was taken for one).
DISCHARGE_COEFFICIENT = (0.1, 1.0)


def _closest(key: str, candidates) -> str | None:
    """The candidate most like ``key`` (a misspelling of it), or None."""
    import difflib
    near = difflib.get_close_matches(str(key), [str(c) for c in candidates], n=1, cutoff=0.7)
    return near[0] if near else None


#: Values :meth:`Table.get` keeps for each key group (its reads of a study's scenes).
READS_KEPT = 4096
#: Each key group's kept reads, by the group's id (with the group, so an id reused by
#: another object is not taken for it).
_READS: dict[int, tuple] = {}


def _reads_of(group) -> dict:
    """The reads kept for a key group."""
    entry = _READS.get(id(group))
    if entry is not None and entry[0] is group:
        return entry[1]
    entry = _READS[id(group)] = (group, {})
    return entry[1]


def _immutable(value) -> bool:
    """Whether a value read may be handed out again: a number, text, flag, None, or a
    tuple of them (a list as written is the scene's own, and is not kept)."""
    if value is None or type(value) in (float, int, str, bool):
        return True
    return type(value) is tuple and all(type(v) in (float, int, str, bool) for v in value)


class Table:
    """A scene table with its dotted name and the scene's barometer.

    Parameters
    ----------
    data : dict
        The TOML table.
    name : str
        Its dotted name in the scene, e.g. ``"valve_gear"``.
    barometer_Pa : float
        Atmospheric pressure [Pa] for gauge readings.
    keys : KeyGroup, optional
        The keys the table may hold; bound, a read of any other key is an
        :class:`~corliss.keys.declared.UndeclaredKeyError`, and a getter called without a
        default or range takes the declared ones.
    """

    def __init__(self, data: dict, name: str, barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa,
                 keys: KeyGroup | None = None):
        if not isinstance(data, dict):
            raise InputError(name, data, "a table (a [section] in the scene)")
        self.data = data
        self.name = name
        self.barometer_Pa = barometer_Pa
        self.keys = keys
        self._read: set[str] = set()
        #: The bound group's kept reads (:func:`_reads_of`), found at the first read.
        self._kept: dict | None = None

    def bind(self, keys: KeyGroup) -> "Table":
        """Bind the table to the group of keys it may hold (a gear's or governor's,
        known once its ``type`` is read).

        Parameters
        ----------
        keys : KeyGroup
            The declared keys; any key read so far must be among them, but ``type``
            (read to choose the group: the registry declares it).

        Returns
        -------
        Table
            This table.
        """
        self.keys = keys
        self._kept = None
        for k in self._read - {"type"}:
            keys[k]
        return self

    def bound(self, keys: KeyGroup) -> "Table":
        """This table bound to ``keys`` if it is not bound yet (a parser called with a
        bare table, outside the loader), else as it is.

        Parameters
        ----------
        keys : KeyGroup
            The parser's key group.

        Returns
        -------
        Table
            This table.
        """
        return self.bind(keys) if self.keys is None else self

    def _declared(self, key: str, getter: str | None = None):
        """The declaration of ``key`` (None for an unbound table); reading a key the
        bound group does not declare, or with a getter of another kind, is a
        programming error."""
        if self.keys is None:
            return None
        k = self.keys[key]
        if getter is not None and getter != k.kind and not (
                getter == "quantity" and k.is_quantity) and not (
                getter == "raw"):
            raise UndeclaredKeyError(f"{self.key(key)} is declared a {k.kind}, read as a "
                                     f"{getter}: read it with Table.get")
        return k

    def _what(self, key: str) -> str:
        """`` (what the key is)`` from its declaration, for a message; empty unbound."""
        if self.keys is None:
            return ""
        return f" ({self.keys[key].doc.rstrip('.')})"

    def _default(self, key: str, default, getter: str):
        """``default`` if given, else the declared one (when it is a value)."""
        k = self._declared(key, getter)
        if default is _MISSING and k is not None and k.default is not REQUIRED \
                and k.default is not None and not isinstance(k.default, Derived):
            return k.default
        return default

    def _within(self, key: str, within):
        """``within`` if given, else the declared range."""
        k = self._declared(key)
        return k.within if within is None and k is not None else within

    def key(self, key: str) -> str:
        """Dotted name of ``key`` in this table.

        Parameters
        ----------
        key : str
            A key of the table.

        Returns
        -------
        str
            ``"table.key"``.
        """
        return f"{self.name}.{key}" if self.name else key

    def has(self, key: str) -> bool:
        """Whether the scene gives ``key`` (which counts as reading it).

        Parameters
        ----------
        key : str
            A declared key.

        Returns
        -------
        bool
            True when the table holds it.
        """
        self._declared(key)
        self._read.add(key)
        return key in self.data

    def get(self, key: str, default=_MISSING, *, within: tuple | None = None):
        """``key`` read by its declaration: its kind, default, range and choices.

        A value read once is kept (:data:`READS_KEPT` a key group) and given again for
        the same key group, key, value as written, default, range and barometer: a
        study loads its base scene's unchanged keys once, not once a run.  Only a
        value that was read without error is kept (a refused one is read again, and
        refused again, each time).

        Parameters
        ----------
        key : str
            A key the bound group declares.
        default : object, optional
            For an absent key whose declared default is
            :class:`~corliss.keys.declared.Derived`: the value computed, as a scene would write
            it; :data:`~corliss.keys.declared.REQUIRED`
            where the settings read make an optional key required.
        within : (float, float), optional
            A range [SI] found from other keys, narrowing the declared one.

        Returns
        -------
        object
            The value in SI for a quantity (a pair ``(head, crank)`` for a key given
            once or per end), a float, int, str or bool for a plain kind, the value as
            written for the others; None for an absent optional key.
        """
        if self.keys is None:
            return self._get(key, default, within=within)
        raw = self.data.get(key, _MISSING)
        # a float by its repr: -0.0 is not 0.0 (equal, and hashed alike)
        memo_key = (key, type(raw), repr(raw) if type(raw) is float else raw, default,
                    within, self.barometer_Pa)
        kept = self._kept
        if kept is None:
            kept = self._kept = _reads_of(self.keys)
        try:
            value = kept.get(memo_key, _MISSING)
        except TypeError:           # a list, or a default that cannot be hashed
            return self._get(key, default, within=within)
        if value is not _MISSING:
            # (kept only after a read of this group's: the key is declared)
            self._read.add(key)
            return value
        value = self._get(key, default, within=within)
        if _immutable(value):
            if len(kept) >= READS_KEPT:
                kept.clear()
            kept[memo_key] = value
        return value

    def _get(self, key: str, default=_MISSING, *, within: tuple | None = None):
        """:meth:`get`, read each time."""
        if self.keys is None:
            raise UndeclaredKeyError(f"{self.key(key)}: Table.get needs a table bound to "
                                     "its key group")
        k = self._declared(key)
        if default is REQUIRED:
            default = _MISSING
        elif default is _MISSING:
            if isinstance(k.default, Derived) and key not in self.data:
                raise UndeclaredKeyError(f"{self.key(key)}: its default is derived "
                                         f"({k.default.text}); pass it to Table.get")
            default = _MISSING if k.default is REQUIRED else k.default
        if default is None and key not in self.data:
            self._read.add(key)
            return None
        if k.within is not None and within is not None:
            within = (max(k.within[0], within[0]), min(k.within[1], within[1]))
        within = k.within if within is None else within
        if k.ends:
            return self._ends(key, k.kind, default, within)
        if k.kind == "pressure":
            return self.pressure(key, default)
        if k.is_quantity:
            return self.quantity(key, k.kind, default, within=within)
        if k.kind == "number":
            return self.number(key, default, within=within)
        if k.kind == "integer":
            return self.integer(key, default, **({"within": within} if within else {}))
        if k.kind == "string":
            return self.string(key, default)
        if k.kind == "choice":
            return self.choice(key, k.choices, default)
        if k.kind == "flag":
            v = self.raw(key, default)
            if not isinstance(v, bool):
                raise InputError(self.key(key), v, "true or false")
            return v
        return self.raw(key, default)

    def _ends(self, key: str, kind: str, default, within) -> tuple[float, float]:
        """A quantity given once for both ends, or as [head, crank]."""
        raw = self.raw(key, default)
        if isinstance(raw, list):
            if len(raw) != 2:
                raise InputError(self.key(key), raw, "one value, or a list [head, crank] of two")
            head, crank = (units.parse(v, kind, self.key(key), barometer_Pa=self.barometer_Pa,
                                       within=within) for v in raw)
            return head, crank
        v = units.parse(raw, kind, self.key(key), barometer_Pa=self.barometer_Pa, within=within)
        return (v, v)

    def raw(self, key: str, default=_MISSING):
        """The value as written; a missing key without a default is an error.

        Parameters
        ----------
        key : str
            A declared key.
        default : object, optional
            The value of an absent key; without one (and none declared) the key is
            required.

        Returns
        -------
        object
            The value as the scene writes it.
        """
        default = self._default(key, default, "raw")
        self._read.add(key)
        if key in self.data:
            return self.data[key]
        if default is _MISSING:
            near = _closest(key, [k for k in self.data if k not in self._read])
            hint = f" (the scene has {self.key(near)}: a misspelling?)" if near else ""
            if not near and self.keys is not None:
                # a key given in its place that this table does not take (a slide
                # valve's lead on a link motion, which takes only the advance)
                stray = sorted(k for k in self.data if k not in self.keys)
                if stray:
                    hint = (f" (the scene has {', '.join(self.key(k) for k in stray)}, "
                            f"which {self.keys.name} does not take)")
            raise InputError(self.key(key), None, f"a value: this key is required{hint}")
        return default

    def quantity(self, key: str, kind: str, default=_MISSING, *,
                 within: tuple[float, float] | None = None) -> float:
        """A quantity string in SI, inside its kind's physical range
        (:data:`corliss.keys.units.RANGES`) narrowed to ``within`` [SI] if given.

        Parameters
        ----------
        key : str
            The key.
        default : object, optional
            The value of an absent key, as a scene writes it; without one, the declared
            default, or the key is required.
        kind : str
            A kind of :mod:`corliss.keys.units` (the declared one).
        within : (float, float), optional
            The key's own range [SI]; without one, the declared range.

        Returns
        -------
        float
            The value [SI].
        """
        default = self._default(key, default, kind)
        within = self._within(key, within)
        raw = self.raw(key, default)
        return units.parse(raw, kind, self.key(key), barometer_Pa=self.barometer_Pa,
                           within=within)

    def length(self, key: str, default=_MISSING, *, positive: bool = False,
               within: tuple[float, float] | None = None) -> float:
        """A length [m]; ``positive``: at least a micron (a part that exists).

        Parameters
        ----------
        key : str
            The key.
        default : object, optional
            The value of an absent key, as a scene writes it; without one, the declared
            default, or the key is required.
        positive : bool
            At least a micron.
        within : (float, float), optional
            The key's own range [SI]; without one, the declared range.

        Returns
        -------
        float
            The length [m].
        """
        if positive and within is None:
            within = (MICRON_m, math.inf)
        return self.quantity(key, "length", default, within=within)

    def pressure(self, key: str, default=_MISSING) -> float:
        """An absolute pressure [Pa], above absolute zero.

        Parameters
        ----------
        key : str
            The key.
        default : str, optional
            The value of an absent key, as a scene writes it.

        Returns
        -------
        float
            The pressure [Pa] absolute.
        """
        default = self._default(key, default, "pressure")
        v = self.quantity(key, "pressure", default)
        if not v > 0.0:
            raise InputError(self.key(key), self.raw(key, default),
                             "a pressure above absolute zero (check gauge and vacuum readings "
                             f"against the barometer, {self.barometer_Pa / units.PSI_Pa:.4g} psia)")
        return v

    def angle(self, key: str, default=_MISSING, *,
              within: tuple[float, float] | None = None) -> float:
        """An angle [rad], narrowed to ``within`` [rad] if given.

        Parameters
        ----------
        key : str
            The key.
        default : object, optional
            The value of an absent key, as a scene writes it; without one, the declared
            default, or the key is required.
        within : (float, float), optional
            The key's own range [SI]; without one, the declared range.

        Returns
        -------
        float
            The angle [rad].
        """
        return self.quantity(key, "angle", default, within=within)

    def number(self, key: str, default=_MISSING, *,
               within: tuple[float, float] | None = None) -> float:
        """A plain finite number (a fraction, a ratio), inside ``within`` if given.

        Parameters
        ----------
        key : str
            The key.
        default : object, optional
            The value of an absent key, as a scene writes it; without one, the declared
            default, or the key is required.
        within : (float, float), optional
            Its range; without one, the declared range.

        Returns
        -------
        float
            The number.
        """
        default = self._default(key, default, "number")
        within = self._within(key, within)
        v = self.raw(key, default)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InputError(self.key(key), v, "a plain number")
        if within is not None and not within[0] <= v <= within[1]:
            raise InputError(self.key(key), v, f"a number from {within[0]:g} to {within[1]:g}"
                             + self._what(key))
        return float(v)

    def integer(self, key: str, default=_MISSING, *, within: tuple[int, int] | None = None
                ) -> int:
        """A whole number within ``within`` (by default 0 to 10,000: a count).

        Parameters
        ----------
        key : str
            The key.
        default : object, optional
            The value of an absent key, as a scene writes it; without one, the declared
            default, or the key is required.
        within : (int, int), optional
            Its range; without one, the declared range, else 0 to 10,000.

        Returns
        -------
        int
            The number.
        """
        default = self._default(key, default, "integer")
        within = self._within(key, within) or (0, 10_000)
        v = self.raw(key, default)
        if isinstance(v, bool) or not isinstance(v, int):
            raise InputError(self.key(key), v, "a whole number")
        if not within[0] <= v <= within[1]:
            raise InputError(self.key(key), v, f"a whole number from {within[0]} to {within[1]}"
                             + self._what(key))
        return v

    def string(self, key: str, default=_MISSING) -> str:
        """A string.

        Parameters
        ----------
        key : str
            The key.
        default : str, optional
            The value of an absent key.

        Returns
        -------
        str
            The string as written.
        """
        default = self._default(key, default, "string")
        v = self.raw(key, default)
        if not isinstance(v, str):
            raise InputError(self.key(key), v, "a string")
        return v

    def choice(self, key: str, choices: tuple[str, ...] | None = None, default=_MISSING) -> str:
        """One of ``choices`` (by default the declared ones).

        Parameters
        ----------
        key : str
            The key.
        choices : tuple of str, optional
            The words it takes.
        default : str, optional
            The value of an absent key.

        Returns
        -------
        str
            The word.
        """
        default = self._default(key, default, "choice")
        if choices is None:
            choices = self._declared(key).choices
        v = self.raw(key, default)
        if v not in choices:
            raise InputError(self.key(key), v, "one of " + ", ".join(repr(c) for c in choices))
        return v

    def finish(self, elsewhere: dict | None = None) -> None:
        """Refuse keys that no getter read (misspellings, keys of another gear).

        A key the bound group declares but these settings did not read is refused
        saying when it is read; any other names the closest declared key, and the types
        in ``elsewhere`` that do take it.

        Parameters
        ----------
        elsewhere : dict, optional
            ``{type name: KeyGroup}`` of the other types this table could be (the
            other gears of a ``[valve_gear]``), to say which take an unknown key.
        """
        unknown = sorted(set(self.data) - self._read)
        if unknown:
            k = unknown[0]
            if self.keys is not None and k in self.keys:
                when = self.keys[k].when
                raise InputError(self.key(k), self.data[k], f"no {k} here: {self.keys.name} "
                                 f"reads it only {when or 'with other settings'} (corliss "
                                 f"explain {self.name}.{k})")
            names = self.keys.names if self.keys is not None else self._read
            known = ", ".join(sorted(names))
            near = _closest(k, names)
            hint = f"{self.key(near)}? " if near else ""
            who = self.name or "the scene"
            if self.keys is not None and self.name in ("valve_gear", "lp_valve_gear",
                                                        "governor"):
                who = f"{self.name} of type {self.keys.name}"
            takers = sorted(n for n, g in (elsewhere or {}).items()
                            if g is not self.keys and k in g)
            other = f" ({k} is a key of {', '.join(takers)})" if takers else ""
            raise InputError(self.key(k), self.data[k],
                             f"a known key; {hint}{who} takes: {known}{other}")
