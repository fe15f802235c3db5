"""Regenerate the pictures of README.md and the docs (``docs/img/*.png``) from the current code.

Each picture is a page the commands write, photographed by headless Chromium with the helpers of
``tests/browser.py`` (Debian's ``chromium``: ``apt-get install -y chromium``)::

    python docs/make_images.py              # every picture
    python docs/make_images.py report       # only docs/img/report.png

``report.png`` is the top of ``hexaleg report``'s page, ``view.png`` the gait in ``hexaleg view``
coloured by motor torque, ``sphere.png`` the end of the stand → sphere transformation. The commands
run in a temporary folder; nothing but the pictures is written into the checkout.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IMG = ROOT / "docs" / "img"
sys.path.insert(0, str(ROOT / "tests"))

from browser import chromium, finish, start_screenshot  # noqa: E402


@dataclass(frozen=True)
class Picture:
    """One picture: the ``hexaleg`` command that writes the page and how it is photographed.

    Attributes:
        name: File stem in ``docs/img/``.
        command: Arguments of ``hexaleg`` (``{dir}`` is the temporary folder).
        page: The page it writes, relative to the temporary folder.
        size: Window (and picture) size, px.
        virtual_time_ms: Page time before the shot (an animation's time for the viewer pages).
    """

    name: str
    command: tuple[str, ...]
    page: str
    size: tuple[int, int]
    virtual_time_ms: int


PICTURES = (
    Picture("report", ("report", "--out", "{dir}/report"), "report/report.html", (1100, 1500),
            1000),
    Picture("view", ("view", "--joints", "torque", "--html", "{dir}/view.html"), "view.html",
            (960, 600), 1500),
    # the transformation lasts 2 s (transform_motion's duration) after the page loads: shot at
    # its end, the sphere (the page's load takes page time too; 2.3 s showed the closed ring)
    Picture("sphere", ("view", "--motion", "transform", "--html", "{dir}/sphere.html"),
            "sphere.html", (960, 600), 2300),
)


def make(picture: Picture, workdir: Path) -> Path:
    """Run the picture's command in ``workdir`` and photograph its page into ``docs/img``."""
    args = [a.replace("{dir}", str(workdir)) for a in picture.command]
    subprocess.run([sys.executable, "-m", "hexaleg.cli", *args], cwd=workdir, check=True,
                   stdout=subprocess.DEVNULL)
    png = IMG / f"{picture.name}.png"
    finish(start_screenshot((workdir / picture.page).as_uri(), png, size=picture.size,
                            virtual_time_ms=picture.virtual_time_ms), timeout=120.0)
    if not png.is_file():
        raise RuntimeError(f"chromium wrote no {png}")
    return png


def main(names: list[str]) -> int:
    """Make the named pictures (all without names); exit status 2 for an unknown name or no
    Chromium."""
    known = {p.name: p for p in PICTURES}
    unknown = [n for n in names if n not in known]
    if unknown:
        print(f"unknown picture {unknown[0]!r}: one of {', '.join(known)}", file=sys.stderr)
        return 2
    if chromium() is None:
        print("chromium is not on PATH: apt-get install -y chromium", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="hexaleg-images-") as tmp:
        for name in names or list(known):
            print(f"wrote {make(known[name], Path(tmp)).relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
