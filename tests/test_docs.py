"""The documentation site (issue 16) builds from a checkout without a single warning,
and holds what it promises: a page for every public module, the notebooks with their
stored figures, a figure for every gallery example, and no citation of a private
copy's line numbers anywhere in the package, its scenes, tests or documentation.

The build is the README's command, ``sphinx-build -W --keep-going -b html docs DIR``:
offline (nothing fetched), the notebooks shown as stored (``tests/test_notebooks.py``
runs them), the gallery's short examples executed.
"""

from __future__ import annotations

import json
import os
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import pytest

import corliss

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"


def _public_modules() -> list[str]:
    """Every module of the package whose dotted name has no part with a leading
    underscore."""
    names = ["corliss"]
    for info in pkgutil.walk_packages(corliss.__path__, "corliss."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return sorted(names)


def _stored_figures(path: Path) -> int:
    nb = json.loads(path.read_text(encoding="utf-8"))
    return sum(1 for c in nb["cells"] if c["cell_type"] == "code"
               for o in c.get("outputs", []) if "image/png" in o.get("data", {}))


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    assert (DOCS / "scene-reference.md").is_file(), (
        "docs/scene-reference.md, the scene key reference generated from the loader's "
        "declarations, is missing: the site's toctree names it")
    tmp = tmp_path_factory.mktemp("docs")
    out = tmp / "html"
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
           "-d", str(tmp / "doctrees"), str(DOCS), str(out)]
    env = {**os.environ, "MPLBACKEND": "Agg"}
    proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=900)
    assert proc.returncode == 0, f"sphinx-build failed or warned:\n{proc.stderr[-8000:]}"
    # numpydoc reports a docstring section it does not know as a Python warning, which
    # -W does not turn into an error; it is a warning of the build all the same.
    numpydoc = [line for line in proc.stderr.splitlines()
                if "numpydoc" in line and "Warning" in line]
    assert not numpydoc, "numpydoc warned:\n" + "\n".join(numpydoc)
    return out


def test_every_public_module_has_its_api_page(site):
    missing = [m for m in _public_modules() if not (site / "api" / f"{m}.html").is_file()]
    assert not missing, f"no API page for {missing}"


def test_the_notebooks_are_shown_with_their_stored_figures(site):
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    assert notebooks
    for nb in notebooks:
        page = site / "notebooks" / f"{nb.stem}.html"
        assert page.is_file(), f"no page for {nb.name}"
        shown = len(re.findall(r"<img [^>]*src=\"[^\"]*\.png\"", page.read_text("utf-8")))
        assert shown >= _stored_figures(nb) >= 1, f"{nb.name}: {shown} figures shown"


def test_every_gallery_example_ran_and_drew_its_figure(site):
    """A still figure (sphinx-gallery's ``sphx_glr_<example>_001`` image) or an
    animation embedded in the page (``matplotlib_animations``)."""
    examples = sorted((ROOT / "examples").glob("plot_*.py"))
    assert examples
    for ex in examples:
        page = (site / "auto_examples" / f"{ex.stem}.html").read_text("utf-8")
        drawn = f"sphx_glr_{ex.stem}_001" in page or 'class="animation"' in page
        assert drawn, f"{ex.name} drew no figure"


def test_the_pages_are_all_there(site):
    for page in ("getting-started", "scenes", "scene-reference", "governing", "studies",
                 "accuracy", "bibliography", "changelog", "notebooks", "architecture",
                 "validation/condensation", "physics/thermo", "physics/valves",
                 "physics/engine", "physics/effects", "physics/governors"):
        assert (site / f"{page}.html").is_file(), page


#: A citation of a line of a private text copy (the letter L and the line's number), or
#: of a section of someone's private reading notes.
PRIVATE_LINE = re.compile(r"\bL\d{3,5}\b|\bnotes,? §|\bof the notes\b")


def test_no_citation_points_at_a_private_line_number():
    """Books are cited by article and page (the bibliography's editions); a line number
    of someone's OCR file, or a section of their notes, helps no reader."""
    found = []
    for folder, pattern in (("corliss", "*.py"), ("tests", "*.py"), ("scenes", "*.toml"),
                            ("docs", "*.md"), ("examples", "*.py"), ("benchmarks", "*.py")):
        for path in sorted((ROOT / folder).rglob(pattern)):
            if any(part.startswith((".", "_")) and part != "__init__.py"
                   for part in path.relative_to(ROOT).parts):
                continue
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if PRIVATE_LINE.search(line):
                    found.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not found, "line numbers of a private copy cited:\n" + "\n".join(found)
