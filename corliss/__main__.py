"""``python -m corliss``: the ``corliss`` command (:func:`corliss.cli.main`)."""

import sys

from corliss.cli import main

sys.exit(main())
