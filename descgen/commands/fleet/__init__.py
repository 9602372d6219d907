"""A fleet's recordings: tf-audit spread over an engine (local processes or Ray), its findings
as a table (Parquet), and the fleet report rolled up by robot, description version and day."""
