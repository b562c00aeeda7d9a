"""The robot's own files read through the one reader (issue 53): what a learner's robot includes
(xacro includes, ``load_yaml``), the meshes it names and the files those name (an OBJ's
material file), the package's robot as validate, grade and launch read it, and the folders of
a workspace are reached beneath the learner's folders, component by component, never through
a link out of them; a folder swapped for a link while the robot loads reads nothing outside.

Oracles: a canary written here outside the learner's folders (its bytes must appear in no
output and no model), the kernel's FIFOs (a read that waits hangs the test's timeout), and a
real racing process (multiprocessing, flipping a folder and a link as fast as it can).
"""

from __future__ import annotations

import multiprocessing
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

CANARY = "CANARYe7a1"
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def bras_kit(*args: str, cwd: Path, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"}
    return subprocess.run([sys.executable, "-m", "bras_kit", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=timeout, stdin=subprocess.DEVNULL)


def outside_part(folder: Path) -> Path:
    """A xacro part whose joint names the canary (validate quotes a joint's missing parent)."""
    folder.mkdir(parents=True, exist_ok=True)
    part = folder / "part.xacro"
    part.write_text(f'<robot {XACRO_NS}><joint name="{CANARY}_j" type="fixed"><parent link="{CANARY}"/>'
                    '<child link="base"/></joint></robot>')
    return part


def robot_including(folder: Path, include: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    main = folder / "robot.urdf.xacro"
    main.write_text(f'<robot name="r" {XACRO_NS}><link name="base"/><xacro:include filename="{include}"/></robot>')
    return main


# each way an include leaves the learner's folder: a relative climb, an absolute path, a folder
# on the way that is a link out, the included file itself a link out
def climb(sub: Path, outside: Path) -> str:
    return os.path.relpath(outside / "part.xacro", sub / "urdf")


def absolute(sub: Path, outside: Path) -> str:
    return str(outside / "part.xacro")


def linked_folder(sub: Path, outside: Path) -> str:
    (sub / "urdf" / "parts").symlink_to(outside, target_is_directory=True)
    return "parts/part.xacro"


def linked_file(sub: Path, outside: Path) -> str:
    (sub / "urdf" / "part.xacro").symlink_to(outside / "part.xacro")
    return "part.xacro"


WAYS_OUT = [climb, absolute, linked_folder, linked_file]


@pytest.mark.parametrize("way", WAYS_OUT)
def test_an_include_out_of_the_learners_folder_is_refused_when_read_beneath_it(tmp_path, way):
    from bras_kit.core.errors import BrasKitError
    from bras_kit.model.authoring import load

    outside = tmp_path / "outside"
    outside_part(outside)
    sub = tmp_path / "eleve"
    (sub / "urdf").mkdir(parents=True)
    main = robot_including(sub / "urdf", way(sub, outside))
    with pytest.raises(BrasKitError) as caught:
        load(str(main), roots=(str(sub),))
    assert CANARY not in str(caught.value.message) and "part.xacro" in str(caught.value.message)
    # the same file named by its user is read as xacro reads it (the include anywhere): the canary's joint
    assert any(j.name == f"{CANARY}_j" for j in load(str(main)).joints)


@pytest.mark.parametrize("way", WAYS_OUT)
def test_grade_reads_no_include_out_of_a_submission(tmp_path, way):
    outside = tmp_path / "outside"
    outside_part(outside)
    sub = tmp_path / "subs" / "alice"
    (sub / "urdf").mkdir(parents=True)
    robot_including(sub / "urdf", way(sub, outside))
    done = bras_kit("grade", str(tmp_path / "subs"), "-o", str(tmp_path / "report"), cwd=tmp_path)
    assert "Traceback" not in done.stderr, done.stderr
    assert CANARY not in done.stdout + done.stderr
    for path in (tmp_path / "report").rglob("*"):
        if path.is_file():
            assert CANARY.encode() not in path.read_bytes(), path


@pytest.mark.parametrize("way", WAYS_OUT)
def test_validate_of_a_folder_reads_no_include_out_of_it(tmp_path, way):
    outside = tmp_path / "outside"
    outside_part(outside)
    sub = tmp_path / "mine"
    (sub / "urdf").mkdir(parents=True)
    robot_including(sub / "urdf", way(sub, outside))
    done = bras_kit("validate", str(sub), cwd=tmp_path)
    assert "Traceback" not in done.stderr, done.stderr
    assert CANARY not in done.stdout + done.stderr, done.stdout
    assert done.returncode != 0  # the refusal is said (BK10x), never a robot passed over in silence


def test_a_urdf_in_a_folder_that_is_a_link_out_is_read_only_when_named_itself(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "x.urdf").write_text(f'<robot name="r"><link name="a"/><joint name="j" type="fixed">'
                                    f'<parent link="a"/><child link="{CANARY}"/></joint></robot>')
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "ok.urdf").write_text('<robot name="ok"><link name="base"/></robot>')
    (mine / "x.urdf").symlink_to(outside / "x.urdf")
    done = bras_kit("validate", str(mine), cwd=tmp_path)
    assert CANARY not in done.stdout + done.stderr and done.returncode != 0, done.stdout
    named = bras_kit("validate", str(mine / "x.urdf"), cwd=tmp_path)  # the user's own choice of file
    assert CANARY in named.stdout + named.stderr


# ---------------------------------------------------------------- meshes


STL = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n"


def package_with_mesh(tmp_path: Path, mesh: str) -> Path:
    root = tmp_path / "ws" / "src" / "pkg"
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text("<package format='3'><name>pkg</name></package>")
    (root / "urdf" / "r.urdf").write_text(f'<robot name="r"><link name="base"><visual><geometry>'
                                          f'<mesh filename="{mesh}"/></geometry></visual></link></robot>')
    return root


@pytest.mark.parametrize("mesh", ["package://pkg/meshes/m.stl", "file://OUTSIDE/m.stl", "../meshes/m.stl"])
def test_a_mesh_out_of_the_package_is_refused_for_a_learners_robot(tmp_path, mesh):
    from bras_kit.core.errors import ModelError
    from bras_kit.model.authoring import load
    from bras_kit.render.scene import resolve_mesh_path

    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "m.stl").write_bytes(STL)
    root = package_with_mesh(tmp_path, mesh.replace("OUTSIDE", str(outside)))
    (root / "meshes").symlink_to(outside, target_is_directory=True)
    urdf = str(root / "urdf" / "r.urdf")
    learner = load(urdf, roots=(str(root),))
    with pytest.raises(ModelError) as caught:
        resolve_mesh_path(learner.links[0].visuals[0].geometry.filename, learner)
    assert "refused" in str(caught.value.message)
    own = load(urdf)  # the user's own robot: any regular file, as RViz reads it
    assert os.path.samefile(resolve_mesh_path(own.links[0].visuals[0].geometry.filename, own), outside / "m.stl")


def test_an_objs_material_file_is_read_beneath_the_learners_folder(tmp_path):
    """An OBJ's ``mtllib`` through a folder linked out: the outside colour never reaches the
    learner's robot; inside the package the same file gives its colour (trimesh's own reading)."""
    from bras_kit.meshes import load_mesh, set_disk_cache

    set_disk_cache(False)
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "m.mtl").write_text("newmtl rouge\nKd 0.9 0.1 0.1\n")
    root = tmp_path / "pkg"
    (root / "meshes").mkdir(parents=True)
    obj = "mtllib {}\nusemtl rouge\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    (root / "meshes" / "linked.obj").write_text(obj.format("mats/m.mtl"))
    (root / "meshes" / "mats").symlink_to(outside, target_is_directory=True)
    (root / "meshes" / "own").mkdir()
    (root / "meshes" / "own" / "m.mtl").write_text("newmtl rouge\nKd 0.1 0.8 0.1\n")
    (root / "meshes" / "inside.obj").write_text(obj.format("own/m.mtl"))
    linked = load_mesh(str(root / "meshes" / "linked.obj"), roots=(str(root),))
    assert all(p.color is None or abs(p.color[0] - 0.9) > 0.2 for p in linked.pieces())
    inside = load_mesh(str(root / "meshes" / "inside.obj"), roots=(str(root),))
    assert [tuple(round(c, 2) for c in p.color[:3]) for p in inside.pieces()] == [(0.1, 0.8, 0.1)]


