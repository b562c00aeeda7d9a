"""Grading a class: the same code path on a local process pool or a Dask cluster (both are
``concurrent.futures`` executors), a progress bar on a terminal, resume by content hash, and
Ctrl-C keeping what was finished."""

from __future__ import annotations

import concurrent.futures as futures
import contextlib
import os
import shutil
import sys
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures.process import BrokenProcessPool
from typing import IO, Any

from ..core import backends
from ..core.errors import BrasKitError, os_reason
from ..core.message import M, Message
from ..core.wording import quoted
from .rubric import Rubric
from .submissions import Submission, content_hash
from .worker import Options, grade


@contextlib.contextmanager
def executor(jobs: int | None = None, scheduler: str | None = None) -> Iterator[futures.Executor]:
    """A local process pool of ``jobs`` workers, or the Dask cluster at ``scheduler``."""
    if scheduler:
        Client = backends.dask_distributed().Client  # noqa: N806  (a class)
        try:
            client = Client(scheduler, timeout=10)
        except (OSError, TimeoutError) as exc:
            raise BrasKitError(M("cannot reach the Dask scheduler {scheduler}: {reason}", scheduler=scheduler,
                                 reason=os_reason(exc) if isinstance(exc, OSError) and exc.errno else quoted(str(exc))),
                               hint=M("start it with 'dask scheduler' and its workers with 'dask worker {scheduler}'",
                                      scheduler=scheduler)) from None
        try:
            yield client.get_executor()
        finally:
            client.close()
        return
    import multiprocessing

    workers = jobs or os.cpu_count() or 1
    # fork: workers start at once and share what this process already imported
    pool = futures.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("fork"),
                                       initializer=_start_worker, initargs=(rasteriser_threads(workers),))
    try:
        yield pool
    finally:
        pool.shutdown(wait=False, cancel_futures=True)


_marker: str | None = None  # in a pool worker: the file naming the submission it is grading


