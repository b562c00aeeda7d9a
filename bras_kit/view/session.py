"""One browser's view: its own copy of the arm in the scene and its own panel, like RViz and
joint_state_publisher_gui side by side. Every connected browser gets a Session; a classroom
projector and a laptop move their arms independently."""

from __future__ import annotations

import html
import math
import random
import threading
import time
from typing import Any

import numpy as np

from ..core.i18n import say
from ..core.message import M, Message
from ..findings.report import element_text
from ..motion.sources import motion_title
from .model import ViewModel, wxyz
from .panel import (
    ERROR_RED,
    axes_legend,
    banner,
    echo_rows,
    joint_box_text,
    label_name,
    label_places,
    read_joint_box,
)

ROOT = "/bras"
# a launch without joint_state_publisher(_gui): no slider window, as in ROS (BK620 says why)
NO_SLIDER_WINDOW = M("No joint_state_publisher(_gui) is started: no sliders. The joints stay at 0 until a node "
                     "publishes /joint_states (bras-kit run in another terminal).")
GEOMETRIES = ("visual", "collision", "both")
# Past this many visual triangles (Talos has 206k), a browser drawing WebGL on the CPU
# (SwiftShader, a school laptop without a GPU driver) spends seconds a frame on the
# image-based lighting and the shadow maps: such robots are lit by plain lights instead, with
# no shadows, which looks nearly the same (issue 25: Talos's first frame in 3 s).
HEAVY_TRIANGLES = 50_000
# Past this many links (Talos has 60) the TF axes and the frame names start hidden: sixty of
# each bristle over a humanoid and hide it. The names are made only once the learner ticks
# "Frame names". A browser drawing on the CPU shows the robot sooner (Talos: their text atlas
# and shaders cost it about 0.75 s, the axes 0.3 s).
MANY_LINKS = 20
DEFAULT_HDRI = "city"  # the environment map viser's page shows when none is configured
# a slider's own number box (Mantine's, in the browser) reads "0,5" as 5 and knows no pi/2 nor
# 90deg: hidden; the joint's text box below its slider reads typed values with the CLI's parser
_HIDE_SLIDER_BOXES = "<style>.mantine-Slider-root + .mantine-NumberInput-root{display:none}</style>"

# viser's client (1.1.1) has its own words, in English: notices (client/src/BrowserWarning.tsx),
# tooltips and labels of its panels (client/src/dock/, ControlPanel/). In any other language a
# small script, sent through viser's own RunJavascriptMessage, rewords them where they appear
# (text, tooltip, title, aria-label, placeholder), without touching viser's client. Keys are
# viser's exact English; values the catalog's message.
_CLIENT_WORDS: dict[str, Message] = {
    "Software WebGL rendering detected": M("Software WebGL rendering detected"),
    "WebGL is running in software mode, not on your GPU. Performance may be degraded. If this is unexpected, "
    "check that hardware acceleration is enabled in your browser settings.": M(
        "WebGL runs in software, not on your graphics card: the page may be slower. If that is unexpected, "
        "check that hardware acceleration is on in your browser's settings."),
    "WebGL unavailable": M("WebGL unavailable"),
    "WebGL is unavailable. This may be caused by hardware acceleration being disabled \u2014 check your browser "
    "settings.": M("WebGL is unavailable: hardware acceleration may be off in your browser's settings."),
    "Connected": M("Connected"),
    "Minimize": M("Minimize"),
    "Expand": M("Expand"),
    "Collapse": M("Collapse"),
    "Minimize panel": M("Minimize the panel"),
    "Expand panel": M("Expand the panel"),
    "Minimize panels": M("Minimize the panels"),
    "Expand panels": M("Expand the panels"),
    "Collapse panel area": M("Fold the panel area"),
    "Collapse column": M("Fold the column"),
    "Expand column": M("Unfold the column"),
    "Disconnect": M("Disconnect"),
    "Server": M("Server"),
    "Server URL": M("Server address"),
    "Share": M("Share"),
    "Share (needs connection)": M("Share (needs a connection)"),
    "Dev Settings": M("Developer settings"),
    "Configuration & diagnostics": M("Settings and diagnostics"),
    "Orbit Origin Tool": M("Orbit centre tool"),
    "Scene tree": M("Scene tree"),
    "Playback speed": M("Playback speed"),
    "Adaptive": M("Adaptive"),
    "Dark Mode": M("Dark mode"),
    "WebGL Stats": M("WebGL statistics"),
    "Show Viser Logo": M("Show the Viser logo"),
    "Log Camera to Console": M("Log the camera to the console"),
    "Show Orbit Crosshair": M("Show the orbit crosshair"),
    "Device Pixel Ratio": M("Device pixel ratio"),
    "Discard any panel rearrangement and restore the layout the server set.": M(
        "Discard any change to the panels' layout and restore the one the page started with."),
    "Clear visibility override": M("Clear the visibility override"),
    "Toggle visibility override": M("Override the visibility"),
    "Expand image": M("Enlarge the image"),
    "Expand plot": M("Enlarge the plot"),
    "Contains unsubmitted changes.": M("Holds changes not sent yet."),
    "Return to GUI": M("Back to the panel"),
    "Open navigation": M("Open the navigation"),
    "Close navigation": M("Close the navigation"),
    "Close props": M("Close the properties"),
    "About Viser": M("About Viser"),
    "Auto-created anchor for client-local children": M("Anchor made for this browser's own nodes"),
    "Client-local: only this client sees this node": M("This browser's own: only it shows this node"),
}
# the same, where viser adds a name after them (``Edit props for /bras``)
_CLIENT_PREFIXES: dict[str, Message] = {
    "Edit props for ": M("Edit the properties of "),
    "Collapse panel ": M("Fold the panel "),
    "Expand panel ": M("Unfold the panel "),
}
_CLIENT_SCRIPT = """(() => {
  const words = %s, prefixes = %s;
  const word = (text) => {
    if (text == null) return null;
    const key = text.trim();
    if (Object.prototype.hasOwnProperty.call(words, key)) return text.replace(key, words[key]);
    for (const [english, local] of prefixes) if (text.startsWith(english)) return local + text.slice(english.length);
    return null;
  };
  const attributes = ["title", "aria-label", "placeholder"];
  const fix = (node) => {
    if (node.nodeType === 3) {
      const local = word(node.nodeValue);
      if (local !== null && local !== node.nodeValue) node.nodeValue = local;
      return;
    }
    if (node.nodeType !== 1) return;
    for (const name of attributes) {
      const local = word(node.getAttribute(name));
      if (local !== null && local !== node.getAttribute(name)) node.setAttribute(name, local);
    }
    for (const child of node.childNodes) fix(child);
  };
  fix(document.body);
  new MutationObserver((changes) => {
    for (const change of changes) {
      if (change.type === "childList") change.addedNodes.forEach(fix);
      else fix(change.target);
    }
  }).observe(document.body, {subtree: true, childList: true, characterData: true, attributes: true,
                             attributeFilter: attributes});
})();"""


