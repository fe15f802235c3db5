"""The gait energy report of one robot: configuration, analysis, rendering."""
