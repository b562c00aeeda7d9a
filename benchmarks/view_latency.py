"""How fast is bras-kit view? Side by side with viser's own URDF loader (ViserUrdf + yourdfpy),
the peer a viser user would reach for.

1. start -> first frame: from creating the viewer to the orange forearm drawn in headless
   chromium (WebGL on the CPU);
2. slider change -> link transforms sent: median and 95th percentile over 200 changes, for
   bras-kit's session and for ViserUrdf.update_cfg on the same robot;
3. file save -> model shown again: the tutorial arm, and Talos (a 30+-link mesh robot from
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
            return path, str(share / "example-robot-data" / "robots")
    return None


def _percentiles(samples: list[float]) -> str:
    ordered = sorted(samples)
    return f"median {statistics.median(ordered):6.2f} ms, p95 {ordered[int(0.95 * len(ordered))]:6.2f} ms"


def first_frame() -> float:
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from playwright.sync_api import sync_playwright
    from test_view import _free_port, _orange, _wait

    from bras_kit.authoring import arm
    from bras_kit.view import Source, Viewer

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS)
        start = time.perf_counter()
        with Viewer(Source(robot=arm()), port=_free_port()) as viewer:
            page = browser.new_page(viewport={"width": 1000, "height": 700})
            page.goto(viewer.url)
            _wait(lambda: len(_orange(page)) > 200, 60)
            elapsed = time.perf_counter() - start
        browser.close()
    return elapsed


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
    with Viewer(source, port=0 or 8790, watch=False) as viewer:
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
        server = viser.ViserServer(host="127.0.0.1", port=8792, verbose=False)
        try:
            peer = ViserUrdf(server, model)
            joints = model.actuated_joint_names
            for _ in range(changes):
                cfg = np.array([rng.uniform(-1, 1) for _ in joints])
                start = time.perf_counter()
                peer.update_cfg(cfg)
                theirs.append(1000 * (time.perf_counter() - start))
        finally:
            server.stop()
    del urdf_text
    return ours, theirs


def reload_time(path: Path, package_root: str | None, runs: int = 5) -> float:
    from bras_kit.view import Source, Viewer

    with tempfile.TemporaryDirectory() as folder:
        copy = Path(folder) / path.name
        shutil.copy(path, copy)
        source = Source(path=str(copy), package_paths=(package_root,) if package_root else ())
        with Viewer(source, port=8793) as viewer:
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


def main() -> None:
    import subprocess
    import sys

    print(f"start -> first frame in chromium (tutorial arm): {first_frame():.2f} s")
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
    if talos:
        print(f"  talos_reduced  {reload_time(*talos):.3f} s")


if __name__ == "__main__":
    main()
