"""``hexaleg sweep``: the options of a sweep parsed and the sweep run."""
