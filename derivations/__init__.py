"""Symbolic derivations of the wheelchair equations of motion (sympy).

Modules
-------
zero_width
    The zero-width (bicycle) model of chapter 5 of Collins (1987), eqs 5-1..5-18.
full_width
    The full-width, five degree-of-freedom planar model of chapter 6: a
    first-principles Kane's-method derivation (the ``exact`` variant), Table
    6-1 and eqs 6-17/6-18 as printed (the ``thesis`` variant, what program
    WCHAIR integrates), their term-by-term comparison and linearisations.
generate
    Writes the plain-Python numeric modules ``stability/_generated/*.py``.
compare_variants
    Eigenvalue effect of each thesis-vs-exact difference for the thesis chair.
slope
    The exact model on a plane with cross slope and grade (gravity on the chair
    and on each caster, slope normal loads), steady straight running, and the
    zero-width model on a slope; generates ``_generated/slope.py``.
shimmy
    The towed wheel (rigid or spring pivot, rigid or relaxation-length tire);
    generates ``_generated/shimmy.py``.
full_width_relaxed
    The exact full-width linear model with caster-tire relaxation and pin
    lateral compliance (the chair's shimmy mode); generates
    ``_generated/full_width_relaxed.py``.
tipping
    Static tipping of the rigid chair on a tilted plane (checks only; the
    run-time geometry is ``stability/tipping/angles.py``).

Nothing in the :mod:`stability` package imports this package at run time.
"""
