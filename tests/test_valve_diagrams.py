"""The Zeuner and Bilgram diagrams of every bundled scene that draws them: every event's
crank line at the angle the events table reports, every label clear of every drawn
line and of the other labels, the whole construction inside the axes.

Spangler, *Valve-Gears*, Arts. 11-17 (Zeuner: the crank lines through the meetings of
the valve circles with the lap and exhaust-lap circles are admission, cut-off, release
and compression of each end) and Art. 149 (Bilgram: the crank lines tangent to the lap
circles about d).
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from corliss.engine.model import build_gear, scene_events  # noqa: E402
from corliss.plot import plot_bilgram_diagram, plot_zeuner_diagram  # noqa: E402
from corliss.plot.gear_panels import find_by_class, plot_porter_allen  # noqa: E402
from corliss.plot.gears import GEAR_PANELS, EVENT_WORDS, plot_lapped_valve  # noqa: E402
from corliss.plot.labels import crosses  # noqa: E402
from corliss.scene.loader import bundled_scenes, load_scene  # noqa: E402


def _diagram_scenes(drawing) -> list[str]:
    """The bundled scenes whose gear is drawn by ``drawing``."""
    out = []
    for name, path in sorted(bundled_scenes().items()):
        scene = load_scene(path)
        if find_by_class(GEAR_PANELS, build_gear(scene)) is drawing:
            out.append(name)
    return out


SCENES = _diagram_scenes(plot_lapped_valve)
PORTER_ALLEN = _diagram_scenes(plot_porter_allen)
DRAW = {"zeuner": plot_zeuner_diagram, "bilgram": plot_bilgram_diagram}


def _drawn(name: str, kind: str):
    scene = load_scene(bundled_scenes()[name])
    fig, ax = plt.subplots(figsize=(6.5, 7))
    out = DRAW[kind](build_gear(scene), ax, scene.output.units)
    fig.canvas.draw()
    return scene, fig, out


def _angle_deg(line) -> float:
    """The direction of a crank line drawn from o, from its far end's data."""
    xs, ys = line.get_data()
    return math.degrees(math.atan2(float(ys[-1]), float(xs[-1]))) % 360.0


def _diff(a: float, b: float) -> float:
    return abs((a - b + 180.0) % 360.0 - 180.0)


def test_the_lapped_valve_scenes_are_many():
    """The parametrised tests below see the slide valves, link motions, radial gears and
    shaft governors of the bundled scenes, and the Porter-Allen scenes (a guard against
    an empty parametrisation)."""
    assert len(SCENES) >= 15, SCENES
    assert len(PORTER_ALLEN) >= 1


@pytest.mark.parametrize("name", SCENES)
def test_each_zeuner_crank_line_is_the_event_the_events_table_reports(name):
    """Each crank line on the Zeuner diagram points where the events table
    (``corliss events``, :func:`corliss.engine.model.scene_events`) puts that event, and
    there is a line for every event the table holds and none besides.

    The diagram finds its lines from its own construction, where the polar of the
    valve's displacement meets the lap and exhaust-lap circles (Arts. 12, 15-16), solved
    to 1e-12 rad; the table finds them on the ports' signed openings to 1e-13 rad (Illinois
    steps), and the drawn line's end gives its angle back to some 1e-14 rad.  1e-6 deg
    is those errors with room to spare, while a line for the wrong end, the wrong
    circle or the wrong crossing is degrees off."""
    scene, fig, out = _drawn(name, "zeuner")
    try:
        table = scene_events(scene)
        drawn = out["lines"]["crank_lines"]
        for end in ("head", "crank"):
            for event in EVENT_WORDS:
                want = table[end][f"{event}_deg"]
                line = drawn[end].get(event)
                if want is None:
                    assert line is None, (end, event)
                    continue
                assert line is not None, f"{name}: no crank line for {end} {event}"
                assert _diff(_angle_deg(line), want) < 1e-6, (end, event, _angle_deg(line), want)
                # the legend names the line with the table's angle, to its decimal
                assert f"{end} {EVENT_WORDS[event]}, {want:.1f}" in line.get_label()
    finally:
        plt.close(fig)


