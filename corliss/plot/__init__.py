"""Plots in period style.  Every function takes ``ax=None``, returns what it drew and
never calls ``show()``; matplotlib is imported when a figure is first drawn.

- :mod:`corliss.plot.cards`: indicator cards and crank-effort diagrams;
- :mod:`corliss.plot.gears`: valve travel, Zeuner and Bilgram diagrams, and the
  drawings of gears whose motion is not one lapped valve;
- :mod:`corliss.plot.transients`: load steps and governor characteristics;
- :mod:`corliss.plot.willans`: Willans lines across the load range.
"""

from corliss.plot.cards import plot_card, plot_crank_effort
from corliss.plot.gears import (bilgram_events, plot_bilgram_diagram, plot_valve_travel,
                                plot_zeuner_diagram)
from corliss.plot.transients import plot_load_step, plot_static_characteristic
from corliss.plot.willans import plot_willans

__all__ = ["bilgram_events", "plot_bilgram_diagram", "plot_card", "plot_crank_effort",
           "plot_load_step", "plot_static_characteristic", "plot_valve_travel",
           "plot_willans", "plot_zeuner_diagram"]
