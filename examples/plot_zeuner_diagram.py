"""
Valve travel and Zeuner diagram of a slide valve
================================================

The default scene's valve gear, without running the engine: the valve's travel against
crank angle (the exact linkage with its finite eccentric rod over Zeuner's harmonic
form), Zeuner's polar diagram, whose circle on the eccentric cuts the lap circles at
the events (Spangler, *Valve-Gears*, Arts. 16-22), and Bilgram's diagram (Arts.
149-150). This is what ``corliss gear scenes/default.toml`` draws.
"""

import corliss
from corliss.engine.model import build_gear
from corliss.plot import plot_gear

scene = corliss.load_scene(corliss.default_scene_path())
gear = build_gear(scene)

events = corliss.scene_events(scene)
for end in ("head", "crank"):
    e = events[end]
    print(f"{end:5s}: admission {e['admission_deg']:6.1f} deg, cut-off {e['cutoff_frac']:.3f}, "
          f"release {e['release_frac']:.3f}, compression {e['compression_frac']:.3f}")

drawn = plot_gear(gear, units_system="US")
