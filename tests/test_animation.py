"""``corliss animate``: the moving picture of a gear is the gear.

The valve drawn in each frame stands where the gear's own travel puts it at that
frame's crank angle, and every rod drawn between two joints has the length the scene
gives it: the picture is the linkage, not a cartoon of it.  For the Corliss gear the
drawn valves turn through the gear's own valve angles, the trip and the dash-pot
included.

Tolerances: the drawn valve is the gear's valve position converted to inches and back,
so it agrees to rounding (1e-12 of the travel); between the 1/2 deg knots of the exact
gears' tables the spline that ``travel`` reads differs from the linkage solved at the
frame's angle by at most 2e-12 m (measured; a cubic spline's error at 1/2 deg, h^4/384
of the travel's fourth derivative), so 1e-9 m is a bound, three orders of magnitude
above both.  A rod's length is a distance between two solved joints: the closed forms
and Newton solves (stopped at 1e-13 of the rod) hold it to 1e-14 relative; the brief
asks 1e-9 of it.
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
from corliss.plot.animation import animate_gear, exact_linkage_spec, rod_lengths  # noqa: E402
from corliss.valves.link_motion import LinkMotion  # noqa: E402
from corliss.valves.radial_gear import RadialGear, SimpleRadialSpec  # noqa: E402

SCENES = Path(__file__).resolve().parent.parent / "scenes"
FOUR = {"default": "eccentric", "hinkley-stephenson-link": "stephenson",
        "walschaerts-locomotive": "walschaerts", "corliss-trip-gear": "corliss"}
#: An animation made for its frames and closed unsaved warns that it rendered nothing.
pytestmark = pytest.mark.filterwarnings("ignore:Animation was deleted without rendering")


@pytest.fixture(autouse=True)
def _collect_animations():
    """Collect each test's animations before its teardown ends, under the filter above:
    left to the garbage collector, one is deleted during a later test of another file
    on the same worker, whose warnings summary then shows it."""
    yield
    gc.collect()
VALVE_TOL_m = 1e-9
ROD_REL_TOL = 1e-9


def _gear(name):
    scene = corliss.load_scene(SCENES / f"{name}.toml")
    spec, _ = exact_linkage_spec(scene.gear)
    scene = dataclasses.replace(scene, gear=spec)
    return scene, build_gear(scene)


def _snapshot(folder: Path) -> dict:
    return {str(p.relative_to(folder)): (p.read_bytes() if p.is_file() else None)
            for p in sorted(folder.rglob("*"))}


@pytest.mark.parametrize("name", list(FOUR))
def test_the_command_writes_the_animation_of_each_gear(name, tmp_path, capsys):
    assert cli.main(["animate", name, "--out", str(tmp_path), "--frames", "12",
                     "--no-card"]) == 0
    path = tmp_path / f"{name}.animation.gif"
    assert f"wrote {path}" in capsys.readouterr().out
    with Image.open(path) as im:
        assert im.n_frames == 12
        assert im.size[0] >= 600
    assert [p.name for p in tmp_path.iterdir()] == [path.name]


def test_the_card_is_traced_and_html_is_written(tmp_path, capsys):
    """With the steady run (the default), the card panel is drawn; HTML holds every
    frame for its player."""
    assert cli.main(["animate", "default", "--out", str(tmp_path), "--frames", "6",
                     "--format", "html"]) == 0
    text = (tmp_path / "default.animation.html").read_text()
    assert text.count("data:image/png;base64") == 6
    assert text.lstrip().startswith("<!DOCTYPE html>")
    # self-contained: no request leaves the page (no http(s) or protocol-relative
    # address in any src, href, url() or import), and no icon-font class is left
    import re
    fetched = re.findall(r"(?:src|href)\s*=\s*[\"']?\s*(?:https?:)?//|url\(\s*[\"']?\s*"
                         r"(?:https?:)?//|@import", text, flags=re.I)
    assert not fetched, fetched
    assert "fa fa-" not in text and "http://" not in text and "https://" not in text


def _drawn_valve_m(drawn) -> float:
    xy = drawn["artists"]["valve"].get_xy()[:8]
    shift = np.mean(xy[:, 0] - drawn["valve_rest"][:, 0])
    return drawn["valve_sense"] * shift / drawn["scale"]


@pytest.mark.parametrize("name,frames", [("default", 24), ("hinkley-stephenson-link", 100),
                                         ("walschaerts-locomotive", 100),
                                         ("joy-radial-gear", 30), ("gooch", 30)])
def test_the_drawn_valve_stands_where_the_gears_travel_puts_it(name, frames):
    """At several crank angles (100 frames: 3.6 deg apart, most between the exact gears'
    table knots) the valve's outline is displaced by the gear's travel there; the Joy
    gear and the Gooch link too."""
    if name == "gooch":
        gear, stroke_m = _link(name)
    else:
        scene, gear = _gear(name)
        stroke_m = scene.engine.stroke_m
    drawn = animate_gear(gear, None, frames=frames, stroke_m=stroke_m)
    try:
        assert drawn["kind"] == {**FOUR, "joy-radial-gear": "radial", "gooch": "gooch_allen"}[name]
        for i in (0, 7, frames // 3, frames // 2 + 1, frames - 5):
            drawn["update"](i)
            theta = drawn["angles_rad"][i]
            want = float(gear.travel(np.array([theta]))[0])
            assert _drawn_valve_m(drawn) == pytest.approx(want, abs=VALVE_TOL_m), (i, theta)
        # the travel is not trivially zero: the valve moves more than its lap
        assert np.ptp(gear.travel(drawn["angles_rad"])) > 2 * max(gear.spec.lap_m)
    finally:
        plt.close(drawn["figure"])


def _overlap(a, b):
    return max(0.0, min(a[1], b[1]) - max(a[0], b[0]))


@pytest.mark.parametrize("name", ["default", "hinkley-stephenson-link",
                                  "walschaerts-locomotive"])
def test_the_ports_drawn_open_as_the_gear_opens_them(name):
    """Read off the picture: each steam port is open where the drawn valve leaves it
    uncovered, to the space outside the valve or to its cavity; which of the two holds
    steam is the admission's (a D valve outside, Walschaerts' piston valve inside).
    Those openings are the gear's own port openings at the frame's crank angle."""
    scene, gear = _gear(name)
    drawn = animate_gear(gear, None, frames=36, stroke_m=scene.engine.stroke_m)
    seat = drawn["seat_m"]
    assert seat["inside"] == (name == "walschaerts-locomotive")
    far = 10.0
    try:
        for i in range(0, 36, 5):
            drawn["update"](i)
            xy = drawn["artists"]["valve"].get_xy()[:8] / drawn["scale"]
            o_l, c_l, c_r, o_r = xy[0, 0], xy[1, 0], xy[4, 0], xy[5, 0]
            left, cavity, right = (-far, o_l), (c_l, c_r), (o_r, far)
            steam_h, exh_h = ((cavity, left) if seat["inside"] else (left, cavity))
            steam_c, exh_c = ((cavity, right) if seat["inside"] else (right, cavity))
            seen = [_overlap(seat["head"], steam_h), _overlap(seat["head"], exh_h),
                    _overlap(seat["crank"], steam_c), _overlap(seat["crank"], exh_c)]
            want = gear.openings(np.array([drawn["angles_rad"][i]]))[:, 0]
            assert seen == pytest.approx(list(want), abs=VALVE_TOL_m), i
    finally:
        plt.close(drawn["figure"])


def _marshall():
    """Spangler's Problem 50 gear (r = 2 1/2 in, l1 = 23 1/8 in, valve rod pinned
    16 5/8 in from the guided end, 60 in valve rod) with Problem 55's 18 1/2 in
    reversing link, as tests/test_radial_gears.py builds it: no bundled scene has one."""
    inch = 0.0254
    spec = SimpleRadialSpec(kind="marshall", eccentricity_m=2.5 * inch, link_m=23.125 * inch,
                            valve_arm_m=16.625 * inch, max_inclination_rad=math.atan(0.75),
                            valve_rod_m=60 * inch, guide_radius_m=18.5 * inch,
                            lap_m=(1.25 * inch,) * 2, exhaust_lap_m=(0.0, 0.0),
                            port_width_m=6 * inch, port_length_m=10 * inch, motion="exact")
    return RadialGear(spec), 0.3


def _link(kind):
    """The Hinkley locomotive's link motion (Peabody's, the bundled scene) rebuilt as a
    Gooch or an Allen link (no bundled scene has one), solved exactly."""
    scene, gear = _gear("hinkley-stephenson-link")
    return LinkMotion(dataclasses.replace(gear.spec, kind=kind)), scene.engine.stroke_m


RODS_AT_LEAST = {"default": 1, "hinkley-stephenson-link": 2, "walschaerts-locomotive": 9,
                 "corliss-trip-gear": 13, "joy-radial-gear": 9, "marshall": 5, "gooch": 5,
                 "allen": 5}


@pytest.mark.parametrize("name", list(RODS_AT_LEAST))
def test_every_drawn_rod_has_the_scenes_length(name):
    """A physics check that the picture is the linkage: the endpoints of each rod drawn
    are as far apart as the scene's rod is long, in every frame checked."""
    if name == "marshall":
        gear, stroke_m = _marshall()
    elif name in ("gooch", "allen"):
        gear, stroke_m = _link(name)
    else:
        scene, gear = _gear(name)
        stroke_m = scene.engine.stroke_m
    drawn = animate_gear(gear, None, frames=36, stroke_m=stroke_m)
    try:
        for i in (0, 5, 13, 22, 31):
            joints = drawn["update"](i)
            rods = drawn["rods"]()
            assert len(rods) >= RODS_AT_LEAST[name]
            for rod, (line, length_m) in rods.items():
                x, y = line.get_xdata(), line.get_ydata()
                drawn_m = math.hypot(x[1] - x[0], y[1] - y[0]) / drawn["scale"]
                assert drawn_m == pytest.approx(length_m, rel=ROD_REL_TOL), (rod, i)
            for rod, (between, spec) in rod_lengths(joints).items():
                assert between == pytest.approx(spec, rel=ROD_REL_TOL), (rod, i)
    finally:
        plt.close(drawn["figure"])


