"""Studies: one engine run many times.  Steady runs of one scene over grids, Latin
hypercubes and Monte Carlo designs of its keys, on local processes or a Dask cluster
(``corliss study``); across its load range (``corliss sweep``); governed by throttling
and by cut-off (``corliss compare``).

- :mod:`corliss.studies.sampling`: the sampling designs (:func:`make_design`);
- :mod:`corliss.studies.responses`: which summary keys a study may record;
- :mod:`corliss.studies.runner`: :func:`study`, the runs, local or on Dask;
- :mod:`corliss.studies.study_result`: :class:`StudyResult`, one tidy table, and
  :func:`scene_data_of`, a row's scene rebuilt from the base scene;
- :mod:`corliss.studies.load_range`: :func:`~corliss.studies.load_range.load_range`,
  steady runs across the load range and the Willans line;
- :mod:`corliss.studies.compare`: :func:`~corliss.studies.compare.compare`, throttling
  against cut-off governing, its result in :mod:`corliss.studies.compare_result`.
"""

from corliss.studies.sampling import DESIGNS, Design, make_design
from corliss.studies.responses import DEFAULT_RESPONSES, response_keys
from corliss.studies.study_result import StudyResult, scene_data_of
from corliss.studies.runner import study

__all__ = ["DEFAULT_RESPONSES", "DESIGNS", "Design", "StudyResult", "make_design",
           "response_keys", "scene_data_of", "study"]
