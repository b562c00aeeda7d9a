"""One self-contained HTML file that replays a motion in 3D with no server: viser's scene
serializer and its client, which ships inside the viser wheel (nothing is fetched online)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core import backends
from ..model.robot import Robot
from .model import view_model, wxyz
from .origin import refuse_other_origins
from .panel import label_name, label_places
from .session import ROOT, _nice, client_words_script
from .viewer import never_share, quiet


def export_html(robot: Robot, states: Any, *, package_paths: tuple[str, ...] = (),
                frames: bool = True, names: bool = True, lang: str = "en", title: str | None = None) -> str:
    """The HTML page replaying ``states`` (a :class:`~bras_kit.motion.JointStates`) on ``robot``,
    titled ``title`` (default: the robot's name), viser's own words in ``lang``."""
    viser = backends.viser()

    model = view_model(robot, package_paths)
    times = np.asarray(states.times, dtype=float)
    positions = np.asarray(states.positions, dtype=float)
    names_in_states = list(states.names)
    with quiet():
        server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
    never_share(server)
    refuse_other_origins(server)  # alive while the scene is recorded: no other page may read it
    try:
        scene = server.scene
        length = 0.12 * model.scale
        scene.add_grid(f"{ROOT}/grid", width=4 * model.scale, height=4 * model.scale,
                       cell_size=_nice(model.scale / 5), section_size=_nice(model.scale))
        handles, labels = [], []
        for index, link in enumerate(model.tree.links):
            handles.append(scene.add_frame(f"{ROOT}/link{index}", axes_length=length, axes_radius=length / 22,
                                           origin_radius=length / 10, show_axes=frames))
            if names:
                labels.append(scene.add_label(label_name(index), link, font_screen_scale=0.8,
                                              anchor="bottom-left"))
        sent: dict[int, tuple[float, ...]] = {}
        for k, mesh in enumerate(model.visuals):
            scene.add_mesh_simple(f"{ROOT}/link{mesh.link}/visual{k}", mesh.vertices.astype(np.float32),
                                  mesh.faces.astype(np.uint32), color=mesh.color,
                                  opacity=None if mesh.opacity >= 1.0 else mesh.opacity)

        def place(row: np.ndarray) -> None:
            poses = model.poses(dict(zip(names_in_states, row)))
            for frame, pose in zip(handles, poses):
                frame.position = pose[:3, 3]
                frame.wxyz = wxyz(pose[:3, :3])
            # each name placed in the scene with its frame, in the same step (see label_name)
            for k, (label, place) in enumerate(zip(labels, label_places(poses, model.scale))):
                position = tuple(float(v) for v in place)
                if sent.get(k) != position:
                    label.position = position
                    sent[k] = position

        place(positions[0] if len(positions) else np.zeros(0))
        _frame_camera(server, model, names_in_states, positions)
        serializer = server.get_scene_serializer()
        for k in range(1, len(times)):
            serializer.insert_sleep(float(times[k] - times[k - 1]))
            place(positions[k])
        if len(times) > 1:
            serializer.insert_sleep(float(times[1] - times[0]))
        return _localized(serializer.as_html(), lang, title or f"{robot.name or 'robot'} · bras-kit")
    finally:
        with quiet():
            server.stop()


def _localized(page: str, lang: str, title: str) -> str:
    """viser's page (its client's build/index.html: ``<html lang="en">``, ``<title>Viser</title>``)
    with the page's language, its title, and the script that words viser's client in ``lang``
    (the live page sends the same script through viser's RunJavascriptMessage; a file has no
    server, so it runs from the end of the body, where document.body exists)."""
    import html
    import re

    page = re.sub(r'<html lang="[^"]*"', f'<html lang="{html.escape(lang)}"', page, count=1)
    page = re.sub(r"<title>[^<]*</title>", f"<title>{html.escape(title)}</title>", page, count=1)
    script = client_words_script(lang)
    if script:
        end = page.rindex("</body>")
        # a "</" inside the words would end the script element early
        page = page[:end] + "<script>" + script.replace("</", "<\\/") + "</script>" + page[end:]
    return page


PLAYER_PIXELS = 48  # the exported page's play bar along the bottom


def page_camera(model: Any, names: list[str], positions: np.ndarray) -> Any:
    """The page's camera (a :class:`~bras_kit.view.framing.CameraPlacement`) on the box the robot
    sweeps over the whole motion, tight (the page has no panel: only the play bar at the bottom)."""
    from .framing import place_camera

    rows = positions[:: max(1, len(positions) // 24)] if len(positions) else [np.zeros(0)]
    points = np.vstack([model.box_points(dict(zip(names, row))) for row in rows])
    return place_camera(points, panel=0, bottom=PLAYER_PIXELS, margin=1.05)


def _frame_camera(server: Any, model: Any, names: list[str], positions: np.ndarray) -> None:
    placement = page_camera(model, names, positions)
    camera = server.initial_camera
    camera.fov = placement.fov
    camera.near = placement.near
    camera.far = placement.far
    camera.position = placement.position
    camera.look_at = placement.look_at


def _free_port() -> int:
    import socket

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])
