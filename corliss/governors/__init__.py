"""Governors: every named governor reduced to one common form the speed loop integrates.

See :mod:`corliss.governors.mechanism` for the form (Lagrange's equation for the
governor's coordinate z in [0, 1]) and the registry; :mod:`corliss.governors.flyball`
for Watt's, Porter's, the spring-loaded, the Porter-Allen and the Corliss governors;
:mod:`corliss.governors.shaft` for the shaft governors (Erie, Armington & Sims, Ball,
Buckeye, Thompson).
"""

from corliss.governors.mechanism import (GOVERNORS, Governor, GovernorMechanism,  # noqa: F401
                                         GovernorType, governor_type, register)
from corliss.governors import flyball, shaft  # noqa: F401,E402  (they register themselves)
