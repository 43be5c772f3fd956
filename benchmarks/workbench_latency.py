"""Control-to-card latency of the workbench page, in a real browser.

For each scene, ``corliss workbench --no-browser`` is started on a free loopback port
and the page opened in headless chromium (Debian's, through Playwright).  After the
first card, one slider is stepped by a key press, alternately right and left, and the
time from the key press to the summary beside the card showing the new run's numbers
is taken from this side (the browser's round trip, the run in the worker process and
the drawing included; polled every few milliseconds), together with the server's own
figure from the page's status line (from the change reaching the server to the
drawing sent).  The default scene at ``fast`` is the one with a target: under 150 ms.

Usage::

    python benchmarks/workbench_latency.py [--repeats 15] [--fidelity fast]

Prints a table and writes ``benchmarks/results/workbench_latency.csv``; with
``--shots DIR`` also a screenshot of each scene's page, and of the default scene's
gear in motion and its eccentricity run below its lap (the documentation's).
"""

from __future__ import annotations

import argparse
import csv
import os
import re
import shutil
import socket
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
#: (scene, the slider stepped, what it is)
SCENES = [("default", "valve_gear.lap[head]", "plain slide valve, head-end lap"),
          ("hinkley-stephenson-link", "valve_gear.block", "Stephenson link, block position"),
          ("corliss-trip-gear", "valve_gear.setting", "Corliss trip gear, cut-off setting")]


def _css(name: str) -> str:
    return "wb-" + "".join(c if c.isalnum() else "-" for c in name)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


#: In the page: press a key on a slider's handle and wait, frame by frame, until the
#: summary shows another power and the status says redrawn; the milliseconds between,
#: and the status.  Bokeh draws its widgets in shadow roots: found by walking them.
STEP = """
async ([cls, key]) => {
  const deep = (root, sel) => {
    const hit = root.querySelector(sel);
    if (hit) return hit;
    for (const el of root.querySelectorAll('*')) {
      if (el.shadowRoot) { const r = deep(el.shadowRoot, sel); if (r) return r; }
    }
    return null;
  };
  const host = deep(document, '.' + cls);
  const handle = deep(host.shadowRoot || host, '.noUi-handle');
  const power = () => (deep(document, 'td.wb-num') || {}).textContent;
  const toml = deep(document, '.wb-toml');
  const area = deep(toml.shadowRoot || toml, 'textarea');
  const scene = () => area.value;
  const before = power(), text = scene();
  const t0 = performance.now();
  handle.dispatchEvent(new KeyboardEvent('keydown', {key: key, bubbles: true}));
  let card = null, status = null;
  while (true) {
    await new Promise(r => requestAnimationFrame(r));
    const done = deep(document, '.wb-done');
    if (card === null && power() !== before && done) {
      card = performance.now() - t0;
      status = done.textContent;
    }
    if (card !== null && scene() !== text) return [card, status, performance.now() - t0];
    if (performance.now() - t0 > 60000) throw new Error('no redraw in 60 s');
  }
}
"""


def measure(scene: str, control: str, repeats: int, fidelity: str, exe: str,
            shot: str | None = None) -> dict:
    from playwright.sync_api import sync_playwright
    port = _free_port()
    proc = subprocess.Popen([sys.executable, "-m", "corliss.cli.commands", "workbench", scene,
                             "--no-browser", "--port", str(port), "--fidelity", fidelity],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(600):
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                time.sleep(0.2)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=exe, args=["--no-sandbox"])
            page = browser.new_page(viewport={"width": 1500, "height": 1130})
            page.goto(f"http://127.0.0.1:{port}/")
            page.wait_for_selector(".wb-done", timeout=600_000)
            client, server, whole = [], [], []
            for i in range(repeats + 2):          # the first two warm the page up
                key = "ArrowRight" if i % 2 == 0 else "ArrowLeft"
                ms, status, all_ms = page.evaluate(STEP, [_css(control), key])
                m = re.search(r"redrawn in (\d+) ms", status)
                if i >= 2:
                    client.append(ms)
                    whole.append(all_ms)
                    server.append(float(m.group(1)))
                time.sleep(0.1)
            if shot:
                page.mouse.move(0, 0)
                page.screenshot(path=shot, full_page=True)
            if shot and scene == "default":     # the gear in motion, asked for
                page.locator(".wb-animate button").click()
                page.wait_for_selector(".wb-motion-frames", timeout=600_000)
                page.mouse.move(0, 0)
                page.locator(".wb-motion").screenshot(path=shot.replace(".png", "-motion.png"))
            if shot and scene == "default":     # a gear the loader refuses, shown
                page.locator(".wb-valve-gear-eccentricity .noUi-handle").focus()
                page.keyboard.press("Home")
                page.locator(".wb-valve-gear-eccentricity-error").wait_for(state="visible")
                page.mouse.move(0, 0)
                page.screenshot(path=shot.replace(".png", "-refused.png"),
                                clip={"x": 0, "y": 0, "width": 1500, "height": 560})
            browser.close()
    finally:
        proc.terminate()
        proc.wait(timeout=20)
    return {"scene": scene, "control": control, "fidelity": fidelity, "repeats": repeats,
            "browser_median_ms": statistics.median(client),
            "browser_max_ms": max(client),
            "all_panels_median_ms": statistics.median(whole),
            "server_median_ms": statistics.median(server)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--fidelity", default="fast")
    ap.add_argument("--shots", help="a folder for a screenshot of each scene's page")
    ap.add_argument("--scenes", nargs="+", help="only these of the three scenes")
    ap.add_argument("--out", default=os.path.join(HERE, "results", "workbench_latency.csv"))
    args = ap.parse_args()
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        sys.exit("no chromium: apt-get install chromium")
    rows = []
    for scene, control, what in SCENES:
        if args.scenes and scene not in args.scenes:
            continue
        shot = os.path.join(args.shots, f"workbench-{scene}.png") if args.shots else None
        r = measure(scene, control, args.repeats, args.fidelity, exe, shot)
        r["what"] = what
        rows.append(r)
        print(f"{scene:26s} {control:24s} card: browser median {r['browser_median_ms']:6.1f} "
              f"ms (max {r['browser_max_ms']:6.1f}), server median "
              f"{r['server_median_ms']:6.1f} ms; every panel {r['all_panels_median_ms']:6.1f} "
              "ms", flush=True)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
