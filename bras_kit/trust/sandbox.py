"""Run a function in a forked child process with limits on CPU time, memory and wall time.

This is the second wall around untrusted input (the first is the allow-list xacro
evaluator): if a bug lets a file hang or eat memory, the child is stopped by the kernel
(``RLIMIT_CPU``, ``RLIMIT_AS``) or killed by the parent when the wall-clock time runs out,
and the caller gets a clean :class:`ResourceLimitError`.

::

    from bras_kit.trust.sandbox import run_limited
    text = run_limited(expand, path, cpu_seconds=20, memory_bytes=2 << 30, wall_seconds=30)

The function and its arguments are inherited through ``fork`` (nothing is pickled on the
way in); the result, or the :class:`~bras_kit.core.errors.BrasKitError` it raised, comes back
pickled through a pipe. Any other exception in the child becomes a ``BrasKitError``.
On platforms without ``fork`` the function runs in-process (with no second wall).
"""

from __future__ import annotations

import contextlib
import os
import pickle
import select
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any, Generic, TypeVar

from ..core.errors import BrasKitError
from ..core.message import M, Message

T = TypeVar("T")

DEFAULT_CPU_SECONDS = 30
DEFAULT_WALL_SECONDS = 45.0
DEFAULT_MEMORY_BYTES = 2 << 30  # on top of what the process already maps
MAX_RESULT_BYTES = 256 << 20


class ResourceLimitError(BrasKitError):
    """The child ran out of time or memory, or died. ``kind`` says which limit: "wall", "cpu",
    "memory", "size" (a result too large) or "signal" (the child was killed otherwise)."""

    kind = "limit"


class Stopped(BrasKitError):
    """The caller asked the child to stop (``run_limited(..., stop=event)``): it was killed."""


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
           cpu_seconds: int, memory_bytes: int, contain: Any) -> None:
    import resource

    status = 0
    me = os.getpid()
    try:
        _tighten(resource.RLIMIT_CPU, cpu_seconds, cpu_seconds + 1)
        limit = _mapped_bytes() + memory_bytes
        _tighten(resource.RLIMIT_AS, limit, limit)
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        try:
            if contain is not None:
                contain.enter(keep=(write_fd, *contain.keep))  # from here on, in the contained process
            me = os.getpid()
            payload = ("ok", function(*args, **kwargs))
        except BrasKitError as exc:
            payload = ("error", _error_fields(exc))
        except MemoryError:
            payload = ("limit", "memory")
        except RecursionError:
            payload = ("limit", "recursion")
        except BaseException as exc:  # noqa: BLE001 - anything else is reported, not raised
            payload = ("crash", f"{type(exc).__name__}: {exc}"[:500])
        if os.getpid() != me:  # a process the function forked came back here: only the child answers
            os._exit(0)
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
        if module.split(".")[0] != "bras_kit":  # never import what a child names, beyond bras-kit
            raise ImportError(module)
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
                what: Message | str | None = None, contain: Any = None, stop: Any = None,
                result_bytes: int = MAX_RESULT_BYTES, **kwargs: Any) -> T:
    """``function(*args, **kwargs)`` in a child process under limits; its result or its error.

    ``what`` names the work in messages (``M("expanding {path}", path=...)``; "this file" unless told).
    ``contain`` (a :class:`bras_kit.trust.contain.Containment`) walls the child in before the
    function runs: its result is then read as data from a stranger (:class:`_DataUnpickler`).
    ``stop`` (a :class:`threading.Event`): once set, the child is killed and :class:`Stopped` raised.
    ``result_bytes``: the most this process reads of the child's answer (larger: a "size" limit).
    Inside :func:`children_from_a_server`, the child is forked by that server when the call can be
    sent to it (no ``stop``, no keyword arguments for the function).
    """
    server = _server
    if server is not None and stop is None and not kwargs and os.getpid() == server.owner:
        return server.run(function, *args, cpu_seconds=cpu_seconds, memory_bytes=memory_bytes,
                          wall_seconds=wall_seconds, what=what, contain=contain, result_bytes=result_bytes)
    return _fork_here(function, args, kwargs, cpu_seconds, memory_bytes, wall_seconds, what, contain, stop,
                      result_bytes)


