"""Layer 3 — dynamics: prepare (spring-independent) and evaluate (per spring design), contact
forces, energy."""
