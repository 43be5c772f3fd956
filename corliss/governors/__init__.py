"""Governors: static characteristics, dynamics, and the actuators that reset a gear.

The registry is empty until the governors issue lands; a scene with a
``[governor]`` section is refused with a clear message meanwhile.
"""

GOVERNORS: dict = {}
