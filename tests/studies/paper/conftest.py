"""Fixtures of the paper study's tests: the default joint and one reproduction, made once."""

from __future__ import annotations

from typing import Any

import pytest

from hexaleg.studies.paper.joint import PaperJoint
from hexaleg.studies.paper.reproduce import reproduce


@pytest.fixture(scope="session")
def paper_result() -> dict[str, Any]:
    """:func:`reproduce` of the default joint at 256 samples per period (``paper.json``)."""
    return reproduce(PaperJoint(), n=256)
