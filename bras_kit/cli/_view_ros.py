"""bras-kit view --ros: the viewer on the live ROS 2 graph (bras_kit.view.live_ros), served as
``bras-kit view`` serves a file."""

from __future__ import annotations

import argparse
import sys

from ..core.i18n import say
from ..core.message import M

WAIT_FOR_DESCRIPTION = 10.0  # seconds: discovery (up to 2.5 s) and robot_state_publisher's start


def run_ros(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..live.watch import ros_python

    if args.file is not None or args.motion or args.node or args.export:
        raise ParameterError(M("--ros shows the robot and the motion of the live graph: it takes no FILE, --motion, "
                               "--node nor --export"),
                             hint=M("drop them, or drop --ros"))
    if not 0 <= args.port <= 65535:
        raise ParameterError(M("--port {port} is out of range", port=args.port),
                             hint=M("give a port between 1024 and 65535, e.g. 8080"))
    python = ros_python()  # no rclpy: one line, exit 3, before anything starts
    from ..view.live_ros import RosFeed

    lang = args.lang
    feed = RosFeed(python).start()
    try:
        print(say(M("waiting for /robot_description on the ROS 2 graph..."), lang), file=sys.stderr, flush=True)
        robot = feed.wait_for_robot(WAIT_FOR_DESCRIPTION)
        if robot is None:
            return _no_robot(feed, lang)
        return _serve(args, feed, robot)
    except KeyboardInterrupt:
        return 0
    finally:
        feed.stop()


def _no_robot(feed: object, lang: str | None) -> int:
    """No robot to show: say why, as doctor --ros would, and exit 1."""
    from ..findings.report import finding_text

    results = feed.results()  # type: ignore[attr-defined]
    print(say(M("no robot came on /robot_description in {seconds:.0f} s: nothing to show", seconds=WAIT_FOR_DESCRIPTION),
              lang), file=sys.stderr)
    for result in results:
        for found in result.findings:
            print(finding_text(result.path, found, lang))
    return 1


def _serve(args: argparse.Namespace, feed: object, robot: object) -> int:
    from ..view import Source, Viewer
    from ._common import open_page, warn

    if args.host not in ("127.0.0.1", "localhost", "::1"):
        warn(M("listening on {host}: anyone who can reach this computer can see and move the arm", host=args.host),
             args.lang)
    viewer = Viewer(Source(robot=robot), host=args.host, port=args.port, lang=args.lang,  # type: ignore[arg-type]
                    geometry=args.geometry)
    viewer.source_label = "/robot_description"
    feed.attach(viewer)  # type: ignore[attr-defined]
    try:
        print(say(M("bras-kit view: {url} (Ctrl-C to stop)", url=viewer.url), args.lang), flush=True)
        print(say(M("showing the live ROS 2 graph: /robot_description, moving with /joint_states"), args.lang),
              file=sys.stderr, flush=True)
        open_page(viewer.url, args)
        viewer.wait(until=lambda: not feed.running)  # type: ignore[attr-defined]
    except KeyboardInterrupt:
        pass
    finally:
        viewer.stop()
    if not feed.running:  # type: ignore[attr-defined]
        print(say(M("the ROS 2 probe stopped: the page no longer follows the graph"), args.lang), file=sys.stderr)
        return 1
    return 0
