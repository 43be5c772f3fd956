"""The ``corliss`` command line.

- :mod:`corliss.cli.commands`: the command itself (:func:`~corliss.cli.commands.main`), its
  parser assembled from each family's subcommands, logging and signals;
- :mod:`corliss.cli.common`: what every command shares (exit statuses, the scene loaded, the
  output folder checked before work, the progress bar);
- :mod:`corliss.cli.run_command`: ``corliss run``;
- :mod:`corliss.cli.gear_commands`: ``events``, ``gear``, ``animate``, ``design``;
- :mod:`corliss.cli.study_commands`: ``sweep``, ``compare``, ``study``, ``fit``;
- :mod:`corliss.cli.catalogue_commands`: ``list``, ``explain``;
- :mod:`corliss.cli.tool_commands`: ``bench``, ``workbench``;
- :mod:`corliss.cli.heartbeat`: the line that tells how long a slow first step has taken.
"""
