"""Layer 5 — studies: what the commands produce (paper, report, sweep, view)."""
