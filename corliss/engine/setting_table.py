"""A quantity of a governed gear tabulated over its settings, each setting's found
when first needed and read linearly between them.

The speed loop reads a governed gear's port areas over a grid of settings
(:func:`corliss.engine.transient.build_tables`); the quantities a turn reads besides
(each end's cut-off for the turn's row, the valve edges' leak scales) are tabulated on
the same grid by :class:`SettingTable`.  Finding a setting's value costs the gear's
events or openings over a turn, and a load step visits a few settings, so each is found
only when a turn first reads beside it.
"""

from __future__ import annotations

from typing import Callable

import numpy as np


class SettingTable:
    """Values of a gear's quantity at tabulated settings, found lazily, read linearly
    between them (``numpy.interp`` on the two settings either side, clamped to the
    table's ends).

    Parameters
    ----------
    settings : ndarray
        The settings tabulated [-], increasing.
    find : callable
        Setting [-] -> the quantity's values there, a sequence of floats of a fixed
        length (NaN where undefined).
    """

    def __init__(self, settings, find: Callable[[float], object]):
        self.settings = np.asarray(settings, dtype=float)
        self.find = find
        self.values: np.ndarray | None = None
        self.known = np.zeros(self.settings.size, dtype=bool)

    def _fill(self, j: int) -> None:
        v = np.asarray(self.find(float(self.settings[j])), dtype=float)
        if self.values is None:
            self.values = np.full((v.size, self.settings.size), np.nan)
        self.values[:, j] = v
        self.known[j] = True

    def at(self, setting: float) -> np.ndarray:
        """The quantity's values at a setting, linear between the tabulated ones.

        Parameters
        ----------
        setting : float
            The gear's setting [-]; beyond the table, its end's.

        Returns
        -------
        ndarray
            One value per component of ``find``'s result [its unit].
        """
        n = self.settings.size
        k = min(max(int(np.searchsorted(self.settings, setting, side="right")) - 1, 0),
                max(n - 2, 0))
        for j in range(k, min(k + 2, n)):
            if not self.known[j]:
                self._fill(j)
        assert self.values is not None
        if n == 1:
            return self.values[:, 0].copy()
        g = self.settings[k:k + 2]
        return np.array([np.interp(setting, g, row[k:k + 2]) for row in self.values])
