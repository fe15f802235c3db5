"""The sweep study: a grid of gaits and spring designs, run in parallel, stored as it goes."""
