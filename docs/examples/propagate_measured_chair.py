"""Carry the measured chair's uncertainty to two answers (docs/measure.md).

Run from the repository root: ``python docs/examples/propagate_measured_chair.py``.
"""

import numpy as np

from stability import chair, linear
from stability.uncertainty import delta_method, load_uncertainty, propagate

c = chair.load("docs/examples/measured_chair.toml")
u = load_uncertainty("docs/examples/measured_chair.uncertainty.toml")


def outputs(chairs):
    """Free-caster divergence rate at 0.75 m/s (1/s) and locked-caster critical speed (m/s), one row per chair."""
    return np.array([[linear.divergence(ch, [0.75])[0].rate, linear.zero_width(ch).critical_speed]
                     for ch in chairs])


mc = propagate(c, u, outputs, samples=2000, seed=1)
dm = delta_method(c, u, outputs)
for j, name in enumerate(["rate at 0.75 m/s (1/s)", "locked-caster critical speed (m/s)"]):
    top = sorted(((n, float(s[j])) for n, s in mc.shares.items()), key=lambda kv: -kv[1])[:3]
    print(f"{name}: nominal {mc.nominal[j]:.3f}; Monte Carlo 95 % [{mc.low[j]:.3f}, {mc.high[j]:.3f}], "
          f"delta method [{dm.low[j]:.3f}, {dm.high[j]:.3f}]; variance shares "
          + ", ".join(f"{n} {s:.2f}" for n, s in top))
