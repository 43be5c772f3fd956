"""Reading one TOML table of a scene: typed getters that name the key on error.

Every getter records the key it read; :meth:`Table.finish` then refuses any key that
was not read, so a misspelt key is an error instead of a silent default.
"""

from __future__ import annotations

import math

from corliss import units
from corliss.errors import InputError

_MISSING = object()
#: The least length of a part that exists [m].
MICRON_m = 1e-6
#: A port's or a pipe's coefficient of discharge [-]: valve ports have 0.6 to 0.9, a
#: perfect nozzle 1; below a tenth no port passes steam (1e-12 was taken for one).
DISCHARGE_COEFFICIENT = (0.1, 1.0)


def _closest(key: str, candidates) -> str | None:
    """The candidate most like ``key`` (a misspelling of it), or None."""
    import difflib
    near = difflib.get_close_matches(str(key), [str(c) for c in candidates], n=1, cutoff=0.7)
    return near[0] if near else None


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
    """

    def __init__(self, data: dict, name: str, barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa):
        if not isinstance(data, dict):
            raise InputError(name, data, "a table (a [section] in the scene)")
        self.data = data
        self.name = name
        self.barometer_Pa = barometer_Pa
        self._read: set[str] = set()

    def key(self, key: str) -> str:
        """Dotted name of ``key`` in this table."""
        return f"{self.name}.{key}" if self.name else key

    def has(self, key: str) -> bool:
        self._read.add(key)
        return key in self.data

    def raw(self, key: str, default=_MISSING):
        """The value as written; a missing key without a default is an error."""
        self._read.add(key)
        if key in self.data:
            return self.data[key]
        if default is _MISSING:
            near = _closest(key, [k for k in self.data if k not in self._read])
            hint = f" (the scene has {self.key(near)}: a misspelling?)" if near else ""
            raise InputError(self.key(key), None, f"a value: this key is required{hint}")
        return default

    def quantity(self, key: str, kind: str, default=_MISSING, *,
                 within: tuple[float, float] | None = None) -> float:
        """A quantity string in SI, inside its kind's physical range
        (:data:`corliss.units.RANGES`) narrowed to ``within`` [SI] if given."""
        raw = self.raw(key, default)
        return units.parse(raw, kind, self.key(key), barometer_Pa=self.barometer_Pa,
                           within=within)

    def length(self, key: str, default=_MISSING, *, positive: bool = False,
               within: tuple[float, float] | None = None) -> float:
        """A length [m]; ``positive``: at least a micron (a part that exists)."""
        if positive and within is None:
            within = (MICRON_m, math.inf)
        return self.quantity(key, "length", default, within=within)

    def pressure(self, key: str, default=_MISSING) -> float:
        v = self.quantity(key, "pressure", default)
        if not v > 0.0:
            raise InputError(self.key(key), self.raw(key, default),
                             "a pressure above absolute zero (check gauge and vacuum readings "
                             f"against the barometer, {self.barometer_Pa / units.PSI_Pa:.4g} psia)")
        return v

    def angle(self, key: str, default=_MISSING, *,
              within: tuple[float, float] | None = None) -> float:
        """An angle [rad], narrowed to ``within`` [rad] if given."""
        return self.quantity(key, "angle", default, within=within)

    def number(self, key: str, default=_MISSING, *,
               within: tuple[float, float] | None = None) -> float:
        """A plain finite number (a fraction, a ratio), inside ``within`` if given."""
        v = self.raw(key, default)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InputError(self.key(key), v, "a plain number")
        if within is not None and not within[0] <= v <= within[1]:
            raise InputError(self.key(key), v, f"a number from {within[0]:g} to {within[1]:g}")
        return float(v)

    def integer(self, key: str, default=_MISSING, *, within: tuple[int, int] = (0, 10_000)
                ) -> int:
        """A whole number within ``within`` (by default 0 to 10,000: a count)."""
        v = self.raw(key, default)
        if isinstance(v, bool) or not isinstance(v, int):
            raise InputError(self.key(key), v, "a whole number")
        if not within[0] <= v <= within[1]:
            raise InputError(self.key(key), v, f"a whole number from {within[0]} to {within[1]}")
        return v

    def string(self, key: str, default=_MISSING) -> str:
        v = self.raw(key, default)
        if not isinstance(v, str):
            raise InputError(self.key(key), v, "a string")
        return v

    def choice(self, key: str, choices: tuple[str, ...], default=_MISSING) -> str:
        v = self.raw(key, default)
        if v not in choices:
            raise InputError(self.key(key), v, "one of " + ", ".join(repr(c) for c in choices))
        return v

    def finish(self) -> None:
        """Refuse keys that no getter read (misspellings, keys of another gear)."""
        unknown = sorted(set(self.data) - self._read)
        if unknown:
            k = unknown[0]
            known = ", ".join(sorted(self._read))
            near = _closest(k, self._read)
            hint = f"{self.key(near)}? " if near else ""
            raise InputError(self.key(k), self.data[k],
                             f"a known key; {hint}{self.name or 'the scene'} takes: {known}")
