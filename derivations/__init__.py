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

Nothing in the :mod:`stability` package imports this package at run time.
"""
