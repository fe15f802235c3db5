"""Forward simulation in MuJoCo: does the robot still walk with the springs, and does the saving
survive real contacts and a real servo?

:mod:`~hexaleg.studies.simulate.mjcf` and :mod:`~hexaleg.studies.simulate.model` build the robot
(its Pinocchio model as MJCF, a ground with contacts in physical units,
:mod:`~hexaleg.studies.simulate.ground`), :mod:`~hexaleg.studies.simulate.state` maps vectors
between Pinocchio and MuJoCo, :mod:`~hexaleg.studies.simulate.springs` builds hexaleg's spring
laws, :mod:`~hexaleg.studies.simulate.controllers` the servos,
:mod:`~hexaleg.studies.simulate.stepping` runs a model, :mod:`~hexaleg.studies.simulate.measures`
judges a run, :mod:`~hexaleg.studies.simulate.run` simulates with and without the springs beside
the analysis, :mod:`~hexaleg.studies.simulate.study` and :mod:`~hexaleg.studies.simulate.write`
are ``hexaleg simulate``, :mod:`~hexaleg.studies.simulate.motion_file` keeps each run's motion
for ``hexaleg view --simulation``, :mod:`~hexaleg.studies.simulate.design_file` reads
``design.json``.
MuJoCo is imported where a model is built, so importing this package stays light. See
``docs/simulate.md``.
"""

from hexaleg.studies.simulate.controllers import CONTROLLERS, Servo
from hexaleg.studies.simulate.design_file import design_table, read_design
from hexaleg.studies.simulate.ground import Ground
from hexaleg.studies.simulate.model import SimModel, build_model
from hexaleg.studies.simulate.run import Run, Settings, Simulation, simulate

__all__ = ["CONTROLLERS", "Ground", "Run", "Servo", "Settings", "SimModel", "Simulation",
           "build_model", "design_table", "read_design", "simulate"]