def client_words_script(lang: str) -> str:
    """The script that words viser's own client in ``lang`` (empty in English)."""
    import json

    if lang == "en":
        return ""
    words = {english: say(message, lang) for english, message in _CLIENT_WORDS.items()}
    prefixes = [[english, say(message, lang)] for english, message in _CLIENT_PREFIXES.items()]
    return _CLIENT_SCRIPT % (json.dumps(words, ensure_ascii=False), json.dumps(prefixes, ensure_ascii=False))


def _canvas_size(camera: Any) -> tuple[int, int] | None:
    """The browser's canvas (width, height) in pixels, or None before it has said it (or while
    it is not laid out)."""
    try:
        width, height = int(camera.image_width), int(camera.image_height)
    except (AssertionError, AttributeError, TypeError, ValueError):  # no report yet
        return None
    return (width, height) if width >= 16 and height >= 16 else None



def _same_place(a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray]) -> bool:
    """Two cameras (position, look_at) at the same place, to a thousandth of their distance."""
    tolerance = 1e-3 * max(float(np.linalg.norm(a[0] - a[1])), 1e-6)
    return bool(np.allclose(a[0], b[0], atol=tolerance) and np.allclose(a[1], b[1], atol=tolerance))


def _camera_at(camera: Any, place: tuple[np.ndarray, np.ndarray]) -> bool:
    """Whether a browser's reported camera is at ``place`` (position, look_at)."""
    try:
        reported = (np.asarray(camera.position, float), np.asarray(camera.look_at, float))
    except (AssertionError, AttributeError, TypeError, ValueError):  # no report yet
        return False
    return _same_place(reported, place)

