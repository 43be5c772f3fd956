"""
Willans line of a Corliss engine
================================

Steady cards of the 20 x 42 in Corliss engine (``scenes/corliss-governor.toml``) at a
series of cut-off settings, as its trip governor would set them, and the steam an hour
against the indicated power. For a throttled engine the points lie on a straight line,
Willans's (P. W. Willans, *Min. Proc. Inst. C.E.* 93, 1888), whose intercept is the
steam the engine spends at no load; governed by cut-off, the line bends, the steam per
horse-power being least at the engine's economical cut-off (Marks, *Relative
Proportions*, Art. 2, p. 13). The thin line is the straight line fitted through the points.
This is what ``corliss sweep scenes/corliss-governor.toml --settings 0.2,0.4,0.6,0.8,1``
draws.
"""

import corliss
from corliss.studies.load_range import load_range

scene = corliss.load_scene(corliss.bundled_scenes()["corliss-governor"]).with_fidelity("fast")
sweep = load_range(scene, "setting", [0.2, 0.4, 0.6, 0.8, 1.0])

print(sweep.points[["knob_frac", "indicated_power_W", "steam_rate_kg_per_h",
                    "cutoff_head_frac"]].to_string(index=False))

drawn = sweep.plot("willans")
