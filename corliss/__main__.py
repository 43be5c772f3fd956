"""``python -m corliss``: the ``corliss`` command (:func:`corliss.cli.commands.main`)."""

import sys

from corliss.cli.commands import main

if __name__ == "__main__":
    sys.exit(main())