def test_the_corliss_valves_turn_through_the_gears_own_angles_with_the_trip():
    """Each drawn Corliss valve's working edge is turned from mid position by the
    gear's valve angle: the spindle's (latched) for the exhaust valves, and for the
    steam valves (signed opening + lap) / valve radius from the gear's own tripped
    openings (Spangler Art. 155: released by the cam, closed by the dash-pot).  Among
    the frames, a steam valve is seen released with its dash-pot still closing: its
    angle then lies strictly between the closed position (the lap) and the angle the
    plate would have given it."""
    scene, gear = _gear("corliss-trip-gear")
    s = gear.spec
    laps = np.array([s.steam_lap_m[0], s.exhaust_lap_m[0], s.steam_lap_m[1], s.exhaust_lap_m[1]])
    radii = np.array([s.steam.valve_radius_m, s.exhaust.valve_radius_m] * 2)
    drawn = animate_gear(gear, None, frames=72, stroke_m=scene.engine.stroke_m)
    closing_seen = 0
    try:
        for i in range(72):
            joints = drawn["update"](i)
            theta = drawn["angles_rad"][i]
            own = (gear.signed_openings(np.array([theta]))[:, 0] + laps) / radii
            latched = gear.spindle_angles(np.array([theta]))[:, 0]
            for p, (line, centre, base, sense) in enumerate(drawn["artists"]["valve_edges"]):
                x, y = line.get_xdata()[1], line.get_ydata()[1]
                turned = sense * math.remainder(math.atan2(y - centre[1], x - centre[0]) - base,
                                                2 * math.pi)
                assert turned == pytest.approx(own[p], abs=1e-9), (i, p)
                if p in (1, 3):
                    assert turned == pytest.approx(latched[p], abs=1e-9)
            for e, p in enumerate((0, 2)):
                if joints.released[e] and 0.0 < joints.dashpot_held_frac[e] < 1.0:
                    closing_seen += 1
                    assert laps[p] / radii[p] < own[p] < latched[p]
    finally:
        plt.close(drawn["figure"])
    assert closing_seen >= 2          # the dash-pot's 0.04 s at 80 rpm is 19 deg: 3 frames


