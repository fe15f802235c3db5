"""The gait and its springs designed together for a required speed (``hexaleg codesign``)."""
