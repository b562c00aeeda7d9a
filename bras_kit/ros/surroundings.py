"""What a learner's workspace, shell and machine got wrong, found without ROS 2: ``bras-kit doctor``.

Each check reads files and environment variables and returns :class:`Concern` data; the doctor
words them. The rules rest on the tools' own sources:

- the workspace: colcon's install tree (a package's files under ``install/PKG``), its markers
  (colcon-core ``verb/__init__.py`` lines 67-110: ``build/.built_by``, ``install/.colcon_install_layout``;
  ``location.py`` lines 157-205: ``log/COLCON_IGNORE`` and ``log/latest``), the package.xml name;
- the shell: ``ament_index_python`` 1.8.1 (``resources.py`` lines 58-91, ``search_paths.py`` lines
  21-33): a package is looked for in each prefix of AMENT_PREFIX_PATH in order, the first one
  holding ``share/ament_index/resource_index/packages/PKG`` wins;
- the machine: rmw_implementation and rcutils (Jazzy: which rmw library loads, see
  :func:`rmw_library`), rcl 9.2.0 (Jazzy) ``init.c`` lines 156-200 and ``localhost.c`` lines 27-52
  (ROS_LOCALHOST_ONLY), ``discovery_options.c`` lines 43-86 and 110-181 (the discovery range, the
  static peers), ``domain_id.c`` (through :func:`bras_kit.ros.bus.domain_id`), and Fast DDS
  v2.14.6, ``SharedMemTransport.cpp`` line 57 (a 512 KiB segment per participant) and
  ``RTPSParticipantImpl.cpp`` lines 562-568 ("Unable to Register SHM Transport").
"""

from __future__ import annotations

import glob
import os
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

from ..core.message import M, Message, Mn
from .workspace import Workspace

OK, NOTE, FAIL = "ok", "note", "fail"
INDEX = os.path.join("share", "ament_index", "resource_index", "packages")
# rcl 9.2.0 init.c lines 171-176, 188-194 and 196-200; discovery_options.c lines 77-81 and 153-157
RCL_LOCALHOST_DEPRECATED = ("ROS_LOCALHOST_ONLY is deprecated but still honored if it is enabled. "
                            "Use ROS_AUTOMATIC_DISCOVERY_RANGE and ROS_STATIC_PEERS instead.")
RCL_LOCALHOST_WINS = "'localhost_only' is enabled, 'automatic_discovery_range' and 'static_peers' will be ignored."
RCL_LOCALHOST_OFF = "'localhost_only' is disabled, 'automatic_discovery_range' and 'static_peers' will be used."
RCL_INVALID_RANGE = "Invalid value '{value}' specified for 'ROS_AUTOMATIC_DISCOVERY_RANGE', assuming localhost only"
RCL_PEER_TOO_LONG = "Static peer {peer} specified to 'ROS_STATIC_PEERS' is too long (maximum of {maximum}); skipping"
RANGES = ("OFF", "LOCALHOST", "SUBNET", "SYSTEM_DEFAULT")  # discovery_options.c lines 62-76; "" is SUBNET
STATIC_PEER_MAX = 256 - 1  # rmw discovery_options.h: RMW_DISCOVERY_OPTIONS_STATIC_PEERS_MAX_LENGTH 256, less the NUL
# Fast DDS v2.14.6 RTPSParticipantImpl.cpp lines 566-568
FASTDDS_SHM_FAILED = "Unable to Register SHM Transport. SHM Transport is not supported in the current platform."
SHM_SEGMENT = 512 * 1024  # SharedMemTransport.cpp line 57: each participant's segment
# the tutorial's launch (robot_state_publisher, joint_state_publisher_gui, rviz2), the learner's node and
# the ros2 daemon: one participant each (rmw_fastrtps makes one per context)
TUTORIAL_PARTICIPANTS = 5
FASTDDS_RMWS = ("", "rmw_fastrtps_cpp", "rmw_fastrtps_dynamic_cpp")  # "" is Jazzy's default, Fast DDS
COLCON_GENERATED = ("package.bash", "package.dsv", "package.ps1", "package.sh", "package.zsh",
                    "local_setup.bash", "local_setup.dsv", "local_setup.ps1", "local_setup.sh", "local_setup.zsh")
