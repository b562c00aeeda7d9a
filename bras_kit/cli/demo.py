"""bras-kit demo: everything the tutorial builds, for the built-in arm, in one folder."""

from __future__ import annotations

import argparse
import os
import sys
import time

from ..core.i18n import labelled, say
from ..core.message import M
from ._common import SEVERITY_WORDS, add_force_argument, warn

DEMO_POSE = {"epaule": 0.8, "coude": 1.2}


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("outdir", nargs="?", default="bras-kit-demo", metavar="OUTDIR",
                        help="folder to write into (default: ./bras-kit-demo)")
    parser.add_argument("--wrist", action="store_true")
    parser.add_argument("--duration", type=float, default=9.0, help="of tutorial motion in the GIF (default 9)")
    parser.add_argument("--fps", type=float, default=20.0, help="of the GIF (default 20, as the tutorial's node)")
    parser.add_argument("--size", default="480x360", help="default 480x360")
    parser.add_argument("--backend", default="auto", choices=("auto", "egl", "osmesa", "software"))
    add_force_argument(parser)


def _step(message: str) -> float:
    print(f"- {message} ...", end="", flush=True)
    return time.perf_counter()


def _done(start: float, path: str) -> None:
    print(f" {path} ({time.perf_counter() - start:.1f} s)")


def run(args: argparse.Namespace) -> int:
    from ..core.message import M
    from ..model.authoring import arm
    from ..motion import check_limits, sample_loop, tutorial_motion
    from ..render import parse_size, render_motion, render_pose, save_gif, save_png
    from ..render.renderer import used_software_fallback
    from ..scaffold.package import scaffold_package
    from ..trust.outputs import write_to
    from ..validate import validate

    outdir = args.outdir
    owned = _claim(outdir, args.force)
    size = parse_size(args.size)
    robot = arm(wrist=args.wrist)
    states = sample_loop(tutorial_motion(robot), args.duration, args.fps)
    # the diagrams (matplotlib only) are drawn by a second process while this one renders
    with _Diagrams(robot, states, args.lang) as diagrams:
        variant = M("with the wrist 'poignet'") if args.wrist else "epaule + coude"
        print(say(M("bras-kit demo: the tutorial arm '{name}' ({variant}) -> {folder}/", name=robot.name,
                    variant=variant, folder=outdir), args.lang))
        made: list[str] = []

        def save(name: str, writer) -> str:
            path = os.path.join(outdir, name)
            write_to(path, args.force or name in owned, writer, announce=False)
            made.append(name)
            _remember(outdir, owned | set(made))
            return path

        start = _step(say(M("scaffolding the ROS 2 package"), args.lang))
        package_dir = os.path.join(outdir, "bras_description")
        scaffold_package(package_dir, wrist=args.wrist, force=args.force or "bras_description" in owned, lang=args.lang)
        made.append("bras_description")
        _remember(outdir, owned | set(made))
        _done(start, package_dir + "/")

        start = _step(say(M("validating the URDF"), args.lang))
        findings = validate(robot, lang=args.lang)
        problems = [f for f in findings if f.severity in ("error", "warning")]
        print(" " + say(M("{count} errors or warnings ({seconds:.1f} s)", count=len(problems),
                          seconds=time.perf_counter() - start), args.lang))
        for finding in problems:
            print(f"    {finding.code} {say(SEVERITY_WORDS[finding.severity], args.lang)}: "
                  f"{say(finding.message, args.lang)}")

        start = _step(say(M("rendering the pose {pose} with TF axes",
                            pose=", ".join(f"{k}={v}" for k, v in DEMO_POSE.items())), args.lang))
        picture = render_pose(robot, DEMO_POSE, size=size, tf=True, backend=args.backend)
        pose_png = save("pose.png", lambda path: save_png(picture, path))
        _done(start, pose_png)

        start = _step(say(M("animating the tutorial motion ({duration:g} s at {fps:g} fps)", duration=args.duration,
                            fps=args.fps), args.lang))
        gif = save(f"{robot.name}.gif",
                   lambda path: save_gif(render_motion(robot, states, size=size, backend=args.backend), path, fps=args.fps))
        _done(start, gif)
        if used_software_fallback():
            warn(M("the pictures came from the pure-CPU renderer (no OpenGL here): "
                   "'bras-kit doctor' says what to install"))
        for violation in check_limits(robot, states):
            leaves = M("{joint} leaves its velocity limit at t={time:.2f} s", joint=violation.joint,
                       time=violation.time) if violation.kind == "velocity" else \
                M("{joint} leaves its position limit at t={time:.2f} s", joint=violation.joint, time=violation.time)
            print("    " + labelled(M("warning"), say(leaves, args.lang), args.lang))

        start = _step(say(M("drawing the frame tree"), args.lang))
        frames_pdf = save("frames.pdf", diagrams.writer("frames.pdf"))
        save("frames.png", diagrams.writer("frames.png"))
        _done(start, frames_pdf + " (+ .png)")

        start = _step(say(M("plotting joint angles and the tip path"), args.lang))
        plot_png = save("motion.png", diagrams.writer("motion.png"))
        _done(start, plot_png)

        print(say(M("done. Open {gif} to see the arm move; {package} is ready for colcon build on a ROS 2 machine.",
                    gif=gif, package=package_dir), args.lang))
        print(_next_steps(args.lang))
        sys.stdout.flush()
        return 1 if any(f.severity == "error" for f in findings) else 0


