"""The workbench page: a Bokeh document of controls and the drawings they redraw.

One :class:`Workbench` per browser session.  A control's change edits the scene's
tables; the edited scene is run in the worker process (:class:`Runner`), never on the
server's event loop, so the page answers while a slow run works (it says it is
working).  Changes that come while a run is in flight are coalesced: when it ends,
the newest settings run next.  A scene the loader refuses shows the loader's message
beside the control it names (or the control just moved), and the last good drawing
stays.  The page's TOML is the source scene's text with the settings put in place
(:func:`corliss.workbench.scene_text.edited_text`), saved by the browser itself: the
server writes no file and takes no path from the page.

The card and the numbers beside it go to the page first, the other panels on the next
tick.  The gear in motion is drawn on demand in a second worker
(:mod:`corliss.workbench.motion`), so the card is redrawn meanwhile.  The page's
settings are kept in its address as the controls move, and a page opened at such an
address starts from them (:mod:`corliss.workbench.address`); in a notebook
(:func:`corliss.workbench.notebook.view`) the address is left alone.
"""

from __future__ import annotations

import html
import logging
import multiprocessing
import threading
import time
import tomllib
from concurrent.futures import Future, ProcessPoolExecutor, ThreadPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from functools import partial

import numpy as np
from bokeh.layouts import column, row
from bokeh import models as bkm         # Div by its module: its docstring upsets numpydoc
from bokeh.models import (Button, CheckboxGroup, ColumnDataSource, CustomJS, LabelSet,
                          RadioButtonGroup, Select, Slider, Span, TextAreaInput)
from bokeh.plotting import figure

from corliss.keys.edits import with_keys
from corliss.workbench.address import address_query, read_address
from corliss.workbench.compute import compute_view
from corliss.workbench.controls import Control, controls_for, scene_value
from corliss.workbench.motion import motion_view
from corliss.workbench.scene_text import edited_text

log = logging.getLogger(__name__)

_NAN = float("nan")
#: A run still in flight after this long says it is working [ms].
WORKING_AFTER_ms = 120
_PORT_STYLE = {"head_steam": ("black", "solid"), "crank_steam": ("black", "dashed"),
               "head_exhaust": ("#888888", "solid"), "crank_exhaust": ("#888888", "dashed")}


class Runner:
    """The worker processes the runs go to, shared by every session of a server: one
    for the cards, one for the gear in motion (so that an animation being drawn never
    holds up a card).

    Parameters
    ----------
    in_process : bool, optional
        Run in threads of this process instead (tests of the page's logic); a run
        then holds the interpreter while compiled code runs.
    """

    def __init__(self, in_process: bool = False):
        self.in_process = in_process
        self._lock = threading.Lock()
        self._pools: dict = {}

    def _executor(self, which: str):
        if which not in self._pools:
            if self.in_process:
                self._pools[which] = ThreadPoolExecutor(max_workers=1)
            else:
                self._pools[which] = ProcessPoolExecutor(
                    max_workers=1, mp_context=multiprocessing.get_context("spawn"))
        return self._pools[which]

    def _submit(self, which: str, fn, *args) -> Future:
        with self._lock:
            try:
                return self._executor(which).submit(fn, *args)
            except BrokenProcessPool:       # the worker died (killed): start another
                log.warning("the workbench's worker process stopped; starting another")
                del self._pools[which]
                return self._executor(which).submit(fn, *args)

    def submit(self, data: dict, name: str, source: str | None) -> Future:
        """Run :func:`~corliss.workbench.compute.compute_view` of a scene's tables.

        Parameters
        ----------
        data : dict
            The scene's tables.
        name, source : str
            The scene's name and file.

        Returns
        -------
        concurrent.futures.Future
            Its view.
        """
        return self._submit("card", compute_view, data, name, source)

    def submit_motion(self, data: dict, name: str, source: str | None) -> Future:
        """Draw :func:`~corliss.workbench.motion.motion_view` of a scene's tables, in
        the second worker.

        Parameters
        ----------
        data : dict
            The scene's tables.
        name, source : str
            The scene's name and file.

        Returns
        -------
        concurrent.futures.Future
            Its frames.
        """
        return self._submit("motion", motion_view, data, name, source)

    def shutdown(self) -> None:
        """Stop the workers."""
        with self._lock:
            for pool in self._pools.values():
                pool.shutdown(wait=False, cancel_futures=True)
            self._pools = {}


