"""Rough contact (section 5): asperities stop the approach at kappa = kappa*.

    reduced.py    the contact phases of the reduced model (free, sliding, locked) and its run
    full.py       contact as a unilateral constraint with Coulomb friction in the full model
    roughness.py  a minimum gap that varies at random along both surfaces (Gaussian or self-affine)
    rough.py      the reduced model with that varying gap
    rough_full.py the full model with that varying gap: hard (phases) or compliant contact
    laws.py       Stribeck friction and the compliant Greenwood-Williamson asperity contact
    steady.py     steady rolling (5.6)-(5.12), the onset of sliding (6.4), the speed law (6.1)
"""
