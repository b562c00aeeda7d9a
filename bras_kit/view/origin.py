"""Only the page bras-kit serves may open its websocket (docs/security.md).

A browser lets any web page open a websocket to any address, loopback included, and says
which page asked in the ``Origin`` header (RFC 6455, 4.1 and 10.2); the server must check it.
Without the check, a site visited while ``bras-kit view`` or ``launch`` runs could read the
learner's robot and meshes from it and move the arm. The check compares the ``Origin`` with
the ``Host`` the browser addressed (the page's own origin), and, against DNS rebinding (a
site's name made to resolve to 127.0.0.1), accepts a host name only if it names this
computer's loopback, or the address given with ``--host``. A handshake without ``Origin``
comes from no browser page (a script has no page to protect) and is let in.

viser (1.x) takes no ``origins`` for its websockets server, so the check runs as its first
connection callback, before any message is sent: a refused connection is closed with code
1008, "policy violation" (RFC 6455, 7.4.1), and has received nothing.
"""

from __future__ import annotations

from typing import Any
from urllib.parse import urlsplit

LOOPBACK_NAMES = frozenset({"127.0.0.1", "localhost", "::1"})
ANY_ADDRESS = frozenset({"0.0.0.0", "::", ""})
POLICY_VIOLATION = 1008


def same_origin(origin: str | None, host: str | None, served_on: str) -> bool:
    """Whether a handshake with these ``Origin`` and ``Host`` headers comes from the page of a
    server listening on ``served_on``."""
    if origin is None:
        return True
    if not host or origin.lower() != f"http://{host}".lower():
        return False
    name = urlsplit(origin).hostname or ""
    if name in LOOPBACK_NAMES:
        return True
    return served_on in ANY_ADDRESS or name == served_on.strip("[]").lower()


def refuse_other_origins(server: Any) -> None:
    """Close every websocket of ``server`` (a ``viser.ViserServer``) whose page is not its own."""
    sockets = server._websock_server  # viser's infra server: its callbacks run before any message is sent
    served_on = str(server.get_host())

    async def check(client: Any) -> None:
        connection = sockets._live_connections.get(client.client_id)
        if connection is None:
            return
        headers = connection.request.headers
        if not same_origin(headers.get("Origin"), headers.get("Host"), served_on):
            await connection.close(POLICY_VIOLATION, "this page is not bras-kit's")

    sockets.on_client_connect(check)