SHOWN_FILES = 3
OSRELEASE = "/proc/sys/kernel/osrelease"


@dataclass(frozen=True)
class Concern:
    """One thing found. ``area``: workspace, shell or machine; ``status``: ok, note or fail."""

    area: str
    status: str
    name: Message
    found: Message | str
    fix: Message | str | None = None


def _environ(environ: Mapping[str, str] | None) -> Mapping[str, str]:
    return os.environ if environ is None else environ


def _prefixes(environ: Mapping[str, str]) -> list[str]:
    """AMENT_PREFIX_PATH as ament_index_python splits it (search_paths.py line 33), empty parts left out."""
    return [os.path.normpath(p) for p in environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]


def _when(seconds: float) -> str:
    return time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(seconds))


# ---------------------------------------------------------------- the workspace


def package_prefix(workspace: Workspace, name: str) -> str:
    """Where colcon installs ``name``: install/NAME (isolated, the default) or install/ (merged)."""
    layout = os.path.join(workspace.install, ".colcon_install_layout")
    try:
        with open(layout, encoding="utf-8") as file:
            merged = file.read().strip() == "merged"
    except OSError:
        merged = False
    return workspace.install if merged else os.path.join(workspace.install, name)


def _installed_pairs(workspace: Workspace, folder: str, name: str) -> Iterator[tuple[str, str]]:
    """(installed file, its source): each data_files entry of setup.py (read statically, as the
    package rules read it: a file lands in DESTINATION under its own name, setuptools'
    install_data), then the files of share/NAME that have a source at the same place in the
    package, and the Python modules."""
    prefix = package_prefix(workspace, name)
    yield from _data_files_pairs(prefix, folder)
    share = os.path.join(prefix, "share", name)
    for here, dirs, files in os.walk(share):
        rel_dir = os.path.relpath(here, share)
        if rel_dir.split(os.sep)[0] in ("hook", "environment"):
            dirs[:] = []
            continue
        for file in sorted(files):
            if rel_dir == "." and file in COLCON_GENERATED:
                continue
            yield os.path.join(here, file), os.path.normpath(os.path.join(folder, rel_dir, file))
    for site in sorted(glob.glob(os.path.join(glob.escape(prefix), "lib", "python3*", "*-packages"))):
        for here, dirs, files in os.walk(site):
            dirs[:] = [d for d in dirs if d != "__pycache__" and not d.endswith(".egg-info")]
            rel_dir = os.path.relpath(here, site)
            if rel_dir == ".":
                continue
            for file in sorted(f for f in files if f.endswith(".py")):
                yield os.path.join(here, file), os.path.join(folder, rel_dir, file)


def _data_files_pairs(prefix: str, folder: str) -> Iterator[tuple[str, str]]:
    from .package import Package

    setup = Package(folder).setup
    for entry in (setup.data_files or []) if setup is not None else []:
        if os.path.isabs(entry.destination):
            continue
        for source in entry.sources:
            yield (os.path.normpath(os.path.join(prefix, entry.destination, os.path.basename(source))),
                   os.path.normpath(os.path.join(folder, source)))


def _differs(installed: str, source: str) -> bool:
    try:
        with open(installed, "rb") as a, open(source, "rb") as b:
            return a.read() != b.read()
    except OSError:
        return False


def stale_copies(workspace: Workspace, name: str, folder: str) -> list[tuple[str, str, float, float]]:
    """(source relative to the root, installed file, source's mtime, installed's mtime) of each
    installed copy that differs from its source. A link (``--symlink-install``) is never stale."""
    out, seen = [], set()
    for installed, source in _installed_pairs(workspace, folder, name):
        if installed in seen:
            continue
        seen.add(installed)
        if os.path.islink(installed) or not os.path.isfile(source) or os.path.islink(source):
            continue
        if _differs(installed, source):
            out.append((os.path.relpath(source, workspace.root), installed, os.path.getmtime(source),
                        os.path.getmtime(installed)))
    return out


