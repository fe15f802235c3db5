"""One co-design of the default robot at 0.06 m/s, shared by the co-design tests (~30 s: the
search's budget cut to 60 evaluations, 2 restarts; the full-size run is
``analysis/codesign_hexaleg.py``)."""

from __future__ import annotations

import pytest

from hexaleg.studies.codesign.build import codesign


@pytest.fixture(scope="session")
def codesigned():
    return codesign("hexaleg", 0.06, max_evaluations=60, restarts=2)
