"""Designs over a box of conditions: the robust program, a frozen design under changed
conditions, and the robustness maps."""
