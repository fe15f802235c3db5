"""``hexaleg codesign``: the gait and its springs designed together (issue #31)."""
