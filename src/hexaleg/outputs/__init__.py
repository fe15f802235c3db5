"""Layer 6 — outputs: plots, HTML templates, text summaries and the Meshcat viewer page."""
