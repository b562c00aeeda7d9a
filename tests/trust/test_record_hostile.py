"""Hostile nodes against the record of their run (tests/data/hostile_code/record/): the stand-in
runs in the node's own process, so each of these reaches what the stand-in keeps. bras-kit's
process must print and store no more than the bounds, and nothing the stand-in did not check.

Oracles: the corpus files read by hand (the names they plant, the counts they publish, what they
print, computed here by arithmetic), the terminal's control characters looked for in every line
bras-kit prints, and the kernel's own count of peak memory (``ru_maxrss`` of a subprocess and of
the children it waited for). Before this change, 200,000 references to one 2,000-joint message
took ``run -o`` past 3.6 GB, and a node printing 2 GB took its child to its memory limit.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys

import pytest
from paths import TESTS

from bras_kit.core.errors import BrasKitError
from bras_kit.core.i18n import say
from bras_kit.ros.capture import HEAD_CHARS, TAIL_CHARS
from bras_kit.run import run_findings, run_node
from bras_kit.run.report import summary
from bras_kit.trust.contain import available

CORPUS = TESTS / "data" / "hostile_code" / "record"
CONTAIN = "require" if available().ok else "off"
PLANTED = ("\x1b", "\x07", "\u202e")
MIB = 1 << 20


def clean(text: str) -> bool:
    return not any(c in text for c in PLANTED)


def shown(recording) -> list[str]:
    """Every line bras-kit shows of the run: its summary and its findings, in English and French."""
    from bras_kit.model.authoring import arm

    out = [say(m, lang) for m in summary(recording) for lang in ("en", "fr")]
    return out + [say(f.message, lang) for f in run_findings(recording, arm()) for lang in ("en", "fr")]


def codes(recording) -> dict[str, str]:
    from bras_kit.model.authoring import arm

    return {f.code: say(f.message, "en") for f in run_findings(recording, arm())}


def peak(code: str, timeout: float = 300) -> dict:
    """Run ``code`` (which prints one JSON line last) in a fresh interpreter: its answer, with the
    peak resident memory of that process and of the children it waited for, in MiB."""
    # VmHWM, the peak of this process's own memory since its exec (ru_maxrss of RUSAGE_SELF starts
    # from the forking process's: pytest's own, however large); its children were forked after it
    wrapper = (code + "\nimport resource as _r, json as _j, re as _re\n"
               "_hwm = int(_re.search(r'VmHWM:\\s+(\\d+)', open('/proc/self/status').read()).group(1))\n"
               "print(_j.dumps({'self': _hwm >> 10, 'children': _r.getrusage(_r.RUSAGE_CHILDREN).ru_maxrss >> 10}))\n")
    env = dict(os.environ, PATH=os.path.dirname(sys.executable) + os.pathsep + os.environ.get("PATH", ""))
    done = subprocess.run([sys.executable, "-c", wrapper], capture_output=True, text=True, timeout=timeout, env=env,
                          stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stderr[-3000:]
    lines = done.stdout.strip().splitlines()
    return {**json.loads(lines[-1]), "stdout": lines[:-1], "stderr": done.stderr}


def test_a_node_renamed_after_rclpy_checked_its_name_is_recorded_under_the_checked_name():
    r = run_node(str(CORPUS / "rename_after_check.py"), duration=1.0, contain=CONTAIN)
    # sent before the rename, and after node._name changed: the name rclpy checked
    assert [(m.node, m.topic) for m in r.messages] == [("bras_node", "/joint_states")] * 2
    assert r.nodes == ["bras_node"] and {p.node for p in r.publishers} == {"bras_node"}
    # the third message, and the last publisher, carry the stand-in's own copies changed: left out
    assert r.refused_count == 3 and len(r.publishers) == 2
    lines = shown(r)
    assert all(clean(text) for text in lines), [t for t in lines if not clean(t)]
    assert "BK658" in codes(r)


def test_entries_added_to_the_stand_in_lists_are_checked_and_left_out():
    r = run_node(str(CORPUS / "append_lists.py"), duration=1.0, contain=CONTAIN)
    assert r.nodes == ["bras_node"] and r.publishers == [] and r.subscriptions == [] and r.timers == []
    assert r.split_strings == [] and r.messages == []
    assert [log[3] for log in r.logs] == ["a log of its own"]
    assert r.refused_count == 9  # 2 nodes, 2 publishers, 1 subscription, 1 timer, 1 split string, 2 messages, 1 log
    assert r.overflow == {"messages": 1}  # the tuple: not a line of the record
    found = codes(r)
    assert "BK658" in found and "BK657" in found
    assert all(clean(text) for text in shown(r))


def test_a_replaced_record_writer_cannot_plant_names_paths_or_sizes():
    r = run_node(str(CORPUS / "replace_functions.py"), duration=1.0, contain=CONTAIN)
    assert r.nodes == ["bras_node"] and r.publishers == [] and r.source == ""
    assert r.ended == "error" and r.rate_sleeps == 0
    assert len(r.output) == 1 << 17 and r.overflow.get("text") == 1  # 500,000 characters claimed: cut
    assert [m.fields["position"] for m in r.messages] == [[0.5]]  # the forged line that is well-formed
    assert all(clean(text) for text in shown(r))


def test_entries_past_the_bound_of_a_list_are_counted():
    r = run_node(str(CORPUS / "many_publishers.py"), duration=1.0, contain=CONTAIN)
    assert [p.topic for p in r.publishers] == [f"/topic_{k}" for k in range(1000)]
    assert r.overflow == {"entries": 4000}
    assert "pieces of the record of the run past its bounds (entries): 4000" in codes(r)["BK657"]


def test_a_replaced_pickle_sending_objects_is_no_record():
    with pytest.raises(BrasKitError) as caught:
        run_node(str(CORPUS / "replace_pickle.py"), duration=1.0, contain=CONTAIN)
    assert "no record bras-kit can read" in str(caught.value.message)


@pytest.mark.slow
def test_two_hundred_thousand_references_to_a_big_message_stay_within_the_bounds(tmp_path):
    """``bras-kit run -o`` of the node that took it past 3.6 GB: the CSV holds what the record
    kept, BK657 says how many were not kept, and bras-kit's process stays small."""
    out = tmp_path / "js.csv"
    got = peak(f"import sys; from bras_kit.cli import main\n"
               f"code = main(['run', {str(CORPUS / 'many_references.py')!r}, '--duration', '1', '-o', {str(out)!r}])\n"
               f"print('exit', code)")
    assert got["self"] < 600, got  # MiB; 3.6 GB before
    assert got["children"] < 600, got
    with open(out, newline="") as stream:
        rows = csv.reader(stream)
        assert next(rows) == ["time", "name", "position", "velocity"]
        count = sum(1 for _ in rows)
    line_bytes = 56_000  # one 2,000-joint message's line of the record, about (see record_wire)
    assert count % 2000 == 0
    kept = count // 2000  # a row per joint of each message kept
    assert 32 * MIB // (line_bytes + 2_000) <= kept <= 32 * MIB // (line_bytes - 2_000)
    assert any("BK657" in line for line in got["stdout"]), got["stdout"][-5:]


