"""Labels placed where no curve runs.

A label drawn at a fixed offset from its point lands on a curve as often as not (the
atmospheric line's name under the exhaust line, an event's name on its own end's
line).  :func:`place_clear` moves each label, among a few positions near its point, to
the first whose box crosses none of the given lines, and gives a white halo to one
that finds no clear place.
"""

from __future__ import annotations

import numpy as np

#: Offsets [points] tried for an annotation, nearest first: right and above, right and
#: below, left and above, left and below, then further out.
OFFSETS_PT = ((3, 4), (3, -11), (-22, 4), (-22, -11), (6, 12), (6, -18), (-30, 12),
              (-30, -18), (12, 20), (12, -26))


def _renderer(fig):
    """The figure's renderer: its canvas's, or for a figure made without pyplot (a
    bare canvas) the one matplotlib would save it with."""
    get = getattr(fig.canvas, "get_renderer", None)
    if get is not None:
        return get()
    get = getattr(fig, "_get_renderer", None)
    return get() if get is not None else None


def crosses(text, lines, renderer) -> bool:
    """Whether a text's box crosses any of ``lines`` as drawn.

    Parameters
    ----------
    text : matplotlib.text.Text
        A text or annotation on the axes.
    lines : list of matplotlib.lines.Line2D
        The curves it must keep clear of.
    renderer : matplotlib.backend_bases.RendererBase
        The figure's renderer (for the text's extent).

    Returns
    -------
    bool
        True when the box (in display units) meets a line's path.
    """
    box = text.get_window_extent(renderer)
    for line in lines:
        path = line.get_path().transformed(line.get_transform())
        if path.intersects_bbox(box, filled=False):
            return True
    return False


def place_clear(texts, lines, positions=None) -> int:
    """Move each text to the first place near its point whose box crosses no line.

    Parameters
    ----------
    texts : list of matplotlib.text.Text
        The labels: annotations (moved by their offset, :data:`OFFSETS_PT`) or texts
        (moved to the data positions ``positions[i]`` gives, each a list of (x, y)).
    lines : list of matplotlib.lines.Line2D
        The curves to keep clear of.
    positions : list of list of (float, float), optional
        For plain texts, the data positions to try, in order (None for an
        annotation).

    Returns
    -------
    int
        How many labels found no clear place (given a white halo instead).
    """
    if not texts:
        return 0
    fig = texts[0].figure
    renderer = _renderer(fig)
    if renderer is None:
        return 0
    blocked = 0
    for i, t in enumerate(texts):
        tries = positions[i] if positions is not None else None
        # an annotation's position is its text's offset from the point; a text's, its
        # place in data
        tries = OFFSETS_PT if tries is None else tries
        first = t.get_position()
        for pos in tries:
            t.set_position(pos)
            if not crosses(t, lines, renderer):
                break
        else:
            t.set_position(first)
            t.set_bbox(dict(facecolor="white", edgecolor="none", pad=0.5, alpha=0.85))
            blocked += 1
    return blocked


def merge_rays(rays, within_deg: float = 3.0) -> list:
    """Crank lines whose labels would overprint, taken together.

    Parameters
    ----------
    rays : list of (float, str)
        ``(angle [deg], label)`` of each line.
    within_deg : float, optional
        Lines closer than this [deg] share one label.

    Returns
    -------
    list of (float, str)
        ``(angle [deg], label)``: the mean angle of each group (the lines' angles taken
        on the circle) and its labels joined by ``" / "``, in order of angle.
    """
    groups: list[list[tuple[float, str]]] = []
    for a, text in sorted(((a % 360.0, t) for a, t in rays), key=lambda r: r[0]):
        if groups and (a - groups[-1][-1][0]) < within_deg:
            groups[-1].append((a, text))
        else:
            groups.append([(a, text)])
    # the first and last groups meet across 0 deg
    if len(groups) > 1 and (groups[0][0][0] + 360.0 - groups[-1][-1][0]) < within_deg:
        groups[0] = [(a - 360.0, t) for a, t in groups.pop()] + groups[0]
    out = []
    for g in groups:
        mean = sum(a for a, _ in g) / len(g)
        out.append((mean % 360.0, ", ".join(t for _, t in g)))
    return out


