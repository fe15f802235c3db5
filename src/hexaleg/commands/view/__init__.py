"""``hexaleg view``: a motion of the run, or a simulated run, drawn in the browser: the parser
(:mod:`~hexaleg.commands.view.command`) and what is shown and how it is served
(:mod:`~hexaleg.commands.view.study`)."""
