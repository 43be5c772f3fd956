"""
Four valve gears in motion
==========================

Each animation turns the crank once and draws the gear as its exact solve places it at
every crank angle, beside the valve over its ports, the four port openings against
crank angle and, where a steady run is given, the indicator card traced as the crank
turns: the plain slide valve on its eccentric, the Stephenson link (the Hinkley
locomotive's, a scene in Zeuner's form drawn as its exact linkage), the Walschaerts
gear, and the Corliss wrist plate, whose steam valves the cam releases and the
dash-pots close.  The command line writes the same pictures as GIF or HTML::

    corliss animate walschaerts-locomotive --frames 72

Each animation is kept in a variable of its own until the page embeds it.
"""

import dataclasses

import matplotlib.pyplot as plt

import corliss
from corliss.engine.model import build_gear
from corliss.plot.animation import animate_gear, exact_linkage_spec


def gear_of(name):
    """A bundled scene, and its gear solved as its linkage."""
    scene = corliss.load_scene(corliss.bundled_scenes()[name])
    spec, _ = exact_linkage_spec(scene.gear)
    scene = dataclasses.replace(scene, gear=spec)
    return scene, build_gear(scene)


# %%
# The plain slide valve, with the card of a steady run at the fast fidelity
scene, gear = gear_of("default")
result = corliss.simulate(scene.with_fidelity("fast"))
anim_slide = animate_gear(gear, result, frames=24, title=scene.title)["animation"]

# %%
# The Stephenson link: eccentrics, rods, the curved link and its block
scene, gear = gear_of("hinkley-stephenson-link")
drawn = animate_gear(gear, None, frames=24, stroke_m=scene.engine.stroke_m,
                     title=scene.title)
anim_stephenson = drawn["animation"]

# %%
# Walschaerts: return crank, link, radius rod, combination lever and union link
scene, gear = gear_of("walschaerts-locomotive")
drawn = animate_gear(gear, None, frames=24, stroke_m=scene.engine.stroke_m,
                     title=scene.title)
anim_walschaerts = drawn["animation"]

# %%
# The Corliss wrist plate: the steam valves tripped and closed by their dash-pots
scene, gear = gear_of("corliss-trip-gear")
drawn = animate_gear(gear, None, frames=24, stroke_m=scene.engine.stroke_m,
                     title=scene.title)
anim_corliss = drawn["animation"]
plt.show()
