"""The one reader resolves a path beneath its root by descriptor (bras_kit.trust.beneath.open_beneath,
bras_kit.trust.learner_files): one test per trick, in both of its ways (the kernel's openat2 with
RESOLVE_BENEATH, and the walk of one component at a time used where the kernel lacks it), a
generated tree of links checked against the kernel's own resolution, and a real process racing
a folder against a link while bras-kit reads.

Oracles: the kernel's resolution of each path (os.path.realpath, os.stat of what it names: the
file read must be the one inside), openat2(2)'s manual (RESOLVE_BENEATH: no component may leave
the root, absolute links refused) and a canary in every file outside the root, which must never
be read.
"""

from __future__ import annotations

import multiprocessing
import os
import socket
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bras_kit.trust import beneath as beneath_module
from bras_kit.trust.beneath import FOLDER, Outside, open_beneath
from bras_kit.trust.learner_files import (
    Unreadable,
    copy_file,
    list_folder,
    read_bytes,
    read_text,
    walk,
    write_file,
)

CANARY = "bras-kit-canary-7f3e"


@pytest.fixture(params=["openat2", "walk"])
def way(request, monkeypatch):
    """Each test twice: with the kernel's openat2, and with the walk alone (openat2 missing)."""
    if request.param == "walk":
        monkeypatch.setattr(beneath_module, "_openat2", lambda *args: None)
    elif beneath_module._openat2(os.open("/", os.O_RDONLY | os.O_DIRECTORY), ".", os.O_RDONLY | os.O_DIRECTORY) \
            is None:
        pytest.fail("this kernel has no openat2: the walk alone is tested")
    return request.param


@pytest.fixture
def tree(tmp_path):
    root, outside = tmp_path / "pkg", tmp_path / "outside"
    (root / "urdf").mkdir(parents=True)
    (root / "urdf" / "bras.urdf").write_text("<robot name='bras'/>")
    outside.mkdir()
    (outside / "bras.urdf").write_text(CANARY)
    (outside / "package.xml").write_text(CANARY)
    return root, outside


def kind(root, path, **options) -> str:
    with pytest.raises(Unreadable) as caught:
        read_bytes(str(path), (str(root),), **options)
    assert CANARY not in str(caught.value)
    return caught.value.kind


def test_a_file_inside_is_read(tree, way):
    root, _ = tree
    assert read_text(str(root / "urdf" / "bras.urdf"), (str(root),)) == "<robot name='bras'/>"
    assert read_text("urdf/bras.urdf", (str(root),)) == "<robot name='bras'/>"


def test_a_linked_urdf_folder_out_of_the_package_is_refused(tree, way):
    root, outside = tree
    os.rename(root / "urdf", root / "old")
    (root / "urdf").symlink_to(outside)
    assert kind(root, root / "urdf" / "bras.urdf") == "link_out"


def test_a_linked_folder_that_stays_inside_is_followed(tree, way):
    root, _ = tree
    (root / "description").symlink_to("urdf")
    (root / "absolute").symlink_to(root / "urdf")  # absolute, and inside: followed as beneath() follows it
    assert read_text("description/bras.urdf", (str(root),)) == "<robot name='bras'/>"
    assert read_text("absolute/bras.urdf", (str(root),)) == "<robot name='bras'/>"


def test_dot_dot_within_the_root_is_followed_and_out_of_it_refused(tree, way):
    root, _ = tree
    assert read_text("urdf/../urdf/./bras.urdf", (str(root),)) == "<robot name='bras'/>"
    assert kind(root, "../outside/bras.urdf") == "outside"
    assert kind(root, "urdf/../../outside/bras.urdf") == "outside"


def test_a_link_made_of_dot_dots_out_is_refused(tree, way):
    root, _ = tree
    (root / "urdf" / "up").symlink_to("../../outside")
    assert kind(root, "urdf/up/bras.urdf") == "link_out"


def test_absolute_paths_and_links_elsewhere_are_refused(tree, way):
    root, outside = tree
    assert kind(root, outside / "bras.urdf") == "outside"
    (root / "urdf" / "abs.urdf").symlink_to(outside / "bras.urdf")
    assert kind(root, "urdf/abs.urdf") == "link_out"


@pytest.mark.parametrize("target", ["/proc/self/environ", "/proc/self/root/etc/hostname", "/dev/zero",
                                    "/dev/stdin", "/proc/self/fd/0"])
def test_links_to_proc_and_dev_are_refused(tree, way, target):
    root, _ = tree
    (root / "urdf" / "x.urdf").symlink_to(target)
    assert kind(root, "urdf/x.urdf") == "link_out"


