"""The command layer: one subpackage per ``hexaleg`` command — its options parsed, the run
built, the library called, the files written. No domain logic; commands do not import each
other (tests/test_layers.py)."""
