"""What this install of bras-kit can do, and how to fix what it cannot (``bras-kit doctor``).

Each check is a small function returning a :class:`Check`: what it found, its status, and the
fix when something is missing. The checks do the real thing on a small scale (an OpenGL
picture drawn and its pixels counted, a ball dropped in MuJoCo and its fall compared with
g t^2 / 2), so "ok" means the feature works here, not merely that a package is installed.

:data:`CHECKS` is the list ``bras-kit doctor`` runs, in order; a feature adds its section by
adding a function to it. A check that raises is reported as a failed check, never a traceback.
"""

from __future__ import annotations

import os
import platform
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from ..core import backends
from ..core.errors import BrasKitError
from ..core.message import M, Message, Mn

OK, NOTE, FAIL = "ok", "note", "fail"
SUPPORTED_PYTHONS = ((3, 10), (3, 11), (3, 12), (3, 13))  # each checked by .ci/run
TEST_PICTURE = (64, 48)
TEST_POSE = {"epaule": 0.8, "coude": 1.2}
SOFTWARE_GL = ("llvmpipe", "softpipe", "swrast", "swiftshader", "software rasterizer")


@dataclass(frozen=True)
class Check:
    """One line of the report. ``status``: ``ok`` (works), ``note`` (works, with a limit worth
    knowing) or ``fail`` (does not work here: ``fix`` says what to do)."""

    name: Message | str
    status: str
    found: Message | str
    fix: Message | str | None = None


def check_versions() -> Check:
    from .. import __version__

    version = platform.python_version()
    found = M("Python {python} ({implementation}), bras-kit {version}", python=version,
              implementation=platform.python_implementation(), version=__version__)
    if sys.version_info[:2] in SUPPORTED_PYTHONS:
        return Check(M("versions"), OK, found)
    return Check(M("versions"), NOTE, found,
                 M("bras-kit is tested on Python {versions}; another version may work but is not checked",
                   versions=[f"{major}.{minor}" for major, minor in SUPPORTED_PYTHONS]))


def check_opengl() -> Check:
    """A small picture drawn off-screen: with OpenGL (EGL, then OSMesa), else by the pure-CPU renderer."""
    from ..model.authoring import arm
    from ..render import Renderer

    robot = arm()
    failure: BrasKitError | None = None
    for backend in ("egl", "osmesa"):
        try:
            start = time.perf_counter()
            with Renderer(robot, size=TEST_PICTURE, backend=backend) as renderer:
                picture = renderer.render(TEST_POSE)
                device = _gl_renderer_name()
            seconds = time.perf_counter() - start
        except BrasKitError as exc:
            failure = failure or exc
            continue
        drawn = _drawn_pixels(picture)
        if drawn == 0:
            return Check(M("OpenGL"), FAIL, M("{backend} draws a blank picture ({device})", backend=backend.upper(),
                                                device=device or "?"),
                         M("update the graphics driver, or draw with --backend software"))
        kind = (M("software rendering, no GPU ({device})", device=device) if _is_software(device)
                else M("hardware ({device})", device=device or "?"))
        return Check(M("OpenGL"), OK, M("{backend}, {kind}; a {width}x{height} test picture with {pixels} arm pixels "
                                        "in {seconds:.2f} s", backend=backend.upper(), kind=kind,
                                        width=TEST_PICTURE[0], height=TEST_PICTURE[1], pixels=drawn,
                                        seconds=seconds))
    with Renderer(robot, size=TEST_PICTURE, backend="software") as renderer:
        drawn = _drawn_pixels(renderer.render(TEST_POSE))
    assert failure is not None
    fix = failure.hint if failure.hint else M(
        "on Debian/Ubuntu install Mesa's EGL: sudo apt-get install {packages}",
        packages=backends.OPENGL_SYSTEM_PACKAGES)
    return Check(M("OpenGL"), FAIL, M("none ({reason}); pictures come from the pure-CPU fallback, slower "
                                      "({pixels} arm pixels in the test picture)", reason=failure.message, pixels=drawn),
                 fix)


