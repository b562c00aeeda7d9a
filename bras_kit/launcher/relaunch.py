"""A launch kept live beside its page: the package's own nodes move the arm until the page is
closed, and a file of the package saved builds and launches it again (one evaluation printed
and shown: robot, Fixed Frame, sliders, checks, nodes). The last save always wins."""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any, Protocol

from ..core.message import Message, Mn
from .reporter import Reporter
from .session import Launched, LaunchRequest, Superseded, launch


class LaunchPage(Protocol):
    """What the relaunch needs of a page (bras_kit.view.Viewer is one)."""

    rviz_state: Any  # its ``written``: the files Save Config wrote (no save of the learner's), or None

    def wait(self, until: Callable[[], bool]) -> None: ...

    def show_joint_state(self, names: Sequence[str], positions: Sequence[float]) -> None: ...

    def show_launch(self, launch: Any, package_paths: tuple[str, ...] | None = None) -> None: ...

    def show_checks(self) -> None: ...


def live(request: LaunchRequest, launched: Launched, page: LaunchPage, reporter: Reporter | None = None,
         stamps: dict[str, Any] | None = None) -> None:
    """Until the page's wait ends (Ctrl-C), the package's own nodes run live into ``page``; a file
    saved since ``stamps`` (the files the first build read) builds and launches again."""
    from ..core.errors import BrasKitError
    from ..run.live import LiveNodes, changed_files, executables_of, package_stamps

    reporter = reporter or Reporter(request.lang)
    nodes = LiveNodes(request.folder, [], page.show_joint_state)

    def start(current: Launched) -> None:
        nonlocal nodes
        names, parameters = (executables_of(current.nodes, current.result.build.package) if current.started
                             else ([], {}))
        nodes = LiveNodes(request.folder, names, page.show_joint_state, parameters, reporter.lang,
                          beside=request.others)
        nodes.start()  # a Ctrl-C while they start still finds them in ``nodes``

    current_stamps = stamps or package_stamps(request.folder)
    saved: list[str] = []

    def changed() -> bool:
        """Whether a file of the package was saved since the stamps (then ``saved`` names them and
        the stamps are what the next build reads). Save Config's own file is no save."""
        nonlocal current_stamps
        now = package_stamps(request.folder, before=current_stamps)
        written = page.rviz_state.written if page.rviz_state is not None else set()
        files = changed_files(current_stamps, now)
        saved[:] = [p for p in files if os.path.abspath(p) not in written]
        written.difference_update(os.path.abspath(p) for p in files)
        current_stamps = now
        return bool(saved)

    def say_saved(message: Callable[[str, int], Message]) -> None:
        names = ", ".join(os.path.relpath(p, request.folder) for p in saved[:3])
        reporter.error(message(names, min(len(saved), 3)))

    try:
        start(launched)
        while True:
            saved.clear()
            page.wait(until=changed)
            if not saved:  # Ctrl-C
                break
            nodes.stop()
            say_saved(lambda files, n: Mn("{files} saved: the package is built and launched again",
                                          "{files} saved: the package is built and launched again", n, files=files))
            relaunched = None
            while relaunched is None:
                try:
                    # a save while it builds: that build is dropped and the package built again,
                    # so the last save always wins (stamps are never taken after the build: what
                    # was saved during it is a save)
                    relaunched = launch(request, reporter=reporter, on_evaluated=page.show_launch, superseded=changed)
                except Superseded:
                    say_saved(lambda files, n: Mn(
                        "{files} saved during the build: the package is built and launched again",
                        "{files} saved during the build: the package is built and launched again", n, files=files))
                except BrasKitError as exc:
                    reporter.error(exc.message)
                    break
            if relaunched is None:
                nodes = LiveNodes(request.folder, [], page.show_joint_state)
                continue
            reporter.findings(relaunched.results)
            page.show_checks()  # once the terminal has said them, as the first time
            start(relaunched)
    except KeyboardInterrupt:  # during a rebuild: the same stop as during the wait
        pass
    finally:
        nodes.stop()  # the page is closed by its owner