def children_from_the_server() -> bool:
    """Whether :func:`run_limited`'s children come from this process's fork server
    (:func:`children_from_a_server`): a child forked otherwise, beside its threads, may hang."""
    return _server is not None and os.getpid() == _server.owner


def start_limited(function: Callable[..., T], *args: Any, cpu_seconds: int = DEFAULT_CPU_SECONDS,
                  memory_bytes: int = DEFAULT_MEMORY_BYTES, wall_seconds: float = DEFAULT_WALL_SECONDS,
                  what: Message | str | None = None, contain: Any = None) -> Pending[T]:
    """:func:`run_limited` begun and not waited for: the child works while this process goes on,
    :meth:`Pending.result` waits for its answer (the wall clock counts from now). A pending child
    nobody asks is killed when this process ends."""
    import atexit

    pending = _start(function, args, {}, cpu_seconds, memory_bytes, wall_seconds, what, contain, None)
    atexit.register(pending.close)
    return pending


def _fork_here(function: Callable[..., T], args: tuple[Any, ...], kwargs: dict[str, Any], cpu_seconds: int,
               memory_bytes: int, wall_seconds: float, what: Message | str | None, contain: Any, stop: Any,
               result_bytes: int = MAX_RESULT_BYTES) -> T:
    """:func:`run_limited`, the child forked by this process."""
    return _start(function, args, kwargs, cpu_seconds, memory_bytes, wall_seconds, what, contain, stop,
                  result_bytes).result()


def _start(function: Callable[..., T], args: tuple[Any, ...], kwargs: dict[str, Any], cpu_seconds: int,
           memory_bytes: int, wall_seconds: float, what: Message | str | None, contain: Any, stop: Any,
           result_bytes: int = MAX_RESULT_BYTES) -> Pending[T]:
    if not available():
        if contain is not None:
            raise BrasKitError(M("this system cannot fork a contained child process"))
        return Pending(lambda: function(*args, **kwargs))
    read_fd, write_fd = os.pipe()
    # a child may run a stranger's code (contained or not, a learner's xacro, setup.py, launch
    # file or node): its standard output and error are pipes this process relays through the
    # terminal's gate (bras_kit.trust.inert), whatever writes to them (os.write(1, ...), sys.__stdout__,
    # a C library's log)
    relayed = (os.pipe(), os.pipe())
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # the child
        os.close(read_fd)
        for standard, (relay_read, relay_write) in enumerate(relayed, start=1):
            os.dup2(relay_write, standard)
            os.close(relay_read)
            os.close(relay_write)
        _child(write_fd, function, args, kwargs, cpu_seconds, memory_bytes, contain)
    os.close(write_fd)
    for _, relay_write in relayed:
        os.close(relay_write)
    limits = (M("this file") if what is None else what, cpu_seconds, memory_bytes, wall_seconds, contain, stop,
              result_bytes)
    return Pending(child=(pid, read_fd), deadline=time.monotonic() + wall_seconds, limits=limits,
                   relayed=tuple(relay_read for relay_read, _ in relayed))


class _Relay:
    """A child's standard output and error, shown here as text made inert."""

    # once the child is reaped: what it wrote last is in the pipes already; a process it left
    # behind holding them open is not waited for past a short quiet spell
    DRAIN_SECONDS, QUIET_SECONDS = 2.0, 0.05

    def __init__(self, fds: tuple[int, ...]) -> None:
        import codecs

        self.open = {fd: (codecs.getincrementaldecoder("utf-8")("surrogateescape"), standard)
                     for standard, fd in enumerate(fds, start=1)}

    def take(self, fd: int) -> None:
        """Read what is waiting on ``fd`` and show it (the end of the stream closes it)."""
        decoder, standard = self.open[fd]
        chunk = os.read(fd, 1 << 16)
        text = decoder.decode(chunk, final=not chunk)
        if text:
            from .inert import for_terminal

            stream = sys.stdout if standard == 1 else sys.stderr
            try:
                stream.write(for_terminal(text))
                stream.flush()
            except (OSError, ValueError):  # a reader that went away: the child's words are dropped
                pass
        if not chunk:
            del self.open[fd]
            os.close(fd)

    def drain(self) -> None:
        end = time.monotonic() + self.DRAIN_SECONDS
        while self.open and (left := end - time.monotonic()) > 0:
            ready, _, _ = select.select(list(self.open), [], [], min(left, self.QUIET_SECONDS))
            if not ready:
                break
            for fd in ready:
                self.take(fd)
        self.close()

    def close(self) -> None:
        for fd in list(self.open):
            os.close(fd)
        self.open.clear()


