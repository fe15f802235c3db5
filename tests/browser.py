"""Headless Chromium for the view tests: screenshots of a page and the requests the page made.

Also a script that makes the README picture from a page written by ``hexaleg view --html``::

    hexaleg view --joints torque --html /tmp/view.html
    python tests/browser.py /tmp/view.html docs/img/view.png
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

CHROMIUM_FLAGS = (
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    # WebGL without a GPU: software rendering through ANGLE's SwiftShader backend.
    "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
)
"""Flags that make Chromium render WebGL headless here without touching the network."""


def chromium() -> str | None:
    """Path of a Chromium/Chrome executable on PATH, or None."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def start_screenshot(url: str, png: Path, *, size: tuple[int, int] = (800, 600),
                     virtual_time_ms: int = 1000, net_log: Path | None = None
                     ) -> subprocess.Popen:
    """Start Chromium taking a screenshot of ``url`` after ``virtual_time_ms`` of page time.

    Returns the process (wait on it; its profile directory is removed when it is collected by
    :func:`finish`).
    """
    exe = chromium()
    if exe is None:
        raise RuntimeError("chromium is not on PATH")
    profile = tempfile.mkdtemp(prefix="hexaleg-chromium-")
    args = [exe, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", f"--screenshot={png}",
            f"--window-size={size[0]},{size[1]}", f"--virtual-time-budget={virtual_time_ms}"]
    if net_log is not None:
        args.append(f"--log-net-log={net_log}")
    proc = subprocess.Popen([*args, url], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    proc.profile = profile  # type: ignore[attr-defined]
    return proc


def finish(proc: subprocess.Popen, timeout: float = 60.0) -> None:
    """Wait for a :func:`start_screenshot` process and remove its profile directory."""
    try:
        proc.wait(timeout=timeout)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        shutil.rmtree(proc.profile, ignore_errors=True)  # type: ignore[attr-defined]


def page_requests(net_log: Path) -> list[str]:
    """http(s) URLs requested by the page itself (not by Chromium's own background services).

    Chromium logs its own requests (updates, accounts) with the initiator "not an origin"; a
    request made by a page has the page's origin as initiator ("null" for a file:// page).
    """
    log, _ = json.JSONDecoder().raw_decode(net_log.read_text())
    names = {v: k for k, v in log["constants"]["logEventTypes"].items()}
    urls = []
    for event in log["events"]:
        params = event.get("params", {})
        if names.get(event["type"]) == "URL_REQUEST_START_JOB" and \
                params.get("url", "").startswith(("http://", "https://")) and \
                params.get("initiator") != "not an origin":
            urls.append(params["url"])
    return urls


if __name__ == "__main__":
    page, out = Path(sys.argv[1]).resolve(), Path(sys.argv[2])
    finish(start_screenshot(page.as_uri(), out.resolve(), size=(960, 600), virtual_time_ms=1500))
    print(f"wrote {out}")
