"""
Root locus against a design parameter
=====================================

The eigenvalues of the linear model at 0.75 m/s as the position of the
centre of gravity between the axles varies (``cg_ratio``, thesis Figure 8-9
style; exact model, free casters). Colour runs with the parameter; the
chair's own value is marked.
"""

import matplotlib.pyplot as plt

import stability
from stability import plotting, rootlocus

chair = stability.preset("ej-premier")
locus = rootlocus.parameter_locus(chair, "cg_ratio", speed=0.75)
fig, ax = plt.subplots(figsize=(7.5, 5), layout="constrained")
plotting.parameter_locus(locus, ax=ax, title="Root locus vs c.g. ratio at 0.75 m/s: ej-premier (exact model)")

# %%
# What to conclude: the real eigenvalue that sets the divergence stays in the
# right half-plane over the whole range of c.g. positions, so moving the c.g.
# alone changes how fast the chair diverges but does not make it stable.
real = locus.eigenvalues.real.max(axis=1)
print(f"{locus.label}: from {locus.values[0]:.3g} to {locus.values[-1]:.3g}; "
      f"largest real part {real.min():.2f} to {real.max():.2f} 1/s (own value {locus.nominal:.3g})")
