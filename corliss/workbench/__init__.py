"""The workbench: set an engine by hand in a browser page and watch its card redrawn.

``corliss workbench [SCENE]`` serves the page (:func:`~corliss.workbench.server.serve`)
on the loopback address.  Built on Bokeh, with every asset served from the installed
package.  Needs the ``workbench`` extra (``pip install "corliss[workbench]"``).
"""
