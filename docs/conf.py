"""Sphinx configuration of the corliss documentation.

Build it (offline, nothing fetched) from the repository's root with::

    sphinx-build -W --keep-going -b html docs docs/_build/html

``tests/test_docs.py`` runs the same build and fails on any warning.  The drawn
figures the pages show (``default-card.png``, ``corliss-gear-keys.png``) are redrawn by
``docs/figures.py`` at every build.  Generated
sources (the API pages, the gallery, the notebooks copied from ``notebooks/``) are
written under ``docs/`` at build time and are not committed.
"""

from __future__ import annotations

import filecmp
import shutil
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))

import corliss  # noqa: E402

# -- project -----------------------------------------------------------------------
project = "corliss"
author = "the corliss developers"
copyright = "the corliss developers, MIT licence"
version = release = corliss.__version__

# -- extensions ----------------------------------------------------------------------
extensions = [
    "myst_nb",                    # Markdown pages and the notebooks (MyST)
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"
exclude_patterns = ["_build", "**.ipynb_checkpoints", "auto_examples/*.ipynb",
                    "auto_examples/*.py", "auto_examples/*.zip", "auto_examples/*.md5",
                    "auto_examples/*.codeobj.json", "validation/*.csv"]
templates_path = ["_templates"]

# -- MyST and the notebooks ------------------------------------------------------------
# The notebooks are executed by tests/test_notebooks.py and stored with their figures;
# the documentation shows what is stored and never runs them.
nb_execution_mode = "off"
myst_enable_extensions = ["dollarmath", "deflist", "colon_fence"]
myst_heading_anchors = 3


def _copy_notebooks() -> None:
    """Copy ``notebooks/*.ipynb`` into ``docs/notebooks/`` (Sphinx reads only its own
    folder); a notebook whose copy is already the same is left alone, so an
    incremental build does not reread it."""
    target = DOCS / "notebooks"
    target.mkdir(exist_ok=True)
    sources = sorted((ROOT / "notebooks").glob("*.ipynb"))
    for src in sources:
        dst = target / src.name
        if not dst.exists() or not filecmp.cmp(src, dst, shallow=False):
            shutil.copyfile(src, dst)
    for stale in set(target.glob("*.ipynb")) - {target / s.name for s in sources}:
        stale.unlink()          # a notebook since removed from notebooks/


_copy_notebooks()

# -- the drawn figures --------------------------------------------------------------------
# The README's card and the scene reference's sketches, drawn afresh by docs/figures.py
# (a file is rewritten only when the drawing changed).
sys.path.insert(0, str(DOCS))
import figures  # noqa: E402

figures.write_figures(DOCS)

# -- the API reference -------------------------------------------------------------------
# docs/api/ is generated afresh by autosummary at every build, so that a module since
# removed or renamed leaves no stale page behind.
shutil.rmtree(DOCS / "api", ignore_errors=True)
autosummary_generate = True
autosummary_generate_overwrite = True
autosummary_imported_members = False
autodoc_default_options = {
    "members": True,
    "undoc-members": True,
    "show-inheritance": True,
    "member-order": "bysource",
    "ignore-module-all": True,        # a package documents what it defines, once
}
autodoc_typehints = "none"            # numpydoc's Parameters carry the types and units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False   # members are documented by autodoc, once
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = True
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()   # tests/docstring_rules.py checks them

# -- the gallery --------------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"plot_",
    "matplotlib_animations": True,
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib",),
    "show_memory": False,
}

# -- HTML ---------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"corliss {release}"
html_static_path: list[str] = []
