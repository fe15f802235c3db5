"""The design programs and their searches: the checked inputs, the convex program (fast path
and cvxpy reference), its condensed and bundle forms, the lower-bound scan, the deterministic
search over a family's geometry and the workshop tolerance design."""