def test_a_mesh_that_is_a_fifo_is_refused_without_waiting(tmp_path):
    os.mkfifo(tmp_path / "m.stl")
    done = subprocess.run([sys.executable, "-c", "import sys\nfrom bras_kit.meshes import DecodeError, load_mesh\n"
                           "try:\n    load_mesh(sys.argv[1])\nexcept DecodeError as exc:\n    print('refused', exc)",
                           str(tmp_path / "m.stl")], capture_output=True, text=True, timeout=20)
    assert done.stdout.startswith("refused"), done


# ---------------------------------------------------------------- the package's robot, raced


def _flip(folder: str, outside: str, stop) -> None:  # type: ignore[no-untyped-def]
    real, link, spare = folder, folder + ".link", folder + ".real"
    os.symlink(outside, link)
    while not stop.is_set():
        os.rename(real, spare)
        os.rename(link, real)
        os.rename(real, link)
        os.rename(spare, real)


@pytest.fixture(scope="module")
def made(tmp_path_factory) -> Path:
    base = tmp_path_factory.mktemp("made")
    done = bras_kit("new", str(base / "ws" / "src" / "bras_description"), cwd=base)
    assert done.returncode == 0, done
    return base / "ws" / "src" / "bras_description"


@pytest.mark.slow
def test_the_packages_robot_never_holds_the_outside_file_while_its_folder_is_swapped(made, tmp_path):
    """Package.robot (validate's rules, run's robot, the exercises) while a process flips urdf/
    and a link out as fast as it can: the robot is the package's, or none, never the outside one."""
    import shutil

    from bras_kit.ros.package import Package

    root = tmp_path / "ws" / "src" / "bras_description"
    shutil.copytree(made, root, symlinks=True)
    outside = tmp_path / "outside"
    outside.mkdir()
    urdf = (root / "urdf" / "bras.urdf").read_text()
    (outside / "bras.urdf").write_text(urdf.replace('name="base"', f'name="{CANARY}"'))
    context = multiprocessing.get_context("fork")
    stop = context.Event()
    racer = context.Process(target=_flip, args=(str(root / "urdf"), str(outside), stop), daemon=True)
    racer.start()
    robots = tries = 0
    try:
        deadline = time.monotonic() + 6
        while time.monotonic() < deadline:
            tries += 1
            robot = Package(str(root)).robot
            if robot is not None:
                robots += 1
                assert CANARY not in robot.link_names, tries
    finally:
        stop.set()
        racer.join(10)
    assert robots > 5, (robots, tries)  # the race was run, and the package's robot read