@dataclass
class _Widget:
    control: Control
    widget: object
    error: bkm.Div


def _css(name: str) -> str:
    return "wb-" + "".join(c if c.isalnum() else "-" for c in name)


class Workbench:
    """The page of one browser session.

    Parameters
    ----------
    doc : bokeh.document.Document
        The session's document, filled here.
    text : str
        The source scene's TOML text.
    name : str
        The scene's name (the saved file's name).
    source : str or None
        The scene's file.
    runner : Runner
        Where the runs go.
    fidelity : str or None
        A fidelity preset the page starts at (None: the scene's).
    settings : dict, optional
        ``{control name: value as text}``: settings the page starts with, as its
        address writes them (:mod:`corliss.workbench.address`); the loader's message
        beside each one it refuses.
    address : bool, optional
        Keep the browser's address showing the page's settings (False in a notebook,
        whose address is the notebook's).
    """

    def __init__(self, doc, text: str, name: str, source: str | None, runner: Runner,
                 fidelity: str | None = "fast", settings: dict | None = None,
                 address: bool = True):
        self.doc, self.text, self.name, self.source, self.runner = doc, text, name, source, runner
        self.base = tomllib.loads(text)
        self.edits: dict = {}
        if fidelity is not None:
            self.edits["run.fidelity"] = fidelity
        read = read_address(settings or {}, self.base, self.edits, name)
        self.edits = read.edits
        self.address_errors: dict = read.errors
        self.address_notes: list = read.notes
        self.sync_address = address
        self.motion_busy = False
        self.motion_edits: dict | None = None
        self.busy = False
        self.pending = False
        self.session = getattr(doc, "session_context", None) is not None
        self.future: Future | None = None       # the run asked for last
        self.moved: _Widget | None = None
        self.changed_at = time.perf_counter()
        self.latencies_ms: list[float] = []
        self._build()
        self.request(None)

    # --- state --------------------------------------------------------------------------

    @property
    def data(self) -> dict:
        """The scene's tables with the page's settings.

        Returns
        -------
        dict
            The edited tables.
        """
        return with_keys(self.base, self.edits)

    @property
    def units(self) -> str:
        """The unit system the page shows (the scene's ``output.units``).

        Returns
        -------
        str
            ``"US"`` or ``"SI"``.
        """
        return self.data.get("output", {}).get("units", "US")

    def scene_text(self, edits: dict | None = None) -> str:
        """The scene as TOML: the source's text, its comments kept, the settings in place.

        Parameters
        ----------
        edits : dict, optional
            ``{dotted key: value}`` (default: the page's settings now).

        Returns
        -------
        str
            The text.
        """
        edits = self.edits if edits is None else edits
        return edited_text(self.text, edits) if edits else self.text

    # --- the page -----------------------------------------------------------------------

    def _control_widget(self, c: Control) -> _Widget:
        css = [_css(c.name)]
        if c.widget in ("slider", "superheat"):
            unit = f" [{c.unit}]" if c.unit else ""
            w = Slider(start=c.start, end=c.stop, step=c.step, value=c.value,
                       title=c.label + unit, width=300, css_classes=css, format="0[.][0000]")
        elif c.widget == "effects":
            chosen = c.value if isinstance(c.value, (list, tuple)) else ()    # words
            w = CheckboxGroup(labels=list(c.choices), css_classes=css,
                              active=[i for i, e in enumerate(c.choices) if e in chosen])
        else:
            w = Select(title=c.label, options=list(c.choices), value=c.value, width=300,
                       css_classes=css)
        err = bkm.Div(text="", visible=False, width=300,
                      css_classes=[css[0] + "-error", "wb-error"],
                      styles={"color": "#a00000", "font-size": "12px"})
        item = _Widget(c, w, err)
        self.values[c.name] = c.value
        prop = "active" if c.widget == "effects" else "value"
        w.on_change(prop, partial(self._on_control, item))
        return item

    def _controls_column(self):
        self.values: dict = {}
        self.widgets = [self._control_widget(c) for c in controls_for(self.data, self.units)]
        kids = []
        for it in self.widgets:
            kids += [it.widget, it.error]
        return column(*kids, width=320, height=880, styles={"overflow-y": "auto"})

    def _build(self) -> None:
        self.units_switch = RadioButtonGroup(labels=["US", "SI"], css_classes=["wb-units"],
                                             active=0 if self.units == "US" else 1)
        self.units_switch.on_change("active", self._on_units)
        self.controls = self._controls_column()
        # fixed sizes: a text changed in them lays out nothing else again
        self.status = bkm.Div(text="working...", css_classes=["wb-status"], width=700,
                              height=20)
        self.notes = bkm.Div(text="".join(f"<div>{html.escape(n)}</div>"
                                          for n in self.address_notes),
                             visible=bool(self.address_notes), css_classes=["wb-notes"],
                             width=700, styles={"color": "#a00000", "font-size": "12px"})
        # the page's settings as an address query, kept in a source that is drawn
        # nowhere (nothing laid out again); the browser shows it in its address bar
        # (history.replaceState: no reload, no request)
        self.address = ColumnDataSource({"query": [""]}, name="wb-address")
        if self.sync_address:
            sync = """
                const q = address.data.query[0];
                if (q && q != window.location.search && window.history
                        && window.history.replaceState)
                    window.history.replaceState(window.history.state, "",
                                                window.location.pathname + q);
            """
            self.address.js_on_change("data", CustomJS(args={"address": self.address},
                                                       code=sync))
            # and a look four times a second, should a change come that the callback
            # above missed
            self.doc.js_on_event("document_ready", CustomJS(
                args={"address": self.address},
                code=sync + "setInterval(() => {" + sync + "}, 250);"))
        # the summary and the events in one Div: one message to the page per redraw
        self.numbers = bkm.Div(text="", css_classes=["wb-numbers"], width=380, height=330)

        # both ends' cards in one source (the shorter padded with NaN): one message
        self.card_src = ColumnDataSource({"hx": [], "hy": [], "cx": [], "cy": []})
        self.marks = ColumnDataSource({"x": [], "y": [], "label": [], "end": []})
        self.card = figure(width=720, height=430, title="indicator card", toolbar_location=None,
                           css_classes=["wb-card"])
        self.card.line("hx", "hy", source=self.card_src, color="black", line_width=1.6,
                       legend_label="head end")
        self.card.line("cx", "cy", source=self.card_src, color="#404040",
                       line_width=1.6, line_dash="dashed", legend_label="crank end")
        self.card.scatter("x", "y", source=self.marks, size=6, color="#a00000")
        self.card.add_layout(LabelSet(x="x", y="y", text="label", source=self.marks,
                                      x_offset=4, y_offset=4, text_font_size="9pt"))
        self.card.add_layout(Span(location=0.0, dimension="width", line_color="#666666",
                                  line_width=1))
        self.vacuum = Span(location=0.0, dimension="width", line_color="#999999",
                           line_dash="dotted")
        self.card.add_layout(self.vacuum)
        self.card.legend.location = "center"
        self.card.legend.background_fill_alpha = 0.0
        self.card.legend.border_line_alpha = 0.0

        self.zsrc = ColumnDataSource({"hx": [], "hy": [], "cx": [], "cy": []})
        self.zcircles = ColumnDataSource({"xs": [], "ys": []})
        self.zeuner = figure(width=380, height=380, title="Zeuner diagram", match_aspect=True,
                             toolbar_location=None, css_classes=["wb-zeuner"])
        self.zeuner.line("hx", "hy", source=self.zsrc, color="black", line_width=1.4,
                         legend_label="head-end valve circle")
        self.zeuner.line("cx", "cy", source=self.zsrc, color="black", line_width=1.4,
                         line_dash="dashed", legend_label="crank-end valve circle")
        self.zeuner.multi_line("xs", "ys", source=self.zcircles, color="#888888",
                               legend_label="lap circles")
        self.zeuner.legend.label_text_font_size = "8pt"
        self.zeuner.legend.background_fill_alpha = 0.6
        self.znote = bkm.Div(text="", visible=False, width=380)

        self.psrc = ColumnDataSource({"deg": [], **{p: [] for p in _PORT_STYLE}})
        self.ports = figure(width=720, height=280, title="port openings",
                            toolbar_location=None, css_classes=["wb-ports"],
                            x_axis_label="crank angle from head-end dead centre [deg]")
        for p, (color, dash) in _PORT_STYLE.items():
            self.ports.line("deg", p, source=self.psrc, color=color, line_dash=dash,
                            line_width=1.4, legend_label=p.replace("_", " "))
        self.ports.legend.label_text_font_size = "8pt"
        self.ports.legend.background_fill_alpha = 0.6

        self.toml = TextAreaInput(value=self.scene_text(), rows=12, width=720, title="scene",
                                  css_classes=["wb-toml"], disabled=True)
        self.save = Button(label="save scene (TOML)", css_classes=["wb-save"], width=200)
        self.save.js_on_click(CustomJS(args={"area": self.toml, "name": f"{self.name}.toml"},
                                       code="""
            const blob = new Blob([area.value], {type: "application/toml"});
            const a = document.createElement("a");
            a.href = URL.createObjectURL(blob);
            a.download = name;
            document.body.appendChild(a);
            a.click();
            setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
        """))

        self.animate = Button(label="the gear in motion", css_classes=["wb-animate"],
                              width=200)
        self.animate.on_click(self._on_animate)
        self.motion_status = bkm.Div(text="the gear's linkage, valve and card as the crank "
                                     "turns, drawn from the exact linkage as "
                                     "<code>corliss animate</code> draws it",
                                     css_classes=["wb-motion-status"], width=700)
        self.motion = bkm.Div(text="", css_classes=["wb-motion"], width=720, visible=False)

        head = bkm.Div(text=f"<b>corliss workbench</b>: {html.escape(self.name)}", width=320)
        self.left = column(head, self.units_switch, self.controls)
        right = column(self.status, self.notes,
                       row(self.card, self.numbers),
                       row(self.ports, column(self.zeuner, self.znote)),
                       row(self.animate, self.motion_status), self.motion,
                       row(column(self.save, self.toml)))
        self.layout = row(self.left, right)
        self.doc.add_root(self.layout)
        self.doc.add_root(self.address)
        self.doc.title = f"corliss workbench: {self.name}"
        self._clear_errors()
        self._sync_address()

    # --- events -------------------------------------------------------------------------

    def _on_control(self, item: _Widget, attr, old, new) -> None:
        c = item.control
        if c.widget == "effects":
            new = [c.choices[i] for i in sorted(new)]
        self.values[c.name] = new
        self.address_errors.pop(c.name, None)
        self.edits[c.key] = scene_value(c, new, self.data)
        self.moved = item
        self._sync_address()
        self.request(item)

    def _on_units(self, attr, old, new) -> None:
        self.edits["output.units"] = ("US", "SI")[new]
        self.controls.children = self._controls_column().children
        self.moved = None
        self._clear_errors()
        self._sync_address()
        self.request(None)

    def address_query(self) -> str:
        """The page's settings as its address's query.

        Returns
        -------
        str
            ``"?scene=...&..."`` (:func:`corliss.workbench.address.address_query`).
        """
        data = self.data
        return address_query(self.name, self.units,
                             [(it.control, self.values[it.control.name])
                              for it in self.widgets], data)

    def _sync_address(self) -> None:
        if not self.sync_address:
            return
        try:
            self.address.data = {"query": [self.address_query()]}
        except Exception:       # a setting the loader will refuse: the address waits
            log.debug("no address for these settings", exc_info=True)

    def _clear_errors(self) -> None:
        """Every control's message cleared, but those an address's value left."""
        for it in self.widgets:
            msg = self.address_errors.get(it.control.name)
            it.error.text = "" if msg is None else \
                f"the address's value was not set: {html.escape(msg)}"
            it.error.visible = msg is not None

    # --- the gear in motion ---------------------------------------------------------------

    def _on_animate(self) -> None:
        if self.motion_busy:
            return
        self.motion_busy = True
        self.animate.disabled = True
        edits = dict(self.edits)
        self.motion_status.text = ("<span class='wb-motion-working'>drawing the gear's "
                                   "frames... (the controls go on working)</span>")
        fut = self.runner.submit_motion(with_keys(self.base, edits), self.name, self.source)
        fut.add_done_callback(lambda f: self.doc.add_next_tick_callback(
            partial(self._apply_motion, f, edits)))

    def _apply_motion(self, fut: Future, edits: dict) -> None:
        self.motion_busy = False
        self.animate.disabled = False
        try:
            view = fut.result()
        except Exception as exc:            # the worker died: say so, keep the page
            log.exception("workbench animation failed")
            view = {"ok": False, "message": f"the drawing failed: {exc}"}
        if not view["ok"]:
            self.motion_status.text = ("<span class='wb-motion-refused'>not drawn: "
                                       f"{html.escape(view['message'])}</span>")
            return
        self.motion_edits = edits
        self.motion.text = (f"<img class='wb-motion-frames' alt='{html.escape(view['title'])}'"
                            f" src='data:image/gif;base64,{view['gif']}'>")
        self.motion.visible = True
        self._motion_caption()

    def _motion_caption(self) -> None:
        if self.motion_edits is None or self.motion_busy:
            return
        stale = self.motion_edits != self.edits
        self.motion_status.text = (
            "<span class='wb-motion-done'>" + ("drawn for an earlier setting: press again "
                                               "for this one" if stale else
                                               "the gear in motion at this setting")
            + "</span>")

    def request(self, item) -> None:
        """Run the scene as the controls set it now, or once the run in flight ends.

        Parameters
        ----------
        item : object or None
            The control that changed (None: the page or the units).
        """
        self.changed_at = time.perf_counter()
        if self.session:        # said only of a run that takes a while: no flicker
            self.doc.add_timeout_callback(self._say_working, WORKING_AFTER_ms)
        else:
            self._say_working()
        if self.busy:
            self.pending = True
            return
        self._submit()

    def _say_working(self) -> None:
        if self.busy or self.pending or not self.session:
            self.status.text = "<span class='wb-working'>working...</span>"

    def _submit(self) -> None:
        self.busy, self.pending = True, False
        started, edits = self.changed_at, dict(self.edits)
        stamps = {"changed": started, "submitted": time.perf_counter()}
        fut = self.runner.submit(with_keys(self.base, edits), self.name, self.source)
        self.future = fut

        def done(f):
            stamps["returned"] = time.perf_counter()
            self.doc.add_next_tick_callback(partial(self._apply, f, started, edits, stamps))
        fut.add_done_callback(done)

    def _apply(self, fut: Future, started: float, edits: dict,
               stamps: dict | None = None) -> None:
        self.busy = False
        stamps = stamps or {}
        stamps["applied"] = time.perf_counter()
        try:
            view = fut.result()
        except Exception as exc:            # the worker died: say so, keep the page
            log.exception("workbench run failed")
            view = {"ok": False, "message": f"the run failed: {exc}", "key": None}
        if self.pending:
            self._submit()
        self._motion_caption()
        if not view["ok"]:
            self._show_error(view)
            return
        self._clear_errors()
        self._draw(view, edits)
        end = time.perf_counter()
        ms = 1e3 * (end - started)
        self.latencies_ms.append(ms)
        if stamps:
            log.debug("redraw %.1f ms: to the worker %.1f, worker and back %.1f (the run "
                      "and views %.1f), waiting for the loop %.1f, drawing %.1f", ms,
                      1e3 * (stamps["submitted"] - started),
                      1e3 * (stamps["returned"] - stamps["submitted"]),
                      1e3 * view["compute_s"], 1e3 * (stamps["applied"] - stamps["returned"]),
                      1e3 * (end - stamps["applied"]))
        if not self.busy:
            note = f"; {html.escape(view['note'])}" if view["note"] else ""
            self.status.text = (f"<span class='wb-done'>redrawn in {ms:.0f} ms</span> "
                                f"(run and drawing {1e3 * view['compute_s']:.0f} ms){note}")

    def _show_error(self, view: dict) -> None:
        key = view.get("key")
        # beside the control just moved, and beside the one the message names where
        # that is another (an eccentricity moved below the lap names the lap)
        named = next((it for it in self.widgets if key is not None and
                      (key == it.control.key or key.startswith(it.control.key + "."))), None)
        targets = {id(t): t for t in (self.moved, named) if t is not None}
        self._clear_errors()
        msg = html.escape(view["message"])
        for t in targets.values():
            t.error.text, t.error.visible = msg, True
        if not self.busy:
            self.status.text = ("<span class='wb-refused'>not redrawn: "
                                f"{msg}</span> The last good card stays.")

    def _draw(self, v: dict, edits: dict, defer: bool = True) -> None:
        """The card, its title and the numbers beside it now; the Zeuner diagram, the
        port openings and the scene's text on the next tick (``defer``), so that the
        card reaches the page first."""
        card = v["card"]
        n = max(len(card["head"]["x"]), len(card["crank"]["x"]))
        self.card_src.data = {f"{e[0]}{c}": _padded(card[e][c], n)
                              for e in ("head", "crank") for c in ("x", "y")}
        self.marks.data = card["marks"]
        _set(self.vacuum, "location", card["vacuum"])
        _set(self.card.xaxis[0], "axis_label",
             f"piston position from head-end dead centre [{card['x_unit']}]")
        _set(self.card.yaxis[0], "axis_label", f"pressure [{card['p_unit']}]")
        s = v["summary"]
        self.card.title.text = (f"{v['title']}: {s['indicated power']}, "
                                f"m.e.p. {s['m.e.p.']}")
        rows = "".join(f"<tr><td style='padding-right: 1em'>{html.escape(k)}</td>"
                       f"<td class='wb-num' data-key='"
                       f"{html.escape(k)}'>{html.escape(t)}</td></tr>" for k, t in s.items())
        ev = v["events"]
        td = "<td style='padding: 1px 8px 1px 0'"
        cells = "".join(f"<tr>{td}>{html.escape(e)}</td>{td} class='wb-head'>{h}</td>"
                        f"{td} class='wb-crank'>{c}</td></tr>"
                        for e, h, c in zip(ev["event"], ev["head"], ev["crank"]))
        self.numbers.text = (
            f"<div class='wb-summary'><table class='wb-summary-table'>{rows}</table></div>"
            "<div class='wb-events' style='margin-top: 8px'><table class='wb-events-table' "
            "style='border-collapse: collapse'><tr><th style='text-align:left'>event</th>"
            f"<th>head</th><th>crank</th></tr>{cells}</table></div>")
        if defer:
            self.doc.add_next_tick_callback(partial(self._draw_rest, v, edits))
        else:
            self._draw_rest(v, edits)

    def _draw_rest(self, v: dict, edits: dict) -> None:
        """The Zeuner diagram and the port openings where they changed, and the scene's
        text of the card shown."""
        z = v["zeuner"]
        if z is None:
            self.zeuner.visible = False
            _set(self.znote, "text", "No Zeuner diagram: this gear's motion is not one "
                 "lapped valve (<code>corliss gear</code> draws its own panels).")
            self.znote.visible = True
        else:
            self.zeuner.visible, self.znote.visible = True, False
            _set_data(self.zsrc, {f"{e[0]}{c}": z[e][c] for e in ("head", "crank")
                                  for c in ("x", "y")})
            _set_data(self.zcircles, {"xs": z["circles"]["x"], "ys": z["circles"]["y"]})
        _set_data(self.psrc, v["ports"])
        _set(self.ports.title, "text", v["ports_title"])
        _set(self.ports.yaxis[0], "axis_label", f"port opening [{v['card']['x_unit']}]")
        self.toml.value = self.scene_text(edits)      # the scene of the card shown


