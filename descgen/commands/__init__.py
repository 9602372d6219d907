"""One module or package per command, each calling the stages below and returning a result the
CLI prints: generate and check, import, control, tf-audit and tf-scenario, simulate, sweep, view,
faults, the evidence page (report), and text.py, the text each command prints."""
