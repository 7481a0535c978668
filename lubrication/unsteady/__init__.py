"""Unsteady plane Navier-Stokes flow between two eccentric circular walls that move rigidly.

The fixed concentric annulus r0 <= |w| <= 1 is mapped conformally onto the eccentric
one by a Moebius map that slides with the inner centre; the flow is discretised
by Fourier modes around and Chebyshev points across, in vorticity and the stream
function times the weight H = |1 + conj(p) w|^2/|w| (which makes the exact Stokes
flows two Fourier modes wide at any gap), and stepped by a variable-step IMEX BDF2
that solves the new flow and the new wall velocities in one linear system.

    mapping.py       the map, its metric (five Fourier coefficients), the weight H, the mesh velocity
    spectral.py      Chebyshev and Fourier tools of one resolution
    resolution.py    how many points a geometry needs; the default resolution
    operator.py      the implicit (H psi)-omega operator: apply, assemble, scale, banded LU
    walls.py         wall data of rigid motions, the circulation condition, the loads
    system.py        the monolithic system of one step (flow + C_in + wall velocities)
    timestepping.py  variable-step BDF2 coefficients, predictor, error estimate, step law
    solver.py        UnsteadySolver: state, start, step
    prescribed.py    run_prescribed: prescribed wall motions from rest, time series and snapshots
    snapshots.py     snapshots as VTU files for ParaView, pictures and GIF animations
"""

from .mapping import MIN_ONE_MINUS_KAPPA_UNSTEADY, AnnulusMap
from .prescribed import Harmonic, PrescribedMotion, PrescribedRun, first_steps, march, run_prescribed
from .resolution import Resolution, default_resolution
from .snapshots import (
    FRAMES,
    animate,
    draw_frame,
    flow_mesh,
    in_frame,
    write_vtu_series,
)
from .solver import (
    LOAD_NAMES,
    VELOCITY_NAMES,
    FlowLevel,
    StepControl,
    StepResult,
    UnsteadySolver,
    prescribed_wall,
)
from .timestepping import Bdf

__all__ = ["LOAD_NAMES", "MIN_ONE_MINUS_KAPPA_UNSTEADY", "VELOCITY_NAMES", "AnnulusMap", "Bdf", "FlowLevel",
           "Harmonic", "PrescribedMotion", "PrescribedRun", "Resolution", "StepControl", "StepResult",
           "UnsteadySolver", "default_resolution", "first_steps", "march", "prescribed_wall", "run_prescribed"]
__all__ += ["FRAMES", "animate", "draw_frame", "flow_mesh", "in_frame", "write_vtu_series"]