class Session:
    """The scene nodes and GUI of one client, rebuilt when the model changes."""

    def __init__(self, client: Any, viewer: Any, lang: str) -> None:
        self.client = client
        self.viewer = viewer
        self.lang = lang
        self.values: dict[str, float] = {}
        self.fixed_frame = 0
        self.fixed_name: str | None = getattr(viewer, "fixed_frame", None)  # chosen by name, kept across reloads
        self.playing = False
        self.play_time = 0.0
        self.speed = 1.0
        self.selected: str | None = None  # the link clicked last, its pose read out like tf2_echo
        self.last_update_ms = 0.0
        self._lock = threading.RLock()
        self._frames: list[Any] = []
        self._labels: list[Any] = []
        self._label_places: list[tuple[float, float, float]] = []
        self._visual_nodes: list[Any] = []
        self._collision_nodes: list[Any] = []
        self._sliders: dict[str, Any] = {}
        self._boxes: dict[str, Any] = {}
        self._box_notes: dict[str, str] = {}
        self._model_gui: list[Any] = []
        self._setting = False  # values being set from code: slider callbacks do nothing
        self._framed_for: tuple[int, int] | None = None  # the canvas size the camera was placed for
        self._placed: tuple[np.ndarray, np.ndarray] | None = None  # where it was put: position, look_at
        self._sent: np.ndarray | None = None  # the link poses the browser has, to send only changes
        self._plain_light: Any = None  # the ambient light of a heavy robot (None: viser's lighting)
        self.rviz_panel: Any = None  # bras-kit launch with rviz2: RViz's own panel (view.rviz_panel)
        self._build_panel()
        self.show_model(viewer.model)
        client.camera.on_update(self._camera_reported)
        # viser calls on_client_connect (this session) once the browser's first camera report is
        # in, and runs that report's callbacks without waiting for it: that report is read here
        self._camera_reported(client.camera)

    def w(self, message: Message | str) -> str:
        """``message`` worded in this browser's language, escaped for the panel's HTML."""
        return html.escape(say(message, self.lang))

    def s(self, message: Message) -> str:
        """``message`` worded for a GUI label (plain text)."""
        return say(message, self.lang)

    # -- the camera --------------------------------------------------------------------------
    def _camera_reported(self, camera: Any) -> None:
        """The robot is framed for this browser's canvas once the browser says its size, and again:
        - when that size changes while the camera is still where it was put (a busy browser
          reports its canvas before the page is laid out, then its real size);
        - when the page has put the viewer's first camera (the one for every browser, sized for
          no canvas in particular) over this browser's, as it does when that message comes last,
          and when the learner asks for it back ("Reset View").
        A camera the learner moved stays where they put it."""
        size = _canvas_size(camera)
        if size is None:
            return
        if self._framed_for is None or self._placed is None:
            self.frame_camera()
            return
        initial = self.viewer.server.initial_camera
        first = (np.asarray(initial.position, float), np.asarray(initial.look_at, float))
        if _camera_at(camera, first) and not _same_place(self._placed, first):
            self.frame_camera()
        elif size != self._framed_for and _camera_at(camera, self._placed):
            self.frame_camera()

    def frame_camera(self) -> bool:
        """Put this browser's camera on the robot, sized for its canvas, clear of the panel;
        False while the browser has not said its canvas's size."""
        from .framing import SWEPT_MARGIN, place_camera, reach_points

        camera = self.client.camera
        size = _canvas_size(camera)
        if size is None:
            return False
        points = reach_points(self.model, self.values, self.viewer.motion, self.fixed_frame)
        placement = place_camera(points, size[0], size[1], margin=SWEPT_MARGIN)
        with self.client.atomic():
            camera.fov = placement.fov
            camera.near = placement.near
            camera.far = placement.far
            camera.position = placement.position
            camera.look_at = placement.look_at
        self._framed_for = size
        self._placed = (np.asarray(placement.position, float), np.asarray(placement.look_at, float))
        return True

    # -- the panel that does not depend on the model ------------------------------------------
    def _build_panel(self) -> None:
        gui, s = self.client.gui, self.s
        # the panel's title: viser says "Connected" there, in English, unless given a label
        gui.set_panel_label(f"bras-kit · {self.viewer.model.robot.name or 'robot'}")
        script = client_words_script(self.lang)
        if script:  # viser's own words, in the page's language (its API's message, as plotly is set up)
            from viser import _messages

            self.client.gui._websock_interface.queue_message(_messages.RunJavascriptMessage(source=script))
        self.banner = gui.add_html("", order=0)
        self.status = gui.add_html("", order=0.5)
        with gui.add_folder(s(M("Display")), order=1):
            geometry = self.viewer.geometry
            self.show_visual = gui.add_checkbox(s(M("Visual geometry")), geometry in ("visual", "both"))
            self.show_collision = gui.add_checkbox(s(M("Collision geometry")), geometry in ("collision", "both"))
            few = len(self.viewer.model.tree.links) <= MANY_LINKS  # later models keep the learner's choice
            self.show_frames = gui.add_checkbox(s(M("TF frames (axes)")), few)
            self.legend = gui.add_html(axes_legend(self.lang))
            self.show_names = gui.add_checkbox(s(M("Frame names")), few)
            self.show_grid = gui.add_checkbox(s(M("Grid")), True)
            self.fixed = gui.add_dropdown(s(M("Fixed Frame")), ("-",), initial_value="-")
        for handle in (self.show_visual, self.show_collision, self.show_frames, self.show_names, self.show_grid):
            handle.on_update(lambda _event: self._apply_visibility())
        self.fixed.on_update(lambda _event: self._choose_fixed_frame())
        if self.viewer.rviz_on():  # RViz's own panel sets the Fixed Frame, the TF and Grid displays
            from .rviz_panel import RvizPanel

            for handle in (self.fixed, self.show_frames, self.show_grid):
                handle.visible = False
            self.rviz_panel = RvizPanel(self)
        with gui.add_folder(s(M("Joints")), order=2):
            gui.add_html(_HIDE_SLIDER_BOXES)
            self.joint_folder = gui.add_folder(s(M("Sliders")))
            self.past_limits = gui.add_checkbox(s(M("Allow values past the limits")), False,
                                                hint=s(M("typed values past a joint's limits are refused unless this is on")))
            self.joint_note = gui.add_html("")
            self.buttons = gui.add_button_group("", (s(M("Zero")), s(M("Random pose"))))
            self.buttons.on_click(lambda event: self._button(event.target.value))
        motion = self.viewer.motion
        with gui.add_folder(s(M("Motion")), order=3):
            self.play = gui.add_checkbox(s(M("Play")), bool(self.viewer.autoplay and motion is not None),
                                         disabled=motion is None)
            self.speed_slider = gui.add_slider(s(M("Speed")), 0.1, 3.0, 0.1, 1.0, disabled=motion is None)
            self.scrubber = gui.add_slider(s(M("Time (s)")), 0.0, self._period() or 1.0, 0.01, 0.0,
                                           disabled=motion is None,
                                           hint=s(M("drag to show the motion at that time (pauses it)")))
            self.motion_text = gui.add_html("")
        self.play.on_update(lambda _event: self._toggle_play())
        if self.play.value:  # started playing (view --node): the node moves the arm by itself
            self._toggle_play()
        self.speed_slider.on_update(lambda _event: setattr(self, "speed", float(self.speed_slider.value)))
        self.scrubber.on_update(lambda event: self._scrubbed(event))
        with gui.add_folder(s(M("Readouts")), order=4):
            self.readout = gui.add_html("")
            self.echo = gui.add_html(f"<small><i>{self.w(M('click a link to read its pose in the fixed frame'))}</i></small>")
        with gui.add_folder(s(M("Checks")), order=5):
            self.findings = gui.add_html("")
        if motion is not None:
            self.motion_text.content = f"<small>{self.w(motion_title(motion.label))}</small>"

    def _period(self) -> float:
        motion = self.viewer.motion
        if motion is None:
            return 0.0
        return float(motion.duration or self.viewer.loop_seconds)

    # -- the model ---------------------------------------------------------------------------
    def show_model(self, model: ViewModel) -> None:
        """Draw ``model``; keep the joint values whose joints still exist, and the Fixed Frame."""
        with self._lock, self.client.atomic():
            for handle in [*self._frames, *self._labels]:  # a frame's meshes are its children: they go with it
                handle.remove()
            for handle in self._model_gui:
                handle.remove()
            self._frames, self._labels, self._visual_nodes, self._collision_nodes = [], [], [], []
            self._label_places = []
            self._sent = None
            self._sliders, self._boxes, self._box_notes, self._model_gui = {}, {}, {}, []
            scene = self.client.scene
            self.model = model
            heavy = self._light(model)
            names = [s.joint for s in model.sliders]
            self.values = {name: self.values.get(name, 0.0) for name in names}
            length = 0.12 * model.scale
            self.grid = scene.add_grid(f"{ROOT}/grid", width=4 * model.scale, height=4 * model.scale,
                                       cell_size=_nice(model.scale / 5), section_size=_nice(model.scale))
            self._model_gui.append(self.grid)
            for index in range(len(model.tree.links)):
                frame = scene.add_frame(f"{ROOT}/link{index}", bool(self.show_frames.value), axes_length=length,
                                        axes_radius=length / 22, origin_radius=length / 10)
                self._frames.append(frame)
            self._make_labels()
            for k, mesh in enumerate(model.visuals):
                node = scene.add_mesh_simple(
                    f"{ROOT}/link{mesh.link}/visual{k}", mesh.vertices.astype(np.float32),
                    mesh.faces.astype(np.uint32), color=mesh.color,
                    opacity=None if mesh.opacity >= 1.0 else mesh.opacity,
                    cast_shadow=not heavy, receive_shadow=not heavy)
                node.on_click(lambda _event, link=mesh.link: self.select(model.tree.links[link]))
                self._visual_nodes.append(node)
            for k, mesh in enumerate(model.collisions):
                node = scene.add_mesh_simple(
                    f"{ROOT}/link{mesh.link}/collision{k}", mesh.vertices.astype(np.float32),
                    mesh.faces.astype(np.uint32), color=mesh.color, opacity=mesh.opacity, visible=False,
                    cast_shadow=not heavy, receive_shadow=not heavy)
                node.on_click(lambda _event, link=mesh.link: self.select(model.tree.links[link]))
                self._collision_nodes.append(node)
            links = tuple(model.tree.links)
            choices = links
            if self.rviz_panel is not None:
                self.fixed_name = self.viewer.rviz.fixed_frame
            if self.fixed_name in links:
                self.fixed_frame = links.index(self.fixed_name)
            elif self.viewer.launch is not None and self.fixed_name:
                # RViz keeps a Fixed Frame that is no frame, and draws nothing: so does the page,
                # until the learner picks a frame of the robot (as in RViz's Global Options)
                choices = (*links, self.fixed_name)
                self.fixed_frame = 0
            else:
                self.fixed_frame = 0
            self._setting = True  # new options make viser pick the first one: not the learner's choice
            try:
                self.fixed.options = choices
                self.fixed.value = self.fixed_name if self.fixed_name in choices else links[self.fixed_frame]
            finally:
                self._setting = False
            if self.selected not in links:
                self.selected = None
            sliders = self.viewer.sliders
            with self.joint_folder:
                if sliders:
                    for slider in model.sliders:
                        self._add_joint(slider)
                if not sliders:
                    self._model_gui.append(self.client.gui.add_html(
                        f"<p data-note='no-sliders'><small>{self.w(NO_SLIDER_WINDOW)}</small></p>"))
                elif not model.sliders:
                    self._model_gui.append(self.client.gui.add_markdown(self.s(M("This robot has no movable joint."))))
            self.past_limits.visible = sliders
            self.buttons.visible = sliders
            if self.rviz_panel is not None:
                self.rviz_panel.rebuild()
            self._apply_visibility()
            self.update()
        self.show_checks()

    def _make_labels(self) -> None:
        """The frame names, made the first time they are to be shown."""
        if self._labels or not self.show_names.value:
            return
        scene = self.client.scene
        for index, link in enumerate(self.model.tree.links):
            self._labels.append(scene.add_label(label_name(index), link, font_screen_scale=0.8,
                                                anchor="bottom-left"))
            self._label_places.append((math.nan, math.nan, math.nan))  # not placed yet: update() sends it

    def _light(self, model: ViewModel) -> bool:
        """Light ``model``: viser's own lighting (environment map, shadows), or for a heavy robot
        plain lights and no shadows. Returns whether the robot is heavy."""
        heavy = sum(len(mesh.faces) for mesh in model.visuals) > HEAVY_TRIANGLES
        scene = self.client.scene
        if heavy and self._plain_light is None:
            scene.configure_environment_map(None)
            scene.configure_default_lights(True, cast_shadow=False)
            self._plain_light = scene.add_light_ambient(f"{ROOT}_ambient", intensity=1.0)
        elif not heavy and self._plain_light is not None:
            self._plain_light.remove()
            self._plain_light = None
            scene.configure_environment_map(DEFAULT_HDRI)
            scene.configure_default_lights(True, cast_shadow=True)
        return heavy

    def _add_joint(self, slider: Any) -> None:
        gui = self.client.gui
        value = self.values[slider.joint]
        handle = gui.add_slider(slider.joint, slider.lower, slider.upper, _step(slider), _clip(value, slider),
                                hint=f"{slider.lower:g} .. {slider.upper:g} {slider.unit}")
        handle.on_update(lambda _event, name=slider.joint, h=handle: self._slider_moved(name, h))
        box = gui.add_text(f"{slider.joint} =", joint_box_text(value),
                           hint=self.s(M("a value for {joint}: 0.5, 0,5, pi/4, 90deg", joint=slider.joint)))
        box.on_update(lambda event, name=slider.joint, b=box: self._box_typed(name, b, event))
        self._sliders[slider.joint] = handle
        self._boxes[slider.joint] = box
        self._model_gui += [handle, box]

    def show_checks(self) -> None:
        """The banner (a file that no longer reads, and the number of findings) at the top of the
        panel, the findings in "Checks", and the status line."""
        viewer = self.viewer
        blank = self.blank()
        shown = "" if blank is None else (
            f"<div data-banner='blank' style='background:#fff3e0;border-left:4px solid #e65100;padding:6px 8px;"
            f"margin:0 0 6px 0'><b>{self.w(self._blank_title(blank))}</b><br>{self.w(blank)}</div>")
        checking = viewer.checking
        self.banner.content = shown + banner(viewer.error, viewer.findings, self.lang, checking)
        rows = []
        if viewer.error is not None:
            rows.append(f"<p style='color:{ERROR_RED}'><b>{self.w(M('The file cannot be read'))}</b>: "
                        f"{html.escape(say(viewer.error, self.lang))}</p>")
        for file, finding in sorted(viewer.shown_checks(), key=_what_matters):
            colour = {"error": ERROR_RED, "warning": "#e65100"}.get(finding.severity, "#455a64")
            line = f":{finding.line}" if finding.line else ""
            place = f"{html.escape(file)}{line} " if file else ""
            element = element_text(finding)  # the element it is about, as the terminal names it
            element = f"<code>{html.escape(element)}</code> " if element else ""
            hint = finding.hint
            fix = "" if hint is None else \
                f"<br><small data-hint='{finding.code}'>&rarr; {html.escape(say(hint, self.lang))}</small>"
            rows.append(f"<p style='margin:2px 0' data-finding='{finding.code}' data-severity='{finding.severity}' "
                        f"data-place='{html.escape(file)}{line}'><b style='color:{colour}'>"
                        f"{finding.code}</b>{'' if file else line} {place}"
                        f"<span data-message>{element}{html.escape(say(finding.message, self.lang))}</span>{fix}</p>")
        if checking:  # a launch's checks still running: neither "No finding" nor a count yet
            rows = [f"<p><i>{self.w(M('checking the package...'))}</i></p>"]
        elif not rows:
            rows.append(f"<p style='color:#2e7d32'>{self.w(M('No finding'))}</p>")
        self.findings.content = "".join(rows)
        stamp = time.strftime("%H:%M:%S", time.localtime(viewer.loaded_at))
        self.status.content = (f"<small><b>{html.escape(self.model.robot.name or 'robot')}</b> · "
                               f"{html.escape(say(viewer.source_label, self.lang))} · "
                               f"{self.w(M('loaded at {time}', time=stamp))}</small>")

    # -- moving the arm ----------------------------------------------------------------------
    def update(self) -> None:
        """Send the link poses for the current values, and the readouts."""
        start = time.perf_counter()
        model = self.model
        poses = model.poses(self.values, self.fixed_frame)
        places = label_places(poses, model.scale)
        moved = np.arange(len(poses)) if self._sent is None else \
            np.flatnonzero(np.abs(poses - self._sent).max(axis=(1, 2)) > 1e-9)
        with self.client.atomic():  # one message to the browser: the links move together
            for k in moved:  # only the links that moved (one joint moves its subtree only)
                frame = self._frames[k]
                frame.position = poses[k, :3, 3]
                frame.wxyz = wxyz(poses[k, :3, :3])
            for k in _moved_labels(places, self._label_places) if self._labels else ():
                position = (float(places[k, 0]), float(places[k, 1]), float(places[k, 2]))
                self._labels[k].position = position
                self._label_places[k] = position
        self._sent = poses
        self.last_update_ms = 1000 * (time.perf_counter() - start)
        self._readouts(poses)

    def _readouts(self, poses: np.ndarray) -> None:
        model = self.model
        outside = model.out_of_limits(self.values)
        tip = model.tip(poses)
        rows = [f"<p style='margin:2px 0'><b>{self.w(M('Tip'))}</b> "
                + self.w(M("({link}): x={x} y={y} z={z} m", link=model.tree.links[model.tip_link], x=f"{tip[0]:.3f}",
                           y=f"{tip[1]:.3f}", z=f"{tip[2]:.3f}")) + "</p>"]
        for slider in model.sliders:
            value = self.values.get(slider.joint, 0.0)
            rows.append(self._row(slider.joint, value, slider.unit, slider.joint in outside, ""))
        for follower, value in zip(model.followers, model.follower_values(self.values).values()):
            follows = f" <i>({self.w(M('follows {joint}', joint=follower.leader))})</i>"
            rows.append(self._row(follower.joint, value, follower.unit, follower.joint in outside, follows))
        self.readout.content = "".join(rows)
        if self.selected is not None:
            self._echo(poses)

    def _row(self, joint: str, value: float, unit: str, outside: bool, extra: str) -> str:
        style = "margin:2px 0" + (f";color:{ERROR_RED};font-weight:bold" if outside else "")
        degrees = f" ({math.degrees(value):.1f}°)" if unit == "rad" else ""
        mark = f" — {self.w(M('out of limits'))}" if outside else ""
        return (f"<p style='{style}' data-joint='{html.escape(joint)}'>"
                f"{html.escape(joint)} = {value:.3f} {unit}{degrees}{extra}{mark}</p>")

    def select(self, link: str) -> None:
        """Read out ``link``'s pose in the fixed frame, as ``tf2_echo FIXED LINK`` prints it."""
        with self._lock:
            self.selected = link
            self._echo(self.model.poses(self.values, self.fixed_frame))

    def _echo(self, poses: np.ndarray) -> None:
        links = list(self.model.tree.links)
        if self.selected not in links:
            return
        pose = poses[links.index(self.selected)]
        self.echo.content = echo_rows(links[self.fixed_frame], self.selected, pose, self.lang)

    def set_values(self, values: dict[str, float]) -> None:
        with self._lock:
            self.values.update({k: float(v) for k, v in values.items() if k in self.values})
            self._setting = True
            try:
                for name, handle in self._sliders.items():
                    slider = next(s for s in self.model.sliders if s.joint == name)
                    handle.value = _clip(self.values[name], slider)
                    self._boxes[name].value = joint_box_text(self.values[name])
            finally:
                self._setting = False
            self.update()

    def _slider_moved(self, name: str, handle: Any) -> None:
        if self._setting:
            return
        with self._lock:
            self.values[name] = float(handle.value)
            self._setting = True
            try:
                self._boxes[name].value = joint_box_text(self.values[name])
            finally:
                self._setting = False
            self._box_notes.pop(name, None)
            self._show_box_notes()
            self.update()

    def _box_typed(self, name: str, box: Any, event: Any) -> None:
        """A value typed in a joint's box, read as the CLI reads ``--set``: decimal comma,
        ``pi/2``, ``90deg``; past the limits it is refused (with the degrees hint when it fits)
        unless "Allow values past the limits" is on. Values set from code (no client) are not read."""
        if self._setting or event.client is None:
            return
        slider = next((s for s in self.model.sliders if s.joint == name), None)
        if slider is None:
            return
        with self._lock:
            value, note, accepted = read_joint_box(str(box.value), slider, self.model.robot.joint(name),
                                                   bool(self.past_limits.value))
            if note is None:
                self._box_notes.pop(name, None)
            else:
                self._box_notes[name] = html.escape(say(note, self.lang))
            self._show_box_notes()
            if accepted and value is not None:
                self.values[name] = value
                self._setting = True
                try:
                    self._sliders[name].value = _clip(value, slider)
                finally:
                    self._setting = False
                self.update()

    def _show_box_notes(self) -> None:
        self.joint_note.content = "".join(f"<p style='margin:2px 0;color:{ERROR_RED}' data-note='{html.escape(k)}'>"
                                          f"{v}</p>" for k, v in self._box_notes.items())

    def _button(self, label: str) -> None:
        if label == self.s(M("Zero")):
            self.set_values(dict.fromkeys(self.values, 0.0))
        else:
            self.set_values({s.joint: random.uniform(s.lower, s.upper) for s in self.model.sliders})

    def _toggle_play(self) -> None:
        self.playing = bool(self.play.value)
        for handle in [*self._sliders.values(), *self._boxes.values()]:
            handle.disabled = self.playing

    def _scrubbed(self, event: Any) -> None:
        """The time slider moved by hand: pause, and show the motion at that time (moved by
        playback, from code: no client, nothing to do)."""
        if self.viewer.motion is None or event.client is None:
            return
        with self._lock:
            if self.playing:
                self.play.value = False  # its callback re-enables the sliders
                self.playing = False
            self.play_time = float(self.scrubber.value)
            self._show_time(self.play_time)

    def take_joint_state(self, values: dict[str, float]) -> None:
        """A node's JointState: shown as published (unknown joints are left out, as
        robot_state_publisher leaves them); a playing motion pauses."""
        with self._lock:
            if self.playing:
                self.play.value = False
                self.playing = False
            known = {name: value for name, value in values.items() if name in self.values}
            if known:
                self.set_values(known)

    def advance(self, seconds: float) -> None:
        """Playback: move the motion on by ``seconds`` of wall time (times the speed)."""
        with self._lock:
            if self.viewer.motion is None or not self.playing:
                return
            self.play_time += seconds * self.speed
            self._show_time(self.play_time)

    def _show_time(self, moment: float) -> None:
        motion = self.viewer.motion
        period = self._period()
        when = moment % period if period else moment
        positions = motion.positions(np.array([when]))[0]
        self.set_values(dict(zip(motion.names, (float(v) for v in positions))))
        self.scrubber.value = min(when, float(self.scrubber.max))
        self.motion_text.content = f"<small>{self.w(motion_title(motion.label))} · t = {when:.2f} s</small>"

    # -- display toggles ---------------------------------------------------------------------
    def _apply_visibility(self) -> None:
        with self._lock, self.client.atomic():
            if self.show_names.value and not self._labels:
                self._make_labels()
                self.update()  # places the new names
            if self.rviz_panel is not None:
                self._apply_rviz()
                return
            drawn = self.blank() is None  # as RViz: no robot, or no Fixed Frame to draw it in
            for node in self._visual_nodes:
                node.visible = bool(self.show_visual.value)
            for node in self._collision_nodes:
                node.visible = bool(self.show_collision.value)
            for frame in self._frames:  # a frame hidden hides its meshes (its children)
                frame.show_axes = bool(self.show_frames.value)
                frame.visible = drawn
            for label in self._labels:
                label.visible = bool(self.show_names.value) and drawn
            launch = self.viewer.launch
            # no rviz2 in the launch: no RViz window, not even its grid (BK615)
            self.grid.visible = bool(self.show_grid.value) and (launch is None or launch.rviz_started)

    def _apply_rviz(self) -> None:
        """What RViz draws: each link the RobotModel places, the axes of each frame the TF display
        places, the Grid while a Grid display is on (ros.rviz.config.shown)."""
        from ..ros.rviz.config import GRID, ROBOT_MODEL, TF

        seen = self.viewer.rviz_shown()
        links = list(self.model.tree.links)
        drawn = set(seen.links) if self.viewer.launch.blank() is None else set()
        axes = {f for d in seen.displays if d.display.kind == TF for f in d.drawn}
        model_on = any(d.display.kind == ROBOT_MODEL and d.drawn for d in seen.displays)
        for k, frame in enumerate(self._frames):
            frame.visible = links[k] in drawn or links[k] in axes
            frame.show_axes = links[k] in axes
        for node, mesh in zip(self._visual_nodes, self.model.visuals):
            node.visible = bool(self.show_visual.value) and model_on and links[mesh.link] in drawn
        for node, mesh in zip(self._collision_nodes, self.model.collisions):
            node.visible = bool(self.show_collision.value) and model_on and links[mesh.link] in drawn
        for k, label in enumerate(self._labels):
            label.visible = bool(self.show_names.value) and links[k] in axes
        self.grid.visible = any(d.display.kind == GRID and d.drawn for d in seen.displays)

    def rviz_changed(self, rebuild: bool) -> None:
        """The learner changed RViz's configuration (here or in another page): show what RViz shows."""
        if self.rviz_panel is None:
            return
        with self._lock, self.client.atomic():
            frame = self.viewer.rviz.fixed_frame
            links = list(self.model.tree.links)
            self.fixed_name = frame
            self.fixed_frame = links.index(frame) if frame in links else 0
            if rebuild:
                self.rviz_panel.rebuild()
            else:
                self.rviz_panel.show()
            self.update()
            self._apply_visibility()
        self.show_checks()

    def _choose_fixed_frame(self) -> None:
        links = list(self.model.tree.links)
        if self._setting or (self.fixed.value == self.fixed_name and self.fixed_name not in links):
            return  # set from code, or the Fixed Frame that is no frame, as the page started
        if self.fixed.value in links:
            with self._lock:
                self.fixed_frame = links.index(self.fixed.value)
                self.fixed_name = self.fixed.value
                self.update()
                self._apply_visibility()
                self.show_checks()

    @staticmethod
    def _blank_title(blank: Message) -> Message:
        from ..ros.evaluation import NO_RVIZ

        return M("RViz is not started") if blank is NO_RVIZ else M("RViz shows nothing")

    def blank(self) -> Message | None:
        """Why this page draws no robot, as RViz would draw none (None: it is drawn)."""
        launch = self.viewer.launch
        if launch is None:
            return None
        if self.rviz_panel is not None:
            return launch.blank() or self.viewer.rviz_state.why(self.viewer.rviz_shown())
        return launch.blank() or launch.frame_missing(self.fixed_name)


