"""Layer 1 — the robot: its model (URDF/SRDF in Pinocchio), registry, builder, motors and
springs."""
