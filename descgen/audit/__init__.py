"""Rules over the robot model, shared by ``validate``, ``generate`` and ``audit``."""

from descgen.audit.registry import RULES, RuleInfo, at, iter_rules, rule, run

__all__ = ["RULES", "RuleInfo", "at", "iter_rules", "rule", "run"]
