"""Findings as users and machines read them: text, JSON, SARIF and JUnit (report.py)."""
