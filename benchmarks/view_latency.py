"""How fast is bras-kit view? Side by side with viser's own URDF loader (ViserUrdf + yourdfpy),
the peer a viser user would reach for.

1. start -> first frame: from running ``bras-kit view`` to the orange forearm drawn in headless
   chromium (WebGL on the CPU); and for Talos (example-robot-data's talos_full_v2: 60 links,
   206k triangles) from running ``bras-kit view talos_full_v2.urdf`` and from running a script
   serving the same file with ViserUrdf, to the first frame chromium drew with its dark-grey
   meshes (issue 25: <= 3 s; frames stamped by the DevTools screencast);
2. slider change -> link transforms sent: median and 95th percentile over 200 changes, for
   bras-kit's session and for ViserUrdf.update_cfg on the same robot (issue 25: Talos < 20 ms p95);
3. file save -> model shown again (rebuilt in one connected session): the tutorial arm as URDF
   and as xacro (expanded in the sandbox), and Talos (a 30+-link mesh robot from
   example-robot-data).

    python benchmarks/view_latency.py           # everything
    python benchmarks/view_latency.py --talos   # the two Talos targets only, alternating runs

The machine's load changes these figures a lot (chromium draws on the CPU): run when it is quiet,
and read the ``uptime`` line printed first.
"""

from __future__ import annotations

import math
import shutil
import site
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

CHROMIUM_ARGS = ["--no-sandbox", "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]


def _talos(name: str = "talos_reduced.urdf") -> tuple[Path, str] | None:
    for base in map(Path, site.getsitepackages()):
        share = base / "cmeel.prefix" / "share"
        path = share / "example-robot-data" / "robots" / "talos_data" / "robots" / name
        if path.exists():
            return path, str(share)
    return None


def _percentiles(samples: list[float]) -> str:
    ordered = sorted(samples)
    return f"median {statistics.median(ordered):6.2f} ms, p95 {ordered[int(0.95 * len(ordered))]:6.2f} ms"


def _free_port() -> int:
    import socket

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _scene(png: bytes) -> np.ndarray:
    """The 3D view left of the panel, without viser's "Software WebGL rendering detected" notice
    at its top left (its orange bar and dark title would count as the robot)."""
    from io import BytesIO

    from PIL import Image

    image = np.asarray(Image.open(BytesIO(png)).convert("RGB"))[:700, :590].astype(int)
    image[:200, :330] = 255
    return image


def _orange_pixels(page) -> int:  # type: ignore[no-untyped-def]
    """How many pixels of the forearm's orange the 3D view shows (as tests/view/test_view.py counts)."""


    image = _scene(page.screenshot())
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    return int(((r > 120) & (r - b > 100) & (g > 0.35 * r) & (g < 0.7 * r)).sum())


def _dark(image: np.ndarray) -> int:
    """How many pixels of the 3D view are dark grey: Talos's meshes (0.2 0.2 0.2 and darker,
    shaded) and not the white background, the grey grid, the names or the orange notice."""
    return int(((image[..., 0] < 90) & (image[..., 1] < 90) & (image[..., 2] < 90)).sum())


TALOS_DRAWN = 2500  # dark pixels once drawn (bras-kit about 17,000, ViserUrdf about 3,900); before, about 400


def talos_first_frame(path: Path, package_root: str, runs: int = 5) -> dict[str, list[float]]:
    """Seconds from starting each server (``bras-kit view FILE``, a ViserUrdf script) to the first
    frame chromium drew with Talos's meshes in it; runs alternate so both see the same machine
    load. Frames are streamed with the DevTools screencast, which stamps each with the time the
    compositor drew it. A screenshot would have to wait for the page's main thread, which can
    stay busy a second after the robot is on screen (viser decoding its default environment
    image): polled screenshots read bras-kit's first frame about 1 s late."""
    import base64
    import subprocess
    import sys

    from _process import bras_kit_command, environment
    from playwright.sync_api import sync_playwright

    from bras_kit.model.authoring import load
    from bras_kit.view import view_model
    from bras_kit.view.framing import place_camera

    # the peer's camera starts where bras-kit's does (viser's default sees Talos a few pixels
    # tall): both pictures then hold the same robot at the same size
    camera = place_camera(view_model(load(str(path), package_paths=(package_root,)), (package_root,)).box_points())
    placement = ",".join(f"{v:.6g}" for v in (*camera.position, *camera.look_at, camera.fov))
    commands = {
        "bras-kit view": [*bras_kit_command(), "view", str(path), "--package-path", package_root, "--no-browser"],
        "ViserUrdf": [sys.executable, __file__, "--serve-peer", str(path), package_root, placement],
    }
    times: dict[str, list[float]] = {label: [] for label in commands}
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS)
        for _ in range(runs):
            for label, command in commands.items():
                port = _free_port()
                start = time.time()  # the screencast's stamps are wall-clock seconds
                process = subprocess.Popen([*command, "--port", str(port)], stdout=subprocess.PIPE,
                                           stderr=subprocess.DEVNULL, text=True, env=environment())
                try:
                    assert process.stdout is not None
                    while "http" not in process.stdout.readline():  # the URL line: the server listens
                        pass
                    page = browser.new_page(viewport={"width": 1000, "height": 700})
                    devtools = page.context.new_cdp_session(page)
                    frames: list[tuple[float, str]] = []

                    def keep(event: dict, frames: list = frames, devtools=devtools) -> None:  # type: ignore[type-arg,no-untyped-def]
                        frames.append((event["metadata"]["timestamp"], event["data"]))
                        devtools.send("Page.screencastFrameAck", {"sessionId": event["sessionId"]})

                    devtools.on("Page.screencastFrame", keep)
                    devtools.send("Page.startScreencast", {"format": "jpeg", "quality": 80})
                    page.goto(f"http://127.0.0.1:{port}")
                    drawn = None
                    while drawn is None and time.time() - start < 300:
                        page.wait_for_timeout(50)  # lets the screencast's events in
                        while frames and drawn is None:
                            stamp, data = frames.pop(0)
                            if _dark(_scene(base64.b64decode(data))) >= TALOS_DRAWN:
                                drawn = stamp - start
                    times[label].append(drawn if drawn is not None else math.inf)
                    devtools.send("Page.stopScreencast")
                    page.close()
                finally:
                    process.terminate()
                    process.wait(20)
        browser.close()
    return times


