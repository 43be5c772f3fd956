"""Ceilings on what a user gives: each input has one, checked before any work starts,
and a value over it is refused naming the input, the value and the ceiling.

The table of limits is ``docs/limits.md``; each constant here says why it is where it
is.  A limit is set well above any engine the books describe, low enough that a run
or a file at it finishes in minutes and fits a desktop's memory.
"""

from __future__ import annotations

#: Most cycles of a steady run (``--cycles``, ``[run] cycles``, a meta file's run).  A
#: periodic state is reached in 3 to 60 cycles (the presets' ``max_cycles``); 10,000
#: cycles at the default 1 degree output are 3.6 million rows of time series, a few
#: hundred megabytes, and minutes of run.
MAX_CYCLES = 10_000
#: Longest simulated time of a transient run [s] (``--duration``, ``[run] duration``,
#: ``max_duration``): an hour of an engine's life.
MAX_DURATION_S = 3600.0
#: Most rows of a run's time series [-] (counted before the run by
#: :func:`corliss.engine.output_size.output_samples`: a cycle's output steps times the
#: cycles recorded, a transient's turns times its samples a turn).  10,000 cycles at the
#: default 1 degree output are 3.61 million rows; a row of a steady run is 14 to 30
#: columns, some 200 bytes of CSV and 150 to 250 bytes in memory, so the most a run may
#: write is about a gigabyte of CSV and as much memory: minutes of writing, a desktop's
#: memory.  A card is one cycle of an end: at most 36,001 points (a 0.01 deg step).
MAX_OUTPUT_SAMPLES = 5_000_000
#: Largest card file a fit reads [bytes]: a card digitised at a point per tenth of a
#: degree for four ends is some 14,400 lines, under a megabyte.
MAX_CARD_BYTES = 2_000_000
#: Most points of a card over all its ends [-] (a fit's cost grows with them: 17.5 MB
#: of card took nine minutes and 6 GB).
MAX_CARD_POINTS = 20_000
#: How far a card's ``piston_frac`` may lie outside [0, 1], a digitiser's slip [-].
CARD_FRACTION_SLACK = 0.02
#: Longest scene title [characters]: a title is a line over a figure and in every
#: file's header (a 10 MB title crashed the plot after 144 s).
MAX_TITLE_CHARS = 200
#: Repeats of ``corliss bench`` per setting (the median is taken) [-].
MAX_BENCH_REPEATS = 100
