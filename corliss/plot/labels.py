"""Labels placed where no curve runs.

A label drawn at a fixed offset from its point lands on a curve as often as not (the
atmospheric line's name under the exhaust line, an event's name on its own end's
line).  :func:`place_clear` moves each label, among a few positions near its point, to
the first whose box crosses none of the given lines, and gives a white halo to one
that finds no clear place.
"""

from __future__ import annotations

#: Offsets [points] tried for an annotation, nearest first: right and above, right and
#: below, left and above, left and below, then further out.
OFFSETS_PT = ((3, 4), (3, -11), (-22, 4), (-22, -11), (6, 12), (6, -18), (-30, 12),
              (-30, -18), (12, 20), (12, -26))


def _renderer(fig):
    canvas = fig.canvas
    get = getattr(canvas, "get_renderer", None)
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
