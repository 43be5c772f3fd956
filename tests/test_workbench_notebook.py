"""The workbench in a notebook (``corliss.workbench.view``), built without a browser.

The view Bokeh's ``show`` puts in a notebook is the page's document: here it is built
in a plain Bokeh document, its run taken in a thread of this process, and the card it
draws is read from the document itself.  Given the settings an address of the page
gives (the head-end lap at 1.1 in), its numbers are those of
:func:`corliss.simulate` of the scene with that lap, and cut-off at the head end comes
earlier than at the scene's own lap of 1 in (more steam lap, earlier cut-off:
Spangler, *Valve Gears*, Art. 25); a value the loader refuses is shown beside its
control with the loader's message.  The notebook's own address is left alone.
"""

from __future__ import annotations

import html
import re
import tomllib

import pytest

pytest.importorskip("bokeh", reason="the workbench extra (bokeh) is not installed")

from bokeh.document import Document  # noqa: E402

from corliss import scene_from_dict, simulate  # noqa: E402
from corliss.scene.loader import default_scene_path  # noqa: E402

#: A run in a fresh checkout compiles the kernels first (minutes on a loaded machine).
RUN_s = 900


def _drawn(doc) -> None:
    """Run the document's pending callbacks (what a server session does between
    messages) until none is left: the run's answer drawn, then the rest of the page."""
    for _ in range(10):
        pending = list(doc.session_callbacks)
        if not pending:
            return
        for cb in pending:
            cb.callback()


def _summary(bench) -> dict:
    return dict(re.findall(r"<td[^>]*>([^<]+)</td><td class='wb-num'[^>]*>([^<]+)</td>",
                           bench.numbers.text))


def _events(bench) -> dict:
    rows = re.findall(r"<tr><td[^>]*>([^<]+)</td><td[^>]*class='wb-head'>([^<]+)</td>",
                      bench.numbers.text)
    return dict(rows)


def test_the_notebook_view_of_an_address_setting_draws_that_engine():
    from corliss.workbench import view
    from corliss.workbench.app import Runner

    settings = {"valve_gear.lap[head]": "1.1 in", "run.speed": "fast please"}
    app = view("default", settings=settings, runner=Runner(in_process=True))
    doc = Document()
    app.initialize_document(doc)
    bench = doc.workbench
    try:
        bench.future.result(timeout=RUN_s)
        _drawn(doc)
    finally:
        bench.runner.shutdown()

    lap = next(it.widget for it in bench.widgets if it.control.name == "valve_gear.lap[head]")
    assert lap.value == pytest.approx(1.1, abs=1e-12)
    speed = next(it for it in bench.widgets if it.control.name == "run.speed")
    assert speed.error.visible
    assert "run.speed = 'fast please' is not valid" in html.unescape(speed.error.text)
    assert speed.widget.value == pytest.approx(120.0)      # the scene's speed kept

    # the card drawn is corliss.simulate's of the scene with that lap
    text = bench.toml.value
    assert tomllib.loads(text)["valve_gear"]["lap"] == ["1.1 in", "1 in"]
    result = simulate(scene_from_dict(tomllib.loads(text), name="default"))
    s = result.summary
    shown = _summary(bench)
    assert shown["indicated power"] == f"{s['indicated_power_hp']:.2f} ihp"
    assert shown["steam per ihp-hour"] == f"{s['water_rate_lb_per_ihp_h']:.2f} lb"

    # more lap at the head end, earlier cut-off there (Spangler Art. 25)
    own = tomllib.loads(default_scene_path().read_text())
    own.setdefault("run", {})["fidelity"] = "fast"
    base_cutoff = simulate(scene_from_dict(own, name="default")).events["head"]["cutoff_frac"]
    shown_cutoff = float(_events(bench)["cut-off, fraction of stroke"])
    assert shown_cutoff < base_cutoff
    # the table writes three significant figures
    assert shown_cutoff == pytest.approx(result.events["head"]["cutoff_frac"], abs=5e-4)

    # a notebook's address is its own: the view neither writes nor listens to it
    assert bench.address.data["query"] == [""] and not doc.callbacks.js_event_callbacks