@pytest.mark.slow
def test_a_node_printing_two_gigabytes_leaves_its_head_its_tail_and_the_count():
    got = peak(f"from bras_kit.run import run_node\n"
               f"r = run_node({str(CORPUS / 'prints_gigabytes.py')!r}, duration=1.0, contain={CONTAIN!r})\n"
               f"import json; print(json.dumps([r.output, r.output_tail, r.output_dropped, r.output_dropped_lines]))")
    head, tail, dropped, dropped_lines = json.loads(got["stdout"][-1])
    first, last, block_lines, line = "FIRST LINE OF THE NODE\n", "LAST LINE OF THE NODE\n", 1000 * 2000, 1000
    total = len(first) + block_lines * line + len(last)
    assert len(head) == HEAD_CHARS and head.startswith(first + "y" * 999 + "\n")
    assert len(tail) == TAIL_CHARS and tail.endswith("y" * 999 + "\n" + last)
    assert dropped == total - HEAD_CHARS - TAIL_CHARS
    # line ends between the head and the tail: those of the blocks from offset a to offset b
    a, b = HEAD_CHARS - len(first), total - TAIL_CHARS - len(first)
    assert dropped_lines == b // line - a // line
    assert got["children"] < 300, got  # MiB: the node's process too (it held all it printed before)


