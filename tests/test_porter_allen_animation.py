"""``corliss animate`` on the Porter-Allen gear: its four flat valves over their ports.

Spangler, *Valve-Gears*, Art. 30, Fig. 22: the Porter-Allen's steam valves "consist of
flat plates having rectangular openings through them", the exhaust valves on one stem.
With n openings (``valve_gear.steam_openings``) each w wide and L long, the plate's
edges all moving with it, the steam port's open area is, in closed form,

    A_n(theta) = n L clip(s(theta), 0, w),

s the gear's signed opening (``gear.signed_openings``); an exhaust valve's is
L_e clip(s_e, 0, w_e).  The test reads the plates off the picture (the solid parts
drawn, page coordinates back to the valve's own frame) and the seat's ports, and
finds each port's uncovered length: each must be clip(s, 0, w) and their sum times L
the gear's area, for n = 1 and 2, on both bundled Porter-Allen scenes, at the scenes'
governor settings and at rest (where the plate overtravels its openings, s above w).

Tolerance 1e-9 m: the drawn edges are the gear's travel times the drawing's scale and
back (rounding, 1e-15 relative of inches); 1e-9 m is far above that and far below any
drawing error worth the name (the ports are 1/2 in).
"""

from __future__ import annotations

import dataclasses
import gc
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

import corliss  # noqa: E402
from corliss.cli import commands as cli  # noqa: E402
from corliss.engine.model import build_gear  # noqa: E402
from corliss.plot.scene_animation import animate_scene  # noqa: E402

SCENES = Path(__file__).resolve().parent.parent / "scenes"
NAMES = ("porter-allen-engine", "porter-allen-governor")
TOL_m = 1e-9
pytestmark = pytest.mark.filterwarnings("ignore:Animation was deleted without rendering")


@pytest.fixture(autouse=True)
def _collect_animations():
    """Collect each test's animations before its teardown ends (as test_animation)."""
    yield
    gc.collect()


def _scene(name: str, n: int, setting: float | None = None):
    sc = corliss.load_scene(SCENES / f"{name}.toml")
    g = dataclasses.replace(sc.gear, steam_openings=n,
                            setting=sc.gear.setting if setting is None else setting)
    return dataclasses.replace(sc, gear=g)


def _covered(port, solids) -> float:
    """Length of ``port`` (from, to) under the union of ``solids`` [m]."""
    cuts = sorted((max(a, port[0]), min(b, port[1])) for a, b in solids
                  if min(b, port[1]) > max(a, port[0]))
    total, end = 0.0, port[0]
    for a, b in cuts:
        a = max(a, end)
        if b > a:
            total += b - a
            end = b
    return total


def _drawn_openings(drawn) -> list[list[float]]:
    """Each valve's ports' uncovered lengths [m], read off the drawn plates."""
    panel = drawn["artists"]["plates"]
    sc = drawn["scale"]
    out = []
    for v, parts in zip(panel.valves, panel.plates):
        solids = []
        for patch in parts:
            xa, xb = patch.get_x() / sc, (patch.get_x() + patch.get_width()) / sc
            la, lb = sorted(((xa - v.origin_m) * v.mirror, (xb - v.origin_m) * v.mirror))
            solids.append((la, lb))
        out.append([(b - a) - _covered((a, b), solids) for a, b in v.ports()])
    return out


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("n", [1, 2])
@pytest.mark.parametrize("at_rest", [False, True])
def test_the_plates_drawn_uncover_the_gears_openings(name, n, at_rest):
    """Through the function ``corliss animate`` calls: every port's drawn opening is
    clip(s, 0, w) of the gear's signed opening, and a steam port's n openings times L
    the gear's area n L clip(s, 0, w), at 36 frames (10 deg apart)."""
    scene = _scene(name, n, 0.0 if at_rest else None)
    drawn = animate_scene(scene, frames=36, card=False)
    gear = build_gear(scene)
    sp = gear.spec
    widths = gear.port_widths()
    lengths = (sp.steam_port_length_m, sp.exhaust_port_length_m) * 2
    try:
        assert drawn["kind"] == "porter_allen"
        assert [len(p) for p in _drawn_openings(drawn)] == [n, 1, n, 1]
        seen_open, seen_full = 0, 0
        for i in range(36):
            drawn["update"](i)
            theta = drawn["angles_rad"][i]
            s = gear.signed_openings(np.array([theta]))[:, 0]
            area = gear.areas(np.array([theta]))[:, 0]
            for p, ports in enumerate(_drawn_openings(drawn)):
                want = min(max(s[p], 0.0), widths[p])
                assert ports == pytest.approx([want] * len(ports), abs=TOL_m), (i, p)
                assert sum(ports) * lengths[p] == pytest.approx(area[p], abs=TOL_m * lengths[p])
            seen_open += s[0] > 0.0
            seen_full += s[0] > widths[0]
        assert seen_open >= 2                     # the head steam port opens in the turn
        if at_rest and name == "porter-allen-engine":
            assert seen_full >= 1                 # and overtravels its 1/2 in openings
    finally:
        plt.close(drawn["figure"])


@pytest.mark.parametrize("name", NAMES)
def test_the_command_writes_each_porter_allen_animation(name, tmp_path, capsys):
    """Both bundled scenes write their GIF; a bad ``--frames`` is still refused."""
    assert cli.main(["animate", name, "--out", str(tmp_path), "--frames", "6",
                     "--no-card"]) == 0
    path = tmp_path / f"{name}.animation.gif"
    assert f"wrote {path}" in capsys.readouterr().out
    with Image.open(path) as im:
        assert im.n_frames == 6
    bad = tmp_path / "bad"
    assert cli.main(["animate", name, "--out", str(bad), "--frames", "1"]) == 2
    assert "--frames" in capsys.readouterr().err
    assert not bad.exists()


def test_a_frame_draws_the_crank_the_rock_shaft_at_the_gears_angle():
    """The driving arm drawn is the rock shaft's angle phi = asin(x_s / R_d): its end
    stands R_d (sin phi, -cos phi) from the shaft (rounding)."""
    scene = _scene("porter-allen-engine", 2)
    drawn = animate_scene(scene, frames=12, card=False)
    gear = build_gear(scene)
    try:
        ax = drawn["axes"]["linkage"]
        sc = drawn["scale"]
        for i in (0, 3, 7):
            drawn["update"](i)
            theta = drawn["angles_rad"][i]
            phi = math.asin(gear.steam_drive(np.array([theta]))[0] / gear.spec.drive_arm_m)
            arms = [ln for ln in ax.lines if len(ln.get_xdata()) == 2
                    and ln.get_color() == "k" and ln.get_linewidth() == 2.6]
            (x0, x1), (y0, y1) = arms[0].get_xdata(), arms[0].get_ydata()
            rd = gear.spec.drive_arm_m
            assert (x1 - x0) / sc == pytest.approx(rd * math.sin(phi), abs=TOL_m)
            assert (y1 - y0) / sc == pytest.approx(-rd * math.cos(phi), abs=TOL_m)
    finally:
        plt.close(drawn["figure"])
