"""
A cross slope: the moment a user must hold
==========================================

On a cross slope gravity turns the chair downhill; to hold a straight line
the user must supply a yaw moment, i.e. push one hand rim harder than the
other. The holding moment comes from the chair's statics and tire forces on
the inclined plane (``stability.slope``), with the range that Coulomb pin
friction allows; the points are the published treadmill study's numbers.
"""

import matplotlib.pyplot as plt

import stability
from stability.slope import plots

curves = [plots.holding_curve(stability.preset(n), speed=0.9) for n in ("ej-premier", "manual-front-caster")]
fig, (ax_m, ax_f) = plt.subplots(1, 2, figsize=(10, 4.2), layout="constrained")
plots.plot_holding(curves, ax=ax_m, ax_force=ax_f)
fig.suptitle("Cross slope at 0.9 m/s: ej-premier vs manual-front-caster (exact model)")

# %%
# What to conclude: the holding moment grows in proportion to the slope; on a
# 2 deg sidewalk camber the user of a rear-caster chair must already push one
# rim noticeably harder than the other, all the time.
for c in curves:
    i = list(c.cross_slopes_deg).index(2)
    print(f"{c.chair}: at 2 deg, holding moment {c.holding_moment[i]:.2f} N m, "
          f"hand-rim force difference {c.handrim_difference[i]:.1f} N")
