"""A path stays under its root (bras_kit.trust.beneath) and the one reader of learner files
(bras_kit.trust.learner_files): one test per trick.

Oracles: the kernel's own view of each path made here (a link, a loop, a named pipe, a Unix
socket, /dev/zero, a folder), and openat2(2)'s RESOLVE_BENEATH rules as its manual states them:
a path resolved with its links followed must stay under the root, else it is refused.
"""

from __future__ import annotations

import os
import socket
import threading

import pytest

from bras_kit.trust.beneath import FOLDER, Outside, beneath, beneath_any, is_name_component
from bras_kit.trust.learner_files import Unreadable, copy_file, read_bytes, read_text

SECRET = "bras-kit-trust-secret"


@pytest.fixture
def tree(tmp_path):
    """root/ (the package) with urdf/bras.urdf, and outside/ beside it with a secret."""
    root, outside = tmp_path / "root", tmp_path / "outside"
    (root / "urdf").mkdir(parents=True)
    (root / "urdf" / "bras.urdf").write_text("<robot name='bras'/>")
    outside.mkdir()
    (outside / "secret.txt").write_text(SECRET)
    return root, outside


def refusal(root, path, **options) -> str:
    with pytest.raises(Outside) as caught:
        beneath(str(root), str(path), **options)
    assert SECRET not in str(caught.value)
    return caught.value.kind


def test_a_file_inside_is_given_resolved(tree):
    root, _ = tree
    assert beneath(str(root), "urdf/bras.urdf") == str((root / "urdf" / "bras.urdf").resolve())


def test_dot_dot_that_stays_inside_is_followed_as_openat2_does(tree):
    root, _ = tree
    assert beneath(str(root), "urdf/../urdf/bras.urdf") == str((root / "urdf" / "bras.urdf").resolve())


def test_dot_dot_out_of_the_root_is_refused(tree):
    root, _ = tree
    assert refusal(root, "../outside/secret.txt") == "outside"


def test_an_absolute_path_elsewhere_is_refused(tree):
    root, outside = tree
    assert refusal(root, outside / "secret.txt") == "outside"


def test_an_absolute_path_inside_is_accepted(tree):
    root, _ = tree
    assert beneath(str(root), str(root / "urdf" / "bras.urdf")).endswith("urdf/bras.urdf")


def test_a_symbolic_link_out_is_refused(tree):
    root, outside = tree
    (root / "urdf" / "lien.urdf").symlink_to(outside / "secret.txt")
    assert refusal(root, "urdf/lien.urdf") == "link_out"


def test_a_linked_folder_out_is_refused_for_every_file_below_it(tree):
    root, outside = tree
    (root / "meshes").symlink_to(outside)
    assert refusal(root, "meshes/secret.txt") == "link_out"


def test_a_link_that_stays_inside_is_followed(tree):
    root, _ = tree
    (root / "robot.urdf").symlink_to("urdf/bras.urdf")
    assert beneath(str(root), "robot.urdf") == str((root / "urdf" / "bras.urdf").resolve())


def test_a_loop_of_symbolic_links_is_refused(tree):
    root, _ = tree
    (root / "a.urdf").symlink_to("b.urdf")
    (root / "b.urdf").symlink_to("a.urdf")
    assert refusal(root, "a.urdf") == "loop"


def test_a_named_pipe_is_refused(tree):
    root, _ = tree
    os.mkfifo(root / "tube.urdf")
    assert refusal(root, "tube.urdf") == "fifo"


def test_a_socket_is_refused(tree, tmp_path):
    root, _ = tree
    path = root / "s.sock"
    server = socket.socket(socket.AF_UNIX)
    try:
        server.bind(str(path))
        assert refusal(root, "s.sock") == "socket"
    finally:
        server.close()


def test_a_device_is_refused_even_under_its_own_root():
    assert refusal("/dev", "/dev/zero") == "device"