class Pending(Generic[T]):
    """A child at work (:func:`start_limited`): its pid and the pipe its answer comes through, when
    its wall clock runs out, and run_limited's limits (to word its errors); ``here``: the function
    itself, called by :meth:`result` where no child can be forked."""

    def __init__(self, here: Callable[[], T] | None = None, *, child: tuple[int, int] | None = None,
                 deadline: float = 0.0, limits: tuple[Any, ...] = (), relayed: tuple[int, ...] = ()) -> None:
        self._here, self._child, self._deadline, self._limits = here, child, deadline, limits
        self._relay = _Relay(relayed)

    def close(self) -> None:
        """Kill the child if it is still at work, and reap it (its answer is not read)."""
        if self._child is not None:
            pid, read_fd = self._child
            self._child = None
            os.close(read_fd)
            _kill(pid)
            os.waitpid(pid, 0)
        self._relay.close()

    def result(self) -> T:
        """The child's answer, once (its error raised as run_limited raises it)."""
        import atexit

        atexit.unregister(self.close)
        if self._here is not None:
            return self._here()
        if self._child is None:
            raise RuntimeError("the answer was already read, or the child was closed")
        (pid, read_fd), self._child = self._child, None
        what, cpu_seconds, memory_bytes, wall_seconds, contain, stop, most = self._limits
        chunks: list[bytes] = []
        size = 0
        deadline = self._deadline
        timed_out = too_big = stopped = False
        interrupted = True  # until the loop ends by itself: a Ctrl-C or SIGTERM of this process leaves it
        try:
            while True:
                left = deadline - time.monotonic()
                if left <= 0:
                    timed_out = True
                    break
                if stop is not None and stop.is_set():
                    stopped = True
                    break
                ready, _, _ = select.select([read_fd, *self._relay.open], [], [],
                                            min(left, 0.2 if stop is not None else 1.0))
                for fd in ready:
                    if fd != read_fd:
                        self._relay.take(fd)
                if read_fd not in ready:
                    continue
                chunk = os.read(read_fd, 1 << 20)
                if not chunk:
                    break
                size += len(chunk)
                if size > most:
                    too_big = True
                    break
                chunks.append(chunk)
            interrupted = False
        finally:
            os.close(read_fd)
            if timed_out or too_big or stopped or interrupted:  # interrupted: nobody will read its result
                _kill(pid)
            _, status = os.waitpid(pid, 0)
            if interrupted:
                self._relay.close()
            else:
                self._relay.drain()
        if stopped:
            raise Stopped(M("{what} was stopped", what=what))
        if timed_out:
            raise _limit_error("wall", M("{what} took more than {seconds:g} s and was stopped", what=what,
                                         seconds=wall_seconds),
                               hint=M("the file may loop or recurse without end; simplify it"))
        if too_big:
            raise _limit_error("size", M("{what} made a result larger than {most} MiB and was stopped", what=what,
                                         most=most >> 20))
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
        try:
            kind, value = _load(b"".join(chunks), trusted=contain is None)
        except Exception as exc:  # noqa: BLE001 - a contained child's bytes are a stranger's
            raise BrasKitError(M("{what} failed: {reason}", what=what, reason=f"unreadable result ({exc})"[:500])) from None
        if kind == "ok":
            return value
        if kind == "error":
            raise _rebuild_error(*value)
        if kind == "limit":
            needed = M("{what} needed more memory than allowed and was stopped", what=what) if value == "memory" else \
                M("{what} needed more recursion than allowed and was stopped", what=what)
            raise _limit_error("memory", needed, hint=M("simplify the file (no huge values, no deep recursion)"))
        raise BrasKitError(M("{what} failed: {reason}", what=what, reason=value))


SAFE_BUILTINS = frozenset({"set", "frozenset", "complex", "range", "slice", "bytearray"})


