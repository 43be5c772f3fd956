"""
A governed engine's load step
=============================

The 14 1/2 x 24 in Porter-Allen engine with its Porter governor moving the Fink link's
radius rod (``scenes/porter-allen-governor.toml``), its load halved while it runs: the
crank speed is a state, the governor's position follows Lagrange's equation for its one
coordinate, and the cut-off follows the governor. Shortened here to 6 s with the step at
2 s (the scene runs 30 s with the step at 10 s); the figure shows speed, governor
position and cut-off against time, with the cards before the step and at the end.
"""

import copy

import corliss

path = corliss.bundled_scenes()["porter-allen-governor"]
data = copy.deepcopy(corliss.load_scene(path).data)     # the scene's tables, as read
data["run"]["duration"] = "6 s"
data["load"]["step_time"] = "2 s"
scene = corliss.scene_from_dict(data, name="porter-allen-governor").with_fidelity("fast")
result = corliss.simulate(scene)

s = result.summary
print(f"before the step {s['speed_before_rpm']:.2f} rpm; largest change "
      f"{s['max_deviation_rpm']:+.2f} rpm at {s['time_of_max_deviation_s']:.2f} s; "
      f"at the end {s['final_speed_rpm']:.2f} rpm")

drawn = result.plot("loadstep")
