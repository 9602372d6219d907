"""The model and what every stage shares: the Robot (model.py), findings, units (the one place a
measured value becomes SI), immutable records, and small value helpers. Imports nothing of
descgen above it."""