def workspace_concerns(workspace: Workspace) -> list[Concern]:
    """What is wrong in ``workspace``: stale installed copies, a package not built, a folder named
    unlike its package, colcon's folders under src/."""
    concerns: list[Concern] = []
    built_any = os.path.isdir(workspace.install)
    for package in workspace.packages:
        folder_name = os.path.basename(package.folder)
        shown = os.path.relpath(package.folder, workspace.root)
        if folder_name != package.name:
            concerns.append(Concern("workspace", NOTE, M("package folder"), M(
                "{folder} holds the package '{name}' (package.xml's <name>): colcon, ros2 run and ros2 launch "
                "know it only by that name", folder=shown, name=package.name),
                M("type '{name}' in ros2 launch and ros2 run, or rename the folder to {name} to avoid the "
                  "confusion", name=package.name)))
        if not built_any:
            continue
        prefix = package_prefix(workspace, package.name)
        if not os.path.isdir(os.path.join(prefix, "share", package.name)):
            concerns.append(Concern("workspace", NOTE, M("installed copy"), M(
                "{name} is in src/ but not in install/: it was never built", name=package.name),
                M("build it: colcon build --packages-select {name}, then source install/setup.bash",
                  name=package.name)))
            continue
        stale = stale_copies(workspace, package.name, package.folder)
        if stale:
            newest = max(stale, key=lambda s: s[2])
            files = [s[0] for s in stale]
            concerns.append(Concern("workspace", FAIL, M("installed copy"), Mn(
                "{files} changed since the build of {name} (edited {edited}, built {built}): ros2 launch still "
                "reads the old copy in install/",
                "{files} changed since the build of {name} (last edited {edited}, built {built}): ros2 launch "
                "still reads the old copies in install/",
                len(files), files=files[:SHOWN_FILES] + ([f"+{len(files) - SHOWN_FILES}"]
                                                          if len(files) > SHOWN_FILES else []),
                name=package.name, edited=_when(newest[2]), built=_when(newest[3])),
                M("rebuild: colcon build --packages-select {name}, then source install/setup.bash again "
                  "(or build once with --symlink-install)", name=package.name)))
    concerns += _colcon_inside_src(workspace)
    return concerns


def _colcon_folders(folder: str) -> list[str]:
    """colcon's own folders in ``folder``: build/ (.built_by), install/ (.colcon_install_layout,
    setup.bash), log/ (COLCON_IGNORE, latest)."""
    markers = {"build": (".built_by",), "install": (".colcon_install_layout", "setup.bash"),
               "log": ("COLCON_IGNORE", "latest")}
    found = []
    for name, names in markers.items():
        inside = os.path.join(folder, name)
        if os.path.isdir(inside) and not os.path.islink(inside) and \
                any(os.path.lexists(os.path.join(inside, marker)) for marker in names):
            found.append(name)
    return found


def _colcon_inside_src(workspace: Workspace) -> list[Concern]:
    """build/, install/ or log/ of a colcon run in src/ or in a package folder."""
    places = [workspace.src] + [p.folder for p in workspace.packages]
    for here, dirs, _ in os.walk(workspace.src):  # and the folders between (src/groupe/...)
        depth = os.path.relpath(here, workspace.src).count(os.sep)
        dirs[:] = [d for d in dirs if not d.startswith(".") and d not in ("build", "install", "log")]
        if depth >= 2:
            dirs[:] = []
        if here not in places:
            places.append(here)
    concerns = []
    for place in places:
        found = _colcon_folders(place)
        if found:
            shown = os.path.relpath(place, workspace.root)
            concerns.append(Concern("workspace", FAIL, M("colcon's folders"), M(
                "{folders} in {place}: colcon build was run there, not at the workspace's root {root}",
                folders=[f"{name}/" for name in found], place=shown, root=workspace.root),
                M("remove them (rm -r {paths}), then type colcon build in {root}",
                  paths=" ".join(os.path.join(shown, name) for name in found), root=workspace.root)))
    return concerns


# ---------------------------------------------------------------- the shell


