"""Run a function in a forked child process with limits on CPU time, memory and wall time.

This is the second wall around untrusted input (the first is the allow-list xacro
evaluator): if a bug lets a file hang or eat memory, the child is stopped by the kernel
(``RLIMIT_CPU``, ``RLIMIT_AS``) or killed by the parent when the wall-clock time runs out,
and the caller gets a clean :class:`ResourceLimitError`.

::

    from bras_kit.sandbox import run_limited
    text = run_limited(expand, path, cpu_seconds=20, memory_bytes=2 << 30, wall_seconds=30)

The function and its arguments are inherited through ``fork`` (nothing is pickled on the
way in); the result, or the :class:`~bras_kit.errors.BrasKitError` it raised, comes back
pickled through a pipe. Any other exception in the child becomes a ``BrasKitError``.
On platforms without ``fork`` the function runs in-process (with no second wall).
"""

from __future__ import annotations

import os
import pickle
import select
import signal
import sys
import time
from collections.abc import Callable
from typing import Any, TypeVar

from .errors import BrasKitError
from .message import M, Message

T = TypeVar("T")

DEFAULT_CPU_SECONDS = 30
DEFAULT_WALL_SECONDS = 45.0
DEFAULT_MEMORY_BYTES = 2 << 30  # on top of what the process already maps
MAX_RESULT_BYTES = 256 << 20


class ResourceLimitError(BrasKitError):
    """The child ran out of time or memory, or died. ``kind`` says which limit: "wall", "cpu",
    "memory", "size" (a result too large) or "signal" (the child was killed otherwise)."""

    kind = "limit"


def _limit_error(kind: str, message: Message, **where: Any) -> ResourceLimitError:
    error = ResourceLimitError(message, **where)
    error.kind = kind
    return error


def available() -> bool:
    return hasattr(os, "fork") and sys.platform != "win32"