@pytest.mark.parametrize("name", PORTER_ALLEN)
def test_the_porter_allen_steam_diagram_has_the_steam_events_of_the_events_table(name):
    """The Porter-Allen gear's Zeuner diagram of its steam motion (the radius rod's
    travel against the laps referred to the rod, Arts. 30, 83) carries a crank line at
    each steam admission and cut-off the events table reports, to the same 1e-6 deg
    (the steam valve's opening is ``R_v sin(phi - beta)``, zero exactly where the rod's
    travel equals its equivalent lap); release and compression belong to the exhaust
    valves' own motion and are not on it.  Its labels clear every line."""
    scene = load_scene(bundled_scenes()[name])
    out = plot_porter_allen(build_gear(scene), None, scene.output.units)
    fig = out["figure"]
    try:
        fig.canvas.draw()
        table = scene_events(scene)
        drawn = out["lines"]["crank_lines"]
        for end in ("head", "crank"):
            for event in ("admission", "cutoff"):
                want = table[end][f"{event}_deg"]
                assert _diff(_angle_deg(drawn[end][event]), want) < 1e-6, (end, event)
            assert set(drawn[end]) == {"admission", "cutoff"}
        ax = out["axes"][2]
        renderer = fig.canvas.get_renderer()
        assert not [t.get_text() for t in out["labels"] if crosses(t, list(ax.lines), renderer)]
    finally:
        plt.close(fig)


@pytest.mark.parametrize("kind", ["zeuner", "bilgram"])
@pytest.mark.parametrize("name", SCENES)
def test_no_diagram_label_crosses_a_line_or_another_label(name, kind):
    """Every text on the diagram (the crank lines' numbers, Bilgram's letters o, d, k
    and dk's name) lies where no drawn line runs (its box, as drawn, against each line's
    path: :func:`corliss.plot.labels.crosses`), none given the fallback halo, and no two
    overprint.  The legend stands outside the diagram."""
    _, fig, out = _drawn(name, kind)
    try:
        ax = out["ax"]
        renderer = fig.canvas.get_renderer()
        texts = [t for t in ax.texts if t.get_text()]
        assert len(texts) >= 3
        over = [t.get_text() for t in texts if crosses(t, list(ax.lines), renderer)]
        assert not over, f"{name} {kind}: labels on a line: {over}"
        assert all(t.get_bbox_patch() is None for t in texts)
        boxes = [t.get_window_extent(renderer) for t in texts]
        for i in range(len(boxes)):
            for j in range(i + 1, len(boxes)):
                assert not boxes[i].overlaps(boxes[j]), (texts[i].get_text(), texts[j].get_text())
        legend = ax.get_legend().get_window_extent(renderer)
        assert legend.y1 <= ax.get_window_extent(renderer).y0 + 1.0
    finally:
        plt.close(fig)


@pytest.mark.parametrize("kind", ["zeuner", "bilgram"])
@pytest.mark.parametrize("name", SCENES)
def test_the_whole_construction_lies_inside_the_axes(name, kind):
    """Nothing of the construction is clipped: every circle and line (its data) within
    the axes' limits, every label (its box as drawn) within the axes' box.  Bilgram's
    lap circles about d reach r + lap from o, beyond a frame sized on the throw alone."""
    _, fig, out = _drawn(name, kind)
    try:
        ax = out["ax"]
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        for line in ax.lines:
            xs, ys = (np.asarray(v, dtype=float) for v in line.get_data())
            assert np.nanmin(xs) >= x0 and np.nanmax(xs) <= x1, line.get_label()
            assert np.nanmin(ys) >= y0 and np.nanmax(ys) <= y1, line.get_label()
        for patch in ax.patches:
            box = patch.get_path().get_extents(patch.get_patch_transform())
            assert box.x0 >= x0 and box.x1 <= x1 and box.y0 >= y0 and box.y1 <= y1
        frame = ax.get_window_extent(fig.canvas.get_renderer())
        for t in ax.texts:
            box = t.get_window_extent(fig.canvas.get_renderer())
            assert frame.x0 <= box.x0 and box.x1 <= frame.x1, t.get_text()
            assert frame.y0 <= box.y0 and box.y1 <= frame.y1, t.get_text()
    finally:
        plt.close(fig)
