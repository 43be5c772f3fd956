"""The card's labels sit where no curve runs: each text's box, as drawn, crosses
neither end's card line (the atmospheric line's name, the zero line's, every event's
label), and the legend stands outside the diagram."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

import corliss  # noqa: E402
from corliss.plot.cards import plot_card  # noqa: E402
from corliss.plot.labels import crosses  # noqa: E402
from corliss.scene.loader import find_scene, load_scene  # noqa: E402


@pytest.mark.parametrize("name", ["default", "high-speed-condensing", "corliss-trip-gear"])
def test_no_card_label_crosses_a_curve(name):
    scene = load_scene(find_scene(name)).with_fidelity("fast")
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
    finally:
        plt.close(fig)