class _DataUnpickler(pickle.Unpickler):
    """Reads what a contained child sent: plain data and bras-kit's data classes, nothing that
    runs code when built (no function, no class outside bras-kit, no class with behaviour).
    The child's process is the learner's: its bytes may be forged."""

    def find_class(self, module: str, name: str) -> Any:
        import dataclasses
        import enum
        import importlib

        if module == "builtins" and name in SAFE_BUILTINS:
            return getattr(__import__("builtins"), name)
        if module.split(".")[0] == "bras_kit" and "." not in name and module in sys.modules:
            found = getattr(importlib.import_module(module), name, None)
            if isinstance(found, type) and (dataclasses.is_dataclass(found) or issubclass(found, enum.Enum)):
                return found
        raise pickle.UnpicklingError(f"{module}.{name} is not data")


def _load(data: bytes, trusted: bool) -> Any:
    if trusted:
        return pickle.loads(data)  # noqa: S301 - our own child's bytes
    import io

    value = _DataUnpickler(io.BytesIO(data)).load()
    if not (isinstance(value, tuple) and len(value) == 2 and isinstance(value[0], str)):
        raise pickle.UnpicklingError("not a result")
    if value[0] == "error" and not (isinstance(value[1], tuple) and len(value[1]) == 3
                                    and str(value[1][0]).split(".")[0] == "bras_kit"
                                    and isinstance(value[1][2], dict)):
        raise pickle.UnpicklingError("not an error of bras-kit")
    return value


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
        self._lock = threading.Lock()
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
            what: Message | str | None = None, contain: Any = None, result_bytes: int = MAX_RESULT_BYTES) -> T:
        """:func:`run_limited` with the child forked by the server."""
        limits: dict[str, Any] = {"cpu_seconds": cpu_seconds, "memory_bytes": memory_bytes,
                                  "wall_seconds": wall_seconds, "what": what, "contain": contain,
                                  "result_bytes": result_bytes}
        request = _pickled((function, args, limits)) if self._pid and os.getpid() == self._owner else None
        if request is not None:  # None: no server, or a call that cannot be sent (forked from here)
            try:
                with self._lock:  # one request at a time on the pipes
                    _write(self._requests, request)
                    reply = _receive(self._replies, wall_seconds + 10.0)
            except (OSError, EOFError, TimeoutError, pickle.PickleError):
                reply = None
            if reply is not None:
                kind, value = reply
                if kind == "ok":
                    return value
                raise _rebuild_error(*value)
            self.close()  # gone or stuck: fork from here from now on
        return _fork_here(function, args, {}, cpu_seconds, memory_bytes, wall_seconds, what, contain, None,
                          result_bytes)

    @property
    def owner(self) -> int:
        """The process that started the server (0 once closed): only it can send to it."""
        return self._owner if self._pid else 0

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


_server: ForkServer | None = None  # the server of children_from_a_server, while inside it


@contextlib.contextmanager
def children_from_a_server() -> Iterator[None]:
    """While inside, the children of :func:`run_limited` are forked by a :class:`ForkServer`
    started on entry, not by this process. For a process about to start threads that import
    modules: a child forked while another thread is importing a module waits forever for that
    module's import lock (its holder is a thread the child does not have). The server is forked
    before those threads exist, so its children have none."""
    global _server
    if _server is not None or not available():
        yield
        return
    _server = ForkServer()
    try:
        yield
    finally:
        server, _server = _server, None
        server.close()


def _serve(requests: int, replies: int) -> None:
    """The server's loop: each request run by :func:`run_limited`, its result or error sent back."""
    while True:
        try:
            function, args, limits = _receive(requests, None)
        except EOFError:
            return  # closed by the owner, or the owner died
        try:
            reply: tuple[str, Any] = ("ok", _fork_here(function, args, {}, stop=None, **limits))
        except BrasKitError as exc:
            reply = ("error", _error_fields(exc))
        except Exception as exc:  # noqa: BLE001 - reported to the owner as run_limited reports a crash
            failed = BrasKitError(M("{what} failed: {reason}", what=limits.get("what") or M("this file"),
                                    reason=f"{type(exc).__name__}: {exc}"[:500]))
            reply = ("error", _error_fields(failed))
        _send(replies, reply)


def _pickled(value: Any) -> bytes | None:
    """``value`` as bytes for the pipe, or None when pickle refuses it (a lambda, a lock, an mmap)."""
    try:
        return pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    except (pickle.PickleError, TypeError, AttributeError):
        return None


def _send(fd: int, value: Any) -> None:
    _write(fd, pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL))


def _write(fd: int, data: bytes) -> None:
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
