"""The documentation's drawn figures come from the code: ``docs/figures.py`` (which
``docs/conf.py`` runs at every build) writes the README's card and the Corliss gear's
key sketch, the card's title carries the run's own numbers, and the sketch is drawn to
the gear's geometry with every key of it named."""

from __future__ import annotations

import importlib.util
import math
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402

from corliss.keys import units  # noqa: E402
from corliss.scene.reference import SKETCHES  # noqa: E402
from corliss.valves import GEARS  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
PNG = b"\x89PNG\r\n\x1a\n"


def _figures_module():
    spec = importlib.util.spec_from_file_location("doc_figures", ROOT / "docs" / "figures.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    folder = tmp_path_factory.mktemp("figures")
    return folder, _figures_module().write_figures(folder)


def test_the_docs_build_runs_the_figure_script():
    conf = (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
    assert "figures.write_figures(DOCS)" in conf


def test_the_script_writes_every_figure_the_pages_show(written):
    """Each figure the README and the pages show is one the script writes, as a PNG."""
    folder, _ = written
    mod = _figures_module()
    shown = set(re.findall(r"\]\((?:docs/)?([\w-]+\.png)\)",
                           (ROOT / "README.md").read_text(encoding="utf-8")))
    shown |= {file for file, _ in SKETCHES.values()}
    assert shown <= set(mod.FIGURES), shown - set(mod.FIGURES)
    for name in mod.FIGURES:
        data = (folder / name).read_bytes()
        assert data.startswith(PNG) and len(data) > 10_000, name
        assert (ROOT / "docs" / name).is_file(), f"docs/{name} not committed"


def test_the_readme_card_states_the_runs_power(written):
    """The card's title gives the indicated power of the run it draws (the README's
    card once said 153.7 ihp where the run gave 154.0): the summary's ihp, 745.7 W to
    the horse-power, to the title's one decimal."""
    folder, out = written
    s = out["default-card.png"]
    assert s["indicated_power_hp"] == pytest.approx(s["indicated_power_W"] / 745.6999, rel=1e-6)
    assert 100.0 < s["indicated_power_hp"] < 250.0      # a 12 x 24 in engine at 120 rpm
    assert f"{s['indicated_power_hp']:.1f} ihp" in s["title"]


def test_the_corliss_sketch_is_drawn_to_the_gears_geometry(written):
    """Each chain's stud, arm and the eccentric are drawn at their keys' lengths and
    angles (to rounding): the stud oj at ``stud_radius`` and ``stud_angle`` from o->q,
    the arm ql at ``arm`` and ``arm_angle`` from q->o, the eccentric at
    ``eccentricity`` and ``angular_advance`` past the perpendicular to the crank; and
    every length and angle key of the gear is named on the sketch."""
    from corliss.engine.model import build_gear
    from corliss.scene.loader import find_scene, load_scene

    _, out = written
    drawn = out["corliss-gear-keys.png"]
    spec = build_gear(load_scene(find_scene("corliss-trip-gear"))).spec
    for kind, chain in (("steam", spec.steam), ("exhaust", spec.exhaust)):
        lines = drawn["lines"][kind]
        (x0, x1), (y0, y1) = lines["stud"].get_data()
        assert math.hypot(x1 - x0, y1 - y0) == pytest.approx(
            units.to_unit(chain.stud_radius_m, "in"), rel=1e-12)
        assert math.atan2(y1 - y0, x1 - x0) == pytest.approx(chain.stud_angle_rad, abs=1e-12)
        (qx, lx), (qy, ly) = lines["arm"].get_data()
        assert math.hypot(lx - qx, ly - qy) == pytest.approx(units.to_unit(chain.arm_m, "in"),
                                                           rel=1e-12)
        # from q -> o (the -x direction) to q -> l, positive on the stud's side (+y)
        assert math.atan2(ly - qy, -(lx - qx)) == pytest.approx(chain.arm_angle_rad, abs=1e-12)
    (x0, x1), (y0, y1) = drawn["lines"]["plate"]["eccentric"].get_data()
    assert math.hypot(x1, y1) == pytest.approx(units.to_unit(spec.eccentricity_m, "in"))
    assert math.atan2(x1, y1) == pytest.approx(spec.angular_advance_rad, abs=1e-12)
    texts = " ".join(t.get_text() for ax in drawn["axes"] for t in ax.texts)
    for key in GEARS["corliss"].keys.keys:
        if key.kind in ("length", "angle", "arc") and key.name != "port_length":
            assert key.name in texts, key.name
