"""One self-contained HTML page that plays a motion's Meshcat animation offline.

The viewer JavaScript is inlined from the installed ``meshcat`` package and the scene is
embedded as base64 MessagePack commands, in the order they were sent, so the page needs no
server and fetches nothing. (Meshcat's own ``static_html()`` sends the animation before the
objects it animates, which is why the page is assembled here.) A legend explains the joint
colours and the force-arrow scale.

Source: Meshcat (meshcat-python 0.3 and its three.js viewer) for the command protocol.
"""

from __future__ import annotations

import base64
import html
from pathlib import Path
from typing import Any

import meshcat
import umsgpack

from hexaleg.config import write_file
from hexaleg.motion.trajectory import Motion
from hexaleg.outputs.viewer.colours import colours
from hexaleg.outputs.viewer.scene import Legend, draw_motion
from hexaleg.robot.model import Robot


class PageWindow:
    """A stand-in for ``meshcat.visualizer.ViewerWindow`` that records the commands in the order
    they are sent instead of sending them to a server; ``get_scene()`` (what
    ``meshcat.Visualizer.static_html()`` calls) packs them into a self-contained page."""

    def __init__(self, title: str) -> None:
        self.commands: list[bytes] = []
        self.title = title
        self.legend_html = ""

    def send(self, command: Any) -> None:
        """Record one Meshcat command, MessagePack-encoded."""
        self.commands.append(umsgpack.packb(command.lower()))

    def get_scene(self) -> str:
        """The page: the viewer's JavaScript, the legend and the recorded commands."""
        viewer_js = (Path(meshcat.__file__).parent / "viewer" / "dist" / "main.min.js").read_text()
        commands = ",\n".join(f'"{base64.b64encode(c).decode("ascii")}"' for c in self.commands)
        return _PAGE.format(title=html.escape(self.title), viewer_js=viewer_js,
                            legend=self.legend_html, commands=commands)


_PAGE = """<!DOCTYPE html>
<html>
<head>
<meta charset="utf-8">
<title>{title}</title>
<style>
body {{ margin: 0; }}
#meshcat-pane {{ width: 100vw; height: 100vh; overflow: hidden; }}
#legend {{ position: fixed; left: 8px; bottom: 8px; padding: 6px 8px; font: 12px sans-serif;
  background: rgba(255, 255, 255, 0.85); border-radius: 4px; }}
#legend span.bin {{ display: inline-block; width: 14px; height: 10px; }}
</style>
</head>
<body>
<div id="meshcat-pane"></div>
{legend}
<script>
{viewer_js}
</script>
<script>
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));
// Scene commands (base64 MessagePack), applied synchronously in the order they were recorded.
var commands = [
{commands}
];
for (const c of commands) {{
  viewer.handle_command_bytearray(Uint8Array.from(atob(c), (ch) => ch.charCodeAt(0)));
}}
</script>
</body>
</html>
"""


def legend_html(legend: Legend, springs: str = "") -> str:
    """The page's legend: the springs shown, the joint colour swatches on ±vmax and the
    force-arrow scale.

    Args:
        legend: The scene's scales.
        springs: Which springs the motion was analysed (or simulated) with, in words; "" for
            none named.

    Returns:
        A ``<div id="legend">`` element, or "" when there is nothing to explain.
    """
    lines = [f"<div>springs: {html.escape(springs)}</div>"] if springs else []
    if legend.vmax is not None:
        swatches = "".join(
            '<span class="bin" style="background: rgb({}, {}, {})"></span>'.format(
                *(round(255 * v) for v in c))
            for c in colours())
        label = html.escape(legend.joint_label or "joint value")
        lines.append(f"<div>joints: {label} &nbsp;{-legend.vmax:.3g} {swatches} "
                     f"{legend.vmax:+.3g}</div>")
    if legend.fmax is not None:
        lines.append(f"<div>arrows: foot forces, {legend.arrow_length * 100:.3g} cm = "
                     f"{legend.fmax:.3g} N</div>")
    return f'<div id="legend">{"".join(lines)}</div>' if lines else ""


def page_html(robot: Robot, motion: Motion, *, forces: Any, joint_values: Any,
              joint_label: str, springs: str, fps: float, arrow_length: float,
              marker_radius: float) -> str:
    """Draw a motion (:func:`~hexaleg.outputs.viewer.scene.draw_motion`) into one
    self-contained page with its legend.

    Args:
        robot: The robot.
        motion: The motion.
        forces: As :func:`~hexaleg.outputs.viewer.scene.draw_motion`.
        joint_values: As :func:`~hexaleg.outputs.viewer.scene.draw_motion`.
        joint_label: As :func:`~hexaleg.outputs.viewer.scene.draw_motion`.
        springs: Which springs the motion was analysed with, in words (the legend's first
            line), or "".
        fps: As :func:`~hexaleg.outputs.viewer.scene.draw_motion`.
        arrow_length: As :func:`~hexaleg.outputs.viewer.scene.draw_motion`.
        marker_radius: As :func:`~hexaleg.outputs.viewer.scene.draw_motion`.

    Returns:
        The page.

    Raises:
        InvalidParameterError: as :func:`~hexaleg.outputs.viewer.scene.draw_motion`.
    """
    window = PageWindow(f"hexaleg: {robot.name}" + (f" ({joint_label})" if joint_label else ""))
    viewer = meshcat.Visualizer(window=window)
    _, legend = draw_motion(robot, motion, viewer, forces=forces, joint_values=joint_values,
                            joint_label=joint_label, fps=fps, arrow_length=arrow_length,
                            marker_radius=marker_radius)
    window.legend_html = legend_html(legend, springs)
    return str(viewer.static_html())


def write_page(path: Path, page: str) -> Path:
    """Write a page of :func:`page_html` through :func:`hexaleg.config.write_file`: to a new
    file beside ``path``, renamed over it, so a full disk or an interrupt leaves the earlier
    page whole and a link at ``path`` is replaced, never written through.

    Returns:
        The written path.

    Raises:
        OutputError: the file cannot be written (the message names the path and the reason).
    """
    return write_file(path, page, "the HTML page")