def shell_concerns(workspace: Workspace, environ: Mapping[str, str] | None = None) -> list[Concern]:
    """Is this workspace's install/ sourced in this shell, and does another prefix hide it?"""
    env = _environ(environ)
    built = [p.name for p in workspace.packages
             if os.path.isdir(os.path.join(package_prefix(workspace, p.name), "share", p.name))]
    if not built:
        return []
    prefixes = _prefixes(env)
    source_line = f"source {os.path.join(workspace.install, 'setup.bash')}"
    ours = {name: os.path.normpath(package_prefix(workspace, name)) for name in built}
    missing = [name for name, prefix in ours.items() if prefix not in prefixes]
    concerns = []
    if len(missing) == len(built):
        concerns.append(Concern("shell", FAIL, M("sourced"), M(
            "this terminal never sourced {install}: ros2 does not see {names}", install=workspace.install,
            names=missing), M("type: {line}", line=source_line)))
    elif missing:
        concerns.append(Concern("shell", FAIL, M("sourced"), M(
            "{names} built after this terminal sourced {install}: ros2 does not see them yet",
            install=workspace.install, names=missing), M("type again: {line}", line=source_line)))
    for name, prefix in ours.items():
        if prefix not in prefixes:
            continue
        earlier = [p for p in prefixes[:prefixes.index(prefix)] if os.path.isfile(os.path.join(p, INDEX, name))]
        if earlier:
            concerns.append(Concern("shell", FAIL, M("sourced"), M(
                "{name} is found first in {other}, earlier on AMENT_PREFIX_PATH than this workspace: ros2 "
                "launch and ros2 run use that copy", name=name, other=earlier[0]),
                M("open a new terminal and source only this workspace (remove the other one's source line "
                  "from ~/.bashrc if it is there): {line}", line=source_line)))
    if not concerns:
        concerns.append(Concern("shell", OK, M("sourced"), M("{install} is sourced in this terminal",
                                                            install=workspace.install)))
    return concerns


# ---------------------------------------------------------------- the machine


def localhost_only(environ: Mapping[str, str]) -> str | None:
    """ROS_LOCALHOST_ONLY as rcl reads it (localhost.c lines 45-50): None when unset or empty,
    "enabled" when it starts with 1, else "disabled"."""
    value = environ.get("ROS_LOCALHOST_ONLY", "")
    if value == "":
        return None
    return "enabled" if value.startswith("1") else "disabled"


def discovery_range(environ: Mapping[str, str]) -> tuple[str, bool]:
    """(the range rcl uses, whether rcl warns that the value is invalid): discovery_options.c
    lines 62-84, and init.c lines 188-194 (ROS_LOCALHOST_ONLY=1 forces LOCALHOST)."""
    if localhost_only(environ) == "enabled":
        return "LOCALHOST", False
    value = environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE", "")
    if value == "":
        return "SUBNET", False
    if value in RANGES:
        return value, False
    return "LOCALHOST", True


def static_peers(environ: Mapping[str, str]) -> tuple[list[str], list[str]]:
    """(the peers rcl keeps, those it skips as too long): the value split at ';' (rcutils_split
    leaves empty parts out), discovery_options.c lines 139-158; none with ROS_LOCALHOST_ONLY=1."""
    parts = [p for p in environ.get("ROS_STATIC_PEERS", "").split(";") if p]
    if localhost_only(environ) == "enabled":
        return [], []
    return [p for p in parts if len(p) <= STATIC_PEER_MAX], [p for p in parts if len(p) > STATIC_PEER_MAX]