def _drawn_pixels(picture) -> int:
    """Pixels unlike the corner's background colour: the arm and its shading."""
    import numpy as np

    return int((np.abs(picture.astype(int) - picture[0, 0].astype(int)).sum(axis=2) > 24).sum())


def _gl_renderer_name() -> str:
    """GL_RENDERER of the context the renderer left current ('' when none is)."""
    try:
        backends.opengl()
        from OpenGL import GL

        name = GL.glGetString(GL.GL_RENDERER)
        return name.decode("utf-8", "replace") if isinstance(name, bytes) else ""
    except Exception:  # noqa: BLE001 - no current context: the device stays unnamed
        return ""


def _is_software(device: str) -> bool:
    return any(word in device.lower() for word in SOFTWARE_GL)


BALL = """<mujoco><option timestep="0.002"/><worldbody>
<body pos="0 0 10"><freejoint/><geom type="sphere" size="0.1" mass="1"/></body>
</worldbody></mujoco>"""


def check_mujoco() -> Check:
    """A ball dropped for half a second falls g t^2 / 2 (within 2 %: the integrator's step)."""
    try:
        mujoco = backends.mujoco()
    except BrasKitError as exc:
        return Check(M("MuJoCo"), FAIL, exc.message, exc.hint)
    model = mujoco.MjModel.from_xml_string(BALL)
    data = mujoco.MjData(model)
    seconds = 0.5
    while data.time < seconds - 1e-9:
        mujoco.mj_step(model, data)
    fallen = 10.0 - float(data.qpos[2])
    expected = -float(model.opt.gravity[2]) * data.time ** 2 / 2
    found = M("version {version}: a ball fell {fallen:.3f} m in {seconds} s (g t²/2 = {expected:.3f} m)",
              version=mujoco.__version__, fallen=fallen, seconds=seconds, expected=expected)
    if abs(fallen - expected) > 0.02 * expected:
        return Check(M("MuJoCo"), FAIL, found, M("reinstall it: pip install --force-reinstall mujoco"))
    return Check(M("MuJoCo"), OK, found)


def check_viewer_client() -> Check:
    """viser serves a built web client from its package; without it, it would try to build one with npm."""
    try:
        viser = backends.viser()
    except BrasKitError as exc:
        return Check(M("browser viewer"), FAIL, exc.message, exc.hint)
    index = os.path.join(os.path.dirname(viser.__file__), "client", "build", "index.html")
    version = getattr(viser, "__version__", "?")
    if os.path.isfile(index):
        return Check(M("browser viewer"), OK, M("viser {version}, its web client is installed", version=version))
    return Check(M("browser viewer"), FAIL, M("viser {version} has no built web client ({path} is missing)",
                                              version=version, path=index),
                 M("reinstall viser from its wheel: pip install --force-reinstall --only-binary=:all: viser"))


def check_browser() -> Check:
    """The browser ``bras-kit view`` opens (Python's webbrowser, which honours $BROWSER)."""
    import shutil
    import webbrowser

    try:
        browser = webbrowser.get()
    except webbrowser.Error:
        installed = [name for name in ("firefox", "chromium", "chromium-browser", "google-chrome")
                     if shutil.which(name)]
        found = (M("none that can open here (installed: {names}; no display?)", names=installed) if installed
                 else M("none found"))
        return Check(M("web browser"), NOTE, found,
                     M("'bras-kit view' still serves the arm: open the address it prints in any browser "
                       "(or set $BROWSER)"))
    name = getattr(browser, "name", None) or type(browser).__name__
    return Check(M("web browser"), OK, M("'bras-kit view' opens {name}", name=name))