def serve_peer(path: str, package_root: str, placement: str, port: int) -> None:
    """The peer's server: what a viser user writes to show a URDF (yourdfpy + ViserUrdf), on
    127.0.0.1, printing its URL once the robot is in the scene."""
    import viser
    import yourdfpy
    from viser.extras import ViserUrdf

    def handler(fname: str) -> str:
        return fname.replace("package://", package_root + "/")

    model = yourdfpy.URDF.load(path, filename_handler=handler, build_scene_graph=True, load_meshes=True)
    server = viser.ViserServer(host="127.0.0.1", port=port, verbose=False)
    x, y, z, ax, ay, az, fov = (float(v) for v in placement.split(","))
    server.initial_camera.fov = fov
    server.initial_camera.position = (x, y, z)
    server.initial_camera.look_at = (ax, ay, az)
    ViserUrdf(server, model)
    print(f"ViserUrdf: http://127.0.0.1:{port}", flush=True)
    while True:
        time.sleep(1)


def first_frame(runs: int = 3) -> tuple[float, float]:
    """Median seconds from running ``bras-kit view`` to the URL printed, and to the forearm drawn."""
    import subprocess
    import sys

    from playwright.sync_api import sync_playwright

    to_url, to_frame = [], []
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS)
        for _ in range(runs):
            port = _free_port()
            start = time.perf_counter()
            process = subprocess.Popen([sys.executable, "-m", "bras_kit", "view", "--no-browser", "--port", str(port)],
                                       stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
            try:
                assert process.stdout is not None
                url = process.stdout.readline().split()[2]
                to_url.append(time.perf_counter() - start)
                page = browser.new_page(viewport={"width": 1000, "height": 700})
                page.goto(url)
                while _orange_pixels(page) < 200 and time.perf_counter() - start < 120:
                    time.sleep(0.02)
                to_frame.append(time.perf_counter() - start)
                page.close()
            finally:
                process.terminate()
                process.wait(20)
        browser.close()
    return statistics.median(to_url), statistics.median(to_frame)


class _FakeClient:
    """Enough of a viser client for a Session: the server's own scene and GUI (no browser)."""

    def __init__(self, server) -> None:  # type: ignore[no-untyped-def]
        self.scene, self.gui, self.client_id = server.scene, server.gui, 0
        self.atomic = server.atomic
        self.camera = _NoCamera()


class _NoCamera:
    """A browser that has not said its canvas size yet: the camera is left where it starts."""

    def on_update(self, _callback) -> None:  # type: ignore[no-untyped-def]
        pass


def slider_latency(path: Path | None, package_root: str | None, changes: int = 200) -> tuple[list[float], list[float]]:
    import viser
    import yourdfpy
    from viser.extras import ViserUrdf

    from bras_kit.model.authoring import arm, load
    from bras_kit.view import Source, Viewer
    from bras_kit.view.session import Session

    robot = arm() if path is None else load(str(path), package_paths=(package_root,) if package_root else ())
    source = Source(robot=robot, package_paths=(package_root,) if package_root else ())
    ours, theirs = [], []
    rng = np.random.default_rng(0)
    with Viewer(source, port=_free_port(), watch=False) as viewer:
        session = Session(_FakeClient(viewer.server), viewer, viewer.lang)
        sliders = viewer.model.sliders
        for _ in range(changes):
            slider = sliders[rng.integers(len(sliders))]
            start = time.perf_counter()
            session.values[slider.joint] = float(rng.uniform(slider.lower, slider.upper))
            session.update()
            ours.append(1000 * (time.perf_counter() - start))
    urdf_text = robot.source_text if hasattr(robot, "source_text") else None
    with tempfile.TemporaryDirectory() as folder:
        file = Path(folder) / "robot.urdf"
        if path is None:
            import subprocess
            import sys

            file.write_bytes(subprocess.run([sys.executable, "-m", "bras_kit", "urdf"], capture_output=True).stdout)
        else:
            file = path
        def handler(fname: str) -> str:
            return fname.replace("package://", package_root + "/") if package_root else fname

        model = yourdfpy.URDF.load(str(file), filename_handler=handler, build_scene_graph=True, load_meshes=True)
        from bras_kit.view.viewer import quiet

        with quiet():
            server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
        try:
            peer = ViserUrdf(server, model)
            joints = model.actuated_joint_names
            for _ in range(changes):
                cfg = np.array([rng.uniform(-1, 1) for _ in joints])
                start = time.perf_counter()
                peer.update_cfg(cfg)
                theirs.append(1000 * (time.perf_counter() - start))
        finally:
            with quiet():
                server.stop()
    del urdf_text
    return ours, theirs


def reload_time(path: Path, package_root: str | None, runs: int = 5) -> float:
    from bras_kit.view import Source, Viewer

    with tempfile.TemporaryDirectory() as folder:
        copy = Path(folder) / path.name
        shutil.copy(path, copy)
        source = Source(path=str(copy), package_paths=(package_root,) if package_root else ())
        with Viewer(source, port=_free_port()) as viewer:
            from bras_kit.view.session import Session

            # one connected panel and scene to rebuild, as with one browser open
            viewer.sessions[0] = Session(_FakeClient(viewer.server), viewer, viewer.lang)
            times = []
            for k in range(runs):
                before = viewer.reloads
                time.sleep(0.3)
                start = time.perf_counter()
                copy.write_text(copy.read_text() + f"\n<!-- edit {k} -->\n")
                while viewer.reloads == before and time.perf_counter() - start < 60:
                    time.sleep(0.005)
                times.append(time.perf_counter() - start)
    return statistics.median(times)


def reload_in_browser(runs: int = 5) -> float:
    """Median seconds from saving the tutorial arm with one more joint to its slider in chromium."""
    import subprocess
    import sys

    from playwright.sync_api import sync_playwright

    from bras_kit.view import Source, Viewer

    with tempfile.TemporaryDirectory() as folder, sync_playwright() as playwright:
        path = Path(folder) / "bras.urdf"
        text = subprocess.run([sys.executable, "-m", "bras_kit", "urdf"], capture_output=True, text=True).stdout
        path.write_text(text)
        browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS)
        times = []
        with Viewer(Source(path=str(path)), port=_free_port()) as viewer:
            page = browser.new_page(viewport={"width": 1000, "height": 700})
            page.goto(viewer.url)
            page.wait_for_selector("text=coude", timeout=60_000)
            for k in range(runs):
                joint = f"essai_{k}"
                extra = (f'<link name="l{k}"/><joint name="{joint}" type="revolute"><parent link="avant_bras"/>'
                         f'<child link="l{k}"/><axis xyz="0 1 0"/>'
                         '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
                time.sleep(0.3)
                start = time.perf_counter()
                path.write_text(text.replace("</robot>", extra))
                page.get_by_text(joint, exact=True).wait_for(timeout=30_000)
                times.append(time.perf_counter() - start)
        browser.close()
    return statistics.median(times)


def talos_targets() -> None:
    """Issue 25's two viewer targets on talos_full_v2, bras-kit and ViserUrdf in the same run."""
    import os

    found = _talos("talos_full_v2.urdf")
    if found is None:
        print("example-robot-data is not installed: pip install example-robot-data")
        return
    print(f"load: {' '.join(f'{v:.2f}' for v in os.getloadavg())} (1, 5, 15 min) on {os.cpu_count()} cores")
    print("talos_full_v2: start -> meshes drawn in chromium (5 runs each, alternating)")
    for label, runs in talos_first_frame(*found).items():
        print(f"  {label:14s} median {statistics.median(runs):6.2f} s  best {min(runs):6.2f} s  "
              f"({', '.join(f'{v:.2f}' for v in runs)})")
    ours, theirs = slider_latency(*found)
    print("talos_full_v2: slider change -> transforms sent (200 changes)")
    print(f"  bras-kit {_percentiles(ours)}   |   ViserUrdf {_percentiles(theirs)}")


def main() -> None:
    import subprocess
    import sys

    if "--serve-peer" in sys.argv:
        at = sys.argv.index("--serve-peer")
        serve_peer(*sys.argv[at + 1:at + 4], int(sys.argv[sys.argv.index("--port") + 1]))  # type: ignore[call-arg]
        return
    if "--talos" in sys.argv:
        talos_targets()
        return

    url, frame = first_frame()
    print(f"bras-kit view -> URL printed {url:.2f} s, -> first frame in chromium {frame:.2f} s (tutorial arm, median of 3)")
    talos = _talos()
    print("\nslider change -> transforms sent (200 changes)")
    ours, theirs = slider_latency(None, None)
    print(f"  tutorial arm   bras-kit {_percentiles(ours)}   |   ViserUrdf {_percentiles(theirs)}")
    if talos:
        ours, theirs = slider_latency(*talos)
        print(f"  talos_reduced  bras-kit {_percentiles(ours)}   |   ViserUrdf {_percentiles(theirs)}")
    print("\nfile save -> model shown again (median of 5, including the 0.25 s polling)")
    with tempfile.TemporaryDirectory() as folder:
        arm_file = Path(folder) / "bras.urdf"
        arm_file.write_bytes(subprocess.run([sys.executable, "-m", "bras_kit", "urdf"], capture_output=True).stdout)
        print(f"  tutorial arm   {reload_time(arm_file, None):.3f} s")
        from bras_kit.core.resources import robot_template

        xacro_file = Path(folder) / "bras.urdf.xacro"
        shutil.copy(robot_template(), xacro_file)  # a copy: expanded in the sandboxed child, as a learner's
        print(f"  tutorial xacro {reload_time(xacro_file, None):.3f} s")
    print(f"  tutorial arm, until the new joint's slider shows in chromium {reload_in_browser():.3f} s")
    if talos:
        print(f"  talos_reduced  {reload_time(*talos):.3f} s")
        from bras_kit.model.authoring import load
        from bras_kit.view import view_model

        model = view_model(load(str(talos[0]), package_paths=(talos[1],)), (talos[1],))
        print(f"  (talos_reduced: {len(model.tree.links)} links, {len(model.visuals)} visual meshes, "
              f"{sum(len(m.faces) for m in model.visuals):,} triangles)")
    print()
    talos_targets()


if __name__ == "__main__":
    main()
