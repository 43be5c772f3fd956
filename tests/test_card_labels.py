"""The card's labels sit where no curve runs: each text's box, as drawn, crosses
neither end's card line (the atmospheric line's name, the zero line's, every event's
label), and the legend stands outside the diagram; for every bundled steady scene at
the ``fast`` preset, on the one abscissa every card is drawn on (piston position from
head-end dead centre, the fraction of the stroke above).  The transient cards are on
the same abscissa: their piston position is the one their volume gives."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

import corliss  # noqa: E402
from corliss.keys import units  # noqa: E402
from corliss.plot.cards import plot_card  # noqa: E402
from corliss.plot.labels import crosses  # noqa: E402
from corliss.scene.loader import bundled_scenes, load_scene  # noqa: E402

STEADY = sorted(name for name, path in bundled_scenes().items()
                if load_scene(path).run.mode == "steady")


@pytest.mark.parametrize("name", STEADY)
def test_no_card_label_crosses_a_curve(name):
    scene = load_scene(bundled_scenes()[name]).with_fidelity("fast")
    result = corliss.simulate(scene)
    drawn = plot_card(result)
    ax = drawn["ax"]
    fig = ax.figure
    try:
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        curves = list(drawn["lines"].values())
        texts = [t for t in ax.texts if t.get_text()]
        assert len(texts) >= 2 + 4      # the two lines' names and events of each end
        over = [t.get_text() for t in texts if crosses(t, curves, renderer)]
        assert not over, f"{name}: labels on a curve: {over}"
        # none given the fallback halo: each found a clear place
        assert all(t.get_bbox_patch() is None for t in texts)
        legend = ax.get_legend().get_window_extent(renderer)
        assert legend.x0 >= ax.get_window_extent(renderer).x1 - 1.0
        # the one abscissa: piston position in the scene's units, the stroke's
        # fraction above, whose 0 and 1 fall on the dead centres
        unit = "in" if scene.output.units == "US" else "mm"
        assert ax.get_xlabel() == f"piston position from head-end dead centre [{unit}]"
        top = [c for c in ax.child_axes if c.get_xlabel() == "fraction of the stroke"]
        assert len(top) == 1
        stroke = units.to_unit(scene.engine.stroke_m, unit)
        fwd, _ = top[0]._functions
        assert fwd(stroke) == pytest.approx(1.0, rel=1e-12) and fwd(0.0) == 0.0
    finally:
        plt.close(fig)


def test_a_transient_card_lies_on_the_piston_position_its_volume_gives():
    """The load step's cards are drawn against ``piston_frac``; for each end that is
    the position its volume says: the head end's volume is its clearance plus the
    piston area times the position, the crank end's its clearance plus the annulus
    (piston less rod) times the rest of the stroke (a slider-crank's closure, exact to
    rounding: 1e-12 of the stroke)."""
    import tomllib

    from corliss.plot.transients import plot_load_step

    d = tomllib.loads(bundled_scenes()["corliss-governor"].read_text(encoding="utf-8"))
    d["run"].update(duration="1.5 s", fidelity="fast", record="degree")
    d["load"] = {"power": "150 hp"}
    result = corliss.simulate(corliss.scene_from_dict(d, "card-abscissa"))
    geo = result.geometry
    S = geo.spec.stroke_m
    for phase in ("before", "after"):
        cards = result.cards()[phase]
        (ch, cc) = geo.clearance_m3
        xh = (cards["head"]["V_m3"].to_numpy() - ch) / geo.area_head_m2
        xc = S - (cards["crank"]["V_m3"].to_numpy() - cc) / geo.area_crank_m2
        for end, x in (("head", xh), ("crank", xc)):
            assert cards[end]["piston_frac"].to_numpy() * S == pytest.approx(x, abs=1e-12 * S)
    drawn = plot_load_step(result)
    fig = drawn["figure"]
    try:
        for key in ("card_before", "card_after"):
            ax = drawn["axes"][key]
            assert ax.get_xlabel().startswith("piston position from head-end dead centre")
            line = ax.lines[0]
            x = line.get_xdata()
            stroke_in = units.to_unit(S, "in")
            assert 0.0 <= x.min() < 0.01 * stroke_in and 0.99 * stroke_in < x.max() <= stroke_in
    finally:
        plt.close(fig)
