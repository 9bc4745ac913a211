"""Shared fixtures: paths of the case library."""
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
VERIFICATION = ROOT / "cases" / "verification"


@pytest.fixture
def verification_dir() -> Path:
    return VERIFICATION
