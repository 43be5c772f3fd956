"""The workbench in a Jupyter notebook: the page's view as a Bokeh application.

:func:`view` returns the workbench of a scene as a Bokeh
:class:`~bokeh.application.Application`; Bokeh's ``show`` of it in a notebook (after
``output_notebook()``) runs it on a Bokeh server inside the notebook's kernel and
shows it in the cell's output, with the controls, the drawings and the gear in motion
of the page.  The runs go to a worker process as on the page.  The notebook's address
is its own: the view does not write its settings there; ``settings`` gives it the
settings an address of the page gives (``{"valve_gear.lap[head]": "1.05 in"}``).
"""

from __future__ import annotations

from bokeh.application import Application
from bokeh.application.handlers.function import FunctionHandler

from corliss.workbench.app import Runner, make_document
from corliss.workbench.server import scene_source


def view(scene: str | None = None, *, settings: dict | None = None,
         fidelity: str | None = "fast", runner: Runner | None = None) -> Application:
    """The workbench of a scene, for Bokeh's ``show`` in a notebook.

    Parameters
    ----------
    scene : str, optional
        A scene file or a bundled scene's name (default: the bundled default scene).
    settings : dict, optional
        ``{control name: value as text}``, as the page's address writes them
        (``{"valve_gear.lap[head]": "1.05 in", "run.speed": "150 rpm"}``); a value the
        loader refuses is shown beside its control with its message.
    fidelity : str or None, optional
        The preset the view starts at (default ``"fast"``; None: the scene's).
    runner : Runner, optional
        Where the runs go (default: worker processes of the view's own).

    Returns
    -------
    bokeh.application.Application
        The view: ``bokeh.io.show(view(...))`` in a notebook; each time it is shown,
        a document of its own, whose :class:`~corliss.workbench.app.Workbench` (the
        document's ``workbench``) is added to the application's ``workbenches``
        (``app.workbenches[-1].scene_text()``: the scene of the card shown).

    Raises
    ------
    InputError
        A scene that is not there or does not load, or a fidelity that is not a preset.
    """
    path, text = scene_source(scene, fidelity)
    runner = runner or Runner()
    make = make_document(text, path.stem, str(path), runner, fidelity, settings,
                         address=False)
    opened: list = []

    def modify_doc(doc):
        make(doc)
        opened.append(doc.workbench)

    app = Application(FunctionHandler(modify_doc))
    app.workbenches = opened
    return app