def test_the_summary_says_how_much_of_the_printed_output_was_not_kept():
    from bras_kit.ros.recording import Recording

    r = Recording("n", "n.py", "main", 1.0, 1.0, "returned", output="a", output_tail="b",
                  output_dropped=1_934_000_000, output_dropped_lines=2_000_000)
    assert "1.9 GB (2000000 lines) between its first and last 64 KiB not shown" in say(summary(r)[-2], "en")
    assert "1.9 Go (2000000 lignes)" in say(summary(r)[-2], "fr")


def test_big_messages_are_kept_whole_up_to_the_bounds_and_a_too_large_one_is_counted():
    r = run_node(str(CORPUS / "big_messages.py"), duration=0.05, contain=CONTAIN)
    assert r.overflow == {"too_big": 1}  # 400,000 joints: past one line of the record
    assert len(r.messages) == 50 and all(len(m.fields["name"]) == 2000 for m in r.messages)
    assert r.messages[-1].fields["position"] == [0.05] * 2000
    assert "BK657" in codes(r)


def test_an_endless_line_to_the_relay_is_drained_not_held():
    """The live relay (run beside launch) reads a line up to 1 MiB: a 256 MiB line without end is
    skipped as it streams, and the joint state after it is delivered."""
    got = peak("import os, threading, json\n"
               "from bras_kit.run.node import _relay\n"
               "read, write = os.pipe()\n"
               "states = []\n"
               "thread = _relay(read, states.append)\n"
               "block = b'x' * (1 << 20)\n"
               "for _ in range(256): os.write(write, block)\n"
               "os.write(write, b'\\n' + json.dumps({'name': ['epaule'], 'position': [0.25], 'stamp': 1.0}).encode() + b'\\n')\n"
               "os.write(write, json.dumps({'name': ['epaule'], 'position': ['0.5'], 'stamp': 1.0}).encode() + b'\\n')\n"
               "os.close(write); thread.join(30)\n"
               "print(json.dumps([[s.name, s.position, s.stamp] for s in states]))")
    assert json.loads(got["stdout"][-1]) == [[["epaule"], [0.25], 1.0]]
    assert got["self"] < 120, got  # MiB (the line was 256 MiB)


def test_the_bus_takes_a_bounded_typed_joint_state_only():
    from bras_kit.ros.bus import MAX_PAYLOAD_BYTES, Bus

    class Payload(bytes):
        def to_bytes(self):
            return bytes(self)

    class Sample:
        def __init__(self, data: bytes) -> None:
            self.payload = Payload(data)

    class Session:
        def declare_subscriber(self, key, callback):
            self.callback = callback

    session = Session()
    states: list = []
    Bus(session, None, []).on_joint_state(states.append)
    good = {"name": ["epaule"], "position": [0.25], "stamp": 2.0}
    for data in (b"[" * 100_000, json.dumps({**good, "position": ["0.25"]}).encode(),
                 json.dumps({**good, "name": [1]}).encode(), json.dumps({**good, "position": [True]}).encode(),
                 json.dumps({**good, "name": ["j"] * 20_000, "position": [0.0] * 20_000}).encode(),
                 b'{"name": ["' + b"x" * MAX_PAYLOAD_BYTES + b'"], "position": [0]}', json.dumps(good).encode()):
        session.callback(Sample(data))
    assert [(s.name, s.position, s.stamp) for s in states] == [(["epaule"], [0.25], 2.0)]


@pytest.mark.slow
def test_an_endless_line_from_a_live_node_leaves_bras_kit_small():
    """The node writes a 256 MiB line into the pipe to the relay, then a joint state: the state
    reaches the launch, and bras-kit's process stays small (before: the whole line held)."""
    got = peak("import json\n"
               "from bras_kit.run import run_node\n"
               "states = []\n"
               f"r = run_node({str(CORPUS / 'writes_endless_line.py')!r}, duration=0.5, contain={CONTAIN!r}, live=True,"
               " on_joint_state=states.append)\n"
               "print(json.dumps([[s.name, s.position] for s in states]))")
    assert json.loads(got["stdout"][-1]) == [[["epaule"], [0.25]]]
    assert got["self"] < 200, got  # MiB
