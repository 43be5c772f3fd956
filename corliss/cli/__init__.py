"""The ``corliss`` command line.

- :mod:`corliss.cli.commands`: the commands and their options (:func:`~corliss.cli.commands.main`);
- :mod:`corliss.cli.heartbeat`: the line that tells how long a slow first step has taken.
"""