def test_a_bad_scene_or_frame_count_writes_nothing(tmp_path, capsys):
    out = tmp_path / "new"
    assert cli.main(["animate", "no-such-scene", "--out", str(out)]) == 2
    assert cli.main(["animate", "default", "--out", str(out), "--frames", "1"]) == 2
    assert "--frames" in capsys.readouterr().err
    assert not out.exists()


def test_a_gear_with_no_single_valve_is_refused(tmp_path, capsys):
    assert cli.main(["animate", "gridiron-valve", "--out", str(tmp_path), "--no-card"]) == 2
    assert "valve_gear.type" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_a_failure_while_writing_leaves_the_folder_as_it_was(tmp_path, monkeypatch, capsys):
    """An earlier animation stays byte for byte when the new one fails half written,
    and a folder standing where the file goes is left alone."""
    assert cli.main(["animate", "default", "--out", str(tmp_path), "--frames", "4",
                     "--no-card"]) == 0
    (tmp_path / "default.animation.html").mkdir()
    before = _snapshot(tmp_path)
    import corliss.plot.animation as animation

    def half_written(drawn, path, fmt="gif", fps=12.0):
        Path(path).write_bytes(b"GIF89a half")
        raise OSError(28, "No space left on device (injected)")
    monkeypatch.setattr(animation, "write_animation", half_written)
    capsys.readouterr()
    code = cli.main(["animate", "default", "--out", str(tmp_path), "--frames", "4",
                     "--no-card"])
    # a full disk is the machine's state, not a traceback: the output commit turns it
    # into a run that stopped (exit 5), its reason on stderr, as for every command
    assert code == cli.EXIT_RUN_STOPPED
    assert "No space left on device (injected)" in capsys.readouterr().err
    monkeypatch.undo()
    with pytest.raises(IsADirectoryError):
        cli.main(["animate", "default", "--out", str(tmp_path), "--frames", "4",
                  "--no-card", "--format", "html"])
    assert _snapshot(tmp_path) == before


def test_the_gallery_example_builds_the_four_animations(monkeypatch):
    """examples/plot_moving_gears.py, which the documentation's gallery executes, runs
    with the API as it is and leaves one animation of each gear for the page."""
    import runpy

    from matplotlib.animation import FuncAnimation

    example = Path(__file__).resolve().parent.parent / "examples" / "plot_moving_gears.py"
    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    found = runpy.run_path(str(example))
    anims = [v for v in found.values() if isinstance(v, FuncAnimation)]
    try:
        assert len(anims) == 4
        assert len({id(a._fig) for a in anims}) == 4
    finally:
        plt.close("all")
