"""The files a run, a study, a fit or a design writes out, each whole or not at all.

- :mod:`corliss.files.run_output`: a run's tables, summary and figures;
- :mod:`corliss.files.study_output`: a study's table, scene, summary and figure;
- :mod:`corliss.files.fit_output`: :func:`~corliss.files.fit_output.fit`, a fit and its files;
- :mod:`corliss.files.design_output`: :func:`~corliss.files.design_output.design`, a valve
  designed for the events asked, written back as a scene with its diagrams.
"""
