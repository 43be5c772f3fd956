"""
Indicator card of the default engine
====================================

The bundled default scene, a 12 x 24 in engine with a plain D slide valve at 120 rpm on
100 psig, run steady until its cycle repeats, and its card drawn in the period's style:
head end solid, crank end dashed, gauge pressure over the atmospheric line, the valve
events marked.

The ``fast`` preset (the steam table and the compiled Rosenbrock method at rtol 5e-5)
keeps the example quick; its indicated power is within 0.01 % of the reference on this
scene (see :doc:`/accuracy`).
"""

import corliss

scene = corliss.load_scene(corliss.default_scene_path()).with_fidelity("fast")
result = corliss.simulate(scene)

s = result.summary
print(f"indicated power {s['indicated_power_hp']:.1f} ihp, "
      f"m.e.p. {s['mep_mean_Pa'] / 6894.757:.1f} psi, "
      f"water rate {s['water_rate_lb_per_ihp_h']:.1f} lb/ihp-h, "
      f"head cut-off at {s['events']['head']['cutoff_frac']:.3f} of the stroke")

drawn = result.plot("card")
