"""``hexaleg simulate``: does the robot still walk with the springs, and does the saving survive
real contacts and a real servo?

The engine is :mod:`hexaleg.simulation`; this package is the command and its files:
:mod:`~hexaleg.commands.simulate.study` loads what to simulate, :mod:`~hexaleg.commands.simulate.
write` writes ``simulate.json``, the page and the summary,
:mod:`~hexaleg.simulation.motion_file` keeps each run's motion for ``hexaleg view
--simulation``, :mod:`~hexaleg.design.chain.design_file` reads ``design.json``, and
:mod:`~hexaleg.paper.simulated_joint` is the paper's Adams joint. See
``docs/simulate.md``.
"""

from hexaleg.design.chain.design_file import design_table, read_design

__all__ = ["design_table", "read_design"]