# ---------------------------------------------------------------- folders walked for a workspace and a watch


def test_a_workspace_crawl_follows_links_inside_src_only_and_waits_on_no_pipe(tmp_path):
    from bras_kit.ros.workspace import read_packages

    src = tmp_path / "ws" / "src"
    (src / "a").mkdir(parents=True)
    (src / "a" / "package.xml").write_text("<package format='3'><name>a</name></package>")
    (src / "lien_a").symlink_to(src / "a", target_is_directory=True)  # the same package: found once
    (src / "fifo_pkg").mkdir()
    os.mkfifo(src / "fifo_pkg" / "package.xml")
    outside = tmp_path / "dehors" / "b"
    outside.mkdir(parents=True)
    (outside / "package.xml").write_text(f"<package format='3'><name>{CANARY}</name></package>")
    (src / "b").symlink_to(outside, target_is_directory=True)
    found = subprocess.run([sys.executable, "-c", "import sys; from bras_kit.ros.workspace import read_packages; "
                            "print([p.name for p in read_packages(sys.argv[1])])", str(src)],
                           capture_output=True, text=True, timeout=20)
    assert found.returncode == 0, found.stderr
    assert found.stdout.strip() == "['a', 'fifo_pkg']"  # the pipe's package keeps its folder's name, unread
    assert CANARY not in found.stdout and read_packages(str(src))[0].folder == str(src / "a")


def test_the_watch_list_waits_on_no_included_pipe(tmp_path):
    os.mkfifo(tmp_path / "part.xacro")
    main = robot_including(tmp_path / "urdf", "../part.xacro")
    os.mkfifo(tmp_path / "urdf" / "other.urdf")  # a pipe beside it, named like a robot file
    found = subprocess.run([sys.executable, "-c", "import sys; from bras_kit.view.watch import watched_files; "
                            "print(watched_files(sys.argv[1]))", str(main)],
                           capture_output=True, text=True, timeout=20)
    assert found.returncode == 0, found.stderr
    assert str(main) in found.stdout and "other.urdf" not in found.stdout


# ---------------------------------------------------------------- the exercise track


@pytest.mark.parametrize("way", ["linked_folder", "climb"])
def test_an_exercise_reads_no_include_out_of_the_track(tmp_path, way):
    """The track is learner data: exercise 13's xacro including a part through a link out of
    the track, or by climbing out of it, is refused; the part's canary is shown nowhere."""
    track = tmp_path / "work"
    assert bras_kit("exercises", "init", str(track), cwd=tmp_path).returncode == 0
    outside = tmp_path / "outside"
    outside_part(outside)
    folder = track / "13-xacro"
    main = folder / "bras.urdf.xacro"
    if way == "linked_folder":
        (folder / "parts").symlink_to(outside, target_is_directory=True)
        include = "parts/part.xacro"
    else:
        include = os.path.relpath(outside / "part.xacro", folder)
    main.write_text(main.read_text().replace("</robot>", f'<xacro:include filename="{include}"/></robot>'))
    done = bras_kit("exercises", "check", "13", "--dir", str(track), cwd=tmp_path)
    assert "Traceback" not in done.stderr, done.stderr
    assert CANARY not in done.stdout + done.stderr, done.stdout
    assert "refused to read" in done.stdout + done.stderr, done.stdout