def discovery_concerns(environ: Mapping[str, str] | None = None) -> list[Concern]:
    env = _environ(environ)
    concerns = []
    from ..core.errors import ParameterError
    from .bus import domain_id

    try:
        concerns.append(Concern("machine", OK, M("ROS_DOMAIN_ID"), M("domain {domain}", domain=domain_id(env))))
    except ParameterError as exc:
        concerns.append(Concern("machine", FAIL, M("ROS_DOMAIN_ID"), exc.message, exc.hint))
    only = localhost_only(env)
    if only is not None:
        words = RCL_LOCALHOST_DEPRECATED + " " + (RCL_LOCALHOST_WINS if only == "enabled" else RCL_LOCALHOST_OFF)
        concerns.append(Concern("machine", NOTE, M("ROS_LOCALHOST_ONLY"), M(
            "ROS_LOCALHOST_ONLY={value} is deprecated since Iron; every node started here prints rcl's warning: "
            "{words}", value=env.get("ROS_LOCALHOST_ONLY", ""), words=words),
            M("type: unset ROS_LOCALHOST_ONLY && export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (and remove it "
              "from ~/.bashrc)") if only == "enabled" else M("type: unset ROS_LOCALHOST_ONLY")))
    used, invalid = discovery_range(env)
    given = env.get("ROS_AUTOMATIC_DISCOVERY_RANGE", "")
    if invalid:
        concerns.append(Concern("machine", NOTE, M("discovery range"), M(
            "ROS_AUTOMATIC_DISCOVERY_RANGE={value} is not a range rcl knows; it warns {words}",
            value=given, words=RCL_INVALID_RANGE.format(value=given)),
            M("write one of {ranges}, e.g. export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST", ranges=list(RANGES))))
    elif used == "OFF":
        concerns.append(Concern("machine", NOTE, M("discovery range"), M(
            "ROS_AUTOMATIC_DISCOVERY_RANGE=OFF: nodes started here look for no other node by themselves "
            "(only ROS_STATIC_PEERS): RViz will not see robot_state_publisher"),
            M("type: export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (or unset it)")))
    else:
        concerns.append(Concern("machine", OK, M("discovery range"), M("{range}", range=used)))
    kept, skipped = static_peers(env)
    if env.get("ROS_STATIC_PEERS", "") and only == "enabled":
        concerns.append(Concern("machine", NOTE, M("ROS_STATIC_PEERS"), M(
            "ROS_STATIC_PEERS is ignored while ROS_LOCALHOST_ONLY=1 (rcl: {words})", words=RCL_LOCALHOST_WINS),
            M("type: unset ROS_LOCALHOST_ONLY")))
    for peer in skipped:  # rcl's loop leaves the skipped peer's slot empty (discovery_options.c lines 145-158),
        # and rmw_fastrtps refuses the empty peer: the node is never made (seen with the real rclpy of Jazzy)
        concerns.append(Concern("machine", FAIL, M("ROS_STATIC_PEERS"), M(
            "rcl skips a peer: {words}; its empty place is left in the list, and every node started here fails "
            "to start", words=RCL_PEER_TOO_LONG.format(peer=peer[:40] + "...", maximum=STATIC_PEER_MAX)),
            M("give each peer as an address or host name, separated by ';'")))
    if kept:
        concerns.append(Concern("machine", OK, M("ROS_STATIC_PEERS"), M("{peers}", peers=kept)))
    return concerns


# rmw_implementation (jazzy) src/functions.cpp, load_library, lines 74-128: RMW_IMPLEMENTATION names the
# one library loaded (lines 95-98), else the default rmw_fastrtps_cpp (line 103), else each package of the
# ament index's rmw_typesupport resource in turn (lines 111-121); attempt_to_load_one_rmw (lines 48-72)
# loads rcpputils::get_platform_library_name(NAME), lib<NAME>.so, which rcutils (jazzy) src/shared_library.c
# hands to dlopen as it is (lines 87-97): the dynamic linker looks in LD_LIBRARY_PATH's folders in order,
# then in the system's, never in a prefix's lib/ that LD_LIBRARY_PATH does not name
DEFAULT_RMW = "rmw_fastrtps_cpp"
RMW_TYPESUPPORT = os.path.join("share", "ament_index", "resource_index", "rmw_typesupport")
SYSTEM_LIBRARY_FOLDERS = ("/lib/x86_64-linux-gnu", "/usr/lib/x86_64-linux-gnu", "/lib/aarch64-linux-gnu",
                          "/usr/lib/aarch64-linux-gnu", "/lib64", "/usr/lib64", "/lib", "/usr/lib")


