"""The light frame a steady run builds reads and writes as pandas would.

A steady run's tables are :class:`corliss.frames.frame.Frame` (no pandas imported) and reach
users as DataFrames; the CSVs are written from the frame by hand.  The reference for
each is pandas itself: the same rows give the same DataFrame, and the same table the
same CSV bytes as ``DataFrame.to_csv(index=False, float_format="%.9g")``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from corliss.frames.frame import Frame
from corliss.files.run_output import FLOAT_FORMAT, write_csv

ROWS = [{"cycle": 1, "work_J": 1.5, "m_supply_kg": 0.25},
        {"cycle": 2, "work_J": 2.5e-7, "m_supply_kg": 0.125, "Q_head_J": -3.0}]


def test_rows_make_the_dataframe_pandas_makes():
    """Names in order of first appearance, NaN where a row lacks one, ints as int64."""
    got = Frame.from_rows(ROWS).to_pandas()
    pd.testing.assert_frame_equal(got, pd.DataFrame(ROWS))


def test_reads_match_pandas():
    f = Frame.from_rows(ROWS)
    d = pd.DataFrame(ROWS)
    assert f.columns == list(d.columns) and len(f) == len(d)
    last, last_pd = f.iloc[-1], d.iloc[-1]
    assert list(last.index) == list(last_pd.index)
    assert all(float(last[k]) == float(last_pd[k]) for k in last.index)
    mask = f["cycle"] == f["cycle"].max()
    pd.testing.assert_frame_equal(f[mask].to_pandas(),
                                  d[d["cycle"] == d["cycle"].max()].reset_index(drop=True))
    assert f["work_J"].max() == d["work_J"].max() and f["work_J"].iloc[0] == 1.5
    stacked = Frame.concat([f, f]).to_pandas()
    pd.testing.assert_frame_equal(stacked, pd.concat([d, d], ignore_index=True))
    with pytest.raises(ValueError):
        Frame.concat([f, f[["cycle"]]])


@pytest.mark.parametrize("end", [["head", "crank"], ["head", "crank, lp"]])
def test_csv_bytes_are_pandas_bytes(tmp_path, end):
    """A card table (text and floats, a NaN) as pandas writes it; text that needs
    quoting goes through pandas itself."""
    f = Frame({"end": np.array(end, dtype=object), "p_Pa": [1.0 / 3.0, np.nan],
               "cycle": [1, 2]})
    write_csv(f, tmp_path / "light.csv")
    f.to_pandas().to_csv(tmp_path / "pandas.csv", index=False, float_format=FLOAT_FORMAT)
    assert (tmp_path / "light.csv").read_bytes() == (tmp_path / "pandas.csv").read_bytes()
