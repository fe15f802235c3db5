"""``hexaleg design``: the design chain run and its files written (design.json, design.html,
plots)."""