def _system_library_folders(conf: str = "/etc/ld.so.conf") -> list[str]:
    """The folders ld.so.conf names (ldconfig's cache is made from them), then the trusted defaults."""
    folders: list[str] = []

    def read(path: str, depth: int = 0) -> None:
        try:
            with open(path, encoding="utf-8", errors="replace") as file:
                lines = file.read().splitlines()
        except OSError:
            return
        for line in lines:
            line = line.split("#", 1)[0].strip()
            if line.startswith("include ") and depth < 4:
                pattern = line[len("include "):].strip()
                pattern = pattern if os.path.isabs(pattern) else os.path.join(os.path.dirname(path), pattern)
                for included in sorted(glob.glob(pattern)):
                    read(included, depth + 1)
            elif line.startswith("/"):
                folders.append(line)

    read(conf)
    return list(dict.fromkeys([*folders, *SYSTEM_LIBRARY_FOLDERS]))


def rmw_library(name: str, environ: Mapping[str, str], system: list[str] | None = None) -> str | None:
    """Where the dynamic linker finds ``lib<name>.so`` for rmw_implementation, or None."""
    folders = [p for p in environ.get("LD_LIBRARY_PATH", "").split(os.pathsep) if p]
    for folder in [*folders, *(_system_library_folders() if system is None else system)]:
        path = os.path.join(folder, f"lib{name}.so")
        if os.path.isfile(path):
            return path
    return None


def installed_rmws(environ: Mapping[str, str], system: list[str] | None = None) -> list[str]:
    """The rmw implementations rmw_implementation could load here: the packages the sourced prefixes
    register under rmw_typesupport (or install as rmw_* packages), and the default, whose library
    the dynamic linker finds."""
    names = {DEFAULT_RMW}
    for prefix in _prefixes(environ):
        for folder in (RMW_TYPESUPPORT, INDEX):
            for marker in glob.glob(os.path.join(glob.escape(os.path.join(prefix, folder)), "rmw_*")):
                names.add(os.path.basename(marker))
    names.discard("rmw_implementation")
    return sorted(n for n in names if rmw_library(n, environ, system) is not None)


def rmw_concerns(environ: Mapping[str, str] | None = None, system: list[str] | None = None) -> list[Concern]:
    """RMW_IMPLEMENTATION naming an rmw whose library the dynamic linker does not find (see above)."""
    env = _environ(environ)
    name = env.get("RMW_IMPLEMENTATION", "")
    if not name:
        return []
    if not _prefixes(env) and not env.get("LD_LIBRARY_PATH"):
        return [Concern("machine", NOTE, M("RMW_IMPLEMENTATION"), M(
            "RMW_IMPLEMENTATION={name}, but no ROS 2 is sourced here to hold it", name=name),
            M("type: source /opt/ros/jazzy/setup.bash"))]
    found = rmw_library(name, env, system)
    if found is not None:
        return [Concern("machine", OK, M("RMW_IMPLEMENTATION"), M("{name} ({path})", name=name, path=found))]
    others = installed_rmws(env, system)
    held = [prefix for prefix in _prefixes(env) if os.path.isfile(os.path.join(prefix, "lib", f"lib{name}.so"))]
    if held:  # installed, but where the dynamic linker does not look: LD_LIBRARY_PATH lacks that lib/
        return [Concern("machine", FAIL, M("RMW_IMPLEMENTATION"), M(
            "RMW_IMPLEMENTATION={name}: {path} is there, but LD_LIBRARY_PATH does not name its folder, so "
            "rmw_implementation cannot load it and every node started here stops at rcl's init",
            name=name, path=os.path.join(held[0], "lib", f"lib{name}.so")),
            M("source that prefix's setup.bash (it adds {folder} to LD_LIBRARY_PATH): "
              "source {setup}", folder=os.path.join(held[0], "lib"), setup=os.path.join(held[0], "setup.bash")))]
    return [Concern("machine", FAIL, M("RMW_IMPLEMENTATION"), M(
        "RMW_IMPLEMENTATION={name}, which no sourced prefix installs: every node started here stops at "
        "rcl's init", name=name),
        M("install it (sudo apt install ros-jazzy-{package}), or use one that is here: {others}",
          package=name.replace("_", "-"), others=others or ["?"]))]


