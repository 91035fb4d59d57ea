"""Chair-plus-user parameters: a frozen dataclass, presets and TOML I/O.

The symbols follow Figure 6-1 of Collins (1987) and the variables of program
WCHAIR (Appendix C, BLOCK DATA).  Distances are in metres, masses in kg,
inertias in kg m^2, moments in N m and angles in degrees.

Both rear-caster chairs (the thesis's) and front-caster chairs are first
class: ``caster_position`` says where the casters are and every model moves
the chair forward at positive speed.  ``s1`` and ``s2`` are always positive
distances from the centre of gravity to the main axle and to the caster pins;
:attr:`Chair.x_main` and :attr:`Chair.x_pin` give their signed body
coordinates (x forward, y to the right, SAE axes).

Examples
--------
>>> from stability import chair
>>> c = chair.preset("ej-premier")
>>> c.replace(trail=0.06).trail
0.06
"""

from __future__ import annotations

from stability.chair.io import (
    GROUPS,
    dumps,
    from_mapping,
    load,
    parse_assignment,
    parse_assignments,
    resolve,
    save,
    to_mapping,
    user_table,
)
from stability.chair.model import LIMITS, Chair, check_chair, field_names, valid_range
from stability.chair.presets import POWER_FWD_FIELDS, all_preset_names, preset, preset_names

__all__ = ["user_table",
    "Chair",
    "LIMITS",
    "check_chair",
    "valid_range",
    "field_names",
    "POWER_FWD_FIELDS",
    "preset",
    "preset_names",
    "all_preset_names",
    "load",
    "save",
    "dumps",
    "from_mapping",
    "to_mapping",
    "resolve",
    "parse_assignment",
    "parse_assignments",
    "GROUPS",
]
