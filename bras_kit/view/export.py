"""One self-contained HTML file that replays a motion in 3D with no server: viser's scene
serializer and its client, which ships inside the viser wheel (nothing is fetched online)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import backends
from ..model import Robot
from .model import view_model, wxyz
from .panel import label_offsets
from .session import ROOT, _nice
from .viewer import never_share, quiet


def export_html(robot: Robot, states: Any, *, package_paths: tuple[str, ...] = (),
                frames: bool = True, names: bool = True) -> str:
    """The HTML page replaying ``states`` (a :class:`~bras_kit.motion.JointStates`) on ``robot``."""
    viser = backends.viser()

    model = view_model(robot, package_paths)
    times = np.asarray(states.times, dtype=float)
    positions = np.asarray(states.positions, dtype=float)
    names_in_states = list(states.names)
    with quiet():
        server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
    never_share(server)
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
                labels.append(scene.add_label(f"{ROOT}/link{index}/name", link, font_screen_scale=0.8,
                                              anchor="bottom-left"))
        shifts: dict[int, tuple[float, ...]] = {}
        for k, mesh in enumerate(model.visuals):
            scene.add_mesh_simple(f"{ROOT}/link{mesh.link}/visual{k}", mesh.vertices.astype(np.float32),
                                  mesh.faces.astype(np.uint32), color=mesh.color,
                                  opacity=None if mesh.opacity >= 1.0 else mesh.opacity)

        def place(row: np.ndarray) -> None:
            poses = model.poses(dict(zip(names_in_states, row)))
            for frame, pose in zip(handles, poses):
                frame.position = pose[:3, 3]
                frame.wxyz = wxyz(pose[:3, :3])
            # names of frames at one place stacked, as in the live viewer (sent only when they move)
            for k, (label, offset) in enumerate(zip(labels, label_offsets(poses, 0.045 * model.scale))):
                local = tuple(float(v) for v in poses[k][:3, :3].T @ offset)
                if shifts.get(k, (0.0, 0.0, 0.0)) != local:
                    label.position = local
                    shifts[k] = local

        place(positions[0] if len(positions) else np.zeros(0))
        _frame_camera(server, model, names_in_states, positions)
        serializer = server.get_scene_serializer()
        for k in range(1, len(times)):
            serializer.insert_sleep(float(times[k] - times[k - 1]))
            place(positions[k])
        if len(times) > 1:
            serializer.insert_sleep(float(times[1] - times[0]))
        return serializer.as_html()
    finally:
        with quiet():
            server.stop()


PLAYER_PIXELS = 48  # the exported page's play bar along the bottom


def _frame_camera(server: Any, model: Any, names: list[str], positions: np.ndarray) -> None:
    """The page's camera on the box the robot sweeps over the whole motion, tight (the page has
    no panel: only the play bar at the bottom)."""
    from .framing import place_camera

    rows = positions[:: max(1, len(positions) // 24)] if len(positions) else [np.zeros(0)]
    points = np.vstack([model.box_points(dict(zip(names, row))) for row in rows])
    placement = place_camera(points, panel=0, bottom=PLAYER_PIXELS, margin=1.05)
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