def _padded(a, n: int) -> np.ndarray:
    """``a`` as floats, NaN after its end up to length ``n``."""
    a = np.asarray(a, dtype=float)
    return a if len(a) == n else np.concatenate([a, np.full(n - len(a), np.nan)])


def _set(model, attr: str, value) -> None:
    """Set a property only where it changes (nothing sent to the page otherwise)."""
    if getattr(model, attr) != value:
        setattr(model, attr, value)


def _same(a, b) -> bool:
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    try:
        return np.array_equal(np.asarray(a, dtype=float), np.asarray(b, dtype=float),
                              equal_nan=True)
    except (TypeError, ValueError):
        return False


def _set_data(source, data: dict) -> None:
    """A source's columns set only where one of them changes."""
    old = source.data
    if set(old) != set(data) or not all(_same(old[k], data[k]) for k in data):
        source.data = data


def address_settings(doc) -> dict:
    """The query of the address a session's page was opened at.

    Parameters
    ----------
    doc : bokeh.document.Document
        The session's document.

    Returns
    -------
    dict
        ``{name: text}`` (the first value of each name); empty outside a server
        session.
    """
    ctx = getattr(doc, "session_context", None)
    request = getattr(ctx, "request", None) if ctx is not None else None
    args = getattr(request, "arguments", None) or {}
    return {k: (v[0].decode("utf-8", "replace") if isinstance(v[0], bytes) else str(v[0]))
            for k, v in args.items() if v and not k.startswith("bokeh-")}


def make_document(text: str, name: str, source: str | None, runner: Runner,
                  fidelity: str | None = "fast", settings: dict | None = None,
                  address: bool = True):
    """The function a Bokeh application calls to fill each session's document.

    Parameters
    ----------
    text : str
        The scene's TOML text.
    name : str
        The scene's name.
    source : str or None
        Its file.
    runner : Runner
        The worker shared by the sessions.
    fidelity : str or None, optional
        The preset the page starts at (None: the scene's).
    settings : dict, optional
        Settings every page starts with (``{control name: text}``); with ``address``,
        those of the address a page is opened at come after them.
    address : bool, optional
        Read the settings of the address a page is opened at, and keep its address
        showing the page's settings.

    Returns
    -------
    callable
        ``modify_doc(doc)``, which builds a :class:`Workbench` in ``doc``.
    """
    def modify_doc(doc):
        asked = dict(settings or {})
        if address:
            asked.update(address_settings(doc))
        doc.workbench = Workbench(doc, text, name, source, runner, fidelity, asked, address)
    return modify_doc