def ray_labels(ax, rays, radius: float, centre=(0.0, 0.0), along: bool = False,
               **style) -> list:
    """Labels beyond the ends of crank lines, as the period's drawings letter them:
    each text starts a little past ``radius`` on its line's direction and lies
    outwards of that point, upright (or, ``along``, turned to read along the line).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The diagram (equal aspect).
    rays : list of (float, str)
        ``(angle [deg], label)``, counter-clockwise from the x axis (already merged,
        :func:`merge_rays`).
    radius : float
        Where the lines end [data units]; no line of the diagram may run beyond it
        near a label.
    centre : (float, float), optional
        The point the lines start from [data units].
    along : bool, optional
        Turn each text to the line's direction (for long labels).
    **style
        Passed to ``ax.text`` (``fontsize``, ``color``).

    Returns
    -------
    list of matplotlib.text.Text
        The labels, in the order of ``rays``.
    """
    import matplotlib.transforms as mtransforms

    style = {"fontsize": 6.5, "color": "0.15", **style}
    out = []
    for a, text in rays:
        p = np.radians(a)
        c, s = float(np.cos(p)), float(np.sin(p))
        left = c < -1e-9 or (abs(c) <= 1e-9 and s < 0)
        rot = a + 180.0 if left else a
        # a gap of a few points past the line's end, along the line
        shift = mtransforms.offset_copy(ax.transData, fig=ax.figure, x=3.0 * c, y=3.0 * s,
                                        units="points")
        if along:
            place = dict(rotation=rot % 360.0, rotation_mode="anchor",
                         ha="right" if left else "left", va="center")
        else:
            # the box on the far side of the point from the centre
            place = dict(ha="left" if c > 0.34 else "right" if c < -0.34 else "center",
                         va="bottom" if s > 0.34 else "top" if s < -0.34 else "center")
        out.append(ax.text(centre[0] + radius * c, centre[1] + radius * s, text,
                           transform=shift, **place, **style))
    return out


def fit_inside(ax, texts, margin: float = 0.03, rounds: int = 12) -> None:
    """Widen an equal-aspect diagram's limits until its texts and lines lie inside.

    The limits are set square about their present centre; each round draws the
    figure, takes the extent of every line (data) and text (as drawn) and widens the
    limits to hold them with ``margin`` to spare; a text's size in data units shrinks
    as the limits grow, so a few rounds settle it.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The diagram.
    texts : list of matplotlib.text.Text
        The texts that must lie inside (labels along lines, letters).
    margin : float, optional
        Room left inside the axes, a fraction of the half width [-].
    rounds : int, optional
        Most rounds of widening.

    Returns
    -------
    None
    """
    renderer = _renderer(ax.figure)
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    half = 0.5 * max(x1 - x0, y1 - y0)
    for _ in range(rounds):
        ax.set_xlim(cx - half, cx + half)
        ax.set_ylim(cy - half, cy + half)
        need = 0.0
        for line in ax.lines:
            xs, ys = (np.asarray(v, dtype=float) for v in line.get_data())
            if line.get_transform() is not ax.transData or not np.isfinite(xs).any():
                continue
            need = max(need, float(np.nanmax(np.abs(xs - cx))), float(np.nanmax(np.abs(ys - cy))))
        if renderer is not None:
            ax.apply_aspect()
            inv = ax.transData.inverted()
            for t in texts:
                box = t.get_window_extent(renderer)
                (bx0, by0), (bx1, by1) = inv.transform([[box.x0, box.y0], [box.x1, box.y1]])
                need = max(need, abs(bx0 - cx), abs(bx1 - cx), abs(by0 - cy), abs(by1 - cy))
        if need * (1.0 + 0.5 * margin) <= half:
            break
        half = need * (1.0 + margin)
