"""Rough contact (section 5): asperities stop the approach at kappa = kappa*.

    reduced.py    the contact phases of the reduced model (free, sliding, locked) and its run
    full.py       contact as a unilateral constraint with Coulomb friction in the full model
    roughness.py  a minimum gap that varies at random along both surfaces
    rough.py      the reduced model with that varying gap
    steady.py     steady rolling (5.6)-(5.12), the onset of sliding (6.4), the speed law (6.1)
"""
