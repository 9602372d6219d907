"""The YAML spec: schema (pydantic), loading with positions, and building the SI model.
Validating one (the model judged by the audit's rules too) is descgen/audit/spec.py."""

from descgen.spec.load import Loaded, read_spec, read_spec_text
from descgen.spec.models import RobotSpec

__all__ = ["Loaded", "RobotSpec", "read_spec", "read_spec_text"]
