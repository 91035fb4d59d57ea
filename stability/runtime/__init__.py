"""How the toolkit runs, below every layer (standard library, numpy and matplotlib only).

Atomic output files (:mod:`.files`), the inputs a command reads (:mod:`.readfiles`), progress (:mod:`.progress`),
numerical notes (:mod:`.notes`), interrupts (:mod:`.interrupts`), a command line's OpenBLAS threads (:mod:`.blas`)
and garbage collector (:mod:`.collector`), and the argument checks every layer shares (:mod:`.checks`).
"""
