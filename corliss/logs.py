"""Logging conventions: every module logs to a child of the ``corliss`` logger, and
never prints.

:data:`NOTICE` sits between INFO and WARNING: a one-line account of work that takes
seconds and happens once on a machine (compiling the kernels, building the steam
table), which the command line shows by default and ``-q`` would hide.
"""

from __future__ import annotations

import logging

#: Level of the once-per-machine notices.
NOTICE = 25
logging.addLevelName(NOTICE, "NOTICE")
