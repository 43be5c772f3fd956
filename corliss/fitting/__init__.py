"""Scene keys calibrated to measured indicator cards.

- :mod:`corliss.fitting.card`: card CSV files (long or wide, units in the header) to a
  :class:`~corliss.fitting.card.MeasuredCard`;
- :mod:`corliss.fitting.solver`: the least-squares fit, its uncertainties and the
  :class:`~corliss.fitting.solver.FitResult`.

The command and the public function are :func:`corliss.fit` (:mod:`corliss.files.fit_output`).
"""

from corliss.fitting.card import MeasuredCard, parse_card, read_card
from corliss.fitting.solver import FitResult, fit_card

__all__ = ["FitResult", "MeasuredCard", "fit_card", "parse_card", "read_card"]
