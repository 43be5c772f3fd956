"""Gears are drawn by the plot layer: :func:`corliss.plot.plot_gear` draws the panels of
any gear, and the valve-gear layer knows nothing of drawing."""

import ast
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

from corliss.engine.model import build_gear  # noqa: E402
from corliss.plot import plot_gear  # noqa: E402
from corliss.scene.loader import load_scene  # noqa: E402
from corliss.valves import GEARS, gear_type  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SCENES = sorted((ROOT / "scenes").glob("*.toml"))
VALVES = sorted((ROOT / "corliss" / "valves").glob("*.py"))
#: Panels of each gear's drawing: the Corliss gear's two (wrist plate and spindles, port
#: openings); three for every other (travel, Zeuner, Bilgram; or a double valve's
#: travels, openings and diagram; or the Porter-Allen stems, openings and diagram).
PANELS = {"corliss": 2}


def scene_gears(scene):
    """(registry name, gear) of each cylinder's gear of a scene, as the run builds them."""
    out = [(scene.gear_type, build_gear(scene))]
    if scene.compound is not None:
        cp = scene.compound
        out.append((cp.lp_gear_type, gear_type(cp.lp_gear_type).build(cp.lp_gear)))
    return out


def test_plot_gear_draws_every_gear_of_every_steady_scene():
    import matplotlib.pyplot as plt

    drawn = set()
    for path in SCENES:
        scene = load_scene(path)
        if scene.run.mode != "steady":
            continue
        for name, gear in scene_gears(scene):
            out = plot_gear(gear, units_system=scene.output.units)
            fig = out["figure"]
            try:
                n = PANELS.get(name, 3)
                assert len(out["axes"]) == n, (path.stem, name)
                assert fig.axes == list(out["axes"]), (path.stem, name)
                assert all(ax.lines for ax in fig.axes), (path.stem, name)
            finally:
                plt.close(fig)
            drawn.add(name)
    assert drawn == set(GEARS), sorted(set(GEARS) ^ drawn)


def test_plot_gear_draws_on_a_given_figure_and_a_subclass_takes_its_parents_panels():
    """A gear class not in the registry is drawn as its nearest registered parent: a
    subclass of the gridiron valve gets the gridiron's combined diagram."""
    import matplotlib.pyplot as plt

    from corliss.valves.gridiron import GridironValve
    gear = build_gear(load_scene(ROOT / "scenes" / "gridiron-valve.toml"))

    class Special(GridironValve):
        pass

    fig = plt.figure()
    try:
        out = plot_gear(Special(gear.spec), fig, "SI")
        assert out["figure"] is fig and len(fig.axes) == 3
        assert out["axes"][2].get_title() == "Combined diagram (Arts. 118-119)"
        assert out["axes"][0].get_ylabel() == "displacement [mm]"
    finally:
        plt.close(fig)


def test_importing_the_plot_layer_does_not_import_matplotlib():
    import subprocess
    import sys
    code = "import sys, corliss.plot; assert 'matplotlib' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.parametrize("path", VALVES, ids=lambda p: p.stem)
def test_the_valve_gear_layer_knows_nothing_of_drawing(path):
    """No module of ``corliss/valves`` imports matplotlib or defines a function taking
    an ``ax`` or a ``fig``: drawings belong to :mod:`corliss.plot`."""
    tree = ast.parse(path.read_text(), filename=str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            names = [node.module or ""]
        else:
            names = []
        for name in names:
            assert name.split(".")[0] != "matplotlib", f"{path.name}:{node.lineno} imports {name}"
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            a = node.args
            params = [p.arg for p in a.posonlyargs + a.args + a.kwonlyargs]
            params += [p.arg for p in (a.vararg, a.kwarg) if p is not None]
            bad = {"ax", "fig"} & set(params)
            assert not bad, f"{path.name}:{node.lineno} takes {sorted(bad)}"
