"""What bras-kit reads of the probe is bounded (issue 53: a stranger's publisher on the live
bus): the probe's snapshot is read from a file once its size is known, and a stream line past
its bound is skipped in pieces, never held whole. The probe's own cuts are tested on a real
graph (tests/doctor/test_live_doctor.py::test_a_flooding_publisher_is_judged_on_a_bounded_look)."""

from __future__ import annotations

import io
import json
import subprocess
import sys
import textwrap

from bras_kit.live import watch


def test_a_stream_line_past_its_bound_is_skipped_and_the_next_record_read(monkeypatch):
    monkeypatch.setattr(watch, "MAX_PROBE_LINE", 64)
    stream = io.StringIO('{"kind": "a"}\n{"kind": "' + "x" * 1000 + '"}\n{"kind": "b"}\n')
    assert [r["kind"] for r in watch.read_records(stream)] == ["a", "b"]


def test_a_probe_printing_past_the_bound_is_refused_without_being_read(tmp_path):
    """A probe that prints 400 MB: the command says so, and bras-kit's own memory stays small."""
    fake = tmp_path / "python"
    fake.write_text(textwrap.dedent(f"""\
        #!{sys.executable}
        import sys
        line = '{{"kind": "snapshot", "x": "' + 'x' * (1 << 20) + '"}}\\n'
        for _ in range(400):
            sys.stdout.write(line)
        """))
    fake.chmod(0o755)
    code = textwrap.dedent(f"""\
        import json
        from bras_kit.core.errors import BrasKitError
        from bras_kit.live import watch
        try:
            watch._run_probe({str(fake)!r}, "snapshot", 1.0, {{}})
            said = None
        except BrasKitError as exc:
            said = str(exc)
        # this process's own high-water mark (ru_maxrss would count the parent's, which a vfork shares)
        peak = next(int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("VmHWM:"))
        print(json.dumps([said, peak]))
        """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    said, peak_kib = json.loads(done.stdout.splitlines()[-1])
    assert said is not None and "more than 160 MiB" in said
    assert peak_kib < 200 * 1024  # the 400 MB were never read (the interpreter alone is some 40 MB)


def test_a_probe_within_the_bound_is_read(tmp_path, monkeypatch):
    fake = tmp_path / "python"
    fake.write_text(f"#!{sys.executable}\nprint('noise')\nprint('{{\"kind\": \"snapshot\", \"n\": 1}}')\n")
    fake.chmod(0o755)
    monkeypatch.setattr(watch, "MAX_PROBE_OUTPUT", 64)  # the bound counts bytes: these 47 are read
    assert watch._run_probe(str(fake), "snapshot", 1.0, {}) == {"kind": "snapshot", "n": 1}
