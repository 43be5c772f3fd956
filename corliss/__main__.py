"""``python -m corliss``: the ``corliss`` command (:func:`corliss.cli.commands.main`)."""

import sys

from corliss.cli.commands import main

if __name__ == "__main__":      # not when a documentation tool imports every module
    sys.exit(main())
