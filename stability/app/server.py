"""``python -m stability.app``: serve the explorer on this machine and open it in the browser.

Options: ``--port N`` (default 5006; 0 picks a free port), ``--host`` (default
127.0.0.1, this machine only; any other address serves the page to the
network and is announced with a warning), ``--no-browser``.  The URL is
printed.  The simulator's kernels compile in the background at start-up.
"""

from __future__ import annotations

import argparse
import ipaddress
import socket
import sys
from collections.abc import Sequence
from typing import Any

from stability.cli import OneLineErrorParser, run

__all__ = ["build_parser", "main", "make_server", "free_port", "create_page"]


def build_parser() -> argparse.ArgumentParser:
    """Command-line parser of ``python -m stability.app``.

    Returns
    -------
    argparse.ArgumentParser
    """
    p = OneLineErrorParser(prog="python -m stability.app",
                           description="Serve the interactive explorer (a local web page) and open it in the browser.")
    p.add_argument("--port", type=int, default=5006, help="TCP port (default 5006; 0: a free port, printed)")
    p.add_argument("--host", default="127.0.0.1",
                   help="address to listen on (default 127.0.0.1: this machine only; another address serves the "
                        "page to the network, with a warning)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    return p


def free_port(host: str = "127.0.0.1") -> int:
    """A TCP port free on ``host`` now (the OS picks it).

    Parameters
    ----------
    host : str

    Returns
    -------
    int
    """
    with socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET) as s:
        s.bind((host, 0))
        return int(s.getsockname()[1])


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def make_server(host: str = "127.0.0.1", port: int = 0, show: bool = False) -> tuple[Any, str]:
    """A Bokeh server for the explorer, not yet started, and its URL.

    Parameters
    ----------
    host : str
        Address to listen on.
    port : int
        TCP port; 0 picks a free one.
    show : bool
        Open a browser when started.

    Returns
    -------
    (bokeh.server.server.Server, str)
    """
    import panel as pn

    port = port or free_port(host)
    origins = [f"{host}:{port}", f"localhost:{port}", f"127.0.0.1:{port}"]
    if not _is_loopback(host):
        origins.append("*")
    pn.extension(notifications=False)
    server = pn.serve({"/": create_page}, port=port, address=host, show=show, start=False,
                      title="stability explorer", websocket_origin=origins, verbose=False)
    from stability.app.security import install

    install(server)
    shown = "127.0.0.1" if host in ("0.0.0.0", "::") else host
    return server, f"http://{shown}:{port}/"


def create_page() -> Any:
    """The page of a new browser session (called by the server once per session).

    Returns
    -------
    panel layout
    """
    import panel as pn

    doc = pn.state.curdoc
    deliver = doc.add_next_tick_callback if doc is not None else None
    later = (lambda fn, ms: doc.add_timeout_callback(fn, ms)) if doc is not None else None
    from stability.app.layout_page import LayoutExplorer, layout_in_query

    query = dict(pn.state.session_args or {})
    name = layout_in_query(query)
    if name is not None:                     # a wheel layout preset: its own page (no field editor)
        lx = LayoutExplorer(name, query, deliver=deliver)
        if doc is not None:
            doc.on_session_destroyed(lambda _context: lx.jobs.cancel())
        return lx.layout
    from stability.app.page import Explorer

    ex = Explorer(query=query, deliver=deliver, location=pn.state.location,
                  later=later)
    if doc is not None:                      # a closed page's queued work is dropped
        doc.on_session_destroyed(lambda _context: ex.jobs.cancel())
        pn.state.onload(ex.sync_location)    # once connected: the address bar names the chair shown
    return ex.layout


def _run(args: argparse.Namespace) -> int:
    if not 0 <= args.port <= 65535:
        raise ValueError(f"--port {args.port} is invalid; valid range: 0 to 65535 (0: a free port)")
    try:
        socket.getaddrinfo(args.host, None)
    except OSError:
        raise ValueError(f"--host {args.host!r} is not an address of this machine") from None
    if not _is_loopback(args.host):
        print(f"warning: --host {args.host} serves the explorer to every machine that can reach this address; "
              "it has no login", file=sys.stderr)
    try:
        import panel  # noqa: F401
    except ImportError:
        raise ValueError("the explorer needs Panel: pip install -e \".[app]\"") from None
    from stability.app.jobs import warm_up

    try:
        server, url = make_server(args.host, args.port, show=not args.no_browser)
    except OSError as exc:
        raise ValueError(f"--port {args.port}: cannot listen on {args.host}:{args.port} ({exc.strerror})") from None
    warm_up()
    # the real stdout: the command-line wrapper holds stdout until a command ends, and a server never ends
    print(f"stability explorer: {url}  (Ctrl-C stops it)", file=sys.__stdout__, flush=True)
    server.start()
    if not args.no_browser:
        server.io_loop.add_callback(server.show, "/")
    server.io_loop.start()
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.app``; returns the exit status.

    Parameters
    ----------
    argv : sequence of str, optional

    Returns
    -------
    int
    """
    return run(build_parser(), argv, _run)
