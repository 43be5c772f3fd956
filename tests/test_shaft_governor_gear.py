"""Shaft-governor eccentrics (Spangler Ch. XII) against the book's statements."""

import math

import numpy as np
import pytest

from corliss.valves.events import end_events
from corliss.valves.shaft_governor import ShaftGovernorGear, ShaftGovernorSpec
from corliss.valves.slide_valve import SlideValve, SlideValveSpec

IN = 0.0254
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
S_VALUES = np.linspace(0.0, 1.0, 6)


def head(gear):
    e = end_events(gear, "head", HARMONIC)
    return e["cutoff_frac"], e["lead_m"]


def test_straight_path_keeps_the_lead_and_shortens_the_cut_off():
    """Art. 87: with the sheave slotted so that the centre moves at right angles to the
    crank, B = r sin d = lap + lead is constant while the cut-off varies (Erie, Art. 88;
    Armington & Sims, Art. 89)."""
    g = ShaftGovernorGear(ShaftGovernorSpec("straight", 2.0 * IN, math.radians(25),
                                            (0.75 * IN,) * 2, (0.0, 0.0), 1.0 * IN, 8 * IN,
                                            centre_travel_m=1.6 * IN))
    rows = [head(g.with_setting(s)) for s in S_VALUES]
    leads = [lead for _, lead in rows]
    cuts = [c for c, _ in rows]
    assert np.ptp(leads) < 1e-12
    assert all(a > b for a, b in zip(cuts, cuts[1:]))
    assert cuts[0] > 0.7 and cuts[-1] < 0.2


def test_ball_arc_raises_the_lead_as_cut_off_shortens():
    """Arts. 90-91: the Ball governor's pin swings on an arc about a point of the
    flywheel, and the distribution is "practically the same ... as in a Stephenson's link
    with open rods": lead increases as cut-off shortens."""
    g = ShaftGovernorGear(ShaftGovernorSpec("arc", 2.0 * IN, math.radians(30), (0.75 * IN,) * 2,
                                            (0.0, 0.0), 1.0 * IN, 8 * IN, arc_radius_m=1.5 * IN,
                                            arc_swing_rad=math.radians(60),
                                            arc_start_rad=math.radians(180)))
    rows = [head(g.with_setting(s)) for s in S_VALUES]
    cuts = [c for c, _ in rows]
    leads = [lead for _, lead in rows]
    assert all(a > b for a, b in zip(cuts, cuts[1:]))
    assert all(a < b for a, b in zip(leads, leads[1:]))


def _slide(r_in, delta_deg):
    return SlideValve(SlideValveSpec(r_in * IN, (0.75 * IN,) * 2, (0.0, 0.0),
                                     math.radians(delta_deg), 1.0 * IN, 8 * IN))


def test_advance_alone_and_throw_alone():
    """Arts. 85-86: changing the angular advance alone, "decreased cut-off means more
    lead"; changing the eccentricity alone, "increased cut-off means more lead"."""
    by_advance = [head(_slide(2.0, d)) for d in (20, 30, 40)]      # more advance
    assert by_advance[0][0] > by_advance[1][0] > by_advance[2][0]   # shorter cut-off
    assert by_advance[0][1] < by_advance[1][1] < by_advance[2][1]   # more lead
    by_throw = [head(_slide(r, 30)) for r in (1.6, 2.0, 2.4)]       # more throw
    assert by_throw[0][0] < by_throw[1][0] < by_throw[2][0]         # later cut-off
    assert by_throw[0][1] < by_throw[1][1] < by_throw[2][1]         # more lead
