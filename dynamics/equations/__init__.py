"""The equations of motion: the full model (2.1)-(2.4), the reduced model (2.11), their
closed-form special solutions, the force models they call, and where they stop being valid.

    forces.py    one adapter per lubrication force model, evaluated from jitted code
    full.py      (2.1)-(2.4) in variables regular at eps = 0 and near contact
    reduced.py   (2.11) in stretched Cartesian variables
    special.py   (3.2), (3.3), (3.5), (3.9)-(3.11): solutions that check the integrators
    limits.py    the gap floor, the gap Reynolds number, the runaway stop
"""