def test_a_fifo_a_socket_and_a_folder_are_refused_without_blocking(tree, way):
    root, _ = tree
    os.mkfifo(root / "urdf" / "pipe.urdf")
    server = socket.socket(socket.AF_UNIX)
    server.bind(str(root / "urdf" / "sock"))
    try:
        started = time.monotonic()
        assert kind(root, "urdf/pipe.urdf") == "fifo"
        assert time.monotonic() - started < 1
        assert kind(root, "urdf/sock") == "socket"
        assert kind(root, "urdf") == "folder"
    finally:
        server.close()


def test_a_loop_of_links_is_refused(tree, way):
    root, _ = tree
    (root / "a").symlink_to("b")
    (root / "b").symlink_to("a")
    (root / "self").symlink_to("self/x")
    assert kind(root, "a/bras.urdf") == "loop"
    assert kind(root, "self") == "loop"


def test_a_very_deep_path_is_refused_without_running_out_of_descriptors(tree, way):
    root, _ = tree
    assert kind(root, "/".join(["urdf"] + [".."] * 1) + "/" + "a/" * 3000 + "x") == "too_deep"
    deep = root
    for _ in range(300):
        deep = deep / "d"
    os.makedirs(deep)
    (deep / "f").write_text("deep")
    relative = os.path.relpath(deep / "f", root)
    if way == "walk":  # a descriptor held for each folder: a bound, well below the usual 1,024 open files
        assert kind(root, relative) == "too_deep"
    else:  # the kernel holds none
        assert read_text(relative, (str(root),)) == "deep"
    # a chain of links each adding components, as deep as the kernel allows names
    (root / "grow").symlink_to("grow/grow")
    assert kind(root, "grow/bras.urdf") == "loop"


def test_a_missing_file_and_a_file_as_a_folder(tree, way):
    root, _ = tree
    assert kind(root, "urdf/none.urdf") == "missing"
    assert kind(root, "urdf/bras.urdf/more") == "missing"


def test_the_limit_is_kept(tree, way):
    root, _ = tree
    assert kind(root, "urdf/bras.urdf", limit=5) == "too_large"


def test_listing_and_walking_go_through_the_descriptor_and_never_into_a_link(tree, way):
    root, outside = tree
    (root / "meshes").symlink_to(outside)
    (root / "urdf" / "inner").mkdir()
    (root / "urdf" / "inner" / "x.stl").write_text("solid")
    assert list_folder(str(root), (str(root),)) == [("meshes", "link"), ("urdf", "folder")]
    walked = [(os.path.relpath(place, root), folders, files) for place, folders, files in walk(str(root), (str(root),))]
    assert walked == [(".", ["urdf"], ["meshes"]), ("urdf", ["inner"], ["bras.urdf"]), ("urdf/inner", [], ["x.stl"])]
    with pytest.raises(Unreadable):
        list_folder(str(root / "meshes"), (str(root),))


def test_copy_reads_the_descriptor_and_writes_no_link_in_the_target(tree, tmp_path, way):
    root, outside = tree
    install = tmp_path / "install"
    install.mkdir()
    copy_file(str(root / "urdf" / "bras.urdf"), (str(root),), str(install / "share" / "urdf" / "bras.urdf"),
              target_root=str(install))
    assert (install / "share" / "urdf" / "bras.urdf").read_text() == "<robot name='bras'/>"
    (install / "share" / "launch").symlink_to(outside)  # planted in the install tree: never written through
    with pytest.raises(OSError):
        copy_file(str(root / "urdf" / "bras.urdf"), (str(root),), str(install / "share" / "launch" / "bras.urdf"),
                  target_root=str(install))
    (install / "share" / "urdf" / "new.urdf").symlink_to(outside / "package.xml")
    with pytest.raises(OSError):
        copy_file(str(root / "urdf" / "bras.urdf"), (str(root),), str(install / "share" / "urdf" / "new.urdf"),
                  target_root=str(install))
    assert (outside / "package.xml").read_text() == CANARY
    assert sorted(os.listdir(outside)) == ["bras.urdf", "package.xml"]


def test_write_file_replaces_a_link_and_never_writes_through_it(tree, way):
    root, outside = tree
    (root / "progress.json").symlink_to(outside / "package.xml")
    write_file(str(root), "progress.json", b"{}")
    assert (outside / "package.xml").read_text() == CANARY
    assert not (root / "progress.json").is_symlink() and (root / "progress.json").read_text() == "{}"
    (root / "linked").symlink_to(outside)
    with pytest.raises(Outside):
        write_file(str(root), "linked/bras.urdf", b"x")
    assert sorted(os.listdir(outside)) == ["bras.urdf", "package.xml"]


