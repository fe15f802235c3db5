"""``hexaleg design``: the recommended springs for a robot, the parts to buy, robustness maps."""
