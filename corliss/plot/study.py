"""A study's responses against each varied key, as scatter plots."""

from __future__ import annotations

import numpy as np

from corliss.frames import columns
from corliss.frames.frame import Frame


def _axis(frame, column: str, units_system: str | None):
    """A response column's values and axis label, in ``units_system`` when its name
    ends in a unit :mod:`corliss.frames.columns` converts."""
    values = frame[column].to_numpy(dtype=float)
    if units_system is None:
        try:
            return values, f"{column} [{columns.unit_of(column)}]"
        except KeyError:
            return values, column
    try:
        conv, col_units = columns.convert_columns(Frame({column: values}), units_system)
    except KeyError:
        return values, column
    name = conv.columns[0]
    return conv[name].to_numpy(), f"{name} [{col_units[name]}]"


def plot_study(points, varied: list[dict], responses: list[str], fig=None,
               units_system: str | None = "US") -> dict:
    """Each response (a row of panels) against each varied key (a column).

    One dot a run; failed runs are left out and counted in the title.

    Parameters
    ----------
    points : pandas.DataFrame
        A study's table (:attr:`corliss.studies.study_result.StudyResult.points`).
    varied : list of dict
        The study's varied keys (``key``, ``unit``, ``column``), one panel column each.
    responses : list of str
        The response columns to draw.
    fig : matplotlib.figure.Figure, optional
        Drawn into (made when None, sized for the panels).
    units_system : str, optional
        ``"US"`` or ``"SI"`` for the responses' axes; None keeps them as the summary
        names them.

    Returns
    -------
    dict
        ``{"figure": fig, "axes": axes}``, ``axes`` an ndarray of Axes shaped
        (responses, varied keys).
    """
    import matplotlib.pyplot as plt

    nr, nc = max(1, len(responses)), max(1, len(varied))
    if fig is None:
        fig = plt.figure(figsize=(3.2 * nc + 0.8, 2.4 * nr + 0.8))
    axes = np.atleast_2d(fig.subplots(nr, nc, squeeze=False))
    ok = points[points["status"] == "ok"] if "status" in points else points
    for i, r in enumerate(responses):
        y, ylabel = _axis(ok, r, units_system)
        for j, v in enumerate(varied):
            ax = axes[i, j]
            ax.scatter(ok[v["column"]].to_numpy(dtype=float), y, s=7, color="k", alpha=0.6,
                       lw=0)
            ax.grid(True, color="0.9", lw=0.5)
            if i == nr - 1:
                ax.set_xlabel(f"{v['key']} [{v['unit'] or '-'}]", fontsize=8)
            if j == 0:
                ax.set_ylabel(ylabel, fontsize=8)
            ax.tick_params(labelsize=7)
    failed = len(points) - len(ok)
    fig.suptitle(f"{len(points)} runs" + (f", {failed} failed (not drawn)" if failed else ""),
                 fontsize=10)
    fig.tight_layout()
    return {"figure": fig, "axes": axes}