def test_open_beneath_a_folder(tree, way):
    root, _ = tree
    fd = open_beneath(str(root), "urdf", want=FOLDER)
    try:
        assert sorted(os.listdir(fd)) == ["bras.urdf"]
    finally:
        os.close(fd)


# ---------------------------------------------------------------- a generated tree of links

NAMES = st.sampled_from(["a", "b", "c", "urdf"])
TARGETS = st.one_of(
    st.lists(st.sampled_from(["a", "b", "c", "urdf", "..", ".", "f"]), min_size=1, max_size=4).map("/".join),
    st.sampled_from(["@root/a", "@root/urdf/f", "@out", "@out/f", "/dev/null", "/proc/self"]))


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(links=st.lists(st.tuples(st.lists(NAMES, min_size=1, max_size=3), TARGETS), max_size=6),
       path=st.lists(st.sampled_from(["a", "b", "c", "urdf", "f", ".."]), min_size=1, max_size=5))
def test_generated_trees_read_only_what_the_kernel_resolves_inside(tmp_path_factory, links, path):
    """Whatever links the tree holds, what the reader reads is the file the kernel resolves the
    path to, inside the root; a path the kernel resolves outside is refused; both ways agree."""
    base = tmp_path_factory.mktemp("gen")
    root, out = base / "root", base / "out"
    for folder in (root / "urdf", out):
        folder.mkdir(parents=True)
    (root / "urdf" / "f").write_text("inside")
    (root / "f").write_text("top")
    (out / "f").write_text(CANARY)
    for names, target in links:
        where = root.joinpath(*names)
        if os.path.lexists(where) or not os.path.isdir(where.parent) or os.path.islink(where.parent):
            continue
        where.symlink_to(target.replace("@root", str(root)).replace("@out", str(out)))
    text = "/".join(path)
    results = []
    for forced in (False, True):
        saved = beneath_module._openat2
        if forced:
            beneath_module._openat2 = lambda *args: None
        try:
            results.append(read_text(text, (str(root),)))
        except Unreadable as exc:
            results.append(exc.kind)
        finally:
            beneath_module._openat2 = saved
    assert CANARY not in results
    resolved = os.path.realpath(os.path.join(root, text))
    if results[0] in ("inside", "top"):
        assert resolved.startswith(str(root) + os.sep)
        with open(resolved) as handle:
            assert handle.read() == results[0]
    if not resolved.startswith(str(root) + os.sep):
        assert results[0] not in ("inside", "top")
    # the kernel and the walk agree on what is read; a refusal may be worded apart (the kernel's is not ours)
    assert (results[0] in ("inside", "top")) == (results[1] in ("inside", "top")) or results[0] == "too_deep"
    if results[0] in ("inside", "top"):
        assert results[0] == results[1]


# ---------------------------------------------------------------- a real process racing a folder and a link


def _flip(root: str, outside: str, stop) -> None:  # type: ignore[no-untyped-def]
    """Swap root/urdf between the real folder and a link out, as fast as it can, until told."""
    real, link, spare = os.path.join(root, "urdf"), os.path.join(root, "urdf.link"), os.path.join(root, "urdf.real")
    os.symlink(outside, link)
    while not stop.is_set():
        os.rename(real, spare)
        os.rename(link, real)  # now a link out
        os.rename(real, link)
        os.rename(spare, real)  # the folder back


def racing(root, outside):  # type: ignore[no-untyped-def]
    context = multiprocessing.get_context("fork")
    stop = context.Event()
    process = context.Process(target=_flip, args=(str(root), str(outside), stop), daemon=True)
    process.start()
    return stop, process


def test_a_folder_swapped_for_a_link_while_reading_never_reads_outside(tree, way):
    root, outside = tree
    stop, process = racing(root, outside)
    seen = {"read": 0, "refused": 0}
    try:
        deadline = time.monotonic() + 4
        while time.monotonic() < deadline:
            try:
                text = read_text(str(root / "urdf" / "bras.urdf"), (str(root),))
            except Unreadable as exc:
                assert CANARY not in str(exc)
                seen["refused"] += 1
                continue
            assert text == "<robot name='bras'/>", "the canary outside the package was read"
            seen["read"] += 1
    finally:
        stop.set()
        process.join(5)
    assert seen["read"] > 10 and seen["refused"] > 10, seen  # the race was run, both ways
