"""Tests of hexaleg.outputs.viewer.server: the page served at / on 127.0.0.1 only, other paths
not found, an address it cannot listen on named."""

from __future__ import annotations

import socket
import urllib.error
import urllib.request

import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.outputs.viewer import server


def test_the_page_is_served_at_the_root_on_localhost_only():
    page = "<!DOCTYPE html><title>é</title>"
    url = server.serve_page(page)
    assert url.startswith("http://127.0.0.1:") and url.endswith("/")
    with urllib.request.urlopen(url, timeout=10) as r:
        assert r.read().decode("utf-8") == page
        assert r.headers["Content-Type"] == "text/html; charset=utf-8"
    with pytest.raises(urllib.error.HTTPError) as e:
        urllib.request.urlopen(url + "static/main.js", timeout=10)
    assert e.value.code == 404
    listening = server._SERVERS[-1].server_address[0]
    assert listening == "127.0.0.1"  # not every interface (0.0.0.0), as Meshcat's own server


def test_an_address_it_cannot_listen_on_is_named():
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        with pytest.raises(InvalidParameterError, match=rf"host.*127\.0\.0\.1:{port}"):
            server.serve_page("x", port=port)
    with pytest.raises(InvalidParameterError, match=r"host.*no-such-host\.invalid"):
        server.serve_page("x", host="no-such-host.invalid")
