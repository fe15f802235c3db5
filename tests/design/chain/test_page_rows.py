"""design.html renders a simulated run that did not walk (a sensitivity row without simulated
numbers, :func:`hexaleg.commands.simulate.write.sensitivity_row`): anymal_c's design stopped in
the page template on such a row."""

from __future__ import annotations

from collections import defaultdict

from hexaleg.outputs.html import render_design_html


def test_a_run_that_did_not_walk_is_a_row_not_a_crash(design_written):
    result, _ = design_written
    data = dict(result.data)
    row = {k: v for k, v in data["simulation"][0].items()
           if k in ("label", "controller", "verdict", "predicted_saving", "predicted_electrical",
                    "predicted_baseline")}
    data["simulation"] = [{**row, "verdict": "fell"}, *data["simulation"][1:]]
    html = render_design_html(data, defaultdict(str))
    assert "— fell" in html