def check_cache() -> Check:
    """The user cache folder: where it is, what it holds, and that it can be written."""
    from ..core.cachedir import cache_home

    folder = cache_home()
    files, size = 0, 0
    for root, _dirs, names in os.walk(folder):
        for name in names:
            try:
                size += os.lstat(os.path.join(root, name)).st_size
                files += 1
            except OSError:
                pass
    found = M("{path}: {files}, {size:.1f} MB", path=folder,
              files=Mn("{n} file", "{n} files", files), size=size / 1e6)
    existing = folder
    while not os.path.isdir(existing) and os.path.dirname(existing) != existing:
        existing = os.path.dirname(existing)
    if os.access(existing, os.W_OK | os.X_OK):
        return Check(M("cache folder"), OK, found)
    return Check(M("cache folder"), NOTE, found,
                 M("it cannot be written: commands work but compute everything again; "
                   "set XDG_CACHE_HOME to a folder you own"))


def check_mesh_cache() -> Check:
    """The decoded meshes kept in the cache folder (:mod:`bras_kit.meshes`): how many, how large."""
    from ..meshes import cache_info, disk_cache_enabled
    from ..meshes.cache import MAX_BYTES

    info = cache_info()
    found = M("{meshes}, {size:.1f} MB of at most {limit:.0f} MB, in {path}",
              meshes=Mn("{n} decoded mesh", "{n} decoded meshes", info.entries), size=info.bytes / 1e6,
              limit=MAX_BYTES / 1e6, path=info.folder)
    if not disk_cache_enabled():
        return Check(M("mesh cache"), NOTE, found,
                     M("BRAS_KIT_NO_CACHE is set: every command decodes its mesh files again"))
    return Check(M("mesh cache"), OK, found)


def check_containment() -> Check:
    """The walls around code bras-kit did not write (:mod:`bras_kit.trust.contain`): a small
    function run inside them must find itself alone (pid 1) and /tmp read-only."""
    import errno
    import tempfile

    from ..trust.contain import Containment, available, forget_trial
    from ..trust.sandbox import run_limited

    forget_trial()  # tried for real, not read from this boot's record of an earlier trial
    status = available()
    if not status.ok:
        return Check(M("containment"), NOTE, M("none: {found}", found=status.found),
                     M("{how}; until then 'run' runs your own nodes without walls and 'grade --run-nodes' "
                       "refuses", how=status.how))
    with tempfile.TemporaryDirectory(prefix="bras-kit-doctor-") as workdir:
        pid, refused = run_limited(_inside_walls, contain=Containment(workdir), wall_seconds=20.0)
    if pid != 1 or refused != errno.EROFS:
        return Check(M("containment"), FAIL, M("the walls leak: pid {pid}, a write in /tmp gave errno {errno}",
                                               pid=pid, errno=refused),
                     M("this is a bug in bras-kit; run again with BRAS_KIT_DEBUG=1 and report it"))
    return Check(M("containment"), OK, status.found)


def _inside_walls() -> tuple[int, int]:
    try:
        open("/tmp/bras-kit-doctor-probe", "w").close()
    except OSError as exc:
        return os.getpid(), exc.errno or 0
    return os.getpid(), 0


CHECKS: list[Callable[[], Check]] = [
    check_versions,
    check_opengl,
    check_mujoco,
    check_viewer_client,
    check_browser,
    check_cache,
    check_mesh_cache,
    check_containment,
]


def run_checks(checks: Sequence[Callable[[], Check]] | None = None) -> list[Check]:
    """Every check in order; one that raises becomes a failed line naming the error."""
    results = []
    for check in CHECKS if checks is None else checks:
        try:
            results.append(check())
        except Exception as exc:  # noqa: BLE001 - the doctor reports, it does not crash
            results.append(Check(M("{check}", check=check.__name__), FAIL, M("{error}: {text}", error=type(exc).__name__,
                                                                     text=str(exc).splitlines()[0] if str(exc) else ""),
                                 M("this is a bug in bras-kit; run again with BRAS_KIT_DEBUG=1 and report it")))
            if os.environ.get("BRAS_KIT_DEBUG"):
                raise
    return results


def healthy(results: Sequence[Check]) -> bool:
    return all(result.status != FAIL for result in results)
