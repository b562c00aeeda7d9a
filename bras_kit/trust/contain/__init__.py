"""The containment around the child that runs code bras-kit did not write (docs/security.md).

The child is a ``fork`` of Python (:func:`bras_kit.trust.sandbox.run_limited`): the function to run
and its arguments are already in its memory, so nothing is executed afresh. Before the
learner's code runs, :meth:`Containment.enter` turns that child into a small container made of
what Linux gives any user, without a daemon, root or a helper program:

- a **user namespace** (the child's own uid and gid mapped onto themselves), so the steps
  below need no privilege, and root's powers end at the namespace;
- a **mount namespace** whose root is a fresh read-only tmpfs into which only the granted
  paths are bound, each at its own path: the Python installation, the system libraries, the
  learner's package (read-only) and the run's own folder (read-write). Nothing else exists
  there: not the home folder, not ``~/.ssh``, not ``/tmp``, not ``/proc``, not the sockets of
  ``/run``. The old root is detached (``pivot_root``), as bubblewrap does;
- a **network namespace** with no interface up: no TCP, no UDP, and no abstract Unix socket
  reaches this machine or another, loopback included;
- a **PID namespace**: the code runs as its init (pid 1), sees and can name no process
  outside, so it can neither signal nor trace one; when it ends (or is killed by a limit),
  the kernel kills every process it forked;
- an environment cut down to what a program needs (``PATH``, ``HOME``, the locale, ``ROS_*``...):
  tokens and keys in the others do not reach it;
- its own session and process group (``kill(0, ...)`` would otherwise reach the caller's
  group, and ``TIOCSTI`` the terminal's shell);
- an **unprivileged identity**: the caller's own uid, or for root the overflow user
  (``nobody``), mapped from outside by a helper that stays there, because the kernel never
  counts root in ``RLIMIT_NPROC`` (kernel/fork.c, ``copy_process``: ``real_cred->user !=
  INIT_USER``), whatever its namespace;
- then every capability dropped (the bounding set too) and ``no_new_privs`` set;
  ``RLIMIT_NPROC`` caps the processes it may start, ``RLIMIT_FSIZE`` each file it writes;
- its folder a **bounded tmpfs** (bytes and files) seen only in its mount namespace: what it
  writes there stays in memory and goes with the run, never on this machine's disk;
- a **seccomp filter** (libseccomp, through ``pyseccomp``) that refuses new namespaces
  (``unshare``, ``setns``, ``clone`` with a ``CLONE_NEW*`` flag), mounts (``mount``,
  ``umount2``, ``pivot_root``, the new mount API) and the kernel keyrings, whatever calls them
  (``ctypes`` included).

The package holds one module per concern: :mod:`.kernel` (the C library's calls),
:mod:`.namespaces` (and who the code runs as), :mod:`.view` (the filesystem it sees),
:mod:`.environment`, :mod:`.limits` (capabilities and rlimits), :mod:`.seccomp`, :mod:`.walls`
(the steps in order, in the forked child), :mod:`.record` and :mod:`.probe` (whether this machine
can contain, tried once per boot), :mod:`.modes` (what a command asks for, and its note).

::

    from ..trust.contain import Containment, available
    status = available()                 # what this machine lacks, and how to get it
    if status.ok:
        run_limited(function, ..., contain=Containment(workdir, readable=(package_root,)))
"""

from __future__ import annotations

from .kernel import ContainmentError as ContainmentError
from .limits import MAX_PROCESSES as MAX_PROCESSES
from .modes import ContainmentUnavailable as ContainmentUnavailable
from .modes import containment as containment
from .modes import containment_required as containment_required
from .modes import uncontained_note as uncontained_note
from .probe import Status as Status
from .probe import available as available
from .probe import begin_trial as begin_trial
from .record import forget_trial as forget_trial
from .view import MAX_FOLDER_BYTES as MAX_FOLDER_BYTES
from .view import MAX_FOLDER_FILES as MAX_FOLDER_FILES
from .view import python_paths as python_paths
from .walls import Containment as Containment
