"""Whole-body optimal control with the springs in the dynamics (issue #56).

The motion itself designed by Crocoddyl's box-FDDP (Mastalli et al., "Crocoddyl: An efficient
and versatile framework for multi-contact optimal control", ICRA 2020; Mastalli et al., "A
feasibility-driven approach to control-limited DDP", Autonomous Robots 46, 2022): the whole robot
on its floating base, the contact sequence of a gait pattern, the springs' torques inside the
dynamics (:mod:`~hexaleg.optimal.actuation`), the motor's electrical energy as the cost
(:mod:`~hexaleg.optimal.energy`), the final state the first shifted by the stride
(:mod:`~hexaleg.optimal.periodic`), built in :mod:`~hexaleg.optimal.problem` (its bounds at each
knot, plain kinematics, in :mod:`~hexaleg.optimal.bounds`) and solved into a
:class:`~hexaleg.motion.trajectory.Motion` in :mod:`~hexaleg.optimal.solve`, checked by
:mod:`~hexaleg.optimal.residual`.

Needs the ``optimal`` extra (``pip install "hexaleg[optimal]"``, Crocoddyl 3.2): its modules
import crocoddyl, and ``import hexaleg`` imports none of them.
"""
