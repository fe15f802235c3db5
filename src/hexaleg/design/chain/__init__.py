"""The spring design's chain: nominal run, family candidates, Pareto front, simulated ranking,
stop tolerance, envelope and fatigue, robustness maps, robust design, simulated proof; the
result and its design.json."""
