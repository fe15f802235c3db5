"""``hexaleg simulate``: does the robot still walk with the springs, and does the saving survive
real contacts and a real servo?

The engine is :mod:`hexaleg.simulation`; this package is the command:
:mod:`~hexaleg.commands.simulate.study` builds what to simulate from the run,
:mod:`~hexaleg.commands.simulate.write` writes ``simulate.json``, the page and the summary. See
``docs/simulate.md``.
"""