DIAGRAMS = ("frames.pdf", "frames.png", "motion.png")


def _next_steps(lang: str) -> str:
    """The three things to try after the demo: the live viewer, the lessons, the exercises."""
    steps = (
        ("bras-kit view", M("the arm live in your browser, a slider for each joint")),
        (f"jupyter lab lessons/{lang}", M("the lessons, one notebook per step of the tutorial")),
        ("bras-kit exercises init", M("the tutorial's exercises (the wrist, the masses), checked as you go")),
    )
    width = max(len(command) for command, _ in steps)
    lines = [say(M("next, try:"), lang)]
    lines += [f"  {command.ljust(width)}   {say(what, lang)}" for command, what in steps]
    return "\n".join(lines)


def _draw_diagrams(robot, states, folder: str, lang: str | None) -> None:
    """The demo's figures, written into ``folder``: the frame tree (drawn once, saved as PDF and
    PNG) and the joint-angle and tip-path plot."""
    from ..diagrams import frame_diagram, plot_motion
    from ..diagrams.output import save_figure

    diagram = frame_diagram(robot, DEMO_POSE, lang=lang)
    for name in DIAGRAMS[:2]:
        save_figure(diagram, os.path.join(folder, name))
    plot_motion(robot, states, path=os.path.join(folder, DIAGRAMS[2]), lang=lang)


class _Diagrams:
    """The demo's figures, drawn by a forked process (matplotlib's import and drawing take as long
    as the animation: on two cores the two overlap) into a private temporary folder, then copied
    to their place by the demo's own writer. If that process cannot start or fails, the figures
    are drawn here instead, so a failure says what the in-process drawing says."""

    def __init__(self, robot, states, lang: str | None = None) -> None:
        import concurrent.futures
        import multiprocessing
        import tempfile

        self._robot, self._states, self._lang = robot, states, lang
        self._folder = tempfile.mkdtemp(prefix="bras-kit-demo-")
        self._future = None
        self._pool = None
        try:  # forked before any OpenGL context exists in this process
            self._pool = concurrent.futures.ProcessPoolExecutor(max_workers=1,
                                                                mp_context=multiprocessing.get_context("fork"))
            self._future = self._pool.submit(_draw_diagrams, robot, states, self._folder, lang)
        except (OSError, ValueError, RuntimeError):
            self._future = None
        self._ready = False

    def writer(self, name: str):
        """A writer for :func:`~bras_kit.trust.outputs.write_to` copying the figure ``name``."""
        import shutil

        def write(path: str) -> None:
            if not self._ready:
                self._wait()
            shutil.copyfile(os.path.join(self._folder, name), path)

        return write

    def _wait(self) -> None:
        drawn = False
        if self._future is not None:
            try:
                self._future.result()
                drawn = all(os.path.isfile(os.path.join(self._folder, name)) for name in DIAGRAMS)
            except Exception:  # noqa: BLE001 - drawn again below, where a real error is reported plainly
                drawn = False
        if not drawn:
            _draw_diagrams(self._robot, self._states, self._folder, self._lang)
        self._ready = True

    def __enter__(self) -> _Diagrams:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        import shutil

        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
        shutil.rmtree(self._folder, ignore_errors=True)


MANIFEST = ".bras-kit-demo"


def _claim(outdir: str, force: bool) -> set[str]:
    """Make sure ``outdir`` is ours to write in; return the names an earlier demo made there.

    The demo owns its folder: running it again refreshes what it made (listed in a manifest),
    and it refuses only a folder holding something else, unless ``force``.
    """
    from ..core.errors import OutputExistsError, os_reason
    from ..trust.outputs import OutputError

    if os.path.islink(outdir) or (os.path.lexists(outdir) and not os.path.isdir(outdir)):
        raise OutputError(M("{path} exists and is not a folder", path=outdir), hint=M("name a new folder for the demo"))
    owned: set[str] = set()
    if os.path.isdir(outdir):
        try:
            with open(os.path.join(outdir, MANIFEST), encoding="utf-8") as handle:
                owned = {line.strip() for line in handle if line.strip() and "/" not in line}
        except FileNotFoundError:
            pass
        except OSError as exc:
            raise OutputError(M("cannot read {path}: {reason}", path=os.path.join(outdir, MANIFEST),
                                reason=os_reason(exc))) from None
        foreign = sorted(set(os.listdir(outdir)) - owned - {MANIFEST})
        if foreign and not force:
            shown = ", ".join(foreign[:5]) + (", ..." if len(foreign) > 5 else "")
            raise OutputExistsError(M("{path} holds files the demo did not make ({shown})", path=outdir, shown=shown),
                                    hint=M("name another folder, or pass --force to write beside them"))
    try:
        os.makedirs(outdir, exist_ok=True)
    except OSError as exc:
        raise OutputError(M("cannot create the folder {path}: {reason}", path=outdir, reason=os_reason(exc))) from None
    return owned


def _remember(outdir: str, names: set[str]) -> None:
    """List what the demo made, so the next run may refresh it."""
    from ..trust.outputs import write_text

    path = os.path.join(outdir, MANIFEST)
    write_text(path, "\n".join(sorted(names)), True, announce=False)
