"""One shape for what every ``plot()`` of the Python API returns.

A result's figures are of one axes (the card, the crank effort, the Willans lines, a
fit's card) or of several (the load step's panels, the compare figure, a study's
grid), and their plotting functions return what they drew in their own words
(``{"ax", "lines"}``, ``{"figure", "axes"}``, ``{"ax", "measured", "fitted"}``).
:func:`one_shape` gives every one of them the same keys, so a script or notebook can
treat any kind alike:

- ``"figure"``: the matplotlib Figure;
- ``"axes"``: a list of the Axes drawn on, the main one first;
- ``"ax"``: the main Axes (``axes[0]``);
- ``"lines"``: a dict of the named lines, ``{label: Line2D}`` (the plotting
  function's own names where it gives them; else each line's legend label, or
  ``"line N"``);

with the plotting function's own entries kept beside them.
"""

from __future__ import annotations

#: The keys every ``plot()`` returns.
SHAPE_KEYS = ("figure", "axes", "ax", "lines")


def _axes_list(drawn: dict) -> list:
    axes = drawn.get("axes")
    if axes is None:
        return [drawn["ax"]]
    if isinstance(axes, dict):
        axes = list(axes.values())
    elif hasattr(axes, "ravel"):               # a numpy array of subplots
        axes = list(axes.ravel())
    else:
        axes = list(axes)
    main = drawn.get("ax")
    if main is not None and main in axes:
        axes.remove(main)
        axes.insert(0, main)
    return axes


def _named_lines(axes: list) -> dict:
    out: dict = {}
    for ax in axes:
        for line in ax.get_lines():
            label = line.get_label()
            name = label if label and not label.startswith("_") else f"line {len(out)}"
            while name in out:
                name += "'"
            out[name] = line
    return out


def one_shape(drawn: dict) -> dict:
    """What a plotting function drew, with the keys of :data:`SHAPE_KEYS` set.

    Parameters
    ----------
    drawn : dict
        A plotting function's return: with ``"ax"`` or ``"axes"`` (a list, tuple,
        dict or array of Axes), and maybe ``"figure"`` and ``"lines"``.

    Returns
    -------
    dict
        A new dict: ``figure``, ``axes`` (list, main first), ``ax`` (the main
        Axes) and ``lines`` (``{name: Line2D}``), then the rest of ``drawn``'s
        entries as they were.
    """
    axes = _axes_list(drawn)
    lines = drawn.get("lines")
    if isinstance(lines, (list, tuple)):
        lines = {(ln.get_label() if not ln.get_label().startswith("_") else f"line {i}"): ln
                 for i, ln in enumerate(lines)}
    elif not isinstance(lines, dict):
        lines = _named_lines(axes)
    out = {"figure": drawn.get("figure") or axes[0].figure, "axes": axes, "ax": axes[0],
           "lines": lines}
    out.update({k: v for k, v in drawn.items() if k not in SHAPE_KEYS})
    return out


__all__ = ["SHAPE_KEYS", "one_shape"]