def _mapped_bytes() -> int:
    """Address space the process maps now (children start with the same)."""
    try:
        with open("/proc/self/statm") as handle:
            return int(handle.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def _tighten(which: int, soft: int, hard: int) -> None:
    """Set a limit, never above the one already in force (a sandbox inside a sandbox)."""
    import resource

    _, current = resource.getrlimit(which)
    if current != resource.RLIM_INFINITY:
        soft, hard = min(soft, current), min(hard, current)
    resource.setrlimit(which, (soft, hard))


def _child(write_fd: int, function: Callable[..., Any], args: tuple[Any, ...], kwargs: dict[str, Any],
           cpu_seconds: int, memory_bytes: int) -> None:
    import resource

    status = 0
    try:
        _tighten(resource.RLIMIT_CPU, cpu_seconds, cpu_seconds + 1)
        limit = _mapped_bytes() + memory_bytes
        _tighten(resource.RLIMIT_AS, limit, limit)
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        try:
            payload = ("ok", function(*args, **kwargs))
        except BrasKitError as exc:
            payload = ("error", _error_fields(exc))
        except MemoryError:
            payload = ("limit", "memory")
        except RecursionError:
            payload = ("limit", "recursion")
        except BaseException as exc:  # noqa: BLE001 - anything else is reported, not raised
            payload = ("crash", f"{type(exc).__name__}: {exc}"[:500])
        try:
            data = pickle.dumps(payload, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception as exc:  # noqa: BLE001
            data = pickle.dumps(("crash", f"result cannot be sent back: {exc}"[:500]))
        view = memoryview(data)
        while view:
            written = os.write(write_fd, view[:1 << 20])
            view = view[written:]
    except MemoryError:
        status = 3
    except BaseException:  # noqa: BLE001
        status = 4
    finally:
        os._exit(status)


def _error_fields(exc: BrasKitError) -> tuple[str, str, dict[str, Any]]:
    fields = {k: getattr(exc, k, None) for k in ("path", "line", "element", "hint")}
    extra = {k: v for k, v in vars(exc).items() if k not in fields and k != "message"
             and isinstance(v, (str, int, float, type(None)))}
    return type(exc).__module__, type(exc).__qualname__, {"message": exc.message, **fields, "extra": extra}


def _rebuild_error(module: str, name: str, fields: dict[str, Any]) -> BrasKitError:
    import importlib

    cls: Any = BrasKitError
    try:
        found = importlib.import_module(module)
        for part in name.split("."):
            found = getattr(found, part)
        if isinstance(found, type) and issubclass(found, BrasKitError):
            cls = found
    except (ImportError, AttributeError):
        pass
    extra = fields.pop("extra", {})
    try:
        error = cls(fields.pop("message"), **fields)
    except TypeError:
        error = BrasKitError(str(fields.get("message")))
    for key, value in extra.items():
        setattr(error, key, value)
    return error


def run_limited(function: Callable[..., T], *args: Any, cpu_seconds: int = DEFAULT_CPU_SECONDS,
                memory_bytes: int = DEFAULT_MEMORY_BYTES, wall_seconds: float = DEFAULT_WALL_SECONDS,
                what: Message | str | None = None, **kwargs: Any) -> T:
    """``function(*args, **kwargs)`` in a child process under limits; its result or its error.

    ``what`` names the work in messages (``M("expanding {path}", path=...)``; "this file" unless told).
    """
    if not available():
        return function(*args, **kwargs)
    what = M("this file") if what is None else what
    read_fd, write_fd = os.pipe()
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # the child
        os.close(read_fd)
        _child(write_fd, function, args, kwargs, cpu_seconds, memory_bytes)
    os.close(write_fd)
    chunks: list[bytes] = []
    size = 0
    deadline = time.monotonic() + wall_seconds
    timed_out = too_big = False
    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                timed_out = True
                break
            ready, _, _ = select.select([read_fd], [], [], min(left, 1.0))
            if not ready:
                continue
            chunk = os.read(read_fd, 1 << 20)
            if not chunk:
                break
            size += len(chunk)
            if size > MAX_RESULT_BYTES:
                too_big = True
                break
            chunks.append(chunk)
    finally:
        os.close(read_fd)
        if timed_out or too_big:
            _kill(pid)
        _, status = os.waitpid(pid, 0)
    if timed_out:
        raise _limit_error("wall", M("{what} took more than {seconds:g} s and was stopped", what=what,
                                     seconds=wall_seconds),
                           hint=M("the file may loop or recurse without end; simplify it"))
    if too_big:
        raise _limit_error("size", M("{what} made a result larger than {most} MiB and was stopped", what=what,
                                     most=MAX_RESULT_BYTES >> 20))
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        if sig in (signal.SIGXCPU, signal.SIGKILL):
            raise _limit_error("cpu", M("{what} used more than {seconds} s of CPU and was stopped", what=what,
                                        seconds=cpu_seconds),
                               hint=M("the file may loop or recurse without end; simplify it"))
        raise _limit_error("signal", M("{what} stopped the worker process (signal {signal})", what=what, signal=sig),
                           hint=M("it may need more memory than allowed; simplify the file"))
    if not chunks:
        raise _limit_error("memory", M("{what} ran out of memory and was stopped", what=what),
                           hint=M("the limit is {most} MiB above the program's own size", most=memory_bytes >> 20))
    kind, value = pickle.loads(b"".join(chunks))  # noqa: S301 - our own child's bytes
    if kind == "ok":
        return value  # type: ignore[no-any-return]
    if kind == "error":
        raise _rebuild_error(*value)
    if kind == "limit":
        needed = M("{what} needed more memory than allowed and was stopped", what=what) if value == "memory" else \
            M("{what} needed more recursion than allowed and was stopped", what=what)
        raise _limit_error("memory", needed, hint=M("simplify the file (no huge values, no deep recursion)"))
    raise BrasKitError(M("{what} failed: {reason}", what=what, reason=value))


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


class ForkServer:
    """A small process that forks the limited children of :func:`run_limited` for a big one.

    After a fork, every page the forking process writes to is copied or at least faulted in
    again (copy on write): a grading worker holding OpenGL, pyrender and a class's meshes paid
    some 8,000 page faults per learner for forking the check of each submission, more than the
    check itself. Started while the process is still small, this server forks the children
    instead, and the big process never forks. The function and its arguments go to the server
    pickled (a module-level function and plain data); limits, results and errors are those of
    :func:`run_limited`. The server ends when its owner closes it or dies (the end of its
    request pipe); if it is gone or stuck, :meth:`run` forks from the calling process as before.
    """

    def __init__(self) -> None:
        self._pid = self._owner = 0
        self._requests = self._replies = -1
        if not available():
            return
        request_read, request_write = os.pipe()
        reply_read, reply_write = os.pipe()
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:  # the server
            status = 0
            try:
                os.close(request_write)
                os.close(reply_read)
                _serve(request_read, reply_write)
            except BaseException:  # noqa: BLE001 - its owner forks for itself from then on
                status = 1
            finally:
                os._exit(status)
        os.close(request_read)
        os.close(reply_write)
        self._pid, self._owner = pid, os.getpid()
        self._requests, self._replies = request_write, reply_read

    def run(self, function: Callable[..., T], *args: Any, cpu_seconds: int = DEFAULT_CPU_SECONDS,
            memory_bytes: int = DEFAULT_MEMORY_BYTES, wall_seconds: float = DEFAULT_WALL_SECONDS,
            what: Message | str | None = None) -> T:
        """:func:`run_limited` with the child forked by the server."""
        limits: dict[str, Any] = {"cpu_seconds": cpu_seconds, "memory_bytes": memory_bytes,
                                  "wall_seconds": wall_seconds, "what": what}
        if self._pid and os.getpid() == self._owner:
            try:
                _send(self._requests, (function, args, limits))
                reply = _receive(self._replies, wall_seconds + 10.0)
            except (OSError, EOFError, TimeoutError, pickle.PickleError):
                reply = None
            if reply is not None:
                kind, value = reply
                if kind == "ok":
                    return value  # type: ignore[no-any-return]
                raise _rebuild_error(*value)
            self.close()  # gone or stuck: fork from here from now on
        return run_limited(function, *args, **limits)

    def close(self) -> None:
        """End the server: it finishes the check under way, if any, and goes (killed after a second)."""
        pid, self._pid = self._pid, 0
        if not pid or os.getpid() != self._owner:
            return
        for fd in (self._requests, self._replies):
            try:
                os.close(fd)
            except OSError:
                pass
        deadline = time.monotonic() + 1.0
        try:
            while os.waitpid(pid, os.WNOHANG) == (0, 0):  # its CPU time is counted with its owner's
                if time.monotonic() > deadline:
                    _kill(pid)
                    os.waitpid(pid, 0)
                    break
                time.sleep(0.005)
        except ChildProcessError:
            pass


def _serve(requests: int, replies: int) -> None:
    """The server's loop: each request run by :func:`run_limited`, its result or error sent back."""
    while True:
        try:
            function, args, limits = _receive(requests, None)
        except EOFError:
            return  # closed by the owner, or the owner died
        try:
            reply: tuple[str, Any] = ("ok", run_limited(function, *args, **limits))
        except BrasKitError as exc:
            reply = ("error", _error_fields(exc))
        except Exception as exc:  # noqa: BLE001 - reported to the owner as run_limited reports a crash
            failed = BrasKitError(M("{what} failed: {reason}", what=limits.get("what") or M("this file"),
                                    reason=f"{type(exc).__name__}: {exc}"[:500]))
            reply = ("error", _error_fields(failed))
        _send(replies, reply)


def _send(fd: int, value: Any) -> None:
    data = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    view = memoryview(len(data).to_bytes(8, "little") + data)
    while view:
        view = view[os.write(fd, view[:1 << 20]):]


def _receive(fd: int, timeout: float | None) -> Any:
    """One value written by :func:`_send`: EOFError at the end of the pipe, TimeoutError after ``timeout`` s."""
    deadline = None if timeout is None else time.monotonic() + timeout

    def exactly(count: int) -> bytes:
        chunks: list[bytes] = []
        while count:
            if deadline is not None:
                ready, _, _ = select.select([fd], [], [], max(0.0, deadline - time.monotonic()))
                if not ready:
                    raise TimeoutError
            chunk = os.read(fd, min(count, 1 << 20))
            if not chunk:
                raise EOFError
            chunks.append(chunk)
            count -= len(chunk)
        return b"".join(chunks)

    size = int.from_bytes(exactly(8), "little")
    return pickle.loads(exactly(size))  # noqa: S301 - our own server's or owner's bytes