def test_a_folder_is_not_a_file_and_a_file_is_not_a_folder(tree):
    root, _ = tree
    assert refusal(root, "urdf") == "folder"
    assert refusal(root, "urdf/bras.urdf", want=FOLDER) == "not_folder"
    assert beneath(str(root), "urdf", want=FOLDER) == str((root / "urdf").resolve())


def test_a_missing_file_and_an_empty_path_are_refused(tree):
    root, _ = tree
    assert refusal(root, "urdf/nope.urdf") == "missing"
    assert refusal(root, "") == "empty"


def test_a_root_that_is_itself_a_link_is_judged_by_where_it_leads(tree, tmp_path):
    root, _ = tree
    (tmp_path / "alias").symlink_to(root)
    assert beneath(str(tmp_path / "alias"), "urdf/bras.urdf") == str((root / "urdf" / "bras.urdf").resolve())


def test_beneath_any_names_the_precise_refusal_of_the_root_that_holds_the_path(tree):
    root, outside = tree
    os.mkfifo(root / "tube.urdf")
    with pytest.raises(Outside) as caught:
        beneath_any((str(outside), str(root)), str(root / "tube.urdf"))
    assert caught.value.kind == "fifo"


def test_a_name_component_names_nothing_but_itself():
    assert is_name_component("bras_description")
    assert not any(is_name_component(n) for n in ("", ".", "..", "a/b", "/x", "a\0b"))


# ------------------------------------------------------------------ the reader


def test_the_reader_reads_a_file_of_the_package(tree):
    root, _ = tree
    assert read_text(str(root / "urdf" / "bras.urdf"), (str(root),)) == "<robot name='bras'/>"


def test_the_reader_refuses_dev_zero_without_reading_it():
    """/dev/zero never ends: a reader that opened it would read until memory runs out."""
    with pytest.raises(Unreadable) as caught:
        read_bytes("/dev/zero", ("/dev",))
    assert caught.value.kind == "device"
    with pytest.raises(Unreadable) as caught:
        read_bytes("/dev/zero", ("/tmp",))
    assert caught.value.kind == "outside"


def test_the_reader_refuses_a_named_pipe_without_blocking(tree):
    """Opening a pipe that no one writes to blocks for ever: the reader never opens it."""
    root, _ = tree
    os.mkfifo(root / "tube.urdf")
    done = []
    worker = threading.Thread(target=lambda: done.append(_kind(root / "tube.urdf", root)), daemon=True)
    worker.start()
    worker.join(5.0)
    assert done == ["fifo"]


def _kind(path, root) -> str:
    try:
        read_bytes(str(path), (str(root),))
    except Unreadable as exc:
        return exc.kind
    return ""


def test_the_reader_never_quotes_a_refused_file(tree):
    root, outside = tree
    (root / "urdf" / "lien.urdf").symlink_to(outside / "secret.txt")
    with pytest.raises(Unreadable) as caught:
        read_text(str(root / "urdf" / "lien.urdf"), (str(root),))
    assert caught.value.kind == "link_out" and SECRET not in str(caught.value) and SECRET not in repr(caught.value)


def test_the_reader_limits_the_size(tree):
    root, _ = tree
    (root / "big.urdf").write_bytes(b"x" * 1001)
    with pytest.raises(Unreadable) as caught:
        read_bytes(str(root / "big.urdf"), (str(root),), limit=1000)
    assert caught.value.kind == "too_large"
    assert len(read_bytes(str(root / "big.urdf"), (str(root),), limit=1001)) == 1001


def test_the_reader_is_an_os_error_so_every_caller_that_handled_one_still_does(tree):
    root, outside = tree
    with pytest.raises(OSError):
        read_text(str(outside / "secret.txt"), (str(root),))


def test_a_copy_goes_to_a_new_file_only(tree, tmp_path):
    root, _ = tree
    target = tmp_path / "copy.urdf"
    copy_file(str(root / "urdf" / "bras.urdf"), (str(root),), str(target))
    assert target.read_text() == "<robot name='bras'/>"
    with pytest.raises(FileExistsError):  # never written through what is already there
        copy_file(str(root / "urdf" / "bras.urdf"), (str(root),), str(target))
