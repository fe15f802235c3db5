"""Layer 2 — motion: trajectories the robot follows (gaits, joint motions, the transform)."""