@pytest.mark.slow
def test_an_include_and_a_mesh_never_read_outside_while_their_folder_is_swapped(tmp_path):
    """A process flips urdf/parts (holding the include), urdf/cfg (a load_yaml file) and meshes/
    with links out as fast as it can while a learner's robot loads and its mesh is read, for 4 s
    each: what is read is the package's, or refused, never the outside one."""
    from bras_kit.core.errors import BrasKitError
    from bras_kit.meshes import DecodeError, load_mesh, set_disk_cache
    from bras_kit.model.authoring import load

    set_disk_cache(False)
    root = tmp_path / "pkg"
    (root / "urdf" / "parts").mkdir(parents=True)
    (root / "urdf" / "parts" / "part.xacro").write_text(
        f'<robot {XACRO_NS}><link name="own"/><joint name="j" type="fixed"><parent link="base"/>'
        '<child link="own"/></joint></robot>')
    main = robot_including(root / "urdf", "parts/part.xacro")
    outside = tmp_path / "outside"
    outside_part(outside)
    (root / "meshes").mkdir()
    (root / "meshes" / "m.stl").write_bytes(STL)
    (outside / "m.stl").write_bytes(STL.replace(b"vertex 1 0 0", b"vertex 7 7 7"))
    (root / "urdf" / "cfg").mkdir()
    (root / "urdf" / "cfg" / "v.yaml").write_text("n: own\n")
    (outside / "v.yaml").write_text(f"n: {CANARY}\n")
    yamled = root / "urdf" / "y.urdf.xacro"
    yamled.write_text(f'<robot name="r" {XACRO_NS}><xacro:property name="y" value="${{xacro.load_yaml(\'cfg/v.yaml\')}}"/>'
                      '<link name="${y.n}"/></robot>')
    context = multiprocessing.get_context("fork")
    for folder, attempt in ((root / "urdf" / "parts", lambda: [j.name for j in load(str(main), roots=(str(root),)).joints]),
                            (root / "urdf" / "cfg", lambda: ["j"] if [lk.name for lk in load(
                                str(yamled), roots=(str(root),)).links] == ["own"] else ["outside"]),
                            (root / "meshes", lambda: load_mesh(str(root / "meshes" / "m.stl"), roots=(str(root),))
                             .vertices.max())):
        stop = context.Event()
        racer = context.Process(target=_flip, args=(str(folder), str(outside), stop), daemon=True)
        racer.start()
        read = 0
        try:
            deadline = time.monotonic() + 4
            while time.monotonic() < deadline:
                try:
                    got = attempt()
                except (BrasKitError, DecodeError):
                    continue
                read += 1
                assert got == ["j"] or got == 1.0, got
        finally:
            stop.set()
            racer.join(10)
        assert read > 5, (folder, read)


def test_a_mesh_remembered_for_one_robot_is_not_given_to_a_learner_linking_to_it(tmp_path):
    """grade draws a class in one process: a mesh file decoded once (another learner's, the
    teacher's) is remembered by its path; a learner's link to that path is still read through
    the reader, and refused, never answered from the memory."""
    from bras_kit.meshes import DecodeError, load_mesh, set_disk_cache

    set_disk_cache(False)
    other = tmp_path / "autre" / "m.stl"
    other.parent.mkdir()
    other.write_bytes(STL)
    assert len(load_mesh(str(other)).faces) == 1  # decoded, remembered
    learner = tmp_path / "eleve"
    (learner / "meshes").mkdir(parents=True)
    (learner / "meshes" / "m.stl").symlink_to(other)
    with pytest.raises(DecodeError):
        load_mesh(str(learner / "meshes" / "m.stl"), roots=(str(learner),))


def test_a_one_file_submission_includes_nothing_of_another_learner(tmp_path):
    """alice.urdf.xacro handed in alone sits in the class folder beside bob/: its include of
    bob/urdf/part.xacro is refused (it is judged alone, from a copy in a folder of its own), and
    bob's part appears nowhere in alice's row or page; bob is graded as before."""
    klass = tmp_path / "class"
    outside_part(klass / "bob" / "urdf")
    (klass / "alice.urdf.xacro").write_text(
        f'<robot name="r" {XACRO_NS}><link name="base"/><xacro:include filename="bob/urdf/part.xacro"/></robot>')
    done = bras_kit("grade", str(klass), "-o", str(tmp_path / "report"), cwd=tmp_path)
    assert "Traceback" not in done.stderr, done.stderr
    import csv

    with open(tmp_path / "report" / "grades.csv", encoding="utf-8", newline="") as handle:
        rows = {row[0]: row for row in csv.reader(handle)}
    assert set(rows) >= {"alice", "bob"}
    assert CANARY not in ",".join(rows["alice"]), rows["alice"]
    assert f"no such file: {klass}/bob/urdf/part.xacro" in rows["alice"][-1], rows["alice"]  # as if alone
    assert CANARY.encode() not in (tmp_path / "report" / "learners" / "alice.html").read_bytes()
