"""``hexaleg codesign``: the gait and its springs designed together, its files written."""
