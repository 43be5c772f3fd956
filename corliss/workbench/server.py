"""Serve the workbench page on the loopback address.

The page's every asset (BokehJS, its widgets and styles) is served by this server from
the installed ``bokeh`` package (its ``server`` resources mode): nothing is fetched from
the network, so the page works on a machine with none.  The server listens on
127.0.0.1 unless told otherwise, and accepts the page's websocket only from the host
it was served as.
"""

from __future__ import annotations

import logging
import socket
import webbrowser
from pathlib import Path

from bokeh.application import Application
from bokeh.application.handlers.function import FunctionHandler
from bokeh.server.server import Server
from bokeh.settings import settings

from corliss.engine.options import PRESETS
from corliss.errors import InputError
from corliss.keys.textfiles import read_text
from corliss.logs import NOTICE
from corliss.scene.loader import default_scene_path, find_scene, load_scene
from corliss.workbench.app import Runner, make_document

log = logging.getLogger(__name__)


def free_port(address: str = "127.0.0.1") -> int:
    """A port free on ``address`` now (the system's choice).

    Parameters
    ----------
    address : str, optional
        The address to bind.

    Returns
    -------
    int
        The port.
    """
    with socket.socket(socket.AF_INET6 if ":" in address else socket.AF_INET) as s:
        s.bind((address, 0))
        return s.getsockname()[1]


def scene_source(scene: str | None, fidelity: str | None = "fast") -> tuple[Path, str]:
    """The workbench's scene file and its text, the scene loaded once to check it.

    Parameters
    ----------
    scene : str or None
        A scene file or a bundled scene's name (None: the bundled default scene).
    fidelity : str or None, optional
        The preset the page starts at (None: the scene's).

    Returns
    -------
    tuple
        (its path, its TOML text).

    Raises
    ------
    InputError
        A scene that is not there or does not load, or a fidelity that is not a preset.
    """
    path = Path(find_scene(scene) if scene is not None else default_scene_path())
    load_scene(path)                   # a bad scene is the user's mistake: say so first
    text = read_text(path, "scene", "a scene file (.toml)")
    if fidelity is not None and fidelity not in PRESETS:
        raise InputError("--fidelity", fidelity, "one of " + ", ".join(PRESETS))
    return path, text


def workbench_server(scene: str | None = None, *, port: int | None = None,
                     address: str = "127.0.0.1", fidelity: str | None = "fast",
                     runner: Runner | None = None) -> Server:
    """A Bokeh server of the workbench page, not yet started.

    Parameters
    ----------
    scene : str, optional
        A scene file or a bundled scene's name (default: the bundled default scene).
    port : int, optional
        The port (default: a free one).
    address : str, optional
        The address to listen on (default the loopback address).
    fidelity : str or None, optional
        The preset the page starts at (default ``"fast"``; None: the scene's).
    runner : Runner, optional
        The worker the runs go to (default: a worker process of its own).

    Returns
    -------
    bokeh.server.server.Server
        The server; ``server.port`` is its port, ``server.workbench_url`` its page.

    Raises
    ------
    InputError
        A scene that is not there or does not load, a fidelity that is not a preset,
        a port out of range.
    """
    path, text = scene_source(scene, fidelity)
    if port is None or port == 0:
        port = free_port(address)
    if not 0 < port < 65536:
        raise InputError("--port", port, "a port number from 1 to 65535")
    settings.resources.set_value("server")       # BokehJS from this server, never a CDN
    runner = runner or Runner()
    app = Application(FunctionHandler(make_document(text, path.stem, str(path), runner,
                                                    fidelity)))
    hosts = [f"{address}:{port}"] + ([f"localhost:{port}"] if address == "127.0.0.1" else [])
    server = Server({"/": app}, port=port, address=address, allow_websocket_origin=hosts)
    server.workbench_url = f"http://{address}:{port}/"
    server.workbench_runner = runner
    return server


def serve(scene: str | None = None, *, port: int | None = None, address: str = "127.0.0.1",
          open_browser: bool = True, fidelity: str | None = "fast") -> None:
    """Serve the workbench until interrupted (``corliss workbench``).

    Parameters
    ----------
    scene : str, optional
        A scene file or a bundled scene's name.
    port : int, optional
        The port (default: a free one).
    address : str, optional
        The address to listen on (default 127.0.0.1).
    open_browser : bool, optional
        Open the page in the default browser.
    fidelity : str or None, optional
        The preset the page starts at.
    """
    server = workbench_server(scene, port=port, address=address, fidelity=fidelity)
    server.start()
    log.log(NOTICE, "the workbench is at %s (Ctrl-C stops it)", server.workbench_url)
    if open_browser:
        server.io_loop.add_callback(webbrowser.open, server.workbench_url)
    try:
        server.io_loop.start()
    except KeyboardInterrupt:
        pass
    finally:
        server.workbench_runner.shutdown()
        server.stop()