_SEVERITY_RANK = {"error": 0, "warning": 1, "info": 2}
# what decides what RViz shows of the launch: its configuration (BK610-BK613), /joint_states (BK620)
_VIEW_CODES = ("BK61", "BK62")


def _what_matters(check: tuple[str, Any]) -> tuple[int, int]:
    """The page's order of findings: errors, warnings, infos; within each, those about what RViz
    shows first (sorted() keeps the terminal's order otherwise)."""
    finding = check[1]
    return _SEVERITY_RANK.get(finding.severity, 3), 0 if str(finding.code).startswith(_VIEW_CODES) else 1


def _moved_labels(places: np.ndarray, sent: list[tuple[float, float, float]]) -> np.ndarray:
    """The indices of the names whose place differs from the one the browser has (NaN: none yet)."""
    if not len(places):
        return np.zeros(0, dtype=int)
    before = np.asarray(sent, dtype=float).reshape(-1, 3)
    return np.flatnonzero(~(np.abs(places - before) <= 1e-9).all(axis=1))


def _step(slider: Any) -> float:
    return max((slider.upper - slider.lower) / 1000, 1e-4)


def _clip(value: float, slider: Any) -> float:
    return min(max(value, slider.lower), slider.upper)


def _nice(length: float) -> float:
    """A round grid step near ``length``: 1, 2 or 5 times a power of ten."""
    power = 10.0 ** math.floor(math.log10(max(length, 1e-6)))  # a float: 10 * 1e308 is inf, not an OverflowError
    return min((m * power for m in (1, 2, 5, 10)), key=lambda v: abs(v - length))