def rasteriser_threads(workers: int) -> str:
    """LP_NUM_THREADS for each of ``workers`` processes drawing at once: the cores they leave
    each other ("0": Mesa's software rasteriser draws in the worker's own thread). By default
    llvmpipe starts a thread per core in every process, so workers filling the cores would each
    hand their pictures to threads fighting the other workers for the same cores."""
    return str(max((os.cpu_count() or 1) // max(workers, 1), 1) if (os.cpu_count() or 1) > workers else 0)


def _start_worker(rasteriser: str = "") -> None:
    """Ctrl-C is the parent's to handle: a worker killed by it would break the pool and turn
    the submissions still queued into failures instead of leaving them for --resume.

    When one worker dies, the pool terminates the others (SIGTERM): they take their marker
    away first, so their submissions are graded again rather than blamed.

    ``rasteriser``: the LP_NUM_THREADS of this worker (see :func:`rasteriser_threads`), unless
    the user set it; read by Mesa when the worker opens its first picture.
    """
    import signal

    if rasteriser:
        os.environ.setdefault("LP_NUM_THREADS", rasteriser)

    def terminated(signum: int, frame: object) -> None:
        if _marker is not None:
            with contextlib.suppress(OSError):
                os.unlink(_marker)
        from . import worker

        if worker.workdir_in_use is not None:  # the submission it was unpacking: nothing left behind
            shutil.rmtree(worker.workdir_in_use, ignore_errors=True)
        os._exit(128 + signum)

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, terminated)
    from .worker import start_fork_server

    start_fork_server()  # now, while this worker is small (see bras_kit.trust.sandbox.ForkServer)


class Progress:
    """done / total, failures and rate on one line of a terminal; nothing when piped."""

    def __init__(self, total: int, stream: IO[str] | None = None, lang: str | None = None) -> None:
        self.stream = stream or sys.stderr
        self.lang = lang
        self.enabled = bool(getattr(self.stream, "isatty", lambda: False)())
        self.total, self.done, self.failed = total, 0, 0
        self.start = time.monotonic()

    def update(self, failed: bool) -> None:
        self.done += 1
        self.failed += int(failed)
        if self.enabled:
            from ..core.i18n import say

            rate = self.done / max(time.monotonic() - self.start, 1e-6)
            filled = int(30 * self.done / max(self.total, 1))
            from ..trust.inert import LINE_START, emit

            emit(self.stream, LINE_START, say(M("grading [{bar}] {done}/{total}, {failed} unreadable, {rate:.1f}/s ",
                                                bar="#" * filled + "." * (30 - filled), done=self.done,
                                                total=self.total, failed=self.failed, rate=rate), self.lang), end="")
            self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


def grade_all(submissions: Sequence[Submission], rubric: Rubric, options: Options, *,
              jobs: int | None = None, scheduler: str | None = None,
              previous: dict[str, dict[str, Any]] | None = None,
              on_result: Callable[[dict[str, Any]], None] | None = None) -> tuple[list[dict[str, Any]], bool]:
    """Results in submission order, and whether the batch ran to the end (False after Ctrl-C).

    ``previous`` (learner -> result of an earlier report) is reused when the submission's
    content hash and the rubric are unchanged (``--resume``).
    """
    results: dict[str, dict[str, Any]] = {}
    todo = []
    for submission in submissions:
        old = (previous or {}).get(submission.learner)
        if old and old.get("hash") == content_hash(submission.path) and old.get("rubric") == rubric.digest \
                and old.get("lang") == options.lang:
            results[submission.learner] = old
        else:
            todo.append(submission)
    progress = Progress(len(submissions), lang=options.lang)
    for _ in results:
        progress.update(False)
    finished = True

    def keep(submission: Submission, result: dict[str, Any]) -> None:
        result.update(rubric=rubric.digest, lang=options.lang)
        results[submission.learner] = result
        progress.update(result["status"] != "graded")
        if on_result is not None:
            on_result(result)

    try:
        while todo:
            todo = _run_batch(todo, rubric, options, jobs, scheduler, keep)
    except KeyboardInterrupt:
        finished = False
    finally:
        progress.close()
    ordered = [results[s.learner] for s in submissions if s.learner in results]
    return ordered, finished


def _run_batch(todo: list[Submission], rubric: Rubric, options: Options, jobs: int | None, scheduler: str | None,
               keep: Callable[[Submission, dict[str, Any]], None]) -> list[Submission]:
    """Grade ``todo`` on one executor; returns the submissions to grade again on a fresh one.

    A local worker that dies (a crash in a native library, the kernel's OOM killer) breaks the
    whole process pool: every submission still queued fails with ``BrokenProcessPool``. Each
    worker leaves a marker naming the submission it is on, so only the ones being graded when
    a worker died score zero and the others go to a new pool. (Dask replaces a dead worker
    itself and fails only the task that killed it.)
    """
    again: list[Submission] = []
    with tempfile.TemporaryDirectory(prefix="bras-kit-grade-markers-") as markers, \
            executor(jobs, scheduler) as pool:
        if scheduler:
            pending = {pool.submit(grade, s, rubric, options): s for s in todo}
        else:
            pending = {pool.submit(_grade_marked, markers, s, rubric, options): s for s in todo}
        taken: set[Any] = set()

        def take(future: Any) -> None:
            taken.add(future)
            submission = pending[future]
            try:
                result = future.result()
            except BrokenProcessPool:
                again.append(submission)
                return
            except Exception as exc:  # an error in a worker: that learner only
                result = _failed(submission, rubric, exc, options.lang)
            keep(submission, result)

        try:
            for future in futures.as_completed(pending):
                take(future)
        except KeyboardInterrupt:  # the report keeps every submission finished by then
            for future in pending:
                if future not in taken and future.done() and not future.cancelled():
                    take(future)
            raise
        if again:
            pool.shutdown(wait=True)  # the other workers have taken their markers away once they are gone
            culprits = _marked(markers) or {s.learner for s in again}  # none known: stop rather than loop
            for submission in [s for s in again if s.learner in culprits]:
                keep(submission, _failed(submission, rubric, DiedError(), options.lang))
            again = [s for s in again if s.learner not in culprits]
    order = {s.learner: k for k, s in enumerate(todo)}
    return sorted(again, key=lambda s: order[s.learner])


def _grade_marked(markers: str, submission: Submission, rubric: Rubric, options: Options) -> dict[str, Any]:
    """:func:`grade`, with a file in ``markers`` naming the submission while it is being graded."""
    global _marker
    marker = os.path.join(markers, str(os.getpid()))
    with open(marker, "w", encoding="utf-8") as handle:
        handle.write(submission.learner)
    _marker = marker
    try:
        return grade(submission, rubric, options)
    finally:
        _marker = None
        os.unlink(marker)


def _marked(markers: str) -> set[str]:
    """The submissions being graded by workers that died (their markers are still there)."""
    names = set()
    for entry in os.listdir(markers):
        with contextlib.suppress(OSError), open(os.path.join(markers, entry), encoding="utf-8") as handle:
            names.add(handle.read())
    return names


class DiedError(Exception):
    """A submission whose worker process died while grading it."""


def _failed(submission: Submission, rubric: Rubric, exc: BaseException, lang: str) -> dict[str, Any]:
    from ..core.i18n import say

    if isinstance(exc, DiedError):
        why: Message | str = M("the worker process died while grading it (a crash, or out of memory)")
    else:  # an unexpected error: its type and Python's own words
        why = f"{type(exc).__name__}: {exc}"
    message = say(M("could not be graded: {why}", why=why), lang)
    return {"learner": submission.learner, "path": submission.path, "hash": content_hash(submission.path),
            "status": "unreadable", "picture": None, "animation": None, "main_file": None, "package": False,
            "findings": [{"file": os.path.basename(submission.path), "line": None, "code": "BK103",
                          "severity": "error", "message": message,
                          "hint": say(M("check the submission by hand with bras-kit validate"), lang)}],
            "items": {item.id: 0.0 for item in rubric.items}, "score": 0.0, "max": rubric.total,
            "first_error": f"BK103 {message}", "seconds": 0.0}
