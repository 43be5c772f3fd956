"""The tables a run gives: a light table of named columns and the names of its columns.

- :mod:`corliss.frames.frame`: :class:`~corliss.frames.frame.Frame`, named numpy columns;
- :mod:`corliss.frames.columns`: the column names and summary keys, each ending in its unit.
"""
