"""One browser's view: its own copy of the arm in the scene and its own panel, like RViz and
joint_state_publisher_gui side by side. Every connected browser gets a Session; a classroom
projector and a laptop move their arms independently."""

from __future__ import annotations

import html
import math
import random
import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from .model import ViewModel, wxyz

ROOT = "/bras"


class Session:
    """The scene nodes and GUI of one client, rebuilt when the model changes."""

    def __init__(self, client: Any, viewer: Any, translate: Callable[[str], str]) -> None:
        self.client = client
        self.viewer = viewer
        self.t = translate
        self.values: dict[str, float] = {}
        self.fixed_frame = 0
        self.playing = False
        self.play_time = 0.0
        self.speed = 1.0
        self.last_update_ms = 0.0
        self._lock = threading.RLock()
        self._frames: list[Any] = []
        self._labels: list[Any] = []
        self._visual_nodes: list[Any] = []
        self._collision_nodes: list[Any] = []
        self._sliders: dict[str, Any] = {}
        self._model_gui: list[Any] = []
        self._setting = False  # values being set from code: slider callbacks do nothing
        self._build_panel()
        self.show_model(viewer.model)

    # -- the panel that does not depend on the model ------------------------------------------
    def _build_panel(self) -> None:
        gui, t = self.client.gui, self.t
        self.status = gui.add_html("", order=0)
        with gui.add_folder(t("Display"), order=1):
            self.show_visual = gui.add_checkbox(t("Visual geometry"), True)
            self.show_collision = gui.add_checkbox(t("Collision geometry"), False)
            self.show_frames = gui.add_checkbox(t("TF frames (axes)"), True)
            self.show_names = gui.add_checkbox(t("Frame names"), True)
            self.show_grid = gui.add_checkbox(t("Grid"), True)
            self.fixed = gui.add_dropdown(t("Fixed Frame"), ("-",), initial_value="-")
        for handle in (self.show_visual, self.show_collision, self.show_frames, self.show_names, self.show_grid):
            handle.on_update(lambda _event: self._apply_visibility())
        self.fixed.on_update(lambda _event: self._choose_fixed_frame())
        with gui.add_folder(t("Joints"), order=2):
            self.joint_folder = gui.add_folder(t("Sliders"))
            buttons = gui.add_button_group("", (t("Zero"), t("Random pose")))
            buttons.on_click(lambda event: self._button(event.target.value))
        with gui.add_folder(t("Motion"), order=3):
            self.play = gui.add_checkbox(t("Play"), False, disabled=self.viewer.motion is None)
            self.speed_slider = gui.add_slider(t("Speed"), 0.1, 3.0, 0.1, 1.0,
                                               disabled=self.viewer.motion is None)
            self.motion_text = gui.add_html("")
        self.play.on_update(lambda _event: self._toggle_play())
        self.speed_slider.on_update(lambda _event: setattr(self, "speed", float(self.speed_slider.value)))
        with gui.add_folder(t("Readouts"), order=4):
            self.readout = gui.add_html("")
        with gui.add_folder(t("Checks"), order=5):
            self.findings = gui.add_html("")
        if self.viewer.motion is not None:
            self.motion_text.content = f"<small>{html.escape(self.viewer.motion.label or '')}</small>"

    # -- the model ---------------------------------------------------------------------------
    def show_model(self, model: ViewModel) -> None:
        """Draw ``model``; keep the joint values whose joints still exist."""
        with self._lock, self.client.atomic():
            for handle in self._frames:  # its label and meshes are its children: they go with it
                handle.remove()
            for handle in self._model_gui:
                handle.remove()
            self._frames, self._labels, self._visual_nodes, self._collision_nodes = [], [], [], []
            self._sliders, self._model_gui = {}, []
            scene, t = self.client.scene, self.t
            self.model = model
            names = [s.joint for s in model.sliders]
            self.values = {name: self.values.get(name, 0.0) for name in names}
            length = 0.12 * model.scale
            self.grid = scene.add_grid(f"{ROOT}/grid", width=4 * model.scale, height=4 * model.scale,
                                       cell_size=_nice(model.scale / 5), section_size=_nice(model.scale))
            self._model_gui.append(self.grid)
            for index, link in enumerate(model.tree.links):
                frame = scene.add_frame(f"{ROOT}/link{index}", axes_length=length, axes_radius=length / 22,
                                        origin_radius=length / 10)
                self._frames.append(frame)
                self._labels.append(scene.add_label(f"{ROOT}/link{index}/name", link, font_screen_scale=0.8,
                                                    anchor="bottom-left"))
            for k, mesh in enumerate(model.visuals):
                self._visual_nodes.append(scene.add_mesh_simple(
                    f"{ROOT}/link{mesh.link}/visual{k}", mesh.vertices.astype(np.float32),
                    mesh.faces.astype(np.uint32), color=mesh.color,
                    opacity=None if mesh.opacity >= 1.0 else mesh.opacity))
            for k, mesh in enumerate(model.collisions):
                self._collision_nodes.append(scene.add_mesh_simple(
                    f"{ROOT}/link{mesh.link}/collision{k}", mesh.vertices.astype(np.float32),
                    mesh.faces.astype(np.uint32), color=mesh.color, opacity=mesh.opacity, visible=False))
            choices = tuple(model.tree.links)
            self.fixed.options = choices
            self.fixed_frame = min(self.fixed_frame, len(choices) - 1)
            self.fixed.value = choices[self.fixed_frame]
            with self.joint_folder:
                for slider in model.sliders:
                    handle = self.client.gui.add_slider(
                        slider.joint, slider.lower, slider.upper, _step(slider), _clip(self.values[slider.joint], slider),
                        hint=f"{slider.lower:g} .. {slider.upper:g} {slider.unit}")
                    handle.on_update(lambda _event, name=slider.joint, h=handle: self._slider_moved(name, h))
                    self._sliders[slider.joint] = handle
                    self._model_gui.append(handle)
                if not model.sliders:
                    self._model_gui.append(self.client.gui.add_markdown(t("This robot has no movable joint.")))
            self._apply_visibility()
            self.update()
        self.show_checks()

    def show_checks(self) -> None:
        """The validator's findings, and the error that keeps the last good model on screen."""
        viewer, t = self.viewer, self.t
        rows = []
        if viewer.error:
            rows.append(f"<p style='color:#c62828'><b>{html.escape(t('The file cannot be read'))}</b>: "
                        f"{html.escape(viewer.error)}<br><i>{html.escape(t('the last good model stays on screen'))}</i></p>")
        for finding in viewer.findings:
            colour = {"error": "#c62828", "warning": "#e65100"}.get(finding.severity, "#455a64")
            line = f":{finding.line}" if finding.line else ""
            rows.append(f"<p style='margin:2px 0'><b style='color:{colour}'>{finding.code}</b>{line} "
                        f"{html.escape(finding.text(viewer.lang))}</p>")
        if not rows:
            rows.append(f"<p style='color:#2e7d32'>{html.escape(t('No finding'))}</p>")
        self.findings.content = "".join(rows)
        source = viewer.source_label
        stamp = time.strftime("%H:%M:%S", time.localtime(viewer.loaded_at))
        self.status.content = (f"<small><b>{html.escape(viewer.model.robot.name or 'robot')}</b> · "
                               f"{html.escape(source)} · {html.escape(t('loaded at'))} {stamp}</small>")

    # -- moving the arm ----------------------------------------------------------------------
    def update(self) -> None:
        """Send the link poses for the current values, and the readouts."""
        start = time.perf_counter()
        model = self.model
        poses = model.poses(self.values, self.fixed_frame)
        with self.client.atomic():
            for frame, pose in zip(self._frames, poses):
                frame.position = pose[:3, 3]
                frame.wxyz = wxyz(pose[:3, :3])
        self.last_update_ms = 1000 * (time.perf_counter() - start)
        self._readouts(poses)

    def _readouts(self, poses: np.ndarray) -> None:
        t, model = self.t, self.model
        outside = model.out_of_limits(self.values)
        tip = model.tip(poses)
        rows = [f"<p style='margin:2px 0'><b>{html.escape(t('Tip'))}</b> ({html.escape(model.tree.links[model.tip_link])}): "
                f"x={tip[0]:.3f} y={tip[1]:.3f} z={tip[2]:.3f} m</p>"]
        for slider in model.sliders:
            value = self.values.get(slider.joint, 0.0)
            style = "margin:2px 0" + (";color:#c62828;font-weight:bold" if slider.joint in outside else "")
            degrees = f" ({math.degrees(value):.1f}°)" if slider.unit == "rad" else ""
            mark = f" — {html.escape(t('out of limits'))}" if slider.joint in outside else ""
            rows.append(f"<p style='{style}' data-joint='{html.escape(slider.joint)}'>"
                        f"{html.escape(slider.joint)} = {value:.3f} {slider.unit}{degrees}{mark}</p>")
        for follower, value in zip(model.followers, model.follower_values(self.values).values()):
            style = "margin:2px 0" + (";color:#c62828;font-weight:bold" if follower.joint in outside else "")
            degrees = f" ({math.degrees(value):.1f}°)" if follower.unit == "rad" else ""
            mark = f" — {html.escape(t('out of limits'))}" if follower.joint in outside else ""
            follows = html.escape(t("follows {joint}").format(joint=follower.leader))
            rows.append(f"<p style='{style}' data-joint='{html.escape(follower.joint)}'>"
                        f"{html.escape(follower.joint)} = {value:.3f} {follower.unit}{degrees} <i>({follows})</i>"
                        f"{mark}</p>")
        self.readout.content = "".join(rows)

    def set_values(self, values: dict[str, float]) -> None:
        with self._lock:
            self.values.update({k: float(v) for k, v in values.items() if k in self.values})
            self._setting = True
            try:
                for name, handle in self._sliders.items():
                    slider = next(s for s in self.model.sliders if s.joint == name)
                    handle.value = _clip(self.values[name], slider)
            finally:
                self._setting = False
            self.update()

    def _slider_moved(self, name: str, handle: Any) -> None:
        if self._setting:
            return
        with self._lock:
            self.values[name] = float(handle.value)
            self.update()

    def _button(self, label: str) -> None:
        if label == self.t("Zero"):
            self.set_values(dict.fromkeys(self.values, 0.0))
        else:
            self.set_values({s.joint: random.uniform(s.lower, s.upper) for s in self.model.sliders})

    def _toggle_play(self) -> None:
        self.playing = bool(self.play.value)
        for handle in self._sliders.values():
            handle.disabled = self.playing

    def advance(self, seconds: float) -> None:
        """Playback: move the motion on by ``seconds`` of wall time (times the speed)."""
        motion = self.viewer.motion
        if motion is None or not self.playing:
            return
        self.play_time += seconds * self.speed
        period = motion.duration or self.viewer.loop_seconds
        when = self.play_time % period if period else self.play_time
        positions = motion.positions(np.array([when]))[0]
        self.set_values(dict(zip(motion.names, (float(v) for v in positions))))
        self.motion_text.content = f"<small>{html.escape(motion.label or '')} · t = {when:.2f} s</small>"

    # -- display toggles ---------------------------------------------------------------------
    def _apply_visibility(self) -> None:
        with self.client.atomic():
            for node in self._visual_nodes:
                node.visible = bool(self.show_visual.value)
            for node in self._collision_nodes:
                node.visible = bool(self.show_collision.value)
            for frame in self._frames:
                frame.show_axes = bool(self.show_frames.value)
            for label in self._labels:
                label.visible = bool(self.show_names.value)
            self.grid.visible = bool(self.show_grid.value)

    def _choose_fixed_frame(self) -> None:
        links = list(self.model.tree.links)
        if self.fixed.value in links:
            self.fixed_frame = links.index(self.fixed.value)
            self.update()


def _step(slider: Any) -> float:
    return max((slider.upper - slider.lower) / 1000, 1e-4)


def _clip(value: float, slider: Any) -> float:
    return min(max(value, slider.lower), slider.upper)


def _nice(length: float) -> float:
    """A round grid step near ``length``: 1, 2 or 5 times a power of ten."""
    power = 10 ** math.floor(math.log10(max(length, 1e-6)))
    return min((m * power for m in (1, 2, 5, 10)), key=lambda v: abs(v - length))
