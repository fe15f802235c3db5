"""The physical spring: a helical torsion spring you can buy, its wire, its fatigue, its envelope
over everything its joint may see, where it is mounted, and its law as JSON and as a table."""
