"""Every ``plot()`` of the Python API returns one shape (issue 28: ``plot("card")``
gave ``{"ax", "lines"}`` and ``plot("loadstep")`` ``{"figure", "axes"}``).

Not physics: the contract a script relies on to treat any figure alike
(:func:`corliss.plot.shape.one_shape`), checked on the figures of a steady run, a
compound's low-pressure card, a governed transient and a Willans sweep, each drawn
from a real run.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402
from matplotlib.axes import Axes  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

import corliss  # noqa: E402
from corliss.plot.shape import SHAPE_KEYS  # noqa: E402
from corliss.scene.loader import find_scene, load_scene  # noqa: E402
from corliss.studies.load_range import load_ranges  # noqa: E402


def _check(drawn: dict, kind: str) -> None:
    assert set(SHAPE_KEYS) <= set(drawn), (kind, sorted(drawn))
    assert isinstance(drawn["figure"], Figure), kind
    assert isinstance(drawn["axes"], list) and drawn["axes"], kind
    assert all(isinstance(a, Axes) and a.figure is drawn["figure"] for a in drawn["axes"]), kind
    assert drawn["ax"] is drawn["axes"][0], kind
    assert isinstance(drawn["lines"], dict) and drawn["lines"], kind
    assert all(isinstance(v, Line2D) for v in drawn["lines"].values()), kind
    plt.close(drawn["figure"])


@pytest.fixture(scope="module")
def steady():
    return corliss.simulate(load_scene(find_scene("default")).with_fidelity("fast")
                            .replace_run(cycles=2))


def test_a_steady_runs_figures_have_the_one_shape(steady):
    for kind in ("card", "effort"):
        _check(steady.plot(kind), kind)
    drawn = steady.plot("card")
    assert drawn["lines"]["head"].get_xdata().size > 10       # the plotter's own names


def test_a_compounds_low_pressure_card_has_the_one_shape():
    r = corliss.simulate(load_scene(find_scene("marks-compound-9-14x14")).with_fidelity("fast")
                         .replace_run(cycles=2))
    _check(r.plot("lp_card"), "lp_card")


def test_a_transients_and_a_sweeps_figures_have_the_one_shape():
    sc = load_scene(find_scene("watt-throttling-governor")).with_fidelity("fast")
    r = corliss.simulate(sc.replace_run(duration_s=0.5))
    drawn = r.plot("loadstep")
    _check(drawn, "loadstep")
    sweep = load_ranges(load_scene(find_scene("corliss-governor")).with_fidelity("fast"),
                        {"setting": [0.3, 0.7]})
    _check(sweep.plot("willans"), "willans")
