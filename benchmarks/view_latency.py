"""How fast is bras-kit view? Side by side with viser's own URDF loader (ViserUrdf + yourdfpy),
the peer a viser user would reach for.

1. start -> first frame: from running ``bras-kit view`` to the orange forearm drawn in headless
   chromium (WebGL on the CPU);
2. slider change -> link transforms sent: median and 95th percentile over 200 changes, for
   bras-kit's session and for ViserUrdf.update_cfg on the same robot;
3. file save -> model shown again (rebuilt in one connected session): the tutorial arm as URDF
   and as xacro (expanded in the sandbox), and Talos (a 30+-link mesh robot from
   example-robot-data).

    python benchmarks/view_latency.py
"""

from __future__ import annotations

import shutil
import site
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

CHROMIUM_ARGS = ["--no-sandbox", "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]


def _talos() -> tuple[Path, str] | None:
    for base in map(Path, site.getsitepackages()):
        share = base / "cmeel.prefix" / "share"
        path = share / "example-robot-data" / "robots" / "talos_data" / "robots" / "talos_reduced.urdf"
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


def _orange_pixels(page) -> int:  # type: ignore[no-untyped-def]
    """How many pixels of the forearm's orange the 3D view shows (as tests/test_view.py counts)."""
    from io import BytesIO

    from PIL import Image

    image = np.asarray(Image.open(BytesIO(page.screenshot())).convert("RGB"))[:700, :590].astype(int)
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    return int(((r > 120) & (r - b > 100) & (g > 0.35 * r) & (g < 0.7 * r)).sum())


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


def slider_latency(path: Path | None, package_root: str | None, changes: int = 200) -> tuple[list[float], list[float]]:
    import viser
    import yourdfpy
    from viser.extras import ViserUrdf

    from bras_kit.authoring import arm, load
    from bras_kit.view import Source, Viewer
    from bras_kit.view.session import Session

    robot = arm() if path is None else load(str(path), package_paths=(package_root,) if package_root else ())
    source = Source(robot=robot, package_paths=(package_root,) if package_root else ())
    ours, theirs = [], []
    rng = np.random.default_rng(0)
    with Viewer(source, port=_free_port(), watch=False) as viewer:
        session = Session(_FakeClient(viewer.server), viewer, viewer.t)
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
            viewer.sessions[0] = Session(_FakeClient(viewer.server), viewer, viewer.t)
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


def main() -> None:
    import subprocess
    import sys

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
        from bras_kit._resources import robot_template

        xacro_file = Path(folder) / "bras.urdf.xacro"
        shutil.copy(robot_template(), xacro_file)  # a copy: expanded in the sandboxed child, as a learner's
        print(f"  tutorial xacro {reload_time(xacro_file, None):.3f} s")
    print(f"  tutorial arm, until the new joint's slider shows in chromium {reload_in_browser():.3f} s")
    if talos:
        print(f"  talos_reduced  {reload_time(*talos):.3f} s")
        from bras_kit.authoring import load
        from bras_kit.view import view_model

        model = view_model(load(str(talos[0]), package_paths=(talos[1],)), (talos[1],))
        print(f"  (talos_reduced: {len(model.tree.links)} links, {len(model.visuals)} visual meshes, "
              f"{sum(len(m.faces) for m in model.visuals):,} triangles)")


if __name__ == "__main__":
    main()
