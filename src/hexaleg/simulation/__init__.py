"""The forward-simulation engine: the robot in MuJoCo with hexaleg's springs and a servo.

:mod:`~hexaleg.simulation.mjcf` and :mod:`~hexaleg.simulation.model` build the robot (its
Pinocchio model as MJCF, a ground with contacts in physical units,
:mod:`~hexaleg.simulation.ground`), :mod:`~hexaleg.simulation.state` maps vectors between
Pinocchio and MuJoCo, :mod:`~hexaleg.simulation.springs` builds hexaleg's spring laws,
:mod:`~hexaleg.simulation.controllers` the servos, :mod:`~hexaleg.simulation.stepping` runs a
model (with MuJoCo's stage timers off, :mod:`~hexaleg.simulation.timers`) at the timestep of
:mod:`~hexaleg.simulation.timestep`,
:mod:`~hexaleg.simulation.measures` judges a run, :mod:`~hexaleg.simulation.run` simulates
with and without the springs beside the analysis (with the
:mod:`~hexaleg.simulation.settings`, into a :mod:`~hexaleg.simulation.result`), and
:mod:`~hexaleg.simulation.sensitivity` reruns it under changed settings and controllers.

It sits below the design layer, so a design may simulate its candidates; the command and its
files are :mod:`hexaleg.commands.simulate`. MuJoCo is imported where a model is built, so
importing this package stays light. See ``docs/simulate.md``.
"""

from hexaleg.simulation.controllers import CONTROLLERS, Servo
from hexaleg.simulation.ground import Ground
from hexaleg.simulation.model import SimModel, build_model
from hexaleg.simulation.result import Run, Simulation
from hexaleg.simulation.run import simulate
from hexaleg.simulation.settings import Settings

__all__ = ["CONTROLLERS", "Ground", "Run", "Servo", "Settings", "SimModel", "Simulation",
           "build_model", "simulate"]
