"""The documentation's drawn figures, made from the package at every documentation build.

``docs/conf.py`` calls :func:`write_figures` before Sphinx reads a page, so a figure the
README or a page shows is the one the code draws now; by hand::

    python docs/figures.py [FOLDER]

- ``default-card.png`` (README, index): the default scene's card, run as ``corliss run``
  runs it (the scene's own fidelity), so the numbers in its title are the run's;
- ``corliss-gear-keys.png`` (scene reference): the Corliss gear's keys sketched from the
  bundled ``corliss-trip-gear`` scene's geometry.

A file is rewritten only when its bytes change (the PNGs carry no date or version), so a
build that draws the same figures leaves the checkout as it was.
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import corliss  # noqa: E402
from corliss.engine.model import build_gear  # noqa: E402
from corliss.plot.corliss_keys import plot_corliss_keys  # noqa: E402
from corliss.scene.loader import find_scene, load_scene  # noqa: E402

DOCS = Path(__file__).resolve().parent
#: PNG metadata without the matplotlib version, so the bytes depend on the drawing alone.
METADATA = {"Software": None}


def default_card(path: Path) -> dict:
    """The default scene's card, at the scene's own fidelity, as ``corliss run`` draws it.

    Parameters
    ----------
    path : Path
        The PNG to write.

    Returns
    -------
    dict
        The run's summary, and the card's title under ``"title"``.
    """
    result = corliss.simulate(corliss.load_scene(corliss.default_scene_path()))
    drawn = result.plot("card")
    fig = drawn["ax"].figure
    try:
        _save(fig, path, dpi=100)
    finally:
        plt.close(fig)
    return {**result.summary, "title": drawn["ax"].get_title()}


def corliss_gear_keys(path: Path) -> dict:
    """The Corliss gear's keys on the bundled ``corliss-trip-gear`` scene's geometry.

    Parameters
    ----------
    path : Path
        The PNG to write.

    Returns
    -------
    dict
        What :func:`corliss.plot.corliss_keys.plot_corliss_keys` drew.
    """
    scene = load_scene(find_scene("corliss-trip-gear"))
    drawn = plot_corliss_keys(build_gear(scene), units_system=scene.output.units)
    try:
        drawn["figure"].suptitle(f"Corliss gear's keys: {scene.title}", fontsize=11)
        _save(drawn["figure"], path, dpi=90)
    finally:
        plt.close(drawn["figure"])
    return drawn


def _save(fig, path: Path, dpi: int) -> None:
    """Write the figure as PNG, only when its bytes differ from the file's."""
    import io
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight", metadata=METADATA)
    data = buf.getvalue()
    if not path.exists() or path.read_bytes() != data:
        path.write_bytes(data)


#: Each figure: file name -> drawing.
FIGURES = {"default-card.png": default_card, "corliss-gear-keys.png": corliss_gear_keys}


def write_figures(folder: Path = DOCS) -> dict:
    """Draw every figure of :data:`FIGURES` into ``folder``.

    Parameters
    ----------
    folder : Path, optional
        Where to write them (``docs/`` by default).

    Returns
    -------
    dict
        File name -> what its drawing returned.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    return {name: draw(folder / name) for name, draw in FIGURES.items()}


if __name__ == "__main__":
    write_figures(Path(sys.argv[1]) if len(sys.argv) > 1 else DOCS)
