"""The README's Python example runs exactly as printed, from a checkout's root."""

from __future__ import annotations

import os
import re
from pathlib import Path

import matplotlib
import pandas as pd

ROOT = Path(__file__).resolve().parent.parent


def test_readme_python_example_runs_as_printed(tmp_path, monkeypatch):
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, "the README has no Python example"
    example = blocks[0]
    # run where a user of the checkout runs it: scenes/ beside, out/ written there
    (tmp_path / "scenes").symlink_to(ROOT / "scenes")
    monkeypatch.chdir(tmp_path)
    matplotlib.use("Agg")
    namespace: dict = {}
    exec(compile(example, "README.md", "exec"), namespace)
    card = pd.read_csv(tmp_path / "out" / "card.csv")
    assert {"end", "piston_frac", "p_psia"} <= set(card.columns)
    assert set(card["end"]) == {"head", "crank"}
    assert (tmp_path / "out" / "card.meta.json").is_file()
    assert namespace["drawn"]["ax"].lines
    assert all(Path(p).is_file() for p in namespace["files"].values())
    assert os.access(tmp_path / "out" / "default.summary.json", os.R_OK)
