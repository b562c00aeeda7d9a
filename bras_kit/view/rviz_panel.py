"""RViz's left panel in the launch page: Global Status, Fixed Frame, the Displays with their status
and properties, Add, and Save Config. Every action changes the one :class:`RvizConfig` the viewer
holds (the same model the terminal's findings read), and the page then draws what
:func:`bras_kit.ros.rviz.config.shown` says RViz draws.

The labels are RViz's own (Fixed Frame, Add, RobotModel, Description Topic, TF...), as the tutorial
names them; statuses are RViz's words; our explanations go through the catalog."""

from __future__ import annotations

import html
from typing import Any

from ..core.i18n import say
from ..core.message import M
from ..ros.rviz import config as rviz

LEVEL_COLOURS = {rviz.OK: "#2e7d32", rviz.WARN: "#e65100", rviz.ERROR: "#c62828"}
SHORT = {kind.rsplit("/", 1)[-1]: kind for kind in rviz.KINDS}  # RobotModel -> rviz_default_plugins/RobotModel


def _status_rows(statuses: tuple[rviz.Status, ...], index: int | str) -> str:
    rows = []
    for status in statuses:
        colour = LEVEL_COLOURS.get(status.level, "#455a64")
        rows.append(f"<div style='margin:1px 0' data-rviz-status='{index}' data-level='{status.level}'>"
                    f"<b style='color:{colour}'>{html.escape(status.name)}</b>: {html.escape(status.text)}</div>")
    return "".join(rows)


class RvizPanel:
    """One browser's copy of RViz's Displays panel (the state itself is the viewer's)."""

    def __init__(self, session: Any) -> None:
        self.session = session
        self.rows: list[Any] = []  # the handles of the displays' rows, rebuilt on Add, Remove, Source
        self.statuses: list[Any] = []  # each display's status html, updated on every change
        gui = session.client.gui
        with gui.add_folder("RViz", order=0.8):
            self.global_status = gui.add_html("")
            self.fixed = gui.add_text("Fixed Frame", self.config.fixed_frame,
                                      hint=session.s(M("the frame every other is drawn in (Global Options)")))
            self.fixed.on_update(lambda _event: self._fixed_typed())
            self.displays = gui.add_folder("Displays")
            self.kind = gui.add_dropdown("Add", tuple(SHORT), initial_value="RobotModel")
            self.add = gui.add_button("Add")
            self.add.on_click(lambda _event: self._add())
            self.save_name = gui.add_text(session.s(M("file in rviz/")), session.viewer.rviz_save_name())
            self.save = gui.add_button("Save Config")
            self.save.on_click(lambda _event: self._save(False))
            self.overwrite = gui.add_button(session.s(M("Overwrite")), visible=False)
            self.overwrite.on_click(lambda _event: self._save(True))
            self.saved = gui.add_html("")
        self.rebuild()

    @property
    def config(self) -> rviz.RvizConfig:
        return self.session.viewer.rviz

    # -- what the panel shows -----------------------------------------------------------------
    def rebuild(self) -> None:
        """The displays' rows made anew (after Add, Remove, a new launch)."""
        for handle in self.rows:
            handle.remove()
        self.rows, self.statuses = [], []
        gui = self.session.client.gui
        with self.displays:
            for index, display in enumerate(self.config.displays):
                folder = gui.add_folder(display.name or display.kind.rsplit("/", 1)[-1])
                self.rows.append(folder)
                with folder:
                    self.statuses.append(gui.add_html(""))
                    enabled = gui.add_checkbox("Enabled", display.enabled)
                    enabled.on_update(lambda _e, k=index, h=enabled: self._set(k, "Enabled", bool(h.value)))
                    if display.kind == rviz.ROBOT_MODEL:
                        source = gui.add_dropdown("Description Source", rviz.SOURCES,
                                                  initial_value=display.description_source)
                        source.on_update(lambda _e, k=index, h=source: self._set(k, "Description Source",
                                                                                 str(h.value), rebuild=True))
                        if display.description_source == "Topic":
                            topic = gui.add_text("Description Topic", display.description_topic)
                            topic.on_update(lambda _e, k=index, h=topic: self._set(k, "Description Topic",
                                                                                   str(h.value).strip()))
                        else:
                            path = gui.add_text("Description File", display.description_file)
                            path.on_update(lambda _e, k=index, h=path: self._set(k, "Description File",
                                                                                 str(h.value).strip()))
                    remove = gui.add_button(self.session.s(M("Remove")))
                    remove.on_click(lambda _e, k=index: self._remove(k))
        self.show()

    def show(self) -> None:
        """Global Status and each display's status, from the viewer's shown()."""
        seen = self.session.viewer.rviz_shown()
        status = seen.global_status
        self.global_status.content = (
            f"<div data-rviz='global-status' data-level='{status.level}'><b>Global Status</b> "
            f"{_status_rows((status,), 'global')}</div>")
        if self.fixed.value != self.config.fixed_frame:
            self.fixed.value = self.config.fixed_frame
        for handle, one in zip(self.statuses, seen.displays):
            rows = _status_rows(one.statuses, one.display.name) or \
                f"<i>{html.escape(say(M('unchecked: shows nothing'), self.session.lang))}</i>" * (not one.display.enabled)
            handle.content = f"<div data-rviz-display='{html.escape(one.display.name)}'>{rows}</div>"

    # -- the learner's actions ------------------------------------------------------------------
    def _change(self, config: rviz.RvizConfig, rebuild: bool = False) -> None:
        self.session.viewer.set_rviz(config, rebuild=rebuild, by=self.session)

    def _fixed_typed(self) -> None:
        value = str(self.fixed.value)
        if value != self.config.fixed_frame:
            self._change(rviz.with_fixed_frame(self.config, value))

    def _set(self, index: int, key: str, value: str | bool, rebuild: bool = False) -> None:
        if index < len(self.config.displays):
            self._change(rviz.with_option(self.config, index, key, value), rebuild)

    def _add(self) -> None:
        kind = SHORT.get(str(self.kind.value), rviz.ROBOT_MODEL)
        self._change(rviz.with_display(self.config, rviz.new_display(kind)), rebuild=True)

    def _remove(self, index: int) -> None:
        self._change(rviz.without_display(self.config, index), rebuild=True)

    def _save(self, force: bool) -> None:
        said = self.session.viewer.save_rviz(str(self.save_name.value), force)
        asks = said.asks
        self.overwrite.visible = asks
        colour = "#e65100" if asks or said.failed else "#2e7d32"
        self.saved.content = (f"<p data-rviz='saved' data-state='{said.state}' style='color:{colour}'>"
                              f"{html.escape(say(said.message, self.session.lang))}</p>")
