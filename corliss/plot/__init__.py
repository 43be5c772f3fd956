"""Plots in period style.  Every function takes ``ax=None`` (or ``fig=None``, for a
figure of several panels), returns what it drew and never calls ``show()``;
matplotlib is imported when a figure is first drawn.

- :mod:`corliss.plot.cards`: indicator cards and crank-effort diagrams;
- :mod:`corliss.plot.fit_card`: a measured card over the card fitted to it;
- :mod:`corliss.plot.gears`: valve travel, Zeuner and Bilgram diagrams, and
  :func:`plot_gear`, all the panels of any gear;
- :mod:`corliss.plot.gear_panels`: the panels of gears whose motion is not one lapped
  valve (double valves, the Corliss and Porter-Allen gears);
- :mod:`corliss.plot.crank_lines`: the events' crank lines on the polar valve diagrams;
- :mod:`corliss.plot.corliss_keys`: the Corliss gear's scene keys sketched on its
  geometry;
- :mod:`corliss.plot.labels`: labels placed where no curve runs, diagrams fitted to
  their labels;
- :mod:`corliss.plot.transients`: load steps and governor characteristics;
- :mod:`corliss.plot.willans`: Willans lines across the load range;
- :mod:`corliss.plot.study`: a study's responses against its varied keys.
"""

from corliss.plot.cards import plot_card, plot_crank_effort
from corliss.plot.fit_card import plot_fit_card
from corliss.plot.gears import (bilgram_events, plot_bilgram_diagram, plot_gear,
                                plot_valve_travel, plot_zeuner_diagram)
from corliss.plot.study import plot_study
from corliss.plot.transients import plot_load_step, plot_static_characteristic
from corliss.plot.willans import plot_compare, plot_willans

__all__ = ["bilgram_events", "plot_bilgram_diagram", "plot_card", "plot_crank_effort",
           "plot_fit_card", "plot_gear", "plot_load_step", "plot_static_characteristic",
           "plot_study", "plot_valve_travel", "plot_compare", "plot_willans", "plot_zeuner_diagram"]
