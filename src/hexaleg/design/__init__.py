"""Layer 4 — spring design: the paper's rules, evaluators, optimisation, placement and
robustness."""
