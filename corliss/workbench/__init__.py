"""The workbench: set an engine by hand in a browser page and watch its card redrawn.

``corliss workbench [SCENE]`` serves the page (:func:`~corliss.workbench.server.serve`)
on the loopback address.  Built on Bokeh, with every asset served from the installed
package.  Needs the ``workbench`` extra (``pip install "corliss[workbench]"``).
:func:`view` is the same view in a Jupyter notebook
(:func:`corliss.workbench.notebook.view`), loaded on first use.
"""

import importlib

__all__ = ["view"]


def __getattr__(name: str):
    """Load :func:`view` from its module the first time it is asked for.

    Parameters
    ----------
    name : str
        The attribute asked for.

    Returns
    -------
    object
        :func:`corliss.workbench.notebook.view`.
    """
    if name == "view":
        return importlib.import_module("corliss.workbench.notebook").view
    raise AttributeError(f"module 'corliss.workbench' has no attribute {name!r}")
