"""``hexaleg simulate``: does the robot still walk with the springs, and does the saving survive
real contacts and a real servo?

The engine is :mod:`hexaleg.simulation`; this package is the command and its files:
:mod:`~hexaleg.studies.simulate.study` loads what to simulate, :mod:`~hexaleg.studies.simulate.
write` writes ``simulate.json``, the page and the summary,
:mod:`~hexaleg.studies.simulate.motion_file` keeps each run's motion for ``hexaleg view
--simulation``, :mod:`~hexaleg.studies.simulate.design_file` reads ``design.json``, and
:mod:`~hexaleg.studies.simulate.paper_joint` is the paper's Adams joint. See
``docs/simulate.md``.
"""

from hexaleg.studies.simulate.design_file import design_table, read_design

__all__ = ["design_table", "read_design"]
