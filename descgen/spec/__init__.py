"""The YAML spec: schema (pydantic), loading with positions, and building the SI model."""

from .load import Loaded, load_spec, load_spec_text
from .models import RobotSpec

__all__ = ["Loaded", "RobotSpec", "load_spec", "load_spec_text"]