def shm_concerns(environ: Mapping[str, str] | None = None, path: str = "/dev/shm") -> list[Concern]:
    """/dev/shm against what Fast DDS's shared memory transport needs (see the module's words)."""
    env = _environ(environ)
    if env.get("RMW_IMPLEMENTATION", "") not in FASTDDS_RMWS:
        return []
    need = SHM_SEGMENT * TUTORIAL_PARTICIPANTS
    try:
        stat = os.statvfs(path)
    except OSError:
        free = total = 0
        usable = False
    else:
        free, total = stat.f_bavail * stat.f_frsize, stat.f_blocks * stat.f_frsize
        usable = os.access(path, os.W_OK | os.X_OK)
    fix = M("give it more room: docker run --shm-size=256m ..., or sudo mount -o remount,size=256M {path}",
            path=path)
    if not usable or free < SHM_SEGMENT:
        return [Concern("machine", FAIL, M("/dev/shm"), M(
            "{path}: {free} KiB free of {total} KiB; Fast DDS needs {segment} KiB per node and says '{words}', "
            "then goes through the network", path=path, free=free // 1024, total=total // 1024,
            segment=SHM_SEGMENT // 1024, words=FASTDDS_SHM_FAILED), fix)]
    if free < need:
        return [Concern("machine", NOTE, M("/dev/shm"), M(
            "{path}: {free} KiB free of {total} KiB; the tutorial's launch and node need {need} KiB "
            "({segment} KiB for each of {n} processes): the last ones say '{words}'", path=path,
            free=free // 1024, total=total // 1024, need=need // 1024, segment=SHM_SEGMENT // 1024,
            n=TUTORIAL_PARTICIPANTS, words=FASTDDS_SHM_FAILED), fix)]
    return [Concern("machine", OK, M("/dev/shm"), M("{free} MiB free", free=free // (1024 * 1024)))]


def is_wsl(osrelease: str = OSRELEASE) -> bool:
    """Under WSL, the kernel's release names Microsoft (e.g. 5.15.153.1-microsoft-standard-WSL2)."""
    try:
        with open(osrelease, encoding="utf-8", errors="replace") as file:
            return "microsoft" in file.read().lower()
    except OSError:
        return False


def graphics_concerns(renderer: str | None, environ: Mapping[str, str] | None = None,
                      osrelease: str = OSRELEASE) -> list[Concern]:
    """Will RViz draw? ``renderer``: GL_RENDERER as GLX or EGL reports it (None: no OpenGL here)."""
    env = _environ(environ)
    software = env.get("LIBGL_ALWAYS_SOFTWARE", "") not in ("", "0", "false")
    name = renderer or "?"
    if is_wsl(osrelease):
        if software:
            return [Concern("machine", OK, M("graphics for RViz"), M(
                "WSL2, LIBGL_ALWAYS_SOFTWARE={value}: RViz draws in software", value=env["LIBGL_ALWAYS_SOFTWARE"]))]
        status = FAIL if "d3d12" in name.lower() else NOTE
        return [Concern("machine", status, M("graphics for RViz"), M(
            "WSL2 with the {renderer} renderer: RViz may crash or show a black window on it", renderer=name),
            M("type: export LIBGL_ALWAYS_SOFTWARE=1 (add it to ~/.bashrc), then start RViz again"))]
    if renderer is not None and "llvmpipe" in renderer.lower():
        return [Concern("machine", NOTE, M("graphics for RViz"), M(
            "{renderer}: no GPU (a virtual machine?); RViz draws in software, slowly", renderer=renderer),
            M("in a virtual machine, turn on 3D acceleration in its display settings"))]
    return [Concern("machine", OK, M("graphics for RViz"), M("{renderer}", renderer=name))]


def machine_concerns(environ: Mapping[str, str] | None = None) -> list[Concern]:
    """The environment's ROS 2 settings and /dev/shm (graphics: :func:`graphics_concerns`)."""
    return discovery_concerns(environ) + rmw_concerns(environ) + shm_concerns(environ)
