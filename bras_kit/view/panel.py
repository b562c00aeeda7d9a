"""The words and small computations of the viewer's panel, kept apart from the viser handles so
they can be tested without a browser: the banner, the axes legend, the tf2_echo readout, joint
values typed in a box, and where to put frame names that would cover each other."""

from __future__ import annotations

import html
import math
import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..core.i18n import say
from ..core.message import M, Message, Mn

ERROR_RED = "#c62828"
AXIS_COLOURS = (("x", "#e53935"), ("y", "#43a047"), ("z", "#1e88e5"))  # RViz's TF display


def axes_legend(lang: str) -> str:
    """"x red, y green, z blue" in the colours the axes are drawn with."""
    words = {"x": M("x red"), "y": M("y green"), "z": M("z blue")}
    parts = [f"<b style='color:{colour}'>{html.escape(say(words[axis], lang))}</b>" for axis, colour in AXIS_COLOURS]
    return f"<small data-legend='axes'>{html.escape(say(M('Axes:'), lang))} {' · '.join(parts)}</small>"


def banner(error: Any, findings: Sequence[Any], lang: str, checking: bool = False) -> str:
    """The top of the panel: a red banner while the saved file does not read (file, line, message),
    then the number of findings (and of errors and warnings among them), or ``checking`` that they
    are not in yet."""
    out = []
    if error is not None:
        path = getattr(error, "path", None)
        where = os.path.basename(str(path)) if path else ""
        line = getattr(error, "line", None)
        if where and line:
            place = say(M("{file}, line {line}", file=where, line=line), lang)
        else:
            place = where
        message = say(getattr(error, "message", None) or str(error), lang)
        hint = getattr(error, "hint", None)
        out.append(
            f"<div data-banner='error' style='background:#fdecea;border-left:4px solid {ERROR_RED};"
            f"padding:6px 8px;margin:0 0 6px 0;color:#5f2120'>"
            f"<b style='color:{ERROR_RED}'>{html.escape(say(M('The file cannot be read'), lang))}</b>"
            + (f" — <b>{html.escape(place)}</b>" if place else "")
            + f"<br>{html.escape(message)}"
            + (f"<br><i>{html.escape(say(hint, lang))}</i>" if hint else "")
            + f"<br><small>{html.escape(say(M('the last good model stays on screen until the file reads again'), lang))}"
              "</small></div>")
    if checking:
        out.append(f"<small data-banner='count'><i>{html.escape(say(M('checking the package...'), lang))}</i></small>")
        return "".join(out)
    errors = sum(1 for f in findings if getattr(f, "severity", "") == "error")
    warnings = sum(1 for f in findings if getattr(f, "severity", "") == "warning")
    count: Message = Mn("{n} finding", "{n} findings", len(findings))
    text = say(count, lang)
    if errors:
        text += " · " + say(Mn("{n} error", "{n} errors", errors), lang)
    if warnings:  # the terminal's summary counts them too
        text += " · " + say(Mn("{n} warning", "{n} warnings", warnings), lang)
    colour = ERROR_RED if errors else ("#e65100" if findings else "#2e7d32")
    out.append(f"<small data-banner='count' style='color:{colour}'><b>{html.escape(text)}</b>"
               f" ({html.escape(say(M('see Checks'), lang))})</small>" if findings else
               f"<small data-banner='count' style='color:{colour}'>{html.escape(text)}</small>")
    return "".join(out)


