"""The default scene's outputs, to the bit: start-up work must not change a result.

Making ``corliss run`` start faster (fewer imports, the steam table read uncompressed,
numba started without ``scipy.linalg``) changes nothing that is computed: the cycle
count, the tolerances and every number written stay as they were.  This test holds it:
the three CSVs and the summary JSON of ``corliss run --json --no-plots`` on the bundled
default scene are compared byte for byte with the files the run wrote before that work
(commit 1ffcc6f, the table tier, this project's own kind of machine), the summary's
wall-time line excepted (a wall time is never the same twice).

The digests pin results, not physics: a change meant to alter the default scene's
numbers (a new integrator, a new table) writes new files, and its commit replaces the
digests below, saying why, with what this file prints as a script::

    corliss run --json --no-plots --out d && python tests/test_same_outputs.py d

A difference in the last bit only (another processor's arithmetic) shows here first;
the physics tests say whether it matters.
"""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

from corliss.cli import main

#: SHA-256 of each file the default scene's run writes (commit 1ffcc6f).
DIGESTS = {
    "default.timeseries.csv": "2516f85bf5bf8a1a0d9d3fcad1602c9e9ed95ba8c96a4168ceefef314a5ef8c4",
    "default.cycles.csv": "48c26319fdbe7f426476ee1b58e773cceda04acb6a503e1237a9cd86cc510cd1",
    "default.cards.csv": "a74b0c20ddaa09f37dff034c1cdcbc344b5856ce59b14a2f18adf86412497e5b",
    # the summary JSON without its line "wall_time_s"
    "default.summary.json": "8a3735a616a967fa656e7a969f11e3068e580789cf134112ee0aa7f60055920e",
}


def digests(out_dir: Path) -> dict[str, str]:
    """SHA-256 of each file of :data:`DIGESTS` in ``out_dir`` (the summary without its
    wall-time line)."""
    got = {}
    for name in DIGESTS:
        data = (out_dir / name).read_bytes()
        if name.endswith(".json"):
            data = b"".join(line for line in data.splitlines(keepends=True)
                            if b'"wall_time_s"' not in line)
        got[name] = hashlib.sha256(data).hexdigest()
    return got


def test_default_scene_writes_the_same_bytes_as_before(tmp_path, capsys):
    assert main(["run", "--json", "--no-plots", "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    # --json prints the summary file's text
    assert printed.strip() == (tmp_path / "default.summary.json").read_text().strip()
    assert digests(tmp_path) == DIGESTS


if __name__ == "__main__":
    for name, digest in digests(Path(sys.argv[1])).items():
        print(f'    "{name}": "{digest}",')
