"""A light table of named numpy columns: what a steady run builds instead of a DataFrame.

Importing pandas costs about 0.25 s, a fifth of a warm ``corliss run``; a steady run
needs none of it to compute its summary and write its CSVs.  The engine builds its
tables as :class:`Frame` (columns of equal length, in order), reads them with the small
part of pandas' interface it uses (``frame[name]``, ``frame[mask]``, ``name in frame``,
``frame.iloc[i]``, ``len(frame)``, a column's ``to_numpy``, ``max``, ``min``, ``mean``
and ``iloc``), which pandas' own DataFrame has with the same meaning, and hands
DataFrames to users: :meth:`Frame.to_pandas`, when a result's table is first asked for
(pandas is imported there, not before).

Values are those a DataFrame would hold: a column of floats is float64, of Python
integers int64, of text an object array; a row (``iloc``) maps each name to the
column's value.
"""

from __future__ import annotations

import numpy as np


class _Column(np.ndarray):
    """One column: a numpy array with the few names of a pandas Series the engine reads
    (``to_numpy`` and ``iloc``); arithmetic and reductions are numpy's."""

    def to_numpy(self, dtype=None) -> np.ndarray:
        """The values as a plain numpy array.

        Parameters
        ----------
        dtype : numpy dtype, optional
            The type to convert to (none: as held).

        Returns
        -------
        ndarray
            The column's values.
        """
        return np.asarray(self, dtype=dtype)

    @property
    def iloc(self) -> np.ndarray:
        """The values indexed by position (``column.iloc[-1]``)."""
        return np.asarray(self)


class Row(dict):
    """One row: column name to value, with a Series' ``index`` (the names)."""

    @property
    def index(self) -> list[str]:
        """The column names, in order."""
        return list(self)


class _Rows:
    """``frame.iloc[i]``: the row at position ``i``."""

    def __init__(self, frame: "Frame"):
        self._frame = frame

    def __getitem__(self, i: int) -> Row:
        return Row((name, col[i]) for name, col in self._frame.items())


class Frame:
    """Named one-dimensional columns of one length, in order.

    Parameters
    ----------
    columns : dict, optional
        Column name to values (arrays or sequences of one length).
    """

    def __init__(self, columns: dict | None = None):
        self._cols: dict[str, np.ndarray] = {}
        for name, values in (columns or {}).items():
            self[name] = values

    @classmethod
    def from_rows(cls, rows: list[dict]) -> "Frame":
        """A frame of one row per dict, as ``pandas.DataFrame(rows)`` makes it: the names
        in the order they first appear, NaN where a row lacks one.

        Parameters
        ----------
        rows : list of dict
            The rows.

        Returns
        -------
        Frame
            The table.
        """
        names: dict[str, None] = {}
        for r in rows:
            names.update(dict.fromkeys(r))
        cols = {n: _array([r.get(n, np.nan) for r in rows]) for n in names}
        if any(a.ndim != 1 for a in cols.values()):
            return cls(cols)        # a row holding a sequence: refused as a column is
        # every column one value a row: what setting them one by one checks holds
        out = cls()
        out._cols = cols
        return out

    @classmethod
    def concat(cls, frames: list["Frame"]) -> "Frame":
        """The frames one below the other (``pandas.concat(frames, ignore_index=True)``
        of frames with the same columns).

        Parameters
        ----------
        frames : list of Frame
            Frames with the same column names in the same order.

        Returns
        -------
        Frame
            The stacked table.

        Raises
        ------
        ValueError
            If the frames' columns differ.
        """
        if not frames:
            return cls()
        names = frames[0].columns
        if any(f.columns != names for f in frames):
            raise ValueError("frames of different columns: "
                             + "; ".join(",".join(f.columns) for f in frames))
        return cls({n: np.concatenate([f._cols[n] for f in frames]) for n in names})

    @property
    def columns(self) -> list[str]:
        """The column names, in order."""
        return list(self._cols)

    def items(self):
        """(name, values) of each column, in order.

        Returns
        -------
        iterator
            Pairs of name and numpy array.
        """
        return self._cols.items()

    def __len__(self) -> int:
        return len(next(iter(self._cols.values()))) if self._cols else 0

    def __contains__(self, name) -> bool:
        return name in self._cols

    def __iter__(self):
        return iter(self._cols)

    def __getitem__(self, key):
        if isinstance(key, str):
            return self._cols[key].view(_Column)
        if isinstance(key, list):
            return Frame({n: self._cols[n] for n in key})
        mask = np.asarray(key)
        if mask.dtype != bool:
            raise TypeError("a frame is indexed by a column name, a list of names or a "
                            "boolean mask")
        return Frame({n: c[mask] for n, c in self._cols.items()})

    def __setitem__(self, name: str, values) -> None:
        n = len(self) if self._cols else None
        arr = _array(values if np.ndim(values) else np.full(n or 0, values))
        if arr.ndim != 1 or (n is not None and arr.shape[0] != n):
            raise ValueError(f"column {name!r}: {arr.shape} values for a frame of {n} rows")
        self._cols[name] = arr

    @property
    def iloc(self) -> _Rows:
        """Rows by position: ``frame.iloc[-1]`` is the last row (a :class:`Row`)."""
        return _Rows(self)

    def assign(self, **columns) -> "Frame":
        """A copy with columns added or replaced (a scalar fills its column).

        Parameters
        ----------
        **columns
            Name to values.

        Returns
        -------
        Frame
            The new frame; this one is unchanged.
        """
        out = Frame(self._cols)
        for name, values in columns.items():
            out[name] = values
        return out

    def to_pandas(self):
        """The table as a pandas DataFrame (pandas is imported here).

        Returns
        -------
        pandas.DataFrame
            The same columns, in order, with a default index.
        """
        import pandas as pd
        return pd.DataFrame(dict(self._cols)) if self._cols else pd.DataFrame()


def _array(values) -> np.ndarray:
    """Values as a 1-D numpy array, text as objects (as pandas holds it)."""
    arr = np.asarray(values)
    return arr.astype(object) if arr.dtype.kind in "US" else arr