def echo_rows(fixed: str, link: str, pose: np.ndarray, lang: str) -> str:
    """``link``'s pose in ``fixed`` as ``ros2 run tf2_ros tf2_echo FIXED LINK`` prints it:
    translation, quaternion (x y z w), roll-pitch-yaw in radians and in degrees."""
    from ..kinematics.frames import describe_transform

    facts = describe_transform(pose)
    xyz, quat, rpy = facts["xyz"], facts["quat_xyzw"], facts["rpy"]

    def row(values: Sequence[float], digits: int = 3) -> str:
        return "[" + ", ".join(f"{v + 0.0:.{digits}f}" for v in values) + "]"

    title = say(M("{link} in {fixed} (tf2_echo {fixed} {link})", link=link, fixed=fixed), lang)
    lines = [
        f"<b data-echo='{html.escape(link)}'>{html.escape(title)}</b>",
        f"- {html.escape(say(M('Translation'), lang))}: {row(xyz)} m",
        f"- {html.escape(say(M('Rotation: in Quaternion'), lang))} {row(quat)}",
        f"- {html.escape(say(M('in RPY (radian)'), lang))} {row(rpy)}",
        f"- {html.escape(say(M('in RPY (degree)'), lang))} {row([math.degrees(v) for v in rpy], 1)}",
    ]
    return "<div style='font-size:0.85em'>" + "<br>".join(lines) + "</div>"


def joint_box_text(value: float) -> str:
    """A joint value as its box shows it: up to four decimals, no trailing zeros."""
    text = f"{value:.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def read_joint_box(text: str, slider: Any, joint: Any, allow_past: bool) -> tuple[float | None, Message | None, bool]:
    """What a value typed in a joint's box means: ``(value, note, accepted)``. It is read by the
    CLI's parser (``0,5``, ``pi/4``, ``30deg``); past the joint's limits it is refused unless
    ``allow_past``, with the CLI's hint when the number reads as degrees."""
    from ..core.errors import BrasKitError
    from ..model.expr import parse_joint_value
    from ..motion import value_in_degrees
    from ..motion.limits import TOLERANCE

    if not text.strip():
        return None, None, False
    try:
        value = parse_joint_value(text)
    except BrasKitError:  # often a value half typed: a short note, the slider stays
        return None, M("'{text}' is not a joint value (yet): write 0.5, 0,5, pi/4 or 30deg", text=text.strip()), False
    lower, upper = joint.bounds() if joint is not None else (slider.lower, slider.upper)
    if not (math.isfinite(lower) and math.isfinite(upper)) or lower - TOLERANCE <= value <= upper + TOLERANCE:
        return value, None, True
    if value_in_degrees(joint, value):
        note = M("{joint}={value} rad is past its limits ({lower} .. {upper} rad); it looks like degrees: "
                 "type {value}deg", joint=slider.joint, value=value, lower=lower, upper=upper)
    else:
        note = M("{joint}={value} {unit} is past its limits ({lower} .. {upper} {unit})",
                 joint=slider.joint, value=value, unit=slider.unit, lower=lower, upper=upper)
    if not allow_past:
        note = M("{note}: not applied (tick \"Allow values past the limits\" to go past)", note=note)
    return value, note, allow_past


def label_offsets(poses: np.ndarray, spacing: float) -> np.ndarray:
    """An upward offset (world frame, N x 3) per frame name so names of frames that (nearly)
    coincide stack instead of covering each other: the n-th frame within ``spacing`` of earlier
    ones goes up by n times ``spacing``."""
    origins = poses[:, :3, 3]
    out = np.zeros((len(origins), 3))
    distances = np.linalg.norm(origins[:, None, :] - origins[None, :, :], axis=2)
    earlier_near = np.tril(distances < spacing, k=-1)  # row k: the frames before k within spacing
    out[:, 2] = spacing * earlier_near.sum(axis=1)
    return out


def label_name(index: int) -> str:
    """The scene name of the ``index``-th frame's name. Not a child of the frame's node: viser's
    client (1.1.1, client/src/label/LabelRenderer.tsx, its useFrame) places a label with its
    parent's ``matrixWorld``, which three.js updates only while drawing, after that hook: under a
    moving frame the name is drawn where the frame was one drawing before, 150-200 px behind on
    a slow (software WebGL) page. Under the scene's fixed root, the name's own position, sent
    with the frame's in one message, is read as it comes."""
    return f"/bras/name{index}"


def label_places(poses: np.ndarray, scale: float) -> np.ndarray:
    """Where each frame's name goes in the scene (N x 3): at its frame's origin, names of frames
    that (nearly) coincide stacked upwards (:func:`label_offsets`)."""
    return poses[:, :3, 3] + label_offsets(poses, 0.045 * scale)
