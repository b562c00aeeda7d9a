"""The pages of ``bras-kit view`` and ``bras-kit launch`` (viser): bound to loopback, serving
only the page's own files, and their websocket refused to a page of another origin.

Oracles: the kernel's table of listening sockets (/proc/net/tcp, proc(5)); a file that exists
beside viser's page folder and /etc/passwd, which must not come back through any spelling of
``..``; and Debian's Chromium, whose page of another origin opens the websocket as any web site
could: refused by bras-kit's viewer, let in by a plain viser server (the same page, the same
browser, so the test sees a connection when there is one)."""

from __future__ import annotations

import contextlib
import http.client
import http.server
import os
import signal
import socket
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from pages import free_port as _free_port

pytestmark = pytest.mark.slow

def _listening(port: int) -> list[str]:
    """The local addresses (hex, as the kernel writes them) of TCP sockets listening on ``port``."""
    found = []
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        try:
            lines = Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            local, state = line.split()[1], line.split()[3]
            address, hex_port = local.split(":")
            if state == "0A" and int(hex_port, 16) == port:  # 0A: TCP_LISTEN
                found.append(address)
    return found


def test_the_viewer_listens_on_loopback_only(viewer):
    assert _listening(viewer.server.get_port()) == ["0100007F"]  # 127.0.0.1, little-endian


def test_the_launch_page_listens_on_loopback_only_and_refuses_another_origin(browser, tmp_path):
    from pages import launch as _launch
    from pages import launch_url as _url

    from bras_kit.scaffold.package import scaffold_package

    scaffold_package(tmp_path / "bras_description")
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    errors = tmp_path / "stderr.txt"
    port = _free_port()
    process = _launch([str(tmp_path / "bras_description"), "affichage.launch.py", "--port", str(port),
                       "--duration", "5"], env, errors)
    try:
        url = _url(process, errors)
        assert url.startswith(f"http://127.0.0.1:{port}")
        assert _listening(port) == ["0100007F"]
        assert _from_other_origin(browser, port) == {"messages": 0, "closed": True, "code": 1008}
    finally:
        process.send_signal(signal.SIGINT)
        process.wait(timeout=30)


def _get(port: int, path: str) -> tuple[int, bytes]:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    try:
        connection.putrequest("GET", path, skip_accept_encoding=True)  # the path as written, never normalised
        connection.endheaders()
        response = connection.getresponse()
        return response.status, response.read()
    finally:
        connection.close()


@pytest.mark.parametrize("path", [
    "/../__init__.py", "/../../__init__.py", "/%2e%2e/%2e%2e/__init__.py", "/..%2f..%2f__init__.py",
    "/%2E%2E%2F%2E%2E%2F__init__.py", "/..\\..\\__init__.py", "//etc/passwd", "/../../../../../../etc/passwd",
    "/%2fetc%2fpasswd", "/static/../../../__init__.py",
])
def test_no_url_reaches_a_file_outside_the_pages_folder(viewer, path):
    import viser

    port = viewer.server.get_port()
    status, body = _get(port, path)
    assert status == 404
    outside = (Path(viser.__file__).read_bytes()[:200], Path("/etc/passwd").read_bytes()[:20])
    assert not any(piece in body for piece in outside if piece)
    assert _get(port, "/")[0] == 200  # the page itself is served


OPEN_SOCKET = """async ([url, protocol]) => {
    const socket = new WebSocket(url, [protocol]);
    socket.binaryType = "arraybuffer";
    let messages = 0;
    socket.onmessage = () => { messages += 1; };
    const end = await new Promise((resolve) => {
        socket.onclose = (event) => resolve({closed: true, code: event.code});
        setTimeout(() => resolve({closed: false, code: 0}), 4000);
    });
    socket.close();
    return {messages, ...end};
}"""


@contextlib.contextmanager
def _web_site() -> Iterator[str]:
    """Another web site's page: served from another port of this machine, so another origin
    (RFC 6454: scheme, host and port) that no browser setting tells apart from any site's."""
    class Page(http.server.BaseHTTPRequestHandler):
        def do_GET(self) -> None:  # noqa: N802 - the name http.server calls
            body = b"<!doctype html><title>a web site</title>"
            self.send_response(200)
            self.send_header("Content-Type", "text/html")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *args: object) -> None:
            pass

    site = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Page)
    thread = threading.Thread(target=site.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{site.server_address[1]}"
    finally:
        site.shutdown()
        site.server_close()


def _from_other_origin(browser, port: int) -> dict:
    import viser

    page = browser.new_page()
    try:
        with _web_site() as origin:
            page.goto(origin + "/")
            assert page.evaluate("location.origin") == origin
            return page.evaluate(OPEN_SOCKET, [f"ws://127.0.0.1:{port}", f"viser-v{viser.__version__}"])
    finally:
        page.close()


def test_a_page_of_another_origin_cannot_use_the_viewers_websocket(browser, viewer):
    seen = _from_other_origin(browser, viewer.server.get_port())
    assert seen == {"messages": 0, "closed": True, "code": 1008}


def test_a_plain_viser_server_lets_the_same_page_in_so_the_oracle_sees_a_connection(browser):
    import viser

    server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
    try:
        server.scene.add_box("/box", dimensions=(0.1, 0.1, 0.1))
        time.sleep(0.2)
        seen = _from_other_origin(browser, server.get_port())
    finally:
        server.stop()
    assert seen["messages"] > 0 and seen["closed"] is False


def test_the_viewers_own_page_still_gets_its_scene(browser, viewer):
    import viser

    page = browser.new_page()
    try:
        page.goto(viewer.url)
        seen = page.evaluate(OPEN_SOCKET, [viewer.url.replace("http://", "ws://"), f"viser-v{viser.__version__}"])
    finally:
        page.close()
    assert seen["messages"] > 0 and seen["closed"] is False


def test_a_dns_rebinding_name_is_refused_even_when_origin_and_host_agree():
    from bras_kit.view.origin import same_origin

    # a site whose name resolves to 127.0.0.1: its page's Origin and Host agree, and name no loopback
    assert not same_origin("http://rebind.example:8080", "rebind.example:8080", "127.0.0.1")
    assert same_origin("http://localhost:8080", "localhost:8080", "127.0.0.1")
    assert same_origin("http://192.0.2.7:8080", "192.0.2.7:8080", "0.0.0.0")  # --host 0.0.0.0 exposes it anyway
    assert not same_origin("http://evil.example", "127.0.0.1:8080", "127.0.0.1")


def test_no_socket_outside_loopback_reaches_the_viewer(viewer):
    """Every address of this machine but loopback: the connection is refused by the kernel."""
    port = viewer.server.get_port()
    addresses = {info[4][0] for info in socket.getaddrinfo(socket.gethostname(), None, socket.AF_INET)}
    addresses -= {"127.0.0.1", "127.0.1.1"}
    for address in sorted(addresses):
        with socket.socket() as probe, pytest.raises(ConnectionRefusedError):
            probe.settimeout(5)
            probe.connect((address, port))
