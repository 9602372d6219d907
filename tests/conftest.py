from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"


def require_tool(name: str) -> str:
    """The path of a system tool; skip when absent, fail when CI requires it."""
    path = shutil.which(name)
    if path:
        return path
    if os.environ.get("DESCGEN_REQUIRE_TOOLS") == "1":
        pytest.fail(f"{name} is required (DESCGEN_REQUIRE_TOOLS=1) but not on PATH")
    pytest.skip(f"{name} not installed")


@pytest.fixture
def example_text() -> str:
    return EXAMPLE.read_text()
