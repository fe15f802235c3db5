"""The served view of ``hexaleg view``: one page on a local HTTP server.

The page is the one ``hexaleg view --html`` writes (:func:`hexaleg.outputs.viewer.page.page_html`:
the scene, its animation and its legend, self-contained), so the served and the offline view are
the same. The server is the standard library's :class:`http.server.ThreadingHTTPServer` in a
daemon thread of the calling process — it stops when that process exits — bound to 127.0.0.1
unless another address is asked for.
"""

from __future__ import annotations

import threading
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

from hexaleg.errors import InvalidParameterError

LOCALHOST = "127.0.0.1"
"""The address the view is served on by default: this machine only."""
_SERVERS: list[ThreadingHTTPServer] = []
"""The servers started by this process (kept so that a test or a caller can stop them)."""


def serve_page(page: str, host: str = LOCALHOST, port: int = 0) -> str:
    """Serve ``page`` at ``/`` until this process exits.

    Args:
        page: The HTML page.
        host: The address to listen on (default this machine only).
        port: The port; 0 picks a free one.

    Returns:
        The page's URL, ``http://<host>:<port>/``.

    Raises:
        InvalidParameterError: the server cannot listen there (names the address and why).
    """
    body = page.encode("utf-8")

    class Handler(BaseHTTPRequestHandler):
        def do_GET(self) -> None:
            if self.path.split("?")[0] not in ("/", "/index.html"):
                self.send_error(HTTPStatus.NOT_FOUND, "the view is at /")
                return
            self.send_response(HTTPStatus.OK)
            self.send_header("Content-Type", "text/html; charset=utf-8")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, format: str, *args: object) -> None:
            """Quiet: the command prints its URL once."""

    try:
        server = ThreadingHTTPServer((host, port), Handler)
    except (OSError, OverflowError) as e:
        raise InvalidParameterError("host", f"{host}:{port}", f"an address of this machine to "
                                    f"listen on ({e}); the default is {LOCALHOST}") from None
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, name="hexaleg-view", daemon=True).start()
    _SERVERS.append(server)
    address, bound = server.server_address[:2]
    return f"http://{address!s}:{bound}/"


__all__ = ["LOCALHOST", "serve_page"]
