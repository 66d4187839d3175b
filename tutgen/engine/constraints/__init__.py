"""Constraints: holonomic and velocity constraints among the coordinates (issue 21).

:mod:`~tutgen.engine.constraints.kinematics` builds the constraint Jacobian A, the acceleration terms b,
the velocity analysis q_dot = T q_dot_i and the position analysis (:mod:`~tutgen.engine.constraints.loops`
adds the loop-closure equations of the loop-closing joints), and rejects constraints that are
redundant, that hold at no configuration, or a singular choice of independent coordinates;
:mod:`~tutgen.engine.constraints.dynamics` writes the equations of motion with Lagrange's multipliers
and reduced to the independent coordinates, and checks the two routes against each other.
"""

from tutgen.engine.constraints.dynamics import ConstrainedDynamics, constrained_dynamics, multiplier_symbol
from tutgen.engine.constraints.kinematics import ConstraintKinematics, constraint_kinematics
from tutgen.engine.constraints.loops import with_loop_closures

__all__ = [
    "ConstrainedDynamics",
    "ConstraintKinematics",
    "constrained_dynamics",
    "constraint_kinematics",
    "multiplier_symbol",
    "with_loop_closures",
]
