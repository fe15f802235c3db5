"""``hexaleg report``: the report built and its files written (report.html, report.json,
plots)."""
