"""Names from the live ROS 2 bus reach the terminal through its gate (issue 53, item 3): joint
names a node publishes on /joint_states, link and joint names of the /robot_description text,
robot_state_publisher's own node name and namespace (in rmw's alphabet: checked, shown as they
are), judged by ``doctor --ros`` on a real graph (the real rclpy of Jazzy, in a loopback-only
network namespace), in text for a person, in JSON, and read back with ``--from``.

Oracle: the characters a terminal obeys (ECMA-48's ESC, CSI, OSC, the 8-bit C1 controls,
Unicode's bidi overrides and isolates, Cc and Cf) are in the names the nodes publish (written
here), and none may reach bras-kit's output raw; each must be there as its visible escape.
"""

from __future__ import annotations

import json
import unicodedata
from pathlib import Path

import pytest
from live_graphs import DATA, _run

pytestmark = pytest.mark.slow

OSC = "\x1b]0;PWNED\x07"  # a window title
CSI = "\x1b[2J"  # clear the screen
C1 = "\x9b31m"  # the 8-bit CSI
BIDI = "\u202eevil\u202c"  # right-to-left override, then pop
ISOLATE = "\u2067x\u2069"
JOINTS = [f"epaule{OSC}{CSI}", f"coude{BIDI}{ISOLATE}"]  # two names for the node's two positions
LINK = f"avant_bras{C1}{BIDI}"  # XML takes C1 and bidi characters (not ESC or BEL) in a name


def obeyed(text: str) -> list[str]:
    """The characters of ``text`` a terminal obeys or that reorder text (never the line feed, tab)."""
    return [c for c in text if c not in "\n\t" and (unicodedata.category(c) in ("Cc", "Cf") or c in "\u2028\u2029")]


def hostile_urdf(folder: Path) -> Path:
    tutorial = (DATA / "bras.urdf").read_text(encoding="utf-8")
    text = tutorial.replace('"avant_bras"', f'"{LINK}"')
    assert LINK in text
    path = folder / "hostile.urdf"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def looks(real_rclpy, tmp_path_factory):
    urdf = hostile_urdf(tmp_path_factory.mktemp("live_names"))
    nodes = [["state_publisher.py", str(urdf)], ["animation.py", "--names", ",".join(JOINTS)]]
    return _run(nodes, [["--format", "json"], [], ["--lang", "fr"]])


def test_joint_and_link_names_from_the_bus_reach_no_terminal_raw(looks):
    (code_json, out_json), (code_text, out_text), (_code_fr, out_fr) = looks[0]
    print(looks[1])
    for out in (out_json, out_text, out_fr):
        assert obeyed(out) == [], out
    # the JSON parses back to the very names published; the text shows each as its escape
    document = json.loads(out_json[: out_json.rindex("}") + 1])
    messages = " ".join(f["message"] for f in document["findings"])
    assert JOINTS[0] in messages and JOINTS[1] in messages, messages
    for out in (out_text, out_fr):
        assert "epaule\\x1b]0;PWNED\\x07\\x1b[2J" in out, out
        assert "coude\\u202eevil\\u202c\\u2067x\\u2069" in out, out
    assert code_text == code_json != 0  # names that are not the robot's: an error, in both forms


def test_a_link_name_of_the_live_description_reaches_no_terminal_raw(looks):
    """The link name comes from /robot_description's text (parsed by the safe XML reader): C1's
    8-bit CSI and a bidi override, which XML allows in a name."""
    (_code, out_json), (_, out_text), (_, out_fr) = looks[0]
    document = json.loads(out_json[: out_json.rindex("}") + 1])
    assert LINK in " ".join(f["message"] for f in document["findings"])
    for out in (out_text, out_fr):
        assert "avant_bras\\u009b31m\\u202eevil\\u202c" in out, out
